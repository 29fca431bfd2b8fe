"""rodas4 and ros34pw2 with the exact system Jacobian vs their forward-difference Jacobian (same
run, same code).

The exact variants are the integrators' own loops (source of ``integrators.rodas4.rodas4`` and
``integrators.ros34pw2.ros34pw2``) with the call
``jacobian(...)`` replaced by ``jacobian.system_jacobian(...)`` and its cost counted as one RHS
evaluation (it evaluates the forces once for λ and q̈). Lubricated slider-crank (π-film, c = 0.5 mm,
5000 rpm, 4 revolutions). Accuracy: max |Δq| over the output grid against a reference run
(rtol 1e-11, FD Jacobian) [m or rad].

    python -m benchmarks.jacobian_rodas4 [--joint alshaer2005] [--revs 4] [--repeat 3] [--rtol 1e-6 1e-8]
"""

from __future__ import annotations

import argparse
import importlib
import inspect
import time

import numpy as np
from numba import njit

from jointdyn.jacobian import system_jacobian
from jointdyn.models.slider_crank import SPEED, slider_crank

r4 = importlib.import_module("jointdyn.integrators.rodas4")
rw = importlib.import_module("jointdyn.integrators.ros34pw2")


def exact_variant(mod, name, **consts):
    """The compiled integrator ``mod.name`` with its forward-difference Jacobian call replaced
    by the exact ``system_jacobian`` (counted as one RHS evaluation)."""
    src = inspect.getsource(getattr(mod, name).py_func)
    src = src.replace("@njit(cache=True)\n", "")
    call = "jacobian(t, y, f0, mem, P, Jm, ft, work, fw)"
    assert call in src and "stats[0] += nn + 1" in src
    src = src.replace(call, "system_" + call)
    src = src.replace("stats[0] += nn + 1", "stats[0] += 1")
    ns = dict(vars(mod))
    ns["system_jacobian"] = system_jacobian
    ns.update(consts)  # e.g. REUSE = 1: refresh the (now cheap) Jacobian every step
    exec(src, ns)  # noqa: S102 — the project's own source with one substitution
    return njit(ns[name])


def run(fn, P, system, t_out, rtol, atol):
    t0 = time.perf_counter()
    Y, MEM, nw, stats, status, *_ = fn(
        P, system.y0.copy(), system.mem0.copy(), 0.0, t_out, rtol, atol, 0.0, np.inf, 10**7, True
    )
    return time.perf_counter() - t0, Y, stats, status


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--joint", default="alshaer2005")
    ap.add_argument("--revs", type=float, default=4.0)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--rtol", type=float, nargs="+", default=[1e-6, 1e-8])
    a = ap.parse_args(argv)
    system = slider_crank(a.joint).compile()
    P = system.packed(0.0)
    t_out = np.linspace(0.0, a.revs * 2 * np.pi / SPEED, 2001)
    n = system.n
    variants = [
        ("rodas4", "forward differences", r4.rodas4),
        ("rodas4", "exact", exact_variant(r4, "rodas4")),
        ("ros34pw2", "forward differences", rw.ros34pw2),
        ("ros34pw2", "exact", exact_variant(rw, "ros34pw2")),
        ("ros34pw2", "exact, refreshed every step", exact_variant(rw, "ros34pw2", REUSE=1)),
    ]
    ref = run(r4.rodas4, P, system, t_out, 1e-11, 1e-13)[1]
    print(f"joint {a.joint}, {a.revs:g} rev, n = {2 * n} states; accuracy vs rodas4 at rtol 1e-11")
    head = ("solver", "rtol", "Jacobian", "RHS evals", "accepted", "rejected", "RHS/accepted", "wall [s]")
    print("| " + " | ".join(head) + " | max abs(dq) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for rtol in a.rtol:
        for solver, name, fn in variants:
            run(fn, P, system, t_out, rtol, 1e-10)  # compile / warm
            best = min(run(fn, P, system, t_out, rtol, 1e-10)[0] for _ in range(a.repeat))
            _, Y, st, status = run(fn, P, system, t_out, rtol, 1e-10)
            assert status == 0, status
            err = np.abs(Y[:, :n] - ref[:, :n]).max()
            row = (solver, f"{rtol:g}", name, st[0], st[1], st[2], f"{st[0] / st[1]:.2f}", f"{best:.3f}")
            print("| " + " | ".join(map(str, row)) + f" | {err:.2e} |")


if __name__ == "__main__":
    main()
