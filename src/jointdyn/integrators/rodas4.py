"""Compiled Rodas4: L-stable, stiffly accurate Rosenbrock method of order 4(3) [T13].

Hairer & Wanner, *Solving ODEs II* (1996), §IV.7, coefficients of RODAS (their Table 7.2,
"transformed" form as in the RODAS code). Each step solves with W = I/(hγ) − J:

    W k_i = f(t + c_i h, y + Σ_j a_ij k_j) + Σ_j (C_ij / h) k_j + h d_i f_t,
    y₁ = y + Σ_{j≤5} a_6j k_j + k_6,   error estimate k_6.

J = ∂f/∂y and f_t are forward differences of the compiled right-hand side, recomputed every
step (2n + 1 extra evaluations for n = dim y); W is factorised once per step (dense LU with
partial pivoting). This is the integrator for stiff film and contact phases.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..dynamics import rhs
from ..forces.elements import onset_fraction, step_limit
from .common import MAX_STEPS, OK, RHS_FAILED, STEP_TOO_SMALL, accept_hooks, error_norm, start_outputs

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
def write_dense_rodas(t0, y0, t1, y1, K, mem, t_out, iout, Y, MEM):
    """Write every output time in (t0, t1] with the stiffly accurate continuous extension [T13]."""
    h = t1 - t0
    nn = y0.shape[0]
    while iout < t_out.shape[0] and t_out[iout] <= t1 + 1e-15 * abs(t1):
        th = min(max((t_out[iout] - t0) / h, 0.0), 1.0) if h > 0 else 1.0
        for i in range(nn):
            d1 = 0.0
            d2 = 0.0
            for j in range(5):
                d1 += H[0, j] * K[j, i]
                d2 += H[1, j] * K[j, i]
            Y[iout, i] = (1.0 - th) * y0[i] + th * (y1[i] + (1.0 - th) * (d1 + th * d2))
        MEM[iout] = mem
        iout += 1
    return iout


@njit(cache=True)
def jacobian(t, y, f0, mem, P, Jm, ft, work, fw):
    """Forward-difference ∂f/∂y (columns) and ∂f/∂t. Returns the number of evaluations."""
    nn = y.shape[0]
    n = nn // 2
    eps = 1.4901161193847656e-08
    bad = 0
    for j in range(nn):
        scale = abs(y[j])
        if j >= n:
            scale = max(scale, 1e-3)
        else:
            scale = max(scale, 1e-5)
        d = eps * scale
        work[:] = y
        work[j] += d
        bad |= rhs(t, work, mem, P, fw)
        for i in range(nn):
            Jm[i, j] = (fw[i] - f0[i]) / d
    dt = eps * max(abs(t), 1e-3)
    bad |= rhs(t + dt, y, mem, P, fw)
    for i in range(nn):
        ft[i] = (fw[i] - f0[i]) / dt
    return bad


@njit(cache=True)
def rodas4(P, y0, mem0, t0, t_out, rtol, atol, h0, hmax, max_steps, do_project):
    """Integrate from t0 to t_out[-1]; returns (Y, MEM, n_written, stats, status, t_reached, h_next,
    y_final, mem_final).

    stats = [rhs evaluations, accepted steps, rejected steps, Jacobian evaluations]."""
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
    K = np.zeros((6, nn))
    Jm = np.empty((nn, nn))
    W = np.empty((nn, nn))
    piv = np.zeros(nn, dtype=np.int64)
    f0 = np.empty(nn)
    ft = np.empty(nn)
    yt = np.empty(nn)
    y1 = np.empty(nn)
    fw = np.empty(nn)
    work = np.empty(nn)
    st = accept_hooks(t, y, mem, P, do_project)
    if st != OK:
        return Y, MEM, iout, stats, st, t, h, y, mem
    if rhs(t, y, mem, P, f0) != 0:
        return Y, MEM, iout, stats, RHS_FAILED, t, h, y, mem
    stats[0] += 1
    hmin = 1e-14 * max(1.0, abs(t_end))
    need_jac = True
    fail_status = OK
    while t < t_end:
        if stats[1] + stats[2] >= max_steps:
            return Y, MEM, iout, stats, MAX_STEPS, t, h, y, mem
        if need_jac:
            if jacobian(t, y, f0, mem, P, Jm, ft, work, fw) != 0:
                return Y, MEM, iout, stats, RHS_FAILED, t, h, y, mem
            stats[0] += nn + 1
            stats[3] += 1
            need_jac = False
        h = min(h, hmax, step_limit(y[:n], y[n:], mem, P[4], P[5]))
        h_prop = h
        if t + h >= t_end - 1e-14 * abs(t_end):
            h = t_end - t
        if h < hmin:
            return Y, MEM, iout, stats, STEP_TOO_SMALL if fail_status == OK else fail_status, t, h, y, mem
        inv = 1.0 / (h * GAMMA)
        for i in range(nn):
            for j in range(nn):
                W[i, j] = -Jm[i, j]
            W[i, i] += inv
        if not lu_factor(W, piv):
            stats[2] += 1
            h *= 0.5
            continue
        bad = 0
        for s in range(6):
            if s == 0:
                fw[:] = f0
            else:
                for i in range(nn):
                    acc = y[i]
                    for j in range(s):
                        acc += A[s, j] * K[j, i]
                    yt[i] = acc
                bad |= rhs(t + CT[s] * h, yt, mem, P, fw)
                stats[0] += 1
            for i in range(nn):
                acc = fw[i] + h * D[s] * ft[i]
                for j in range(s):
                    acc += C[s, j] / h * K[j, i]
                K[s, i] = acc
            lu_solve(W, piv, K[s])
        for i in range(nn):
            y1[i] = yt[i] + K[5, i]
        if bad != 0:
            stats[2] += 1
            fail_status = RHS_FAILED
            h *= 0.25
            continue
        en = error_norm(K[5], y, y1, rtol, atol)
        if not np.isfinite(en):
            stats[2] += 1
            fail_status = RHS_FAILED
            h *= 0.25
            continue
        if en > 1.0:
            stats[2] += 1
            h *= max(0.2, 0.9 * en**-0.25)
            continue
        frac = onset_fraction(y[:n], y[n:], y1[:n], y1[n:], mem, P[4], P[5])
        if frac < 1.0:
            stats[2] += 1
            h *= max(frac, 0.01)
            continue
        fail_status = OK
        t_new = t + h
        iout = write_dense_rodas(t, y, t_new, y1, K, mem, t_out, iout, Y, MEM)
        y[:] = y1
        t = t_new
        stats[1] += 1
        st = accept_hooks(t, y, mem, P, do_project)
        if st != OK:
            return Y, MEM, iout, stats, st, t, h, y, mem
        if rhs(t, y, mem, P, f0) != 0:
            return Y, MEM, iout, stats, RHS_FAILED, t, h, y, mem
        stats[0] += 1
        need_jac = True
        h *= min(6.0, max(0.2, 0.9 * max(en, 1e-10) ** -0.25))
    if iout == nout:
        Y[nout - 1] = y
        MEM[nout - 1] = mem
    return Y, MEM, iout, stats, OK, t, h_prop, y, mem
