"""Work–precision of the stiff solvers on the lubricated slider-crank, one run, one process.

Usage: ``python -m benchmarks.work_precision [--quick] [--repeat N] [--clearances 0.5,0.05]
[--error-scale state|clearance]``

Per clearance (π-film pin, 4 crank revolutions, 2881 samples as in the README) and per solver
— ``radau5``, ``rodas4``, ``ros34pw2`` with the exact system Jacobian, ``scipy-radau`` (compiled
RHS, Python per step) — over a ladder of rtol (atol = rtol·1e-3, as ``benchmarks.end_to_end``):
wall time of ``simulate()`` end to end (median of N warm runs), RHS evaluations (exact Jacobians
count one each), accepted / rejected steps, Jacobians and the max crank-moment error
|ΔM|/peak against a converged run (``rodas4``, exact Jacobian, rtol 1e-11, atol 1e-14; its
agreement with ``radau5`` at rtol 1e-12 is printed as the reference's own error bar).

Then, per clearance, the wall time each solver needs for a given accuracy (log–log interpolation
between the two ladder points that bracket it) and the ratios between solvers at equal accuracy.
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import time
import warnings

import numpy as np
from numba import njit

from jointdyn import post
from jointdyn.core.borrowed import borrowed
from jointdyn.errors import SimulationError
from jointdyn.integrators.driver import new_work
from jointdyn.integrators.radau5 import ALPH, BETA, RADAU5, U1, _factor, _solve
from jointdyn.models.slider_crank import SPEED, slider_crank
from jointdyn.multibody.dynamics import rhs
from jointdyn.multibody.jacobian import system_jacobian
from jointdyn.simulation.simulate import SimConfig, simulate

REVS = 4
N_OUT = REVS * 720 + 1
T_END = REVS * 2 * math.pi / SPEED
LADDER = {
    "radau5": (1e-5, 1e-6, 1e-7, 1e-8, 1e-9),
    "rodas4": (1e-6, 1e-7, 1e-8, 1e-9),
    "ros34pw2": (1e-6, 1e-7, 1e-8, 1e-9),
    "scipy-radau": (1e-5, 1e-6, 1e-7, 1e-8),
}
# --error-scale clearance [T186]: rtol is a fraction of the clearance (≈ 30× the state-relative
# rtol for the same error at c = 0.5 mm, ≈ 500× at 0.05 mm), atol 1e-14 (below every rtol·Y_i of
# the ladders); scipy's Radau (its own error norm) keeps the state scales
LADDER_CLEARANCE = {
    "radau5": (1e-4, 3e-5, 1e-5, 3e-6, 1e-6),
    "rodas4": (1e-4, 1e-5, 1e-6, 1e-7),
    "ros34pw2": (1e-4, 3e-5, 1e-5, 1e-6, 1e-7),
    "scipy-radau": LADDER["scipy-radau"],
}
QUICK_CLEARANCE = {"radau5": (1e-5, 3e-6), "rodas4": (1e-6,), "ros34pw2": (1e-6,), "scipy-radau": (1e-7,)}
QUICK = {"radau5": (1e-6, 1e-7), "rodas4": (1e-7,), "ros34pw2": (1e-7,), "scipy-radau": (1e-7,)}
TARGETS = (1e-3, 1e-4, 1e-5)  # accuracies |ΔM|/peak at which solvers are compared


def _system(c_mm: float):
    kw = {"joint": "alshaer2005"} | ({} if c_mm == 0.5 else {"clearance": c_mm * 1e-3})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return slider_crank(**kw).compile()


def _config(solver: str, rtol: float, atol_ratio: float = 1e-3, scale: str = "state") -> SimConfig:
    atol = rtol * atol_ratio if scale == "state" else 1e-14
    return SimConfig(
        t_end=T_END,
        n_out=N_OUT,
        solver=solver,
        rtol=rtol,
        atol=atol,
        jacobian="exact",
        error_scale=scale,
    )


def _error(M, Mr) -> float:
    return float(np.abs(M - Mr).max() / np.abs(Mr).max())


@njit(cache=True)
def _loop(P, y, mem, n, jac):
    P, y, mem = borrowed((P, y, mem))  # as the driver runs them [T208]
    nn = y.shape[0]
    f = np.empty(nn)
    Jm = np.empty((nn, nn))
    ft, w1, w2 = np.empty(nn), np.empty(nn), np.empty(nn)
    rhs(0.0, y, mem, P, f)
    for _ in range(n):
        if jac:
            system_jacobian(0.0, y, f, mem, P, Jm, ft, w1, w2)
        else:
            rhs(0.0, y, mem, P, f)
    return f[0] + Jm[0, 0]


@njit(cache=True)
def _lu_loop(w, h, n, solve):
    """n LU pairs of radau5's iteration matrices at step h, or n Newton solves (real + complex)."""
    s = 0.0
    for _ in range(n):
        if solve:
            _solve(w.Jm, w.W1, w.piv, U1 / h, w.work)
            _solve(w.Jm, w.W2, w.piv2, complex(ALPH / h, BETA / h), w.cz)
            s += w.work[0]
        else:
            _factor(h, w)
            s += w.W1[0, 0]
    return s


def _costs(P, y, mem, n):
    """(RHS evaluation, exact system Jacobian, radau5 LU pair, radau5 Newton solves) wall time [s]
    at (y, mem), mean of n calls (the LU at h = 1e-5 s)."""
    out = []
    for jac in (False, True):
        _loop(P, y, mem, 10, jac)
        t0 = time.perf_counter()
        _loop(P, y, mem, n, jac)
        out.append((time.perf_counter() - t0) / n)
    w = new_work(RADAU5, y, mem, 0.0, np.array([0.0, 1.0]), 1e-5, True)
    system_jacobian(0.0, y, w.f0, mem, P, w.Jm, w.ft, w.work, w.fw)
    w.work[:] = 1.0
    w.cz[:] = 1.0
    for solve in (False, True):
        _lu_loop(w, 1e-5, 10, solve)
        t0 = time.perf_counter()
        _lu_loop(w, 1e-5, n, solve)
        out.append((time.perf_counter() - t0) / n)
    return tuple(out)


def reference(system):
    """(crank moment of the converged run, its difference to an independent one |ΔM|/peak)."""
    ref = post.driving_moment(simulate(system, _config("rodas4", 1e-11, 1e-3)))
    check = post.driving_moment(simulate(system, _config("radau5", 1e-12, 1e-3)))
    return ref, _error(check, ref)


def _run(system, cfg):
    """(results, '' or 'unresolved'): a run the accuracy guard [T111] rejects still has its
    full results (status FORCE_UNRESOLVED); it is timed and reported, marked."""
    try:
        return simulate(system, cfg), ""
    except SimulationError as err:
        if err.results is None or len(err.results.t) != N_OUT:
            raise
        return err.results, "unresolved"


def row(system, Mr, solver, rtol, repeat, scale="state"):
    cfg = _config(solver, rtol, scale=scale)
    _run(system, cfg)  # JIT warm-up
    times, res, note = [], None, ""
    for _ in range(repeat):
        t0 = time.perf_counter()
        res, note = _run(system, cfg)
        times.append(time.perf_counter() - t0)
    return {
        "solver": solver,
        "rtol": rtol,
        "wall_s": statistics.median(times),
        "rhs": res.stats["rhs_evaluations"],
        "accepted": res.stats["accepted_steps"],
        "rejected": res.stats["rejected_steps"],
        "jacobians": res.stats["jacobians"],
        "error": _error(post.driving_moment(res), Mr),
        "guard": note,
    }


def time_at(rows, target: float) -> float:
    """Wall time [s] a solver needs for |ΔM|/peak = target: log–log interpolation between the
    cheapest ladder point at or below the target and the next looser one; nan if no point reaches
    it, and the cheapest such point's time if the loosest one already does."""
    pts = sorted((r["rtol"], r["error"], r["wall_s"], r["guard"]) for r in rows)  # tight → loose
    ok = [p for p in pts if p[1] <= target and not p[3]]
    if not ok:
        return math.nan
    best = ok[-1]  # loosest rtol meeting the target
    looser = [p for p in pts if p[0] > best[0] and not p[3]]
    if not looser:
        return best[2]
    nxt = looser[0]
    if nxt[1] <= best[1] or nxt[2] >= best[2]:
        return best[2]
    f = math.log(target / best[1]) / math.log(nxt[1] / best[1])
    return math.exp(math.log(best[2]) + f * math.log(nxt[2] / best[2]))


def _table(rows, cols):
    out = ["| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    for r in rows:
        out.append(
            "| " + " | ".join(f"{r[c]:.3g}" if isinstance(r[c], float) else str(r[c]) for c in cols) + " |"
        )
    return "\n".join(out)


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m benchmarks.work_precision")
    ap.add_argument("--clearances", default="0.5,0.05", help="radial clearances [mm]")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="two radau5 points and one of each other")
    ap.add_argument("--solvers", default=",".join(LADDER))
    ap.add_argument(
        "--error-scale", default="state", choices=("state", "clearance"), help="SimConfig.error_scale [T186]"
    )
    ap.add_argument("--write", default=None, help="also write FILE's <!-- generated:work_precision --> block")
    a = ap.parse_args(argv)
    lines: list[str] = []

    def say(text: str) -> None:
        print(text)
        lines.append(text)

    ladder = QUICK if a.quick else LADDER
    if a.error_scale == "clearance":
        ladder = QUICK_CLEARANCE if a.quick else LADDER_CLEARANCE
    result = {}
    for c in (float(x) for x in a.clearances.split(",")):
        system = _system(c)
        Mr, ref_err = reference(system)
        mid = simulate(system, _config("radau5", 1e-8))  # a state inside the run (e ≠ 0)
        k = len(mid.t) // 2
        c_rhs, c_jac, c_lu, c_sol = _costs(
            system.packed(0.0, jacobian=True), mid.y[k].copy(), mid.mem[k].copy(), 20_000
        )
        rows = []
        for solver in a.solvers.split(","):
            for rtol in ladder[solver]:
                scale = "state" if solver.startswith("scipy") else a.error_scale
                rows.append(row(system, Mr, solver, rtol, 1 if a.quick else a.repeat, scale))
                print(f"  done c={c} {solver} rtol={rtol:g}", file=sys.stderr)
        say(
            f"\nc = {c:g} mm, error scales {a.error_scale} (scipy-radau: state); reference rodas4 rtol "
            f"1e-11, radau5 rtol 1e-12 differs by {ref_err:.1e}; "
            f"one RHS {c_rhs * 1e6:.2f} µs, one exact Jacobian {c_jac * 1e6:.2f} µs "
            f"(= {c_jac / c_rhs:.1f} RHS, counted as 1 in `rhs`); radau5: LU pair {c_lu * 1e6:.2f} µs, "
            f"Newton solves {c_sol * 1e6:.2f} µs per iteration"
        )
        cols = ["solver", "rtol", "wall_s", "rhs", "accepted", "rejected", "jacobians", "error", "guard"]
        say("\n" + _table(rows, cols))
        by = {s: [r for r in rows if r["solver"] == s] for s in dict.fromkeys(r["solver"] for r in rows)}
        eq = []
        for target in TARGETS:
            t = {s: time_at(rs, target) for s, rs in by.items()}
            e = {"error": target} | {f"{s}_s": v for s, v in t.items()}
            if "radau5" in t:
                for s in t:
                    if s != "radau5":
                        e[f"{s}/radau5"] = t[s] / t["radau5"]
            eq.append(e)
        say(f"\nwall time [s] at equal accuracy, c = {c:g} mm (interpolated; nan: not reached on the ladder)")
        say("\n" + _table(eq, list(eq[0])))
        result[c] = {"rows": rows, "equal_accuracy": eq, "reference_error": ref_err}
        result[c] |= {"rhs_s": c_rhs, "jac_s": c_jac, "lu_s": c_lu, "solve_s": c_sol}
    if a.write:
        from pathlib import Path

        from jointdyn.cli.docs_gen import replace_blocks

        f = Path(a.write)
        body = "\n".join(lines).strip()
        text = replace_blocks(f.read_text(encoding="utf-8"), {"work_precision": body})
        f.write_text(text, encoding="utf-8")
    return result


if __name__ == "__main__":
    main()
