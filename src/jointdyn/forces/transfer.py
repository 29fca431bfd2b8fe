"""Scatter a force pair into the generalised force vector (compiled).

A force **F** applied to body j at a point with arm a_j from its centre of mass, and −**F** to
body i at the same world point (arm a_i from body i's centre), gives
Q_j += [F_x, F_y, a_j × F], Q_i += [−F_x, −F_y, −(a_i × F)] [T8]. Both forces act on the same
line, so the pair has no net moment (Newton's third law, the paper's eqs 20–22 corrected, [T15]).
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def apply_pair(Q, bi, bj, fx, fy, ajx, ajy, aix, aiy):
    """Add **F** on body j (arm a_j) and −**F** on body i (arm a_i) to Q [T8]."""
    if bj >= 0:
        k = 3 * bj
        Q[k] += fx
        Q[k + 1] += fy
        Q[k + 2] += ajx * fy - ajy * fx
    if bi >= 0:
        k = 3 * bi
        Q[k] -= fx
        Q[k + 1] -= fy
        Q[k + 2] -= aix * fy - aiy * fx


@njit(cache=True)
def pair_power(qd, bi, bj, fx, fy, ajx, ajy, aix, aiy):
    """Power the pair delivers to the two bodies, Σ Qᵀq̇ [W] (negative = dissipated)."""
    p = 0.0
    if bj >= 0:
        k = 3 * bj
        p += fx * qd[k] + fy * qd[k + 1] + (ajx * fy - ajy * fx) * qd[k + 2]
    if bi >= 0:
        k = 3 * bi
        p -= fx * qd[k] + fy * qd[k + 1] + (aix * fy - aiy * fx) * qd[k + 2]
    return p


@njit(cache=True)
def pair_jac(DQ, F, DF, ajx, ajy, Daj, aix, aiy, Dai):
    """Add ∂/∂z of the pair transfer [T8, T99] (F on j at arm a_j, −F on i at arm a_i) to DQ (6, 12)."""
    for c in range(12):
        mj = ajx * DF[1, c] - ajy * DF[0, c] + Daj[0, c] * F[1] - Daj[1, c] * F[0]
        mi = aix * DF[1, c] - aiy * DF[0, c] + Dai[0, c] * F[1] - Dai[1, c] * F[0]
        DQ[3, c] += DF[0, c]
        DQ[4, c] += DF[1, c]
        DQ[5, c] += mj
        DQ[0, c] -= DF[0, c]
        DQ[1, c] -= DF[1, c]
        DQ[2, c] -= mi


@njit(cache=True)
def pair_rates(six, siy, sjx, sjy, wi, wj):
    """∂d/∂z and ∂ḋ/∂z (each (2, 12)) of d = P_j − P_i between points on bodies i and j,
    z = (q_i, q_j, q̇_i, q̇_j); s = the points' arms from the body origins [m], w = the bodies'
    angular speeds [rad/s] [T98]."""
    D = np.zeros((2, 12))
    D[0, 0] = -1.0
    D[1, 1] = -1.0
    D[0, 2] = siy
    D[1, 2] = -six
    D[0, 3] = 1.0
    D[1, 4] = 1.0
    D[0, 5] = -sjy
    D[1, 5] = sjx
    Dv = np.zeros((2, 12))
    for k in range(6):
        Dv[0, 6 + k] = D[0, k]
        Dv[1, 6 + k] = D[1, k]
    Dv[0, 2] = wi * six
    Dv[1, 2] = wi * siy
    Dv[0, 5] = -wj * sjx
    Dv[1, 5] = -wj * sjy
    return D, Dv
