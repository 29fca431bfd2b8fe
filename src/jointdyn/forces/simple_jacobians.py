"""Exact Jacobians of the closed-form elements: spring–damper, torsional spring, harmonic torque
and tabulated force [T118].

The first two fill the local (6, 12) block ∂(Q_i, Q_j)/∂z, z = (q_i, q_j, q̇_i, q̇_j), in the layout of
``element_jacobians.journal_jacobian`` (scattered by ``_scatter``, ground columns skipped); the
harmonic torque (∂Q/∂t only) and the tabulated force (whose argument may be the time or any
body's angle) add to the global arrays directly.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from jointdyn.core.kinematics import point_kinematics
from jointdyn.core.layout import ETA_I, ETA_J, XI_I, XI_J
from jointdyn.forces.springs import L0, D, K
from jointdyn.forces.tabulated import ARGUMENT as TARG
from jointdyn.forces.tabulated import DIR_X, DIR_Y, TIME, table_value
from jointdyn.forces.torsion import AMP, K1, K3, OMEGA, PHASE, THETA0, C
from jointdyn.forces.transfer import pair_jac, pair_rates


@njit(cache=True)
def spring_damper_jacobian(q, qd, bi, bj, r, DQ):
    """∂Q/∂z of the point-to-point spring–damper [T9, T118] into DQ (6, 12).

    Returns 0, or 1 at zero length (ℓ = 0: the direction u is undefined, the kernel's guard
    u = x̂ is not differentiable), where the caller uses the finite-difference fallback [T100]."""
    pix, piy, six, siy, vix, viy = point_kinematics(q, qd, bi, r[XI_I], r[ETA_I])
    pjx, pjy, sjx, sjy, vjx, vjy = point_kinematics(q, qd, bj, r[XI_J], r[ETA_J])
    wi = qd[3 * bi + 2] if bi >= 0 else 0.0
    wj = qd[3 * bj + 2] if bj >= 0 else 0.0
    dx = pjx - pix
    dy = pjy - piy
    ell = math.sqrt(dx * dx + dy * dy)
    if ell == 0.0:
        return 1
    ux = dx / ell
    uy = dy / ell
    tx = -uy
    ty = ux
    vx = vjx - vix
    vy = vjy - viy
    # ∂d/∂z and ∂ḋ/∂z, d = P_j − P_i (the same kinematics as the journal's e, [T98])
    Dd, Dv = pair_rates(six, siy, sjx, sjy, wi, wj)
    tv = tx * vx + ty * vy
    elld = ux * vx + uy * vy
    f = -(r[K] * (ell - r[L0]) + r[D] * elld)
    F = np.empty(2)
    F[0] = f * ux
    F[1] = f * uy
    DF = np.empty((2, 12))
    for k in range(12):
        tdd = tx * Dd[0, k] + ty * Dd[1, k]
        dell = ux * Dd[0, k] + uy * Dd[1, k]  # dℓ = u·dd
        delld = tv * tdd / ell + ux * Dv[0, k] + uy * Dv[1, k]  # dℓ̇ = (t·v)(t·dd)/ℓ + u·dv
        df = -(r[K] * dell + r[D] * delld)
        # dF = u df + f du, du = t (t·dd)/ℓ
        DF[0, k] = ux * df + f * tx * tdd / ell
        DF[1, k] = uy * df + f * ty * tdd / ell
    # F on j at arm s_j, −F on i at arm s_i + d [T9, T99]; ∂s/∂φ = ẑ × s
    Dsj = np.zeros((2, 12))
    Dsj[0, 5] = -sjy
    Dsj[1, 5] = sjx
    Dai = np.zeros((2, 12))
    Dai[0, 2] = -siy
    Dai[1, 2] = six
    Dai += Dd
    pair_jac(DQ, F, DF, sjx, sjy, Dsj, six + dx, siy + dy, Dai)
    return 0


@njit(cache=True)
def torsion_spring_jacobian(q, bi, bj, r, DQ):
    """∂Q/∂z of the torsional spring–damper M = −(kθ + k₃θ³) − cθ̇ on j, −M on i [T132, T118]."""
    phi_i = q[3 * bi + 2] if bi >= 0 else 0.0
    phi_j = q[3 * bj + 2] if bj >= 0 else 0.0
    th = phi_j - phi_i - r[THETA0]
    kt = r[K1] + 3.0 * r[K3] * th * th  # ∂M/∂φ_j = −kt, ∂M/∂φ_i = +kt
    for row, sgn in ((5, 1.0), (2, -1.0)):  # Q_j += M, Q_i −= M
        DQ[row, 5] += -sgn * kt
        DQ[row, 2] += sgn * kt
        DQ[row, 11] += -sgn * r[C]
        DQ[row, 8] += sgn * r[C]


@njit(cache=True)
def harmonic_torque_dt(t, bj, r, dQdt):
    """∂Q/∂t of M(t) = A cos(ωt + φ) on body j: −Aω sin(ωt + φ) [T133, T118] (no q, q̇ terms)."""
    if bj >= 0:
        dQdt[3 * bj + 2] += -r[AMP] * r[OMEGA] * math.sin(r[OMEGA] * t + r[PHASE])


@njit(cache=True)
def tabulated_force_jacobian(t, q, qd, bj, ip, r, tab, dQdq, dQdt):
    """∂Q/∂q and ∂Q/∂t of the tabulated force F = f(s)·d on point j [T17, T118], added in place
    (global columns: the argument s may be another body's angle). f′ is the slope of the cell the
    kernel interpolates in (right-hand cell at a node, 0 beyond the table ends); ds/d(arg) = 1
    (the period wrap is piecewise constant). Returns 0."""
    _, f, fp = table_value(t, q, qd, ip, r, tab)
    if bj < 0:
        return 0
    dx = r[DIR_X]
    dy = r[DIR_Y]
    px, py, sx, sy, vx, vy = point_kinematics(q, qd, bj, r[XI_J], r[ETA_J])
    k = 3 * bj
    # arm rotation: ∂(s × F)/∂φ_j = (ẑ × s) × F = −(s · F)
    dQdq[k + 2, k + 2] += -f * (sx * dx + sy * dy)
    # the argument: ∂Q_j/∂s = f′ [d, s × d]
    if ip[TARG] == TIME:
        dQdt[k] += fp * dx
        dQdt[k + 1] += fp * dy
        dQdt[k + 2] += fp * (sx * dy - sy * dx)
    elif ip[TARG] >= 0:
        c = 3 * ip[TARG] + 2
        dQdq[k, c] += fp * dx
        dQdq[k + 1, c] += fp * dy
        dQdq[k + 2, c] += fp * (sx * dy - sy * dx)
    return 0
