"""Cost of the post-processing ``dynamics.outputs`` per sample, in right-hand-side equivalents.

python -m benchmarks.outputs_cost              # perfect slider-crank, 4 rev, 2881 samples
python -m benchmarks.outputs_cost --joint alshaer2005 --solver ros34pw2

Every loop runs on borrowed arrays, as the driver and ``outputs`` do [T208].
Also prints the cost of the pieces a projected sample cannot avoid (docs/theory.md [T193]): one
evaluation of the constraints C (Φ, Φ_q, Φ_t, γ) and one Schur complement with its Cholesky
factor F, at the same samples, and the floor 1 + (2C + F)/RHS they imply.
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np
from numba import njit

from jointdyn.core.borrowed import borrowed
from jointdyn.core.constraints import eval_constraints, eval_constraints_into
from jointdyn.integrators import SOLVERS
from jointdyn.models import slider_crank as sc
from jointdyn.models.slider_crank import slider_crank_config
from jointdyn.multibody.dynamics import _schur_into, cholesky_factor, outputs, rhs
from jointdyn.simulation.simulate import simulate


@njit(cache=True)
def _rhs_loop(ts, ys, mems, P, out):
    ts, ys, mems, P, out = borrowed((ts, ys, mems, P, out))  # as the driver runs it [T208]
    s = 0
    for i in range(ts.shape[0]):
        s += rhs(ts[i], ys[i], mems[i], P, out)
    return s


@njit(cache=True)
def _constraints_loop(ts, ys, P):
    ts, ys, P = borrowed((ts, ys, P))
    n = ys.shape[1] // 2
    m = P.n_rows
    Phi, J, Phit, gam, cs = np.empty(m), np.empty((m, n)), np.empty(m), np.empty(m), np.empty(n)
    s = 0.0
    for i in range(ts.shape[0]):  # with a scratch for the trigonometry, as the hot paths [T223]
        eval_constraints_into(ts[i], ys[i, :n], ys[i, n:], P.cint, P.creal, Phi, J, Phit, gam, cs)
        s += gam[0]
    return s


@njit(cache=True)
def _factor_loop(ts, ys, P):
    ts, ys, P = borrowed((ts, ys, P))
    n = ys.shape[1] // 2
    m = P.n_rows
    Phi, J, Phit, gam, S = np.empty(m), np.empty((m, n)), np.empty(m), np.empty(m), np.empty((m, m))
    eval_constraints(ts[0], ys[0, :n], ys[0, n:], P.cint, P.creal, Phi, J, Phit, gam)
    s = 0.0
    for i in range(ts.shape[0]):
        J[0, 0] += 1e-300 * i  # a new matrix each time (the value is unchanged)
        _schur_into(S, J, P.minv, m, n)
        s += cholesky_factor(S)
    return s


def best(f, repeat):
    """Smallest CPU time of ``repeat`` calls [s] (process time: time the process spends
    descheduled on a shared machine is not counted)."""
    ts = []
    for _ in range(repeat):
        t0 = time.process_time()
        f()
        ts.append(time.process_time() - t0)
    return min(ts)


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m benchmarks.outputs_cost")
    ap.add_argument("--joint", default="perfect")
    ap.add_argument("--solver", default=None)
    ap.add_argument("--revs", type=float, default=4.0)
    ap.add_argument("--repeat", type=int, default=20)
    a = ap.parse_args(argv)
    system = sc.slider_crank(a.joint).compile()
    cfg = slider_crank_config(a.joint, a.revs, solver=a.solver)
    res = simulate(system, cfg)
    P = system.packed(0.0)
    # the raw output states of the integrator (before outputs() projects them in place)
    runner = SOLVERS[res.config["solver"]][0]
    ts = np.linspace(0.0, cfg.t_end, cfg.n_out)
    Y0, MEM, *_ = runner(P, system.y0, system.mem0, 0.0, ts, cfg.rtol, cfg.atol, 0.0, np.inf, 10**9, True)
    out = np.empty(Y0.shape[1])
    _rhs_loop(ts, Y0, MEM, P, out)
    outputs(ts, Y0.copy(), MEM, P, True)
    Yp = Y0.copy()
    outputs(ts, Yp, MEM, P, True)  # projected samples: a second projection does no iteration
    # interleaved rounds, smallest time of each kind: a change of machine load between blocks
    # of repeats would otherwise bias the ratios (the machine is shared)
    kinds = {
        "rhs": lambda: _rhs_loop(ts, Y0, MEM, P, out),
        "outputs": lambda: outputs(ts, Y0.copy(), MEM, P, True),
        "noproj": lambda: outputs(ts, Y0.copy(), MEM, P, False),  # drift report + accelerations
        "onman": lambda: outputs(ts, Yp.copy(), MEM, P, True),
        "copy": lambda: Y0.copy(),
        "constraints": lambda: _constraints_loop(ts, Y0, P),
        "factor": lambda: _factor_loop(ts, Y0, P),
    }
    tmin = {k: math.inf for k in kinds}
    for _ in range(a.repeat):
        for k, f in kinds.items():
            tmin[k] = min(tmin[k], best(f, 1))
    t_rhs, t_copy = tmin["rhs"] / len(ts), tmin["copy"] / len(ts)
    t_out = tmin["outputs"] / len(ts) - t_copy
    t_noproj = tmin["noproj"] / len(ts) - t_copy
    t_onman = tmin["onman"] / len(ts) - t_copy
    t_c, t_f = tmin["constraints"] / len(ts), tmin["factor"] / len(ts)
    end_to_end = best(lambda: simulate(system, cfg), max(1, a.repeat // 4))
    print(
        f"{system.name}, solver {res.config['solver']}, {len(ts)} samples: "
        f"outputs {t_out * 1e6:.2f} µs/sample, "
        f"rhs {t_rhs * 1e6:.2f} µs/evaluation -> {t_out / t_rhs:.2f} RHS-equivalents per sample; "
        f"outputs total {t_out * len(ts) * 1e3:.1f} ms, simulate end to end {end_to_end * 1e3:.1f} ms\n"
        f"  without projection {t_noproj / t_rhs:.2f} RHS-equivalents; samples already on the "
        f"manifold (velocity projection, no position iteration) {t_onman / t_rhs:.2f}\n"
        f"  constraint evaluation C {t_c * 1e6:.2f} µs, Schur complement + Cholesky factor F "
        f"{t_f * 1e6:.2f} µs: floor of a sample needing one correction 1 + (2C + F)/RHS = "
        f"{1 + (2 * t_c + t_f) / t_rhs:.2f} RHS-equivalents"
    )
    return {
        "rhs_equivalents": t_out / t_rhs,
        "us_per_sample": t_out * 1e6,
        "rhs_us": t_rhs * 1e6,
        "floor_rhs_equivalents": 1 + (2 * t_c + t_f) / t_rhs,
    }


if __name__ == "__main__":
    main()
