"""Sum the per-test CPU profile written by ``pytest --cpu-profile PREFIX`` (tests/conftest.py).

``python tests/cpu_profile.py PREFIX [N]`` prints the total CPU [s] (tests' processes and their
waited-for children), the numba compilation inside it, the N most expensive files and tests,
how many (function, signature) pairs were compiled in more than one worker (work the disk
cache did not share), and the kernel sets (method, exact Jacobian, element kinds) that only one
test runs, with the compilation of that test: candidates for a shared set or the slow tier [T373].
"""

import collections
import glob
import json
import sys


def load(prefix: str) -> list[dict]:
    recs = []
    for path in sorted(glob.glob(f"{prefix}-*.jsonl")):
        worker = path[len(prefix) + 1 : -len(".jsonl")]
        with open(path, encoding="utf-8") as f:
            recs += [{**r, "worker": worker} for r in map(json.loads, f) if "id" in r]
    return recs


def processes(prefix: str) -> float:
    """CPU [s] of the whole test processes (start-up and collection included)."""
    total = 0.0
    for path in glob.glob(f"{prefix}-*.jsonl"):
        with open(path, encoding="utf-8") as f:
            total += max((r.get("process", 0.0) for r in map(json.loads, f)), default=0.0)
    return total


def report(recs: list[dict], n: int = 30, process: float = 0.0) -> str:
    total = sum(r["cpu"] + r["child"] for r in recs)
    compile_s = sum(r["compile"] for r in recs)
    lines = [
        f"{len(recs)} tests: {total:.0f} s CPU ({sum(r['child'] for r in recs):.0f} s of it in child "
        f"processes), {compile_s:.0f} s numba compilation in the test processes; the test processes "
        f"in all (start-up and collection included): {process:.0f} s"
    ]
    files: dict = collections.defaultdict(lambda: [0.0, 0.0, 0])
    for r in recs:
        f = files[r["id"].split("::")[0]]
        f[0] += r["cpu"] + r["child"]
        f[1] += r["compile"]
        f[2] += 1
    lines.append(f"\n{'CPU [s]':>8} {'compile':>8} {'tests':>5}  file")
    for name, (cpu, comp, k) in sorted(files.items(), key=lambda kv: -kv[1][0])[:n]:
        lines.append(f"{cpu:8.1f} {comp:8.1f} {k:5d}  {name}")
    lines.append(f"\n{'CPU [s]':>8} {'compile':>8} {'child':>6}  test")
    for r in sorted(recs, key=lambda r: -(r["cpu"] + r["child"]))[:n]:
        lines.append(f"{r['cpu'] + r['child']:8.1f} {r['compile']:8.1f} {r['child']:6.1f}  {r['id']}")
    where = collections.defaultdict(set)
    for r in recs:
        for name, sig in r["funcs"]:
            where[name, sig].add(r["worker"])
    own = [k for k, w in where.items() if len(w) > 1 and k[0].startswith("jointdyn.")]
    lines.append(
        f"\n{len(where)} (function, signature) pairs compiled; jointdyn's compiled in more than one "
        f"worker: {len(own)}"
    )
    users: dict = collections.defaultdict(list)
    for r in recs:
        for method, exact, kinds in r.get("sets", ()):
            users[method, exact, kinds].append(r)
    single = sorted(((k, v[0]) for k, v in users.items() if len(v) == 1), key=lambda kv: -kv[1]["compile"])
    lines.append(
        f"\n{len(users)} kernel sets run; {len(single)} by one test only (method, exact Jacobian, kinds):"
    )
    for (method, exact, kinds), r in single:
        lines.append(f"{r['compile']:8.1f}  {r['id']}\n{'':10}{method} {exact} {kinds}")
    return "\n".join(lines)


if __name__ == "__main__":
    prefix = sys.argv[1]
    print(report(load(prefix), int(sys.argv[2]) if len(sys.argv) > 2 else 30, processes(prefix)))
