"""Sweep throughput: N lubricated slider-crank runs (4 revolutions, π-film) on all cores.

Usage: ``python -m benchmarks.sweep_throughput [--n 1000] [--workers 2]``

Prints cases per minute, total wall time, and the overhead per case compared with a single warm
run of the same case in this process (the difference is process start-up, JIT cache loading,
pickling and per-case file writes).
"""

from __future__ import annotations

import argparse
import os
import statistics
import tempfile
import time

import numpy as np

from jointdyn.studies.runs import run_shipped
from jointdyn.studies.sweep import SweepSpec, run_sweep

BASE = {"model": "slider-crank", "joint": "alshaer2005", "revs": 4, "rtol": 1e-6, "atol": 1e-10}


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m benchmarks.sweep_throughput")
    ap.add_argument("--n", type=int, default=1000)
    ap.add_argument("--workers", type=int, default=os.cpu_count())
    a = ap.parse_args(argv)
    # viscosity × clearance Latin hypercube around the benchmark (all cases run without contact)
    spec = SweepSpec(
        base=BASE,
        sample={"n": a.n, "seed": 1, "ranges": {"viscosity": [0.2, 1.0], "clearance": [5e-5, 5e-4]}},
    )
    singles = []
    for _ in range(5):
        run_shipped("slider-crank", "alshaer2005", 4, rtol=1e-6, atol=1e-10)  # warm
        t0 = time.perf_counter()
        run_shipped("slider-crank", "alshaer2005", 4, rtol=1e-6, atol=1e-10)
        singles.append(time.perf_counter() - t0)
    single = statistics.median(singles)
    with tempfile.TemporaryDirectory() as d:
        t0 = time.perf_counter()
        ds = run_sweep(spec, d, workers=a.workers)
        wall = time.perf_counter() - t0
    failed = int((ds["error"] != "").sum())
    per_case = wall * a.workers / a.n
    print(
        "| cases | workers | wall [s] | cases/min | single warm run [s] | per-case cost in sweep [s] "
        "| overhead/case [s] | failed |"
    )
    print("|---|---|---|---|---|---|---|---|")
    print(
        f"| {a.n} | {a.workers} | {wall:.1f} | {a.n / wall * 60:.0f} | {single:.3f} | {per_case:.3f} | "
        f"{per_case - single:.3f} | {failed} |"
    )
    print(f"median simulate() wall time inside the sweep: {np.nanmedian(ds['wall_time_s'].values):.3f} s")


if __name__ == "__main__":
    main()
