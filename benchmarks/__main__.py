"""Benchmark table: slider-crank, 4 revolutions, jointdyn compiled vs scipy reference path.

Usage: ``python -m benchmarks [--quick] [--cases perfect,dry,...] [--no-cold] [--peers]``

Per case and solver: warm wall time (median of N runs of ``simulate``, kernels compiled and
loaded), cold time (a fresh interpreter with an empty numba cache: import + JIT + run), RHS
evaluations, accepted/rejected steps, the *floor* (RHS evaluations × the bare compiled RHS cost)
and warm/floor, peak RSS of the run's process, and accuracy against a tight-tolerance reference of
the same model (perfect: max |ΔM|/peak of the crank moment; others: RMS moment and max ξ / max
penetration differences). ``--peers`` adds Exudyn (``pip install -e .[peers]``).
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
from numba import njit

from jointdyn import post
from jointdyn.models.slider_crank import SPEED, slider_crank
from jointdyn.multibody.dynamics import rhs
from jointdyn.simulation.simulate import SimConfig, simulate

REVS = 4
T_END = REVS * 2 * math.pi / SPEED
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

CASES = {
    # case: (model kwargs, [(solver, rtol)], reference (solver, rtol))
    "perfect": (
        {"joint": "perfect"},
        [("dopri5", 1e-6), ("dopri5", 1e-8), ("rodas4", 1e-8), ("scipy-dop853", 1e-8)],
        ("dopri5", 1e-12),
    ),
    "dry": (
        {"joint": "dry"},
        [("dopri5", 1e-6), ("dopri5", 1e-7), ("rodas4", 1e-7), ("scipy-dop853", 1e-7)],
        ("dopri5", 1e-10),
    ),
    "ott": ({"joint": "ott"}, [("rodas4", 1e-6), ("rodas4", 1e-7), ("scipy-radau", 1e-7)], ("rodas4", 1e-10)),
    "alshaer2005": (
        {"joint": "alshaer2005"},
        [
            ("rodas4", 1e-6),
            ("rodas4", 1e-7),
            ("rodas4", 1e-8),
            ("ros34pw2", 1e-7),
            ("ros34pw2", 1e-8),
            ("radau5", 1e-6),
            ("radau5", 1e-7),
            ("radau5", 1e-8),
            ("scipy-radau", 1e-7),
        ],
        ("rodas4", 1e-10),
    ),
    "alshaer2005_c0.05mm": (
        {"joint": "alshaer2005", "clearance": 5e-5},
        [
            ("rodas4", 1e-6),
            ("rodas4", 1e-7),
            ("ros34pw2", 1e-7),
            ("radau5", 1e-6),
            ("radau5", 1e-7),
            ("radau5", 1e-8),
            ("scipy-radau", 1e-7),
        ],
        ("rodas4", 1e-10),
    ),
}


@njit(cache=True)
def _rhs_loop(P, y, mem, n):
    yd = np.empty_like(y)
    s = 0.0
    for _ in range(n):
        rhs(0.0, y, mem, P, yd)
        s += yd[-1]
    return s


def rhs_cost(system, y, mem, n=200_000) -> float:
    """Bare compiled RHS cost at state y [s per evaluation]."""
    P = system.packed(0.0)
    _rhs_loop(P, y.copy(), mem.copy(), 10)
    t0 = time.perf_counter()
    _rhs_loop(P, y.copy(), mem.copy(), n)
    return (time.perf_counter() - t0) / n


def metrics(res, ref):
    M, Mr = post.driving_moment(res), post.driving_moment(ref)
    out = {
        "peak_M": float(M.max()),
        "err_M/peak": float(np.abs(M - Mr).max() / np.abs(Mr).max()),
        "d_rms_M": float(abs(np.sqrt(np.mean(M**2)) - np.sqrt(np.mean(Mr**2)))),
    }
    if res.eout.shape[1]:
        out["max_xi"] = float(res.eout[:, 0, 2].max())
        out["d_max_xi"] = float(abs(out["max_xi"] - ref.eout[:, 0, 2].max()))
    return out


def run_once(case, solver, rtol, system=None):
    kw = dict(CASES[case][0])
    system = system or slider_crank(**kw).compile()
    return simulate(
        system, SimConfig(t_end=T_END, n_out=REVS * 360 + 1, solver=solver, rtol=rtol, atol=rtol * 1e-4)
    )


def _subprocess_time(code: str, cold: bool):
    """(wall time [s], peak RSS [MB]) of a fresh interpreter running ``code``."""
    with tempfile.TemporaryDirectory() as d:
        env = dict(os.environ)
        if cold:
            env["NUMBA_CACHE_DIR"] = d
        t0 = time.perf_counter()
        out = subprocess.run(
            [
                sys.executable,
                "-c",
                code + "\nimport resource,sys;print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)",
            ],
            check=True,
            env=env,
            cwd=ROOT,
            capture_output=True,
            text=True,
        )
        return time.perf_counter() - t0, int(out.stdout.split()[-1]) / 1024


def cold_and_rss(case, solver, rtol):
    code = f"from benchmarks.__main__ import run_once; run_once({case!r}, {solver!r}, {rtol!r})"
    cold, _ = _subprocess_time(code, cold=True)
    _, rss = _subprocess_time(code, cold=False)
    return cold, rss


def cli_times():
    """Cold (empty JIT cache) and warm end-to-end `jointdyn run slider-crank` (perfect) [s]."""
    exe = [sys.executable, "-m", "jointdyn", "run", "slider-crank", "--joint", "perfect", "--revs", "4"]
    res = {}
    with tempfile.TemporaryDirectory() as d:
        for label, env in (
            ("cold", dict(os.environ, NUMBA_CACHE_DIR=d)),
            ("warm", dict(os.environ, NUMBA_CACHE_DIR=d)),
        ):
            t0 = time.perf_counter()
            subprocess.run(
                exe + ["--out", os.path.join(d, label)], check=True, env=env, cwd=ROOT, capture_output=True
            )
            res[label] = time.perf_counter() - t0
    return res


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m benchmarks")
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--no-cold", action="store_true", help="skip cold-start/RSS subprocesses")
    ap.add_argument("--quick", action="store_true", help="first solver per case, 1 repeat, no cold start")
    ap.add_argument("--peers", action="store_true", help="also time Exudyn (needs the [peers] extra)")
    a = ap.parse_args(argv)
    repeat = 1 if a.quick else a.repeat
    rows = []
    for case in a.cases.split(","):
        kw, runs, (rsolver, rrtol) = CASES[case]
        system = slider_crank(**kw).compile()
        ref = run_once(case, rsolver, rrtol, system)
        cost = rhs_cost(system, ref.y[-1], ref.mem[-1], 20_000 if a.quick else 200_000)
        for solver, rtol in runs[:1] if a.quick else runs:
            run_once(case, solver, rtol, system)  # JIT warm-up
            times, res = [], None
            for _ in range(repeat):
                res = run_once(case, solver, rtol, system)
                times.append(res.wall_time)
            warm = statistics.median(times)
            floor = res.stats["rhs_evaluations"] * cost
            cold, rss = (math.nan, math.nan) if (a.no_cold or a.quick) else cold_and_rss(case, solver, rtol)
            rows.append(
                {
                    "case": case,
                    "solver": solver,
                    "rtol": rtol,
                    "warm_s": warm,
                    "cold_s": cold,
                    "rss_MB": rss,
                    **res.stats,
                    "floor_s": floor,
                    "warm/floor": warm / floor,
                    **metrics(res, ref),
                }
            )
            print(f"  done {case} {solver} rtol={rtol:g}: {warm:.4f} s", file=sys.stderr)
    if a.peers:
        rows += peer_rows(quick=a.quick)
    cols = [
        "case",
        "solver",
        "rtol",
        "warm_s",
        "cold_s",
        "rss_MB",
        "rhs_evaluations",
        "accepted_steps",
        "rejected_steps",
        "floor_s",
        "warm/floor",
        "peak_M",
        "err_M/peak",
        "d_rms_M",
        "max_xi",
        "d_max_xi",
    ]
    print("| " + " | ".join(cols) + " |")
    print("|" + "---|" * len(cols))
    for r in rows:
        print(
            "| "
            + " | ".join(f"{r[c]:.4g}" if isinstance(r.get(c), float) else str(r.get(c, "")) for c in cols)
            + " |"
        )
    if not a.quick and not a.no_cold:
        t = cli_times()
        print(
            f"\n`jointdyn run slider-crank --joint perfect --revs 4`: cold (empty JIT cache) "
            f"{t['cold']:.1f} s, warm {t['warm']:.2f} s end-to-end"
        )
    return rows


def peer_rows(quick=False):
    """Exudyn on the same mechanism (benchmarks/peers_exudyn.py); rows in the same table."""
    try:
        from benchmarks import peers_exudyn as pe
    except ImportError as err:  # pragma: no cover
        print(f"peers skipped: {err}", file=sys.stderr)
        return []
    rows = []
    n_out = REVS * 360 + 1
    for h in (1e-5,) if quick else (1e-5, 1e-6):
        for name, fn in (("perfect", pe.exudyn_perfect), ("dry", pe.exudyn_dry)):
            try:
                r = fn(h, T_END, n_out)
            except Exception as err:  # report, do not hide
                print(f"exudyn {name} h={h}: {err}", file=sys.stderr)
                continue
            M = np.asarray(r["crank_moment"])
            rows.append(
                {
                    "case": name,
                    "solver": f"exudyn h={h:g}",
                    "rtol": math.nan,
                    "warm_s": r["wall_s"],
                    "peak_M": float(M.max()),
                    "accepted_steps": r.get("steps", ""),
                }
            )
    return rows


if __name__ == "__main__":
    main()
