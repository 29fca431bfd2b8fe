"""A/B of the bare compiled right-hand side between two source trees, in CPU seconds.

Usage: ``python -m benchmarks.rhs_ab OLD_SRC NEW_SRC [--rounds 5] [--n 200000]``, where each
``*_SRC`` is the ``src`` directory of a checkout (e.g. ``git worktree add /tmp/old <commit>`` then
``/tmp/old/src``). Each round runs one fresh process per tree, alternating A, B, A, B … so a load
change on a shared machine hits both; each process times ``n`` evaluations of the compiled RHS
(``dynamics.rhs``) of the slider-crank per joint at its initial state in CPU time
(``time.process_time``), after a warm-up call (so compilation is excluded). Prints the median
over rounds per case and tree and the ratio B/A.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys

CASES = ("perfect", "dry", "alshaer2005", "finite")

CHILD = r"""
import json, sys, time
import numpy as np
from numba import njit
from jointdyn import slider_crank
try:
    from jointdyn.multibody.dynamics import rhs
except ImportError:  # the flat layout before the sub-packages
    from jointdyn.dynamics import rhs

@njit(cache=False)
def loop(P, y, mem, n):
    yd = np.empty_like(y)
    s = 0.0
    for _ in range(n):
        rhs(0.0, y, mem, P, yd)
        s += yd[-1]
    return s

n = int(sys.argv[1])
out = {}
for case in sys.argv[2].split(","):
    system = slider_crank(case).compile()
    P, y, mem = system.packed(0.0), system.y0.copy(), system.mem0.copy()
    loop(P, y.copy(), mem.copy(), 10)
    t0 = time.process_time()
    loop(P, y.copy(), mem.copy(), n)
    out[case] = (time.process_time() - t0) / n
print(json.dumps(out))
"""


def one(src: str, n: int, cases) -> dict:
    env = {**os.environ, "PYTHONPATH": src}
    r = subprocess.run(
        [sys.executable, "-c", CHILD, str(n), ",".join(cases)], env=env, capture_output=True, text=True
    )
    if r.returncode:
        raise SystemExit(f"{src}: {r.stderr.strip().splitlines()[-1]}")
    return json.loads(r.stdout.strip().splitlines()[-1])


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--n", type=int, default=200_000)
    ap.add_argument("--cases", default=",".join(CASES))
    args = ap.parse_args(argv)
    cases = args.cases.split(",")
    one(args.a, 10, cases), one(args.b, 10, cases)  # compile and cache once per tree
    runs: dict[str, list[dict]] = {"a": [], "b": []}
    for _ in range(args.rounds):
        runs["a"].append(one(args.a, args.n, cases))
        runs["b"].append(one(args.b, args.n, cases))
    print(f"| case | A [µs/RHS] | B [µs/RHS] | B/A | (median of {args.rounds} alternating rounds, CPU time)")
    print("|---|---|---|---|")
    for c in cases:
        a = statistics.median(r[c] for r in runs["a"]) * 1e6
        b = statistics.median(r[c] for r in runs["b"]) * 1e6
        print(f"| {c} | {a:.3f} | {b:.3f} | {b / a:.3f} |")


if __name__ == "__main__":
    main()
