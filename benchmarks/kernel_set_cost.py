"""CPU seconds to compile one kernel set [T379] from an empty cache, slot by slot.

    python -m benchmarks.kernel_set_cost                          # alshaer2005, dry, ott
    python -m benchmarks.kernel_set_cost --joints alshaer2005 --before OLD/src --rounds 3

For each slider-crank joint, a fresh process with a new, empty cache (``NUMBA_CACHE_DIR``,
``XDG_CACHE_HOME``) builds the model, then compiles the eight kernels of its kinds
(``forces.kernel_set``, the exact Jacobian included) one by one and reports the CPU time
(``time.process_time``) of each. With ``--before`` the other tree runs first in every round (the
trees alternate, so a load change on a shared machine hits both); the table gives the median over
rounds per slot. The driver chains are not compiled: this is the cost a model with a new
combination of element kinds adds to a first run.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src"

CHILD = r"""
import json, sys, time
from jointdyn.forces.kernel_set import SLOTS, _kernels
from jointdyn.models.slider_crank import slider_crank

kinds = slider_crank(sys.argv[1]).compile().kinds()
out = {}
for name, disp, sig in zip(SLOTS, _kernels(kinds), SLOTS.values(), strict=True):
    t0 = time.process_time()
    disp.compile(sig)
    out[name] = time.process_time() - t0
print(json.dumps(out))
"""


def one(src: Path, joint: str) -> dict:
    """Seconds of CPU per slot for ``joint`` with the sources ``src``, in a fresh empty cache."""
    with tempfile.TemporaryDirectory() as cache:
        env = {**os.environ, "PYTHONPATH": str(src), "NUMBA_CACHE_DIR": cache, "XDG_CACHE_HOME": cache}
        r = subprocess.run([sys.executable, "-c", CHILD, joint], env=env, capture_output=True, text=True)
    if r.returncode:
        raise SystemExit(f"{src} {joint}: {r.stderr.strip().splitlines()[-1]}")
    return json.loads(r.stdout.strip().splitlines()[-1])


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--joints", default="alshaer2005,dry,ott")
    ap.add_argument("--before", help="another src/ tree, measured first in every round")
    ap.add_argument("--rounds", type=int, default=1)
    args = ap.parse_args(argv)
    trees = {"before": Path(args.before), "this": SRC} if args.before else {"this": SRC}
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores at the start")
    for joint in args.joints.split(","):
        runs: dict[str, list[dict]] = {t: [] for t in trees}
        for _ in range(args.rounds):
            for tree, src in trees.items():
                runs[tree].append(one(src, joint))
        slots = list(dict.fromkeys(s for rs in runs.values() for s in rs[0]))  # a slot of one tree: "-"
        print(f"\n{joint}: CPU [s] to compile each kernel (median of {args.rounds})")
        print(f"| slot | {' | '.join(trees)} |")
        print("|---|" + "---|" * len(trees))
        for s in [*slots, "total"]:
            cells = []
            for tree in trees:
                if s != "total" and s not in runs[tree][0]:
                    cells.append("-")
                    continue
                vals = [sum(r.values()) if s == "total" else r[s] for r in runs[tree]]
                cells.append(f"{statistics.median(vals):.2f}")
            print(f"| {s} | {' | '.join(cells)} |")
    print(f"\nload average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores at the end")


if __name__ == "__main__":
    main()
