"""Independent reference path: scipy's ``solve_ivp`` on the same compiled right-hand side.

No projection is possible inside ``solve_ivp``, so this path relies on Baumgarte
stabilisation [T10] (rate ``baumgarte`` [1/s]) and tight tolerances; its drift is reported in
the results like any other run. Contact onsets and separations of journal elements are located
as terminal events (root of the penetration δ); the element memory is advanced at each event
and the integration restarted, so δ̇⁻ is the rate at δ = 0 to the event tolerance.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from ..dynamics import rhs
from ..forces.elements import advance_memory
from ..forces.journal import CONTACT, IN_CONTACT, JOURNAL, ONSET_VEL, V_MIN, penetration
from .common import OK, RHS_FAILED


def scipy_ivp(P, y0, mem0, t0, t_out, rtol, atol, method="Radau", max_step=np.inf):
    """Integrate with ``solve_ivp``; same return tuple as the compiled integrators (accepted and
    rejected step counts are not reported by ``solve_ivp`` and stay 0)."""
    nn = y0.shape[0]
    n = nn // 2
    fint, freal = P[4], P[5]
    mem = mem0.copy()
    stats = np.zeros(4, dtype=np.int64)
    status = [OK]
    contact = [k for k in range(fint.shape[0]) if fint[k, 0] == JOURNAL and fint[k, CONTACT] >= 0]

    def f(t, y):
        out = np.empty_like(y)
        if rhs(t, y, mem, P, out) != 0:
            status[0] = RHS_FAILED
        return out

    def make_event(k):
        def ev(t, y):
            d, _ = penetration(y[:n], y[n:], fint[k, 1], fint[k, 2], freal[k])
            # onset: δ rises through +1e-12 m; separation: δ falls through −1e-12 m (the offsets keep
            # a restart exactly at the root from re-triggering the same event)
            return d - 1e-12 if mem[k, IN_CONTACT] < 0.5 else -d - 1e-12

        ev.terminal = True
        ev.direction = 1.0
        return ev

    events = [make_event(k) for k in contact]
    Y = np.zeros((len(t_out), nn))
    MEM = np.zeros((len(t_out),) + mem.shape)
    iout = 0
    while iout < len(t_out) and t_out[iout] <= t0:
        Y[iout], MEM[iout] = y0, mem
        iout += 1
    t, y = t0, y0.copy()
    first = None
    while t < t_out[-1] and status[0] == OK:
        te = t_out[iout:]
        # after an event restart with a small first step: scipy's initial-step heuristic would
        # otherwise jump deep into the stiff contact and an explicit method can blow up
        sol = solve_ivp(
            f,
            (t, t_out[-1]),
            y,
            method=method,
            t_eval=te,
            rtol=rtol,
            atol=atol,
            max_step=max_step,
            events=events or None,
            first_step=first,
        )
        first = 1e-9 * max(1.0, abs(t_out[-1]))
        stats[0] += sol.nfev
        stats[3] += getattr(sol, "njev", 0)
        for i in range(len(sol.t)):
            for k in contact:  # largest penetration, here over output samples and event states
                d, _ = penetration(sol.y[:n, i], sol.y[n:, i], fint[k, 1], fint[k, 2], freal[k])
                mem[k, 3] = max(mem[k, 3], d)
            Y[iout], MEM[iout] = sol.y[:, i], mem
            iout += 1
        if not sol.success:
            status[0] = RHS_FAILED
            break
        if sol.status == 1:  # an event: advance memory at the event state, restart after it
            k_ev = next(i for i, e in enumerate(sol.t_events) if len(e))
            t, y = sol.t_events[k_ev][0], sol.y_events[k_ev][0].copy()
            d, dd = penetration(
                y[:n], y[n:], fint[contact[k_ev], 1], fint[contact[k_ev], 2], freal[contact[k_ev]]
            )
            if mem[contact[k_ev], IN_CONTACT] < 0.5:
                mem[contact[k_ev], IN_CONTACT] = 1.0
                mem[contact[k_ev], ONSET_VEL] = max(dd, freal[contact[k_ev], V_MIN])
                mem[contact[k_ev], 2] += 1.0
            else:
                mem[contact[k_ev], IN_CONTACT] = 0.0
        else:
            t = t_out[-1]
    if status[0] == OK:
        st = advance_memory(t, y[:n], y[n:], mem, fint, freal, P[6])
        status[0] = st
    t_reached = t_out[iout - 1] if iout else t0
    return Y[:iout], MEM[:iout], iout, stats, status[0], t_reached, 0.0, y, mem
