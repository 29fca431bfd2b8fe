"""Independent reference path: scipy's ``solve_ivp`` on the same compiled right-hand side.

No projection is possible inside ``solve_ivp``, so this path relies on Baumgarte
stabilisation [T10] (rate ``baumgarte`` [1/s]) and tight tolerances; its drift is reported in
the results like any other run. Element memory (contact onset) is updated at terminal events.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from ..dynamics import rhs
from ..forces.elements import NMEM, advance_memory
from .common import MEMORY_FAILED, OK, RHS_FAILED


def scipy_ivp(P, y0, mem0, t0, t_out, rtol, atol, method="Radau", max_step=np.inf):
    """Integrate with ``solve_ivp``; same return tuple as the compiled integrators."""
    n = y0.shape[0] // 2
    mem = mem0.copy()
    stats = np.zeros(4, dtype=np.int64)
    status = [OK]

    def f(t, y):
        out = np.empty_like(y)
        if rhs(t, y, mem, P, out) != 0:
            status[0] = RHS_FAILED
        return out

    sol = solve_ivp(f, (t0, t_out[-1]), y0, method=method, t_eval=t_out, rtol=rtol, atol=atol,
                    max_step=max_step, dense_output=False)
    Y = sol.y.T.copy()
    MEM = np.repeat(mem[None], Y.shape[0], axis=0) if Y.shape[0] else np.zeros((0,) + mem.shape)
    for i in range(Y.shape[0]):
        if advance_memory(t_out[i], Y[i, :n], Y[i, n:], mem, P[4], P[5], P[6]) != 0:
            status[0] = MEMORY_FAILED
    stats[0] = sol.nfev
    stats[1] = len(sol.t)
    stats[3] = getattr(sol, "njev", 0)
    st = status[0] if status[0] != OK else (OK if sol.success else RHS_FAILED)
    t_reached = sol.t[-1] if len(sol.t) else t0
    return Y, MEM, Y.shape[0], stats, st, t_reached, 0.0


__all__ = ["scipy_ivp", "NMEM"]
