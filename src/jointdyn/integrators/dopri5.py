"""Compiled Dormand–Prince 5(4) with error control (Hairer, Nørsett & Wanner 1993, II.5) [T12].

Explicit: good for the perfect and dry-contact mechanisms; the lubricated film is stiff (use
``rodas4``). After every accepted step the state is projected on the constraints and element
memory is advanced; steps are limited so that a contact onset is never skipped — all done by the
shared loop in :mod:`~jointdyn.integrators.driver` [T110], to which :data:`DOPRI5` (the record
of this method, [T230]) hands the hooks below. Dense output: cubic Hermite from k₁ and k₇
(:func:`dense`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from jointdyn.core.arrays import copy_matrix
from jointdyn.integrators.common import error_norm, hermite
from jointdyn.integrators.driver import ATTEMPT_OK, CTL0, ICTL0, Stepper
from jointdyn.multibody.dynamics import rhs

C2, C3, C4, C5 = 1 / 5, 3 / 10, 4 / 5, 8 / 9
A21 = 1 / 5
A31, A32 = 3 / 40, 9 / 40
A41, A42, A43 = 44 / 45, -56 / 15, 32 / 9
A51, A52, A53, A54 = 19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729
A61, A62, A63, A64, A65 = 9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656
A71, A73, A74, A75, A76 = 35 / 384, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84
E1, E3, E4, E5, E6, E7 = 71 / 57600, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40


@njit(cache=True)
def attempt_dopri5(t, h, P, w, rtol, atol):
    """One trial step from (t, w.y) with k₁ = w.f0 to w.y1 (k₇ = f(t+h, y₁) in w.K[6]).

    Returns (0, error norm) or (2, inf) if a right-hand side failed."""
    y, y1, yt, err, mem, K = w.y, w.y1, w.yt, w.err, w.mem, w.K
    nn = y.shape[0]
    k1, k2, k3, k4, k5, k6, k7 = w.f0, K[1], K[2], K[3], K[4], K[5], K[6]
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
    w.stats[0] += 6
    if bad != 0:
        return 2, np.inf
    for i in range(nn):
        err[i] = h * (E1 * k1[i] + E3 * k3[i] + E4 * k4[i] + E5 * k5[i] + E6 * k6[i] + E7 * k7[i])
    return 0, error_norm(err, y, y1, rtol, atol)


# step-size control of Hairer's DOPRI5 code (Hairer, Nørsett & Wanner 1993, §II.4 and the code's
# defaults): Lund's PI stabilisation β = 0.04, factors within [0.2, 10], safety 0.9, no growth
# right after a rejected step [T204]
BETA = 0.04
EXPO1 = 0.2 - 0.75 * BETA
FAC_MIN, FAC_MAX, SAFE = 0.2, 10.0, 0.9

# its own slots of Work.ctl / Work.ictl: the previous error norm, "the last attempt was rejected"
E_PREV = CTL0
REJECTED = ICTL0


@njit(cache=True)
def rejected(res, h, en, ctl, ictl, stats, reuse):
    """Stepper hook: next h after an error-test failure (en > 1), and no growth on the next
    accepted step [T204]."""
    if res == ATTEMPT_OK:
        h *= max(FAC_MIN, SAFE * en**-EXPO1)
        ictl[REJECTED] = 1
    return h


@njit(cache=True)
def accepted(h, h_prop, hmax, en, ctl, ictl, stats, reuse):
    """Stepper hook: next h after an accepted step with error norm ``en`` [T204]."""
    e = max(en, 1e-4)
    fac = SAFE * e**-EXPO1 * ctl[E_PREV] ** BETA
    h_new = h * min(FAC_MAX, max(FAC_MIN, fac))
    if ictl[REJECTED] == 1:
        h_new = min(h_new, h)
    ictl[REJECTED] = 0
    ctl[E_PREV] = e
    return h_new


@njit(cache=True)
def dense(t, t_new, y, f0, y1, K, mem, ctl, ictl, t_out, iout, Y, MEM):
    """Stepper hook: outputs in (t, t_new] by cubic Hermite interpolation from y, k₁ = f(t, y),
    y₁ and k₇ (4th-order accurate state); returns the next output index."""
    h = t_new - t
    while iout < t_out.shape[0] and t_out[iout] <= t_new + 1e-15 * abs(t_new):
        th = (t_out[iout] - t) / h if h > 0 else 1.0
        hermite(y, f0, y1, K[6], h, min(max(th, 0.0), 1.0), Y[iout])
        copy_matrix(MEM[iout], mem)
        iout += 1
    return iout


# k₇ = f(t + h, y₁) is in K[6]: first-same-as-last [T203]
DOPRI5 = Stepper("dopri5", 5, attempt_dopri5, rejected, accepted, dense, fsal=6, ctl=(1.0,), ictl=(0,))
