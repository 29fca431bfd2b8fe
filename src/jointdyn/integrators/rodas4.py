"""Compiled Rodas4: L-stable, stiffly accurate Rosenbrock method of order 4(3) [T13].

Hairer & Wanner, *Solving ODEs II* (1996), §IV.7, coefficients of RODAS (their Table 7.2,
"transformed" form as in the RODAS code). Each step solves with W = I/(hγ) − J:

    W k_i = f(t + c_i h, y + Σ_j a_ij k_j) + Σ_j (C_ij / h) k_j + h d_i f_t,
    y₁ = y + Σ_{j≤5} a_6j k_j + k_6,   error estimate k_6.

J = ∂f/∂y and f_t are recomputed every step: the exact system Jacobian by default
(``jacobian.system_jacobian_into``), or forward differences of the compiled right-hand side
(``common.fd_jacobian``, 2n + 1 extra evaluations for n = dim y); W is factorised once per step
(dense LU with partial pivoting). :data:`RODAS4` is the method's record for the shared step loop
[T230].

Accuracy on stiff films [T217–T219]: RODAS has stage order 1, and on a stiff element driven by
the slow motion (a small-clearance film) the error of its *force* converges at order 1 in h, not
4; its error estimate measures the state's error, not the force's, so at a given rtol the crank
moment is 60–100× less accurate than radau5's at c = 0.05 mm (measured), and the continuous
extension below adds a factor 2.5–22 between step ends. Use radau5 (or ros34pw2) there; rodas4
is for loose bearings and moderate accuracy.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from jointdyn.core.arrays import copy_matrix, copy_vector
from jointdyn.integrators.common import error_norm_scaled
from jointdyn.integrators.driver import ATTEMPT_OK, Stepper
from jointdyn.multibody.dynamics import rhs

GAMMA = 0.25
A = np.array(
    [
        [0.0, 0.0, 0.0, 0.0, 0.0],
        [1.544, 0.0, 0.0, 0.0, 0.0],
        [0.9466785280815826, 0.2557011698983284, 0.0, 0.0, 0.0],
        [3.314825187068521, 2.896124015972201, 0.9986419139977817, 0.0, 0.0],
        [1.221224509226641, 6.019134481288629, 12.53708332932087, -0.687886036105895, 0.0],
        [1.221224509226641, 6.019134481288629, 12.53708332932087, -0.687886036105895, 1.0],
    ]
)
C = np.array(
    [
        [0.0, 0.0, 0.0, 0.0, 0.0],
        [-5.6688, 0.0, 0.0, 0.0, 0.0],
        [-2.430093356833875, -0.2063599157091915, 0.0, 0.0, 0.0],
        [-0.1073529058151375, -9.594562251023355, -20.47028614809616, 0.0, 0.0],
        [7.496443313967647, -10.24680431464352, -33.99990352819905, 11.7089089320616, 0.0],
        [8.083246795921522, -7.981132988064893, -31.52159432874371, 16.31930543123136, -6.058818238834054],
    ]
)
CT = np.array([0.0, 0.386, 0.21, 0.63, 1.0, 1.0])
# dense output (Hairer & Wanner's RODAS continuous extension, stiffly accurate, order 3):
# y(t + θh) = (1−θ) y₀ + θ [y₁ + (1−θ)(d₁ + θ d₂)], d_r = Σ_j H[r, j] k_j
H = np.array(
    [
        [10.12623508344586, -7.487995877610167, -34.80091861555747, -7.992771707568823, 1.025137723295662],
        [-0.6762803392801253, 6.087714651680015, 16.43084320892478, 24.76722511418386, -6.594389125716872],
    ]
)
D = np.array([0.25, -0.1043, 0.1035, -0.0362, 0.0, 0.0])


@njit(cache=True)
def lu_factor(W, piv):
    """In-place LU with partial pivoting. Returns False if singular."""
    n = W.shape[0]
    for k in range(n):
        p = k
        big = abs(W[k, k])
        for i in range(k + 1, n):
            if abs(W[i, k]) > big:
                big = abs(W[i, k])
                p = i
        if big == 0.0 or not np.isfinite(big):
            return False
        piv[k] = p
        if p != k:
            for j in range(n):
                tmp = W[k, j]
                W[k, j] = W[p, j]
                W[p, j] = tmp
        inv = 1.0 / W[k, k]
        for i in range(k + 1, n):
            W[i, k] *= inv
            f = W[i, k]
            if f != 0.0:
                for j in range(k + 1, n):
                    W[i, j] -= f * W[k, j]
    return True


@njit(cache=True)
def lu_solve(W, piv, b):
    n = W.shape[0]
    for k in range(n):
        p = piv[k]
        if p != k:
            tmp = b[k]
            b[k] = b[p]
            b[p] = tmp
    for i in range(n):
        s = b[i]
        for j in range(i):
            s -= W[i, j] * b[j]
        b[i] = s
    for i in range(n - 1, -1, -1):
        s = b[i]
        for j in range(i + 1, n):
            s -= W[i, j] * b[j]
        b[i] = s / W[i, i]


@njit(cache=True)
def attempt_rodas4(t, h, P, w, rtol, atol):
    """One trial step from (t, w.y) with f0 = w.f0 and the Jacobian in w.Jm, w.ft to w.y1
    (stages in w.K). Returns (0, error norm), (1, inf) if W is singular, (2, inf) if a
    right-hand side failed."""
    y, y1, yt, fw, mem, K, W, Jm, piv, ft = w.y, w.y1, w.yt, w.fw, w.mem, w.K, w.W, w.Jm, w.piv, w.ft
    nn = y.shape[0]
    inv = 1.0 / (h * GAMMA)
    for i in range(nn):
        for j in range(nn):
            W[i, j] = -Jm[i, j]
        W[i, i] += inv
    if not lu_factor(W, piv):
        return 1, np.inf
    bad = 0
    for s in range(6):
        if s == 0:
            copy_vector(fw, w.f0)
        else:
            for i in range(nn):
                acc = y[i]
                for j in range(s):
                    acc += A[s, j] * K[j, i]
                yt[i] = acc
            bad |= rhs(t + CT[s] * h, yt, mem, P, fw)
            w.stats[0] += 1
        for i in range(nn):
            acc = fw[i] + h * D[s] * ft[i]
            for j in range(s):
                acc += C[s, j] / h * K[j, i]
            K[s, i] = acc
        lu_solve(W, piv, K[s])
    for i in range(nn):
        y1[i] = yt[i] + K[5, i]
    if bad != 0:
        return 2, np.inf
    return 0, error_norm_scaled(K[5], y, y1, rtol, atol, w.ysc)


@njit(cache=True)
def rejected(res, h, en, ctl, ictl, stats, reuse):
    """Stepper hook: after an error-test failure h ← h·max(0.2, 0.9‖err‖^(−1/4)) [T110]."""
    if res == ATTEMPT_OK:
        h *= max(0.2, 0.9 * en**-0.25)
    return h


@njit(cache=True)
def accepted(h, h_prop, hmax, en, ctl, ictl, stats, reuse):
    """Stepper hook: the elementary controller h ← h·min(6, max(0.2, 0.9‖err‖^(−1/4))) [T110]."""
    e_now = max(en, 1e-10)
    return h * min(6.0, max(0.2, 0.9 * e_now**-0.25))


@njit(cache=True)
def dense(t, t_new, y0, f0, y1, K, mem, ctl, ictl, t_out, iout, Y, MEM):
    """Stepper hook: outputs in (t, t_new] from the stiffly accurate continuous extension [T13];
    returns the next output index."""
    h = t_new - t
    nn = y0.shape[0]
    while iout < t_out.shape[0] and t_out[iout] <= t_new + 1e-15 * abs(t_new):
        th = min(max((t_out[iout] - t) / h, 0.0), 1.0) if h > 0 else 1.0
        for i in range(nn):
            d1 = 0.0
            d2 = 0.0
            for j in range(5):
                d1 += H[0, j] * K[j, i]
                d2 += H[1, j] * K[j, i]
            Y[iout, i] = (1.0 - th) * y0[i] + th * (y1[i] + (1.0 - th) * (d1 + th * d2))
        copy_matrix(MEM[iout], mem)
        iout += 1
    return iout


# a fresh Jacobian for every step (reuse 1 with either kind); stiff: takes the clearance scales
RODAS4 = Stepper("rodas4", 4, attempt_rodas4, rejected, accepted, dense, stiff=True, reuse=(1, 1))
