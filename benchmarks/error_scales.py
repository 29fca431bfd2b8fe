"""The accuracy cases of the defaults ([T116]) under both error scales ([T186]), one process.

Usage: ``python -m benchmarks.error_scales [--cases pi0.5,pi0.05,ott,finite,short,mixed]
[--runs radau5:state:1e-8:1e-10,radau5:clearance:3e-6:1e-10] [--repeat 3]``

Per case (the benchmark slider-crank with the named rod–slider joint, 720 samples per
revolution) and per run ``solver:error_scale:rtol:atol``: ``simulate`` wall time (smallest of
``repeat`` warm runs), accepted / rejected steps, RHS evaluations and the max crank-moment error
|ΔM|/peak against a converged run (rodas4, rtol 1e-11, atol 1e-14, state scales).
"""

from __future__ import annotations

import argparse
import math
import time
import warnings

import numpy as np

from jointdyn import post
from jointdyn.errors import SimulationError
from jointdyn.forces.contact_laws import LankaraniNikravesh, journal_bearing_stiffness
from jointdyn.models import slider_crank as sc
from jointdyn.simulation.simulate import SimConfig, simulate


def _mixed_law(c):
    """The mixed film/contact law of tests/test_mixed_friction.py (steel, n = 1.5, c_r = 0.9)."""
    K = journal_bearing_stiffness(
        sc.JOURNAL_RADIUS + c, sc.JOURNAL_RADIUS, sc.YOUNG, sc.POISSON, sc.YOUNG, sc.POISSON
    )
    return LankaraniNikravesh(stiffness=K, exponent=1.5, restitution=0.9)


# name: (slider_crank kwargs, revolutions)
CASES = {
    "pi0.5": ({"joint": "alshaer2005"}, 4),
    "pi0.05": ({"joint": "alshaer2005", "clearance": 5e-5}, 4),
    "ott": ({"joint": "ott"}, 2),
    "finite": ({"joint": "finite"}, 2),
    "short": ({"joint": "short"}, 2),
    "mixed": (
        {
            "joint": "alshaer2005",
            "clearance": 5e-5,
            "viscosity": 1e-3,
            "contact": _mixed_law(5e-5),
            "asperity_height": 1e-6,
        },
        2,
    ),
}


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m benchmarks.error_scales")
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--runs", default="radau5:state:1e-8:1e-10,radau5:clearance:3e-6:1e-10")
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args(argv)
    runs = [r.split(":") for r in a.runs.split(",")]
    print("| case | solver | error_scale | rtol | atol | simulate [ms] | accepted | rejected | rhs | error |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name in a.cases.split(","):
        kw, revs = CASES[name]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            system = sc.slider_crank(**kw).compile()
        t_end, n_out = revs * 2 * math.pi / sc.SPEED, revs * 720 + 1
        ref_cfg = SimConfig(t_end=t_end, n_out=n_out, solver="rodas4", rtol=1e-11, atol=1e-14)
        Mr = post.driving_moment(simulate(system, ref_cfg))
        for solver, scale, rtol, atol in runs:
            cfg = SimConfig(
                t_end=t_end, n_out=n_out, solver=solver, rtol=float(rtol), atol=float(atol), error_scale=scale
            )
            try:
                simulate(system, cfg)  # JIT warm-up
            except SimulationError as err:
                print(f"| {name} | {solver} | {scale} | {rtol} | {atol} | failed: {str(err)[:80]} |")
                continue
            times = []
            for _ in range(a.repeat):
                t0 = time.perf_counter()
                res = simulate(system, cfg)
                times.append(time.perf_counter() - t0)
            M = post.driving_moment(res)
            err = float(np.abs(M - Mr).max() / np.abs(Mr).max())
            st = res.stats
            print(
                f"| {name} | {solver} | {scale} | {rtol} | {atol} | {min(times) * 1e3:.1f} | "
                f"{st['accepted_steps']} | {st['rejected_steps']} | {st['rhs_evaluations']} | {err:.2e} |",
                flush=True,
            )


if __name__ == "__main__":
    main()
