"""Trajectories for bit-identity checks between two versions of the code.

    PYTHONPATH=<old>/src python -m benchmarks.capture_trajectories old.npz
    PYTHONPATH=<new>/src python -m benchmarks.capture_trajectories new.npz
    python -m benchmarks.capture_trajectories --compare old.npz new.npz

Captures the paper's four cases (1 rev, as the goldens run them) and, per solver, the perfect,
dry and π-film slider-crank (0.25 rev) and a
damped oscillator: y, mem, λ, q̈, element outputs and the step statistics.
"""

import sys
import time

import numpy as np

from jointdyn.forces.springs import SpringDamper
from jointdyn.models import slider_crank as sc
from jointdyn.models.slider_crank import slider_crank_config
from jointdyn.multibody.model import Model
from jointdyn.simulation.simulate import SimConfig, simulate
from jointdyn.studies.reproduce import PAPER_CASES, run_case


def osc(k, d):
    m = Model("oscillator", gravity=(0.0, 0.0))
    m.add_ground_point("O", (0.0, 0.0))
    m.add_body("b", 0.2, 1e-3, position=(0.1 + 1e-3, 0.0), points={"c": (0.0, 0.0)})
    m.add("spring", SpringDamper("ground", "O", "b", "c", stiffness=k, damping=d, free_length=0.1))
    return m.compile()


def same(x, y) -> bool:
    """Bit-identical, or ``y`` is ``x`` with trailing columns of zeros appended on the last axis
    (element outputs or memory slots a newer version added, unused by the model)."""
    if x.shape == y.shape:
        return np.array_equal(x, y, equal_nan=True)
    if x.ndim != y.ndim or x.shape[:-1] != y.shape[:-1] or x.shape[-1] > y.shape[-1]:
        return False
    return np.array_equal(x, y[..., : x.shape[-1]], equal_nan=True) and not np.any(y[..., x.shape[-1] :])


def put(out, name, res):
    out[name + "/y"] = res.y
    out[name + "/mem"] = res.mem
    out[name + "/lam"] = res.lam
    out[name + "/qdd"] = res.qdd
    out[name + "/eout"] = res.eout
    out[name + "/stats"] = np.array(list(res.stats.values()))
    print(name, res.stats, flush=True)


def main():
    out = {}

    if sys.argv[1] == "--compare":
        a, b = np.load(sys.argv[2]), np.load(sys.argv[3])
        bad = [k for k in a.files if k not in b.files or not same(a[k], b[k])]
        for k in bad:
            print("DIFF", k)
        print(f"{len(a.files) - len(bad)}/{len(a.files)} arrays identical")
        return
    only = sys.argv[2] if len(sys.argv) > 2 else ""
    t0 = time.time()
    if "golden" in only or not only:
        for case in PAPER_CASES:
            res, _, _ = run_case(case, 1.0)
            put(out, "golden_" + case.name, res)
    if "solvers" in only or not only:
        for joint, solvers in [
            ("perfect", ["dopri5", "rodas4", "ros34pw2", "scipy-radau"]),
            ("dry", ["dopri5", "rodas4", "scipy-radau"]),
            ("alshaer2005", ["rodas4", "ros34pw2", "dopri5", "scipy-radau"]),
        ]:
            sys_ = sc.slider_crank(joint).compile()
            for s in solvers:
                res = simulate(sys_, slider_crank_config(joint, 0.25, solver=s))
                put(out, f"{joint}_{s}", res)
        for s in ["dopri5", "rodas4", "ros34pw2", "scipy-radau"]:
            res = simulate(osc(1e4, 5.0), SimConfig(t_end=0.2, n_out=201, solver=s, rtol=1e-9, atol=1e-13))
            put(out, f"osc_{s}", res)
    np.savez(sys.argv[1], **out)
    print("done", time.time() - t0)


if __name__ == "__main__":
    main()
