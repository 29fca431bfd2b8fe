"""First run (empty JIT cache) against a warm run of the CLI: where the time and memory go.

    python -m benchmarks.coldstart                      # perfect and alshaer2005, --revs 1
    python -m benchmarks.coldstart --joints perfect --top 25
    python -m benchmarks.coldstart --before /work/main/src   # before/after, back to back
    python -m benchmarks.coldstart --before /work/main/src --joints perfect,alshaer2005,dry --repeat 10

For every joint and every source tree (``--before`` first, then this tree) the command runs
``jointdyn run slider-crank --joint J --revs R --out D`` twice in fresh processes sharing one new
cache directory (``NUMBA_CACHE_DIR``, ``XDG_CACHE_HOME``): *cold* (empty cache: everything is
compiled) and *warm* (cache filled by the cold run). Per process it reports the wall and CPU
time (user + sys: the machine is shared, CPU time is the less disturbed of the two), the import
time of ``jointdyn.cli``, the time spent loading compiled functions from the cache, the number of
compilations and the peak resident set size (``VmHWM``) with the RSS after the imports. For the
cold run of this tree it lists the compile time per compiled function (*self*: its own typing,
lowering and LLVM optimisation of everything linked into it, without the nested compiles of its
callees; *top*: wall time of a compile started from Python, callees included) from numba's event
API (``numba:compile``), and the compile time per module. Finally the import time per top-level
package of ``python -X importtime -c "import jointdyn.cli"``. With ``--repeat N``, the warm
``simulate()`` of the same model and settings is timed N times per tree in the cache the cold run
filled (CPU time; the trees alternated twice), to show that specialising the compiled code on the
model's element kinds [T175] costs no warm speed.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src"


def _rss_kb(field: str) -> int:
    with open("/proc/self/status", encoding="ascii") as f:
        for line in f:
            if line.startswith(field + ":"):
                return int(line.split()[1])
    return -1


def _child(argv: list[str], report: str) -> None:
    """Run the CLI in this process with compile events and cache loads recorded."""
    from numba.core import caching
    from numba.core import event as ev

    compiles: list[tuple[str, float, float, int, str]] = []
    loads = [0, 0.0]

    class Listener(ev.Listener):
        def __init__(self):
            self.stack: list[list[float]] = []

        def on_start(self, event):
            self.stack.append([time.perf_counter(), 0.0])

        def on_end(self, event):
            t0, child = self.stack.pop()
            dt = time.perf_counter() - t0
            if self.stack:
                self.stack[-1][1] += dt
            f = event.data["dispatcher"].py_func
            sig = ", ".join(str(a) for a in event.data["args"])
            compiles.append((f"{f.__module__}.{f.__qualname__}", dt, dt - child, len(self.stack), sig))

    ev.register("numba:compile", Listener())
    load = caching.Cache.load_overload

    def timed_load(self, sig, target_context):
        t0 = time.perf_counter()
        try:
            return load(self, sig, target_context)
        finally:
            loads[0] += 1
            loads[1] += time.perf_counter() - t0

    caching.Cache.load_overload = timed_load
    c0 = os.times()
    t0 = time.perf_counter()
    from jointdyn.cli import app

    t_import = time.perf_counter() - t0
    rss_import = _rss_kb("VmRSS")
    try:
        code = app(argv, standalone_mode=False) or 0
    except SystemExit as e:
        code = int(e.code or 0)
    wall = time.perf_counter() - t0
    c1 = os.times()
    out = {
        "wall": wall,
        "cpu": (c1.user - c0.user) + (c1.system - c0.system),
        "import": t_import,
        "rss_import_mb": rss_import / 1024,
        "peak_rss_mb": _rss_kb("VmHWM") / 1024,
        "cache_loads": loads[0],
        "cache_load_s": loads[1],
        "compiles": compiles,
        "exit": code,
    }
    Path(report).write_text(json.dumps(out), encoding="utf-8")


def _run(src: Path, cache: str, argv: list[str]) -> dict:
    env = dict(os.environ, PYTHONPATH=str(src), NUMBA_CACHE_DIR=os.path.join(cache, "numba"))
    env["XDG_CACHE_HOME"] = cache
    with tempfile.NamedTemporaryFile(suffix=".json", delete=False) as f:
        report = f.name
    t0 = time.perf_counter()
    cmd = [sys.executable, "-m", "benchmarks.coldstart", "--child", report, "--", *argv]
    p = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True)
    outer = time.perf_counter() - t0
    r = json.loads(Path(report).read_text(encoding="utf-8")) if p.returncode == 0 else {"exit": -1}
    os.unlink(report)
    if r["exit"] != 0:
        raise SystemExit(f"{' '.join(argv)} failed ({src}):\n{p.stdout[-1000:]}{p.stderr[-2000:]}")
    r["process"] = outer  # interpreter start-up included
    return r


WARM_CHILD = """
import json, os, sys, time
from jointdyn.models import slider_crank as sc
from jointdyn.models.slider_crank import slider_crank_config
from jointdyn.simulation.simulate import simulate
joint, revs, repeat = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
system = sc.slider_crank(joint).compile()
cfg = slider_crank_config(joint, revs)
simulate(system, cfg)  # loads the kernels from the cache filled by the cold run
cpu = []
for _ in range(repeat):
    t0 = time.process_time()
    simulate(system, cfg)
    cpu.append(time.process_time() - t0)
print(json.dumps(cpu))
"""


def _warm_simulate(src: Path, cache: str, joint: str, revs: str, repeat: int) -> list[float]:
    """CPU times [s] of ``repeat`` warm ``simulate`` calls (the CLI's model and settings)."""
    env = dict(os.environ, PYTHONPATH=str(src), NUMBA_CACHE_DIR=os.path.join(cache, "numba"))
    env["XDG_CACHE_HOME"] = cache
    cmd = [sys.executable, "-c", WARM_CHILD, joint, revs, str(repeat)]
    p = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True, check=True)
    return json.loads(p.stdout.strip().splitlines()[-1])


def _compile_table(compiles, top: int) -> None:
    per = defaultdict(lambda: [0, 0.0, 0.0])
    mods = defaultdict(float)
    for name, inc, exc, depth, _sig in compiles:
        x = per[name]
        x[0] += 1
        x[1] += exc
        if depth == 0:
            x[2] += inc
        mod = name.split(".<locals>")[0].rsplit(".", 1)[0]
        mods[mod if mod.startswith("jointdyn") else mod.split(".")[0] + " (internals)"] += exc
    total = sum(v[1] for v in per.values())
    print(f"\ncompile time per function (cold run; {len(compiles)} compilations, {total:.1f} s in all)")
    print(f"{'self [s]':>9} {'top [s]':>8} {'n':>3}  function")
    for name, (n, exc, inc) in sorted(per.items(), key=lambda kv: -kv[1][1])[:top]:
        print(f"{exc:9.2f} {inc:8.2f} {n:3d}  {name}")
    print("\ncompile time per module (self, summed)")
    for mod, s in sorted(mods.items(), key=lambda kv: -kv[1])[:top]:
        print(f"{s:9.2f}  {mod}")


def _importtime(src: Path, top: int) -> None:
    env = dict(os.environ, PYTHONPATH=str(src))
    cmd = [sys.executable, "-X", "importtime", "-c", "import jointdyn.cli"]
    p = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True)
    pkg = defaultdict(float)
    total = 0.0
    for line in p.stderr.splitlines():
        if not line.startswith("import time:") or "self [us]" in line:
            continue
        self_us, cum_us, name = line[len("import time:") :].split("|")
        name = name.strip()
        pkg[name.split(".")[0]] += int(self_us) / 1e6
        if not name.startswith(" ") and line.split("|")[2].strip() == "jointdyn.cli":
            total = int(cum_us) / 1e6
    print(f"\nimport jointdyn.cli: {total:.2f} s (python -X importtime, self time per top-level package)")
    for name, s in sorted(pkg.items(), key=lambda kv: -kv[1])[:top]:
        print(f"{s:7.3f} s  {name}")


def main(argv=None) -> None:
    if argv is None and len(sys.argv) > 2 and sys.argv[1] == "--child":
        _child(sys.argv[4:], sys.argv[2])
        return
    ap = argparse.ArgumentParser(prog="python -m benchmarks.coldstart")
    ap.add_argument("--joints", default="perfect,alshaer2005")
    ap.add_argument("--revs", default="1")
    ap.add_argument("--before", default=None, help="another src/ tree to measure first")
    ap.add_argument("--top", type=int, default=20)
    ap.add_argument(
        "--repeat",
        type=int,
        default=0,
        help="also time N warm simulate() calls per tree (CPU; trees alternated twice), cold run's cache",
    )
    a = ap.parse_args(argv)
    trees = ([("before", Path(a.before))] if a.before else []) + [("this", SRC)]
    rows = []
    compiles = {}
    sim: dict = defaultdict(list)
    for joint in a.joints.split(","):
        with tempfile.TemporaryDirectory() as c0, tempfile.TemporaryDirectory() as c1:
            caches = dict(zip([label for label, _ in trees], (c0, c1), strict=False))
            for label, src in trees:
                with tempfile.TemporaryDirectory() as out:
                    cli = ["run", "slider-crank", "--joint", joint, "--revs", a.revs, "--out", out]
                    cold = _run(src, caches[label], cli)
                    warm = _run(src, caches[label], [*cli[:-1], out, "--overwrite"])
                rows.append((joint, label, cold, warm))
                if label == "this":
                    compiles[joint] = cold["compiles"]
            for _ in range(2 if a.repeat > 0 else 0):  # interleaved: load changes on a shared machine
                for label, src in trees:
                    sim[joint, label] += _warm_simulate(src, caches[label], joint, a.revs, a.repeat)
    print(f"jointdyn run slider-crank --joint J --revs {a.revs} --out D (fresh processes; wall/CPU [s])")
    head = (
        f"{'joint':<12} {'tree':<6} {'cold wall':>9} {'cold cpu':>8} {'warm wall':>9} {'warm cpu':>8} "
        f"{'cold/warm':>9} {'import':>6} {'load':>5} {'n comp':>6} {'RSS cold':>8} {'RSS warm':>8} "
        f"{'RSS import':>10}"
    )
    print(head)
    for joint, label, c, w in rows:
        print(
            f"{joint:<12} {label:<6} {c['process']:9.1f} {c['cpu']:8.1f} {w['process']:9.2f} {w['cpu']:8.2f} "
            f"{c['cpu'] / w['cpu']:8.1f}x {w['import']:6.2f} {w['cache_load_s']:5.2f} "
            f"{len(c['compiles']):6d} {c['peak_rss_mb']:6.0f}MB {w['peak_rss_mb']:6.0f}MB "
            f"{w['rss_import_mb']:8.0f}MB"
        )
    print("(cold/warm: ratio of CPU times; import/load: warm run's import of jointdyn.cli and cache loads)")
    if sim:
        print(
            f"\nwarm simulate() of the same run, CPU [ms] (min / median of {2 * a.repeat}, trees alternated)"
        )
        for (joint, label), v in sim.items():
            print(f"{joint:<12} {label:<6} {1e3 * min(v):8.2f} {1e3 * statistics.median(v):8.2f}")
    for joint, c in compiles.items():
        print(f"\n== {joint} ==", end="")
        _compile_table(c, a.top)
    _importtime(SRC, a.top)


if __name__ == "__main__":
    main()
