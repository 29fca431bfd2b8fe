"""Compiled ROS34PW2: a Rosenbrock-W method of order 3(2), L-stable and stiffly accurate, that
stays of order 3 with an *approximate* Jacobian [T18]. Rang & Angermann, BIT 45 (2005) 761.

Hairer's form with W = I − γhJ:  W k_i = h f(t + c_i h, y + Σ a_ij k_j) + hJ Σ γ_ij k_j + h²d_i f_t,
y₁ = y + Σ b_i k_i, error Σ (b_i − b̂_i) k_i. Because the order does not rely on J being exact,
the forward-difference Jacobian is reused for up to ``REUSE`` accepted steps (recomputed at once
after a rejection): ≈ 6 RHS evaluations per step instead of Rodas4's ≈ 25. With the exact
Jacobian (the default) a fresh one is taken every step (``REUSE_EXACT``, [T117]). Steps land on the
output times (no dense output: interpolated states of a stiff film give wrong forces).
:data:`ROS34PW2` is the method's record for the shared step loop [T230].
"""

from __future__ import annotations

import numpy as np
from numba import njit

from jointdyn.core.arrays import copy_vector
from jointdyn.integrators.common import error_norm_scaled
from jointdyn.integrators.driver import AGE, ATTEMPT_BAD, ATTEMPT_OK, ATTEMPT_SINGULAR, CTL0, Stepper
from jointdyn.integrators.rodas4 import lu_factor, lu_solve
from jointdyn.multibody.dynamics import rhs

GAMMA = 4.3586652150845900e-01
A = np.array(
    [
        [0.0, 0.0, 0.0],
        [8.7173304301691801e-01, 0.0, 0.0],
        [8.4457060015369423e-01, -1.1299064236397981e-01, 0.0],
        [0.0, 0.0, 1.0],
    ]
)
G = np.array(
    [
        [0.0, 0.0, 0.0],
        [-8.7173304301691801e-01, 0.0, 0.0],
        [-9.0338057013044082e-01, 5.4180672388095326e-02, 0.0],
        [2.4212380706095346e-01, -1.2232505839045147e00, 5.4526025533510214e-01],
    ]
)
B = np.array([2.4212380706095346e-01, -1.2232505839045147e00, 1.5452602553351023e00, 4.3586652150845900e-01])
BH = np.array([3.7810903145819369e-01, -9.6042292212423178e-02, 5.0e-01, 2.1793326075422950e-01])
CT = np.array([0.0, A[1, 0], A[2, 0] + A[2, 1], 1.0])
D = np.array([GAMMA, GAMMA + G[1, 0], GAMMA + G[2, 0] + G[2, 1], GAMMA + G[3, 0] + G[3, 1] + G[3, 2]])
REUSE = 10  # accepted steps a forward-difference Jacobian is kept
# with the exact Jacobian a fresh one every step: measured 2× less wall time at equal accuracy
# than reusing it for 10 steps (python -m benchmarks.work_precision, [T117])
REUSE_EXACT = 1
E_PREV = CTL0  # its own slot of Work.ctl: the previous error norm (PI controller)


@njit(cache=True)
def attempt_ros34pw2(t, h, P, w, rtol, atol):
    """One trial step from (t, w.y) with f0 = w.f0 and the (possibly old) Jacobian in w.Jm,
    w.ft to w.y1. Returns (0, error norm), (1, inf) if W is singular, (2, inf) if a right-hand
    side failed."""
    y, y1, yt, fw, gk, err, mem = w.y, w.y1, w.yt, w.fw, w.gk, w.err, w.mem
    K, W, Jm, piv, ft = w.K, w.W, w.Jm, w.piv, w.ft
    nn = y.shape[0]
    for i in range(nn):
        for j in range(nn):
            W[i, j] = -GAMMA * h * Jm[i, j]
        W[i, i] += 1.0
    if not lu_factor(W, piv):
        return 1, np.inf
    bad = 0
    for s in range(4):
        for i in range(nn):
            acc = y[i]
            g = 0.0
            for j in range(s):
                acc += A[s, j] * K[j, i]
                g += G[s, j] * K[j, i]
            yt[i] = acc
            gk[i] = g
        if s == 0:
            copy_vector(fw, w.f0)
        else:
            bad |= rhs(t + CT[s] * h, yt, mem, P, fw)
            w.stats[0] += 1
        for i in range(nn):
            acc = h * fw[i] + h * h * D[s] * ft[i]
            for j in range(nn):
                acc += h * Jm[i, j] * gk[j]
            K[s, i] = acc
        lu_solve(W, piv, K[s])
    for i in range(nn):
        y1[i] = y[i] + B[0] * K[0, i] + B[1] * K[1, i] + B[2] * K[2, i] + B[3] * K[3, i]
        err[i] = (
            (B[0] - BH[0]) * K[0, i]
            + (B[1] - BH[1]) * K[1, i]
            + (B[2] - BH[2]) * K[2, i]
            + (B[3] - BH[3]) * K[3, i]
        )
    if bad != 0:
        return 2, np.inf
    return 0, error_norm_scaled(err, y, y1, rtol, atol, w.ysc)


@njit(cache=True)
def rejected(res, h, en, ctl, ictl, stats, reuse):
    """Stepper hook: after an error-test failure h ← h·max(0.2, 0.8‖err‖^(−1/3)); a Jacobian that
    is not fresh may be the cause of any rejection (renewed; a singular W renews it always)."""
    if res == ATTEMPT_OK:
        h *= max(0.2, 0.8 * en ** (-1.0 / 3.0))
        if ictl[AGE] > 0:
            ictl[AGE] = reuse
    elif res == ATTEMPT_SINGULAR or res == ATTEMPT_BAD:
        ictl[AGE] = reuse
    return h


@njit(cache=True)
def accepted(h, h_prop, hmax, en, ctl, ictl, stats, reuse):
    """Stepper hook: PI controller (Gustafsson; Hairer & Wanner II §IV.8), exponents 0.7/k,
    0.4/k with k = 3, from the step proposed before landing on an output time."""
    e_now = max(en, 1e-10)
    fac = 0.9 * e_now ** (-0.7 / 3.0) * ctl[E_PREV] ** (0.4 / 3.0)
    ctl[E_PREV] = e_now
    return max(h, h_prop) * min(3.0, max(0.2, fac))


# no dense output: every step lands on the next output time
ROS34PW2 = Stepper(
    "ros34pw2", 3, attempt_ros34pw2, rejected, accepted, stiff=True, reuse=(REUSE, REUSE_EXACT), ctl=(1.0,)
)
