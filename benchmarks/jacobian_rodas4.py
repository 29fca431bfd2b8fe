"""rodas4 with the exact system Jacobian vs its forward-difference Jacobian (same run, same code).

The exact variant is rodas4's own loop (source of ``integrators.rodas4.rodas4``) with the call
``jacobian(...)`` replaced by ``jacobian.system_jacobian(...)`` and its cost counted as one RHS
evaluation (it evaluates the forces once for λ and q̈). Lubricated slider-crank (π-film, c = 0.5 mm,
5000 rpm, 4 revolutions). Accuracy: max |Δq| over the output grid against a reference run
(rtol 1e-11, FD Jacobian) [m or rad].

    python -m benchmarks.jacobian_rodas4 [--joint alshaer2005] [--revs 4] [--repeat 3]
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


def exact_rodas4():
    src = inspect.getsource(r4.rodas4.py_func)
    src = src.replace("@njit(cache=True)\n", "")
    assert "jacobian(t, y, f0, mem, P, Jm, ft, work, fw)" in src and "stats[0] += nn + 1" in src
    src = src.replace(
        "jacobian(t, y, f0, mem, P, Jm, ft, work, fw)", "system_jacobian(t, y, f0, mem, P, Jm, ft, work, fw)"
    )
    src = src.replace("stats[0] += nn + 1", "stats[0] += 1")
    ns = dict(vars(r4))
    ns["system_jacobian"] = system_jacobian
    exec(src, ns)  # noqa: S102 — our own source, one substitution
    return njit(ns["rodas4"])


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
    a = ap.parse_args(argv)
    system = slider_crank(a.joint).compile()
    P = system.packed(0.0)
    t_out = np.linspace(0.0, a.revs * 2 * np.pi / SPEED, 2001)
    n = system.n
    ex = exact_rodas4()
    ref = run(r4.rodas4, P, system, t_out, 1e-11, 1e-13)[1]
    print(f"joint {a.joint}, {a.revs:g} rev, n = {2 * n} states; accuracy vs rtol 1e-11 reference")
    print("| rtol | Jacobian | RHS evals | accepted | rejected | RHS/accepted | wall [s] | max abs(dq) |")
    print("|---|---|---|---|---|---|---|---|")
    for rtol in (1e-6, 1e-8):
        for name, fn in (("forward differences", r4.rodas4), ("exact", ex)):
            run(fn, P, system, t_out, rtol, 1e-10)  # compile / warm
            best = min(run(fn, P, system, t_out, rtol, 1e-10)[0] for _ in range(a.repeat))
            _, Y, st, status = run(fn, P, system, t_out, rtol, 1e-10)
            assert status == 0, status
            err = np.abs(Y[:, :n] - ref[:, :n]).max()
            row = (
                f"{rtol:g}",
                name,
                st[0],
                st[1],
                st[2],
                f"{st[0] / st[1]:.2f}",
                f"{best:.3f}",
                f"{err:.2e}",
            )
            print("| " + " | ".join(map(str, row)) + " |")


if __name__ == "__main__":
    main()
