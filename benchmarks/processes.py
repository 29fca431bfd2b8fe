"""CPU time and peak memory of a CLI command, process by process (Linux): where a job's CPU goes.

    python -m benchmarks.processes                                  # warm reproduce alshaer2005
    python -m benchmarks.processes --cold                           # first run (new home)
    python -m benchmarks.processes --before OLD/src                 # both trees, back to back
    python -m benchmarks.processes --cli "run slider-crank --joint dry --revs 1"

Runs ``jointdyn <cli> --out D`` (``--overwrite`` added for ``reproduce``) in a fresh process
and samples ``/proc`` every 50 ms: for the command and every process it starts (the pool's
workers, the figure-drawing interpreter) the CPU time (user + sys) and the peak resident set
(``VmHWM``) last seen, with its start and end [s after the start] and its command line. The
CPU of a process that lives shorter than one sample period is missed; the total of the command
as the kernel accounts it (``RUSAGE_CHILDREN``, every process waited for) is printed beside the
sum of the rows [T323]. Warm (the default): one untimed run first fills the caches of a new home;
``--cold`` times that first run; ``--home H`` keeps the homes (``H/before``, ``H/this``) and
their caches for the next invocation. The machine may be shared: compare CPU seconds, not wall.
"""

from __future__ import annotations

import argparse
import os
import resource
import shlex
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from benchmarks import end_to_end

ROOT = Path(__file__).resolve().parents[1]
TICK = os.sysconf("SC_CLK_TCK")


def _procs() -> dict[int, tuple[int, float, float]]:
    """{pid: (parent pid, CPU [s], peak RSS [MB])} of every process readable now."""
    out = {}
    for d in os.listdir("/proc"):
        if not d.isdigit():
            continue
        try:
            stat = Path(f"/proc/{d}/stat").read_text()
            hwm = [x for x in Path(f"/proc/{d}/status").read_text().splitlines() if x.startswith("VmHWM")]
        except OSError:
            continue
        f = stat.rsplit(")", 1)[1].split()
        rss = int(hwm[0].split()[1]) / 1024 if hwm else 0.0
        out[int(d)] = (int(f[1]), (int(f[11]) + int(f[12])) / TICK, rss)
    return out


def _descends(pid: int, root: int, procs: dict) -> bool:
    while pid in procs and pid != root:
        pid = procs[pid][0]
    return pid == root


def sample(cmd: list[str], env: dict) -> dict:
    """Run ``cmd``; returns ``{"wall", "cpu_total", "rows": [(pid, cpu, rss, start, end, cmdline)]}``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, env=env, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    seen: dict[int, list] = {}
    while p.poll() is None:
        now = time.perf_counter() - t0
        procs = _procs()
        for pid, (_, cpu, rss) in procs.items():
            if pid != p.pid and not _descends(pid, p.pid, procs):
                continue
            if pid not in seen:
                try:
                    line = Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode()
                except OSError:
                    line = "?"
                seen[pid] = [cpu, rss, now, now, line.strip()]
            seen[pid][0], seen[pid][1], seen[pid][3] = cpu, max(rss, seen[pid][1]), now
        time.sleep(0.05)
    err = p.stderr.read().decode(errors="replace") if p.stderr else ""
    if p.returncode != 0:
        raise RuntimeError(f"{shlex.join(cmd)} failed ({p.returncode}): {err[-500:]}")
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    total = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
    rows = [(pid, *v) for pid, v in seen.items()]
    return {"wall": time.perf_counter() - t0, "cpu_total": total, "rows": rows}


def _label(line: str) -> str:
    if "reproduce_figures" in line or "_draw(" in line:
        return "figure drawing (fresh interpreter)"
    return line[:90]


def measure(src: Path, cli: str, cold: bool, home: str | None = None) -> dict:
    """:func:`sample` of ``jointdyn <cli> --out D`` with sources ``src`` in a new home (or in
    ``home``, kept: its caches are reused)."""
    args = shlex.split(cli)
    with tempfile.TemporaryDirectory() as new, tempfile.TemporaryDirectory() as d:
        env = {**end_to_end.new_user_env(home or new), "PYTHONPATH": str(src)}
        cmd = [sys.executable, "-m", "jointdyn", *args, "--out", os.path.join(d, "o")]
        if args[0] == "reproduce":
            cmd.append("--overwrite")
        if not cold:
            subprocess.run(cmd, env=env, cwd=ROOT, check=True, capture_output=True)
        return sample(cmd, env)


def report(name: str, m: dict) -> str:
    rows = sorted(m["rows"], key=lambda r: r[3])
    first, main_line = (rows[0][0], rows[0][5]) if rows else (None, "")
    lines = [f"{name}: wall {m['wall']:.1f} s, CPU {m['cpu_total']:.2f} s (kernel's count of the command)"]
    lines.append("   CPU [s]  peak RSS [MB]  start-end [s]  process")
    for pid, cpu, rss, t0, t1, line in rows:
        who = "the command" if pid == first else "forked worker" if line == main_line else _label(line)
        lines.append(f"  {cpu:8.2f}  {rss:13.0f}  {t0:5.1f}-{t1:5.1f}  {who}")
    lines.append(f"  {sum(r[1] for r in rows):8.2f}  sum of the sampled processes")
    return "\n".join(lines)


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cli", default="reproduce alshaer2005", help="the CLI command (--out D is added)")
    ap.add_argument("--cold", action="store_true", help="time the first run of a new home")
    ap.add_argument("--before", default=None, help="another src/ tree to measure first")
    ap.add_argument("--home", default=None, help="home directory to use and keep (default: a new one)")
    a = ap.parse_args(argv)
    trees = ([("before", Path(a.before))] if a.before else []) + [("this", ROOT / "src")]
    print(f"jointdyn {a.cli} --out D, {'first run (new home)' if a.cold else 'warm (second run)'}")
    print(f"Machine: {end_to_end.machine_load()} at the start")
    out = {}
    for name, src in trees:
        home = os.path.join(a.home, name) if a.home else None
        if home:
            os.makedirs(home, exist_ok=True)
        out[name] = measure(src, a.cli, a.cold, home)
        print(report(f"{name} ({src})", out[name]), flush=True)
    print(f"Machine: {end_to_end.machine_load()} at the end")
    return out


if __name__ == "__main__":
    main()
