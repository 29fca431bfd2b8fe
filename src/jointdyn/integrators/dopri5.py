"""Compiled Dormand–Prince 5(4) with error control (Hairer, Nørsett & Wanner 1993, II.5) [T12].

Explicit: good for the perfect and dry-contact mechanisms; the lubricated film is stiff (use
``rodas4``). After every accepted step the state is projected on the constraints and element
memory is advanced (:func:`~jointdyn.integrators.common.accept_hooks`); steps are limited so
that a contact onset is never skipped (``step_limit``/``onset_fraction``).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..dynamics import rhs
from ..forces.elements import onset_fraction, step_limit
from .common import (
    MAX_STEPS,
    OK,
    RHS_FAILED,
    STEP_TOO_SMALL,
    accept_hooks,
    error_norm,
    start_outputs,
    write_dense,
)

C2, C3, C4, C5 = 1 / 5, 3 / 10, 4 / 5, 8 / 9
A21 = 1 / 5
A31, A32 = 3 / 40, 9 / 40
A41, A42, A43 = 44 / 45, -56 / 15, 32 / 9
A51, A52, A53, A54 = 19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729
A61, A62, A63, A64, A65 = 9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656
A71, A73, A74, A75, A76 = 35 / 384, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84
E1, E3, E4, E5, E6, E7 = 71 / 57600, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40


@njit(cache=True)
def dopri5(P, y0, mem0, t0, t_out, rtol, atol, h0, hmax, max_steps, do_project):
    """Integrate from t0 to t_out[-1]; returns (Y, MEM, n_written, stats, status, t_reached, h_next,
    y_final, mem_final).

    stats = [rhs evaluations, accepted steps, rejected steps, Jacobians (0)]."""
    nn = y0.shape[0]
    n = nn // 2
    nout = t_out.shape[0]
    Y, MEM, iout = start_outputs(y0, mem0, t0, t_out)
    stats = np.zeros(4, dtype=np.int64)
    h = h0 if h0 > 0 else 1e-6 * max(1.0, abs(t_out[-1] - t0))
    h_prop = h
    mem = mem0.copy()
    y = y0.copy()
    t = t0
    t_end = t_out[-1]
    k1 = np.empty(nn)
    k2 = np.empty(nn)
    k3 = np.empty(nn)
    k4 = np.empty(nn)
    k5 = np.empty(nn)
    k6 = np.empty(nn)
    k7 = np.empty(nn)
    yt = np.empty(nn)
    y1 = np.empty(nn)
    err = np.empty(nn)
    st = accept_hooks(t, y, mem, P, do_project)
    if st != OK:
        return Y, MEM, iout, stats, st, t, h, y, mem
    if rhs(t, y, mem, P, k1) != 0:
        return Y, MEM, iout, stats, RHS_FAILED, t, h, y, mem
    stats[0] += 1
    hmin = 1e-14 * max(1.0, abs(t_end))
    fail_status = OK
    while t < t_end:
        if stats[1] + stats[2] >= max_steps:
            return Y, MEM, iout, stats, MAX_STEPS, t, h, y, mem
        h = min(h, hmax, step_limit(y[:n], y[n:], mem, P[4], P[5]))
        h_prop = h
        if t + h >= t_end - 1e-14 * abs(t_end):
            h = t_end - t
        if h < hmin:
            return Y, MEM, iout, stats, STEP_TOO_SMALL if fail_status == OK else fail_status, t, h, y, mem
        bad = 0
        for i in range(nn):
            yt[i] = y[i] + h * A21 * k1[i]
        bad |= rhs(t + C2 * h, yt, mem, P, k2)
        for i in range(nn):
            yt[i] = y[i] + h * (A31 * k1[i] + A32 * k2[i])
        bad |= rhs(t + C3 * h, yt, mem, P, k3)
        for i in range(nn):
            yt[i] = y[i] + h * (A41 * k1[i] + A42 * k2[i] + A43 * k3[i])
        bad |= rhs(t + C4 * h, yt, mem, P, k4)
        for i in range(nn):
            yt[i] = y[i] + h * (A51 * k1[i] + A52 * k2[i] + A53 * k3[i] + A54 * k4[i])
        bad |= rhs(t + C5 * h, yt, mem, P, k5)
        for i in range(nn):
            yt[i] = y[i] + h * (A61 * k1[i] + A62 * k2[i] + A63 * k3[i] + A64 * k4[i] + A65 * k5[i])
        bad |= rhs(t + h, yt, mem, P, k6)
        for i in range(nn):
            y1[i] = y[i] + h * (A71 * k1[i] + A73 * k3[i] + A74 * k4[i] + A75 * k5[i] + A76 * k6[i])
        bad |= rhs(t + h, y1, mem, P, k7)
        stats[0] += 6
        if bad != 0:
            stats[2] += 1
            fail_status = RHS_FAILED
            h *= 0.25
            continue
        for i in range(nn):
            err[i] = h * (E1 * k1[i] + E3 * k3[i] + E4 * k4[i] + E5 * k5[i] + E6 * k6[i] + E7 * k7[i])
        en = error_norm(err, y, y1, rtol, atol)
        if not np.isfinite(en):
            stats[2] += 1
            fail_status = RHS_FAILED
            h *= 0.25
            continue
        if en > 1.0:
            stats[2] += 1
            h *= max(0.2, 0.9 * en**-0.2)
            continue
        frac = onset_fraction(y[:n], y[n:], y1[:n], y1[n:], mem, P[4], P[5])
        if frac < 1.0:
            stats[2] += 1
            h *= max(frac, 0.01)
            continue
        # accepted
        fail_status = OK
        t_new = t + h
        iout = write_dense(t, y, k1, t_new, y1, k7, mem, t_out, iout, Y, MEM)
        y[:] = y1
        t = t_new
        stats[1] += 1
        st = accept_hooks(t, y, mem, P, do_project)
        if st != OK:
            return Y, MEM, iout, stats, st, t, h, y, mem
        if do_project and P[7] > 0:
            if rhs(t, y, mem, P, k1) != 0:
                return Y, MEM, iout, stats, RHS_FAILED, t, h, y, mem
            stats[0] += 1
        else:
            k1[:] = k7
        h *= min(5.0, max(0.2, 0.9 * max(en, 1e-10) ** -0.2))
    if iout == nout:
        Y[nout - 1] = y
        MEM[nout - 1] = mem
    return Y, MEM, iout, stats, OK, t, h_prop, y, mem
