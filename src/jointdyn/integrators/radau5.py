"""Compiled Radau IIA of order 5 (3 stages, L-stable, stiffly accurate) [T113].

Hairer & Wanner, *Solving ODEs II* (1996), §IV.8, and their code RADAU5: the collocation
system is solved by simplified Newton in transformed variables (one real and one complex
system per iteration, both reduced to half the state dimension for y = [q, q̇], [T181]), started
from the collocation polynomial of the previous step; the Jacobian is kept while the Newton contraction
θ stays ≤ 0.001 and the LU while h does not change; embedded error estimate (E1 solve of
γ₀⁻¹-weighted stage combination, refined after a rejection); Gustafsson's predictive step-size
controller; collocation dense output. The Jacobian is the shared loop's (exact, or forward
differences); :data:`RADAU5` is the method's record for that loop [T230].

The error test uses the user's rtol and atol as they are (as scipy's ``Radau`` does; RADAU5's
mapping rtol' = 0.1·rtol^(2/3) is not applied, [T114]).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from jointdyn.core.arrays import copy_matrix
from jointdyn.integrators.driver import (
    AGE,
    ATTEMPT_DIVERGED,
    ATTEMPT_OK,
    ATTEMPT_SINGULAR,
    CTL0,
    ICTL0,
    Stepper,
)
from jointdyn.integrators.rodas4 import lu_factor, lu_solve
from jointdyn.multibody.dynamics import rhs

SQ6 = np.sqrt(6.0)
C1 = (4.0 - SQ6) / 10.0
C2 = (4.0 + SQ6) / 10.0
C1M1 = C1 - 1.0
C2M1 = C2 - 1.0
C1MC2 = C1 - C2
DD1 = -(13.0 + 7.0 * SQ6) / 3.0
DD2 = (-13.0 + 7.0 * SQ6) / 3.0
DD3 = -1.0 / 3.0
_U1 = (6.0 + 81.0 ** (1.0 / 3.0) - 9.0 ** (1.0 / 3.0)) / 30.0
_ALPH = (12.0 - 81.0 ** (1.0 / 3.0) + 9.0 ** (1.0 / 3.0)) / 60.0
_BETA = (81.0 ** (1.0 / 3.0) + 9.0 ** (1.0 / 3.0)) * np.sqrt(3.0) / 60.0
_CNO = _ALPH**2 + _BETA**2
U1 = 1.0 / _U1
ALPH = _ALPH / _CNO
BETA = _BETA / _CNO
T11, T12, T13 = 9.1232394870892942792e-02, -0.14125529502095420843, -3.0029194105147424492e-02
T21, T22, T23 = 0.24171793270710701896, 0.20412935229379993199, 0.38294211275726193779
T31 = 0.96604818261509293619
TI11, TI12, TI13 = 4.3255798900631553510, 0.33919925181580986954, 0.54177053993587487119
TI21, TI22, TI23 = -4.1787185915519047273, -0.32768282076106238708, 0.47662355450055045196
TI31, TI32, TI33 = -0.50287263494578687595, 2.5719269498556054292, -0.59603920482822492497

NIT = 7  # Newton iterations per step at most
THET = 0.001  # keep the Jacobian while θ ≤ THET
# ... or while θ ≤ THET_COSTLY where a Jacobian costs many right-hand sides: Hairer's advice
# (RADAU5, WORK(3): "increase to 0.1 say when Jacobian evaluations are costly"), for a system with
# a transient jfo film (eleven film steps per Jacobian [T346]); measured in [T349]
THET_COSTLY = 0.03
QUOT1, QUOT2 = 1.0, 1.2  # keep h (and the LU) if h_new/h is in [QUOT1, QUOT2]
SAFE = 0.9
# h_new ∈ [h/5, 2h]: RADAU5 allows 8h; measured on the c = 0.05 mm film, growth beyond 2h mostly
# ran into Newton failures (13 % fewer RHS at rtol 1e-8, same error; c = 0.5 mm unchanged) [T114]
FACL, FACR = 5.0, 0.5
UROUND = 2.220446049250313e-16

# its own slots of Work.ctl (initial values in RADAU5.ctl) and Work.ictl (RADAU5.ictl); the LU
# is valid for the step size ctl[H_LU] and the Jacobian number ictl[LU_JAC] (Work.stats[3])
H_LU, THETA, FACCON, H_OLD, H_ACC, ERR_ACC, NEWT, HHFAC, THET_JAC = range(CTL0, CTL0 + 9)
REJECTED, HAVE_CONT, LU_JAC = range(ICTL0, ICTL0 + 3)
# Work.K rows: Z1–Z3 (0–2), F1–F3 (3–5), collocation polynomial of the last step (6–8)


def tolerances(rtol, atol):
    """The tolerances of the error test: the user's, unchanged [T114]. (RADAU5 maps rtol to
    0.1·rtol^(2/3); measured on the lubricated slider-crank, that made rtol = 1e-8 as loose as
    4.6e-7 and the crank moment 8× less accurate than scipy's Radau at rtol = 1e-7, which does
    not map.)"""
    return rtol, atol


@njit(cache=True)
def _factor(h, w):
    """LU of the two iteration matrices in the reduced (n×n, n = nn/2) form [T181]: with
    J = [[0, I], [A, B]] (f = [q̇, q̈]), σI − J is solved through σI − B − A/σ, for the real
    σ = γ̂/h (W1) and the complex σ = (α + iβ)/h (W2) — RADAU5's second-order structure (its M1
    option); an 8th of the LU flops of the nn×nn form."""
    Jm, W1, W2 = w.Jm, w.W1, w.W2
    n = W1.shape[0]
    fac1 = U1 / h
    isig1 = 1.0 / fac1
    sig = complex(ALPH / h, BETA / h)
    isig = 1.0 / sig
    for i in range(n):
        for j in range(n):
            a = Jm[n + i, j]
            b = Jm[n + i, n + j]
            W1[i, j] = -b - a * isig1
            W2[i, j] = -b - a * isig
        W1[i, i] += fac1
        W2[i, i] += sig
    return lu_factor(W1, w.piv) and lu_factor(W2, w.piv2)


@njit(cache=True)
def _solve(Jm, W, piv, sig, r):
    """(σI − J) z = r in place (r → z, length nn, real or complex) with the LU of
    σI − B − A/σ [T181]: σx − v = r₁, −Ax + (σ − B)v = r₂ ⇒ (σ − B − A/σ)v = r₂ + A r₁/σ,
    x = (r₁ + v)/σ."""
    n = W.shape[0]
    isig = 1.0 / sig
    for i in range(n):
        s = 0.0 * r[0]
        for j in range(n):
            s += Jm[n + i, j] * r[j]
        r[n + i] += s * isig
    lu_solve(W, piv, r[n:])
    for i in range(n):
        r[i] = (r[i] + r[n + i]) * isig


@njit(cache=True)
def attempt_radau5(t, h, P, w, rtol, atol):
    """One trial step (rtol, atol already mapped by :func:`tolerances`). Returns (0, err),
    (1, inf) singular, (2, inf) failed right-hand side, (3, inf) Newton failure (h factor in
    w.ctl[HHFAC])."""
    y, y1, mem, K, ctl, ictl = w.y, w.y1, w.mem, w.K, w.ctl, w.ictl
    nn = y.shape[0]
    scal, ysc = w.err, w.ysc
    for i in range(nn):
        scal[i] = atol + rtol * (ysc[i] if ysc[i] > 0.0 else abs(y[i]))  # [T114], [T186]
    if ctl[H_LU] != h or ictl[LU_JAC] != w.stats[3]:  # a new step size or a new Jacobian
        w.stats[4] += 1
        if not _factor(h, w):
            ctl[H_LU] = -1.0
            return 1, np.inf
        ctl[H_LU] = h
        ictl[LU_JAC] = w.stats[3]
    fac1 = U1 / h
    alphn = ALPH / h
    betan = BETA / h
    fnewt = max(10.0 * UROUND / rtol, min(0.03, rtol**0.5))
    Z1, Z2, Z3, F1, F2, F3 = K[0], K[1], K[2], K[3], K[4], K[5]
    # starting values: extrapolated collocation polynomial of the previous step
    if ictl[HAVE_CONT] == 1:
        c3q = h / ctl[H_OLD]
        c1q = C1 * c3q
        c2q = C2 * c3q
        for i in range(nn):
            ak1, ak2, ak3 = K[6, i], K[7, i], K[8, i]
            z1 = c1q * (ak1 + (c1q - C2M1) * (ak2 + (c1q - C1M1) * ak3))
            z2 = c2q * (ak1 + (c2q - C2M1) * (ak2 + (c2q - C1M1) * ak3))
            z3 = c3q * (ak1 + (c3q - C2M1) * (ak2 + (c3q - C1M1) * ak3))
            Z1[i], Z2[i], Z3[i] = z1, z2, z3
            F1[i] = TI11 * z1 + TI12 * z2 + TI13 * z3
            F2[i] = TI21 * z1 + TI22 * z2 + TI23 * z3
            F3[i] = TI31 * z1 + TI32 * z2 + TI33 * z3
    else:
        for i in range(nn):
            Z1[i] = Z2[i] = Z3[i] = F1[i] = F2[i] = F3[i] = 0.0
    yt, fw = w.yt, w.fw
    a1, a2, a3 = w.work, w.gk, w.ft  # scratch (ft is not used by radau5)
    r2 = w.cz
    sig2 = complex(alphn, betan)
    faccon = max(ctl[FACCON], UROUND) ** 0.8  # RADAU5: at the start of every Newton loop
    theta = ctl[THET_JAC]  # RADAU5: a step that converges in one iteration keeps the Jacobian
    dynold = 1.0
    thqold = 1.0
    newt = 0
    while True:
        if newt >= NIT:
            ctl[HHFAC] = 0.5
            return 3, np.inf
        bad = 0
        for i in range(nn):
            yt[i] = y[i] + Z1[i]
        bad |= rhs(t + C1 * h, yt, mem, P, a1)
        for i in range(nn):
            yt[i] = y[i] + Z2[i]
        bad |= rhs(t + C2 * h, yt, mem, P, a2)
        for i in range(nn):
            yt[i] = y[i] + Z3[i]
        bad |= rhs(t + h, yt, mem, P, a3)
        w.stats[0] += 3
        if bad != 0:
            return 2, np.inf
        newt += 1
        w.stats[5] += 1
        dyno = 0.0
        for i in range(nn):
            g1 = TI11 * a1[i] + TI12 * a2[i] + TI13 * a3[i] - F1[i] * fac1
            g2 = TI21 * a1[i] + TI22 * a2[i] + TI23 * a3[i] - F2[i] * alphn + F3[i] * betan
            g3 = TI31 * a1[i] + TI32 * a2[i] + TI33 * a3[i] - F3[i] * alphn - F2[i] * betan
            Z1[i] = g1
            r2[i] = complex(g2, g3)
        _solve(w.Jm, w.W1, w.piv, fac1, Z1)
        _solve(w.Jm, w.W2, w.piv2, sig2, r2)
        for i in range(nn):
            Z2[i] = r2[i].real
            Z3[i] = r2[i].imag
            dyno += (Z1[i] / scal[i]) ** 2 + (Z2[i] / scal[i]) ** 2 + (Z3[i] / scal[i]) ** 2
        dyno = np.sqrt(dyno / (3 * nn))
        if not np.isfinite(dyno):
            return 2, np.inf
        if newt > 1 and newt < NIT:
            thq = dyno / dynold
            theta = thq if newt == 2 else np.sqrt(thq * thqold)
            thqold = thq
            if theta < 0.99:
                faccon = theta / (1.0 - theta)
                dyth = faccon * dyno * theta ** (NIT - 1 - newt) / fnewt
                if dyth >= 1.0:  # will not converge in time: smaller step
                    qnewt = max(1e-4, min(20.0, dyth))
                    ctl[HHFAC] = 0.8 * qnewt ** (-1.0 / (4.0 + NIT - 1 - newt))
                    ctl[THETA] = theta
                    ctl[FACCON] = faccon
                    return 3, np.inf
            else:
                ctl[HHFAC] = 0.5
                ctl[THETA] = theta
                return 3, np.inf
        dynold = max(dyno, UROUND)
        for i in range(nn):
            F1[i] += Z1[i]
            F2[i] += Z2[i]
            F3[i] += Z3[i]
            Z1[i] = T11 * F1[i] + T12 * F2[i] + T13 * F3[i]
            Z2[i] = T21 * F1[i] + T22 * F2[i] + T23 * F3[i]
            Z3[i] = T31 * F1[i] + F2[i]
        if faccon * dyno <= fnewt:
            break
    ctl[FACCON] = faccon
    ctl[THETA] = theta
    ctl[NEWT] = newt
    # error estimate (Hairer & Wanner IV.8, (8.19)–(8.20)): E1 err = f0 + Σ (dd_i/h) Z_i
    err = a1
    hee1, hee2, hee3 = DD1 / h, DD2 / h, DD3 / h
    for i in range(nn):
        a2[i] = hee1 * Z1[i] + hee2 * Z2[i] + hee3 * Z3[i]
        err[i] = a2[i] + w.f0[i]
        y1[i] = y[i] + Z3[i]
    _solve(w.Jm, w.W1, w.piv, fac1, err)
    en = _rms(err, scal)
    if en >= 1.0 and (w.stats[1] == 0 or ictl[REJECTED] == 1):
        for i in range(nn):
            yt[i] = y[i] + err[i]
        if rhs(t, yt, mem, P, fw) != 0:
            return 2, np.inf
        w.stats[0] += 1
        for i in range(nn):
            err[i] = fw[i] + a2[i]
        _solve(w.Jm, w.W1, w.piv, fac1, err)
        en = _rms(err, scal)
    return 0, max(en, 1e-10)


@njit(cache=True)
def _rms(e, scal):
    s = 0.0
    for i in range(e.shape[0]):
        s += (e[i] / scal[i]) ** 2
    return np.sqrt(s / e.shape[0])


@njit(cache=True)
def _quot(en, ctl):
    fac = min(SAFE, SAFE * (1.0 + 2.0 * NIT) / (ctl[NEWT] + 2.0 * NIT))
    return max(FACR, min(FACL, en**0.25 / fac))


@njit(cache=True)
def rejected(res, h, en, ctl, ictl, stats, reuse):
    """Stepper hook: after a Newton failure h ← h·HHFAC (set by the attempt), after an error-test
    failure h ← h/quot (h/10 before the first accepted step); a Jacobian that is not fresh is
    renewed (not after a singular matrix, whose h the loop halved)."""
    if res == ATTEMPT_DIVERGED:
        stats[6] += 1
        h *= ctl[HHFAC]
        ictl[REJECTED] = 1
    elif res == ATTEMPT_OK:
        ictl[REJECTED] = 1
        h = 0.1 * h if stats[1] == 0 else h / _quot(en, ctl)
    if res != ATTEMPT_SINGULAR and ictl[AGE] > 0:
        ictl[AGE] = reuse
    return h


@njit(cache=True)
def accepted(h, h_prop, hmax, en, ctl, ictl, stats, reuse):
    """Stepper hook: new h after an accepted step (Gustafsson's predictive controller), and the
    Jacobian / LU reuse decision of RADAU5."""
    quot = _quot(en, ctl)
    if stats[1] > 1:
        facgus = (ctl[H_ACC] / h) * (en**2 / ctl[ERR_ACC]) ** 0.25 / SAFE
        quot = max(quot, max(FACR, min(FACL, facgus)))
    ctl[H_ACC] = h
    ctl[ERR_ACC] = max(1e-2, en)
    hnew = min(h / quot, hmax)
    if ictl[REJECTED] == 1:
        hnew = min(hnew, h)
    ictl[REJECTED] = 0
    qt = hnew / h
    if ctl[THETA] <= ctl[THET_JAC] and QUOT1 <= qt <= QUOT2:
        hnew = h  # keep h: the LU stays valid
    if ctl[THETA] > ctl[THET_JAC]:
        ictl[AGE] = reuse  # a new Jacobian before the next step
    return hnew


@njit(cache=True)
def dense(t, t_new, y, f0, y1, K, mem, ctl, ictl, t_out, iout, Y, MEM):
    """Stepper hook: the collocation polynomial of the accepted step (also the next Newton
    start), then the outputs in (t, t_new] from it (order 3 uniformly) [T113]; returns the next
    output index."""
    h = t_new - t
    for i in range(K.shape[1]):
        z1, z2, z3 = K[0, i], K[1, i], K[2, i]
        K[6, i] = (z2 - z3) / C2M1
        ak = (z1 - z2) / C1MC2
        acont3 = (ak - z1 / C1) / C2
        K[7, i] = (ak - K[6, i]) / C1M1
        K[8, i] = K[7, i] - acont3
    ctl[H_OLD] = h
    ictl[HAVE_CONT] = 1
    while iout < t_out.shape[0] and t_out[iout] <= t_new + 1e-15 * abs(t_new):
        s = min(max((t_out[iout] - t_new) / h, -1.0), 0.0) if h > 0 else 0.0
        for i in range(y1.shape[0]):
            Y[iout, i] = y1[i] + s * (K[6, i] + (s - C2M1) * (K[7, i] + (s - C1M1) * K[8, i]))
        copy_matrix(MEM[iout], mem)
        iout += 1
    return iout


def costly_jacobian(w) -> None:
    """Keep the Jacobian of the work ``w`` while θ ≤ ``THET_COSTLY`` instead of ``THET`` [T349]."""
    w.ctl[THET_JAC] = THET_COSTLY


# The Jacobian is kept until the Newton contraction asks for a new one (accepted), so its
# reuse count never runs out; with the exact Jacobian it is taken right after the accepted step
# and gives f(t, y) [T185]. θ, the Newton factor and the previous h start at 1, the LU at none.
RADAU5 = Stepper(
    "radau5",
    5,
    attempt_radau5,
    rejected,
    accepted,
    dense,
    stiff=True,
    reuse=(1 << 60, 1 << 60),
    jacobian_at_accept=True,
    ctl=(-1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, THET),
    ictl=(0, 0, -1),
    tolerances=tolerances,
    stats=("lu_pairs", "newton_iterations", "newton_failures"),
)
