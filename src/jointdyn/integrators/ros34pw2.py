"""Compiled ROS34PW2: a Rosenbrock-W method of order 3(2), L-stable and stiffly accurate, that
stays of order 3 with an *approximate* Jacobian [T18]. Rang & Angermann, BIT 45 (2005) 761.

Hairer's form with W = I − γhJ:  W k_i = h f(t + c_i h, y + Σ a_ij k_j) + hJ Σ γ_ij k_j + h²d_i f_t,
y₁ = y + Σ b_i k_i, error Σ (b_i − b̂_i) k_i. Because the order does not rely on J being exact,
the forward-difference Jacobian is reused for up to ``REUSE`` accepted steps (recomputed at once
after a rejection): ≈ 6 RHS evaluations per step instead of Rodas4's ≈ 25. Steps land on the
output times (no dense output: interpolated states of a stiff film give wrong forces).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..dynamics import rhs
from ..forces.elements import onset_fraction, step_limit
from .common import MAX_STEPS, OK, RHS_FAILED, STEP_TOO_SMALL, accept_hooks, error_norm, start_outputs
from .rodas4 import jacobian, lu_factor, lu_solve

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
REUSE = 10


@njit(cache=True)
def ros34pw2(P, y0, mem0, t0, t_out, rtol, atol, h0, hmax, max_steps, do_project):
    """Integrate from t0 to t_out[-1]; same returns as :func:`~.rodas4.rodas4`."""
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
    K = np.zeros((4, nn))
    Jm = np.empty((nn, nn))
    W = np.empty((nn, nn))
    piv = np.zeros(nn, dtype=np.int64)
    f0 = np.empty(nn)
    ft = np.empty(nn)
    yt = np.empty(nn)
    y1 = np.empty(nn)
    fw = np.empty(nn)
    work = np.empty(nn)
    gk = np.empty(nn)
    err = np.empty(nn)
    st = accept_hooks(t, y, mem, P, do_project)
    if st != OK:
        return Y, MEM, iout, stats, st, t, h, y, mem
    if rhs(t, y, mem, P, f0) != 0:
        return Y, MEM, iout, stats, RHS_FAILED, t, h, y, mem
    stats[0] += 1
    hmin = 1e-14 * max(1.0, abs(t_end))
    age = REUSE  # force a Jacobian on the first step
    e_prev = 1.0  # previous accepted error norm (PI step-size control)
    fail_status = OK
    while t < t_end:
        if stats[1] + stats[2] >= max_steps:
            return Y, MEM, iout, stats, MAX_STEPS, t, h, y, mem
        if age >= REUSE:
            if jacobian(t, y, f0, mem, P, Jm, ft, work, fw) != 0:
                return Y, MEM, iout, stats, RHS_FAILED, t, h, y, mem
            stats[0] += nn + 1
            stats[3] += 1
            age = 0
        h = min(h, hmax, step_limit(y[:n], y[n:], mem, P[4], P[5]))
        h_prop = h
        # land on the next output time
        if iout < nout and t + h >= t_out[iout] - 1e-14 * abs(t_out[iout]):
            h = t_out[iout] - t
        if h < hmin:
            return Y, MEM, iout, stats, STEP_TOO_SMALL if fail_status == OK else fail_status, t, h, y, mem
        for i in range(nn):
            for j in range(nn):
                W[i, j] = -GAMMA * h * Jm[i, j]
            W[i, i] += 1.0
        if not lu_factor(W, piv):
            stats[2] += 1
            h *= 0.5
            age = REUSE
            continue
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
                fw[:] = f0
            else:
                bad |= rhs(t + CT[s] * h, yt, mem, P, fw)
                stats[0] += 1
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
        en = error_norm(err, y, y1, rtol, atol) if bad == 0 else np.inf
        if not np.isfinite(en):
            stats[2] += 1
            fail_status = RHS_FAILED
            h *= 0.25
            age = REUSE
            continue
        if en > 1.0:
            stats[2] += 1
            h *= max(0.2, 0.8 * en ** (-1.0 / 3.0))
            if age > 0:  # a stale Jacobian may be the cause: refresh it
                age = REUSE
            continue
        frac = onset_fraction(y[:n], y[n:], y1[:n], y1[n:], mem, P[4], P[5])
        if frac < 1.0:
            stats[2] += 1
            h *= max(frac, 0.01)
            continue
        fail_status = OK
        t_new = t + h
        y[:] = y1
        t = t_new
        stats[1] += 1
        age += 1
        st = accept_hooks(t, y, mem, P, do_project)
        if st != OK:
            return Y, MEM, iout, stats, st, t, h, y, mem
        while iout < nout and t_out[iout] <= t + 1e-14 * abs(t):
            Y[iout] = y
            MEM[iout] = mem
            iout += 1
        if rhs(t, y, mem, P, f0) != 0:
            return Y, MEM, iout, stats, RHS_FAILED, t, h, y, mem
        stats[0] += 1
        # PI controller (Gustafsson; Hairer & Wanner II §IV.8): exponents 0.7/k and 0.4/k, k = 3
        e_now = max(en, 1e-10)
        fac = 0.9 * e_now ** (-0.7 / 3.0) * e_prev ** (0.4 / 3.0)
        e_prev = e_now
        h = max(h, h_prop) * min(3.0, max(0.2, fac))
    return Y, MEM, iout, stats, OK, t, h_prop, y, mem
