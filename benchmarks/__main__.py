"""Benchmark table: slider-crank, 4 revolutions, jointdyn compiled vs scipy reference path.

Usage: ``python -m benchmarks [--quick] [--cases perfect,dry,...] [--no-cold]``

Per case and solver: warm wall time (median of N runs of the integrator call, compiled kernels
already loaded), cold time (a fresh process with an empty numba cache: import + JIT + run), RHS
evaluations, accepted/rejected steps, accuracy against a tight-tolerance reference of the same
model (perfect: max |ΔM|/peak of the crank moment; others: RMS moment and max ξ differences).
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

from jointdyn import post
from jointdyn.models.slider_crank import SPEED, slider_crank
from jointdyn.simulate import SimConfig, simulate

REVS = 4
T_END = REVS * 2 * math.pi / SPEED

CASES = {
    # case: (model kwargs, [(solver, rtol)], reference (solver, rtol))
    "perfect": ({"joint": "perfect"}, [("dopri5", 1e-6), ("dopri5", 1e-8), ("rodas4", 1e-8),
                                        ("scipy-dop853", 1e-8), ("scipy-radau", 1e-8)], ("dopri5", 1e-12)),
}


def metrics(res, ref):
    M, Mr = post.driving_moment(res), post.driving_moment(ref)
    out = {"peak_M": float(M.max()), "rms_M": float(np.sqrt(np.mean(M**2))),
           "err_M/peak": float(np.abs(M - Mr).max() / np.abs(Mr).max()),
           "d_rms_M": float(abs(np.sqrt(np.mean(M**2)) - np.sqrt(np.mean(Mr**2))))}
    if res.eout.shape[1]:
        xi = res.eout[:, 0, 2].max()
        out["max_xi"] = float(xi)
        out["d_max_xi"] = float(abs(xi - ref.eout[:, 0, 2].max()))
    return out


def cold_time(case: str, solver: str, rtol: float) -> float:
    """Wall time of a fresh interpreter with an empty numba cache: import + JIT + run [s]."""
    code = (f"from benchmarks.__main__ import run_once; run_once({case!r}, {solver!r}, {rtol!r})")
    with tempfile.TemporaryDirectory() as d:
        env = dict(os.environ, NUMBA_CACHE_DIR=d)
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-c", code], check=True, env=env,
                       cwd=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
        return time.perf_counter() - t0


def run_once(case, solver, rtol, system=None):
    kw = CASES[case][0]
    system = system or slider_crank(**kw).compile()
    return simulate(system, SimConfig(t_end=T_END, n_out=REVS * 360 + 1, solver=solver, rtol=rtol,
                                      atol=rtol * 1e-2))


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m benchmarks")
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--no-cold", action="store_true")
    ap.add_argument("--quick", action="store_true", help="1 repeat, no cold start (smoke test)")
    a = ap.parse_args(argv)
    repeat = 1 if a.quick else a.repeat
    rows = []
    for case in a.cases.split(","):
        kw, runs, (rsolver, rrtol) = CASES[case]
        system = slider_crank(**kw).compile()
        ref = run_once(case, rsolver, rrtol, system)
        for solver, rtol in runs[:1] if a.quick else runs:
            run_once(case, solver, rtol, system)  # JIT warm-up
            times, res = [], None
            for _ in range(repeat):
                res = run_once(case, solver, rtol, system)
                times.append(res.wall_time)
            row = {"case": case, "solver": solver, "rtol": rtol, "warm_s": statistics.median(times),
                   "cold_s": float("nan") if (a.no_cold or a.quick) else cold_time(case, solver, rtol),
                   **res.stats, **metrics(res, ref)}
            rows.append(row)
            print(f"  done {case} {solver} rtol={rtol:g}: {row['warm_s']:.4f} s", file=sys.stderr)
    cols = ["case", "solver", "rtol", "warm_s", "cold_s", "rhs_evaluations", "accepted_steps",
            "rejected_steps", "peak_M", "err_M/peak", "d_rms_M", "max_xi", "d_max_xi"]
    print("| " + " | ".join(cols) + " |")
    print("|" + "---|" * len(cols))
    for r in rows:
        cells = []
        for c in cols:
            v = r.get(c, "")
            cells.append(f"{v:.4g}" if isinstance(v, float) else str(v))
        print("| " + " | ".join(cells) + " |")
    return rows


if __name__ == "__main__":
    main()
