"""Independent reference path: scipy's ``solve_ivp`` on the same compiled right-hand side.

No projection is possible inside ``solve_ivp``, so this path relies on Baumgarte
stabilisation [T10] (rate ``baumgarte`` [1/s]) and tight tolerances; its drift is reported in
the results like any other run. Contact onsets and separations of journal elements are located
as terminal events (root of the penetration δ); the element memory is advanced at each event
(and at every output sample) by the same compiled hooks as in the compiled solvers
(:func:`~jointdyn.integrators.common.accept_hooks` without projection), and the integration
restarted, so δ̇⁻ is the rate at δ = 0 to the event tolerance.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from jointdyn.core.layout import BODY_I, BODY_J, TYPE
from jointdyn.forces.journal import CONTACT, IN_CONTACT, JOURNAL, NO_CONTACT, penetration
from jointdyn.integrators.common import INTERRUPTED, OK, RHS_FAILED, accept_hooks
from jointdyn.multibody.dynamics import rhs


def scipy_ivp(P, y0, mem0, t0, t_out, rtol, atol, method="Radau", max_step=np.inf, stop=None):
    """Integrate with ``solve_ivp``; same return tuple as the compiled integrators (accepted and
    rejected step counts are not reported by ``solve_ivp`` and stay 0). ``stop(t)`` is polled
    after every step (a terminal event); when it returns True the run ends with status
    INTERRUPTED at the start of that step, keeping every output sample computed before it."""
    nn = y0.shape[0]
    n = nn // 2
    fint, freal = P.fint, P.freal
    mem = mem0.copy()
    stats = np.zeros(4, dtype=np.int64)
    status = [OK]
    t_stop = [t0]  # where the run stopped when stop() said yes
    contact = [k for k in range(fint.shape[0]) if fint[k, TYPE] == JOURNAL and fint[k, CONTACT] != NO_CONTACT]

    stopped = [False, np.inf]  # stop() said yes; the time the step is cut at

    def f(t, y):
        y = np.ascontiguousarray(y)  # the element kernels take contiguous arrays [T379]
        out = np.empty_like(y)
        if rhs(t, y, mem, P, out) != 0:
            status[0] = RHS_FAILED
        return out

    def make_event(k):
        def ev(t, y):
            d, _ = penetration(y[:n], y[n:], fint[k, BODY_I], fint[k, BODY_J], freal[k])
            # onset: δ rises through +1e-12 m; separation: δ falls through −1e-12 m (the offsets keep
            # a restart exactly at the root from re-triggering the same event)
            return d - 1e-12 if mem[k, IN_CONTACT] < 0.5 else -d - 1e-12

        ev.terminal = True
        ev.direction = 1.0
        return ev

    def stop_event(t, y):
        # -1 until stop() says yes at a step end t_s; then t - t_s⁻ (one ulp before t_s), which
        # changes sign inside the step just taken, so solve_ivp ends it there with its samples
        if not stopped[0] and stop is not None and stop(t):
            stopped[0], stopped[1] = True, np.nextafter(t, -np.inf)
        return t - stopped[1] if stopped[0] else -1.0

    stop_event.terminal = True
    stop_event.direction = 1.0
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
        if stopped[0]:  # said between two segments (e.g. at a contact event)
            status[0], t_stop[0] = INTERRUPTED, t
            break
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
            events=[*events, stop_event],
            first_step=first,
        )
        first = 1e-9 * max(1.0, abs(t_out[-1]))
        stats[0] += sol.nfev
        stats[3] += getattr(sol, "njev", 0)
        for i in range(len(sol.t)):
            # memory (largest penetration, film breakdown) over output samples and event states
            yi = np.ascontiguousarray(sol.y[:, i])
            st = accept_hooks(sol.t[i], yi, mem, P, False)
            Y[iout], MEM[iout] = yi, mem
            iout += 1
            if st != OK:
                status[0] = st
                break
        if status[0] != OK:
            t = sol.t[i]
            break
        if not sol.success:
            status[0] = RHS_FAILED
            break
        if sol.status == 1 and len(sol.t_events[-1]):  # stop() said yes during the last step
            status[0], t_stop[0] = INTERRUPTED, float(sol.t_events[-1][0])
            break
        if sol.status == 1:  # an event: advance memory at the event state, restart after it
            k_ev = next(i for i, e in enumerate(sol.t_events) if len(e))
            t, y = sol.t_events[k_ev][0], sol.y_events[k_ev][0].copy()
            # the event state has δ = +1e-12 m (onset) or −1e-12 m (separation): the shared hook
            # records the onset velocity / the separation exactly as after a compiled step
            st = accept_hooks(t, y, mem, P, False)
            if st != OK:
                status[0] = st
                break
        else:  # reached the end: the hooks already ran at the last output sample
            t, y = t_out[-1], np.ascontiguousarray(sol.y[:, -1])
    t_reached = t_stop[0] if status[0] == INTERRUPTED else (t_out[iout - 1] if iout else t0)
    return Y[:iout], MEM[:iout], iout, stats, status[0], t_reached, 0.0, y, mem
