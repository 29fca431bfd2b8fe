"""System Jacobian ∂f/∂y of the first-order equations of motion, exact (compiled) [T101–T104].

f(t, y) = [q̇, q̈] with q̈ from M q̈ = Q + Φ_qᵀλ, Φ_q q̈ = γ̂ (:mod:`jointdyn.dynamics`). Differentiating
the saddle-point system at fixed (q̈, λ) gives [T101]

    M dq̈ − Φ_qᵀ dλ = dQ + (∂(Φ_qᵀλ)/∂q) dq,     Φ_q dq̈ = dγ̂ − (∂(Φ_q q̈)/∂q) dq,

solved with the same Schur complement S = Φ_q M⁻¹ Φ_qᵀ as the accelerations. ∂Q comes from the
force elements (:mod:`jointdyn.forces.element_jacobians`), the constraint terms from the row
Hessians of [T102, T103] (revolute, translational; angle rows are linear).
:func:`system_jacobian` has the signature and meaning of ``integrators.rodas4.jacobian``.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .dynamics import accelerations, cholesky_factor, cholesky_substitute
from .forces.element_jacobians import force_jacobian
from .forces.elements import NOUT
from .joints.constraints import (
    ALPHA,
    ANGLE_DRIVER,
    REVOLUTE,
    ROW,
    TRANSLATIONAL,
    eval_constraints,
    translational_frame,
)
from .kinematics import body_state, point_kinematics
from .layout import BODY_I, BODY_J, ETA_I, ETA_J, TYPE, XI_I, XI_J


@njit(cache=True)
def _add_row(Hs, gq, row, bi, bj, lam_r, qdd, qd, Hlam, Dacc, Dvel, Gq, Gqd):
    """Accumulate one constraint row with local Hessian Hs (6×6 over (q_i, q_j)) and ∂γ/∂q_local
    gq (6): Φ_qᵀλ, Φ_q q̈, Φ_q q̇ derivatives and ∂γ/∂q̇ = −2 Hs q̇ [T102]."""
    idx = np.empty(6, dtype=np.int64)
    for a in range(2):
        b = bi if a == 0 else bj
        for s in range(3):
            idx[3 * a + s] = 3 * b + s if b >= 0 else -1
    for a in range(6):
        ia = idx[a]
        if ia < 0:
            continue
        Gq[row, ia] += gq[a]
        for b in range(6):
            ib = idx[b]
            if ib < 0 or Hs[a, b] == 0.0:
                continue
            Hlam[ia, ib] += lam_r * Hs[a, b]
            Dacc[row, ib] += qdd[ia] * Hs[a, b]
            Dvel[row, ib] += qd[ia] * Hs[a, b]
            Gqd[row, ib] += -2.0 * qd[ia] * Hs[a, b]


@njit(cache=True)
def constraint_derivatives(t, q, qd, qdd, lam, cint, creal, Hlam, Dacc, Dvel, Gq, Gqd, gt):
    """Second-order constraint terms at (q, q̇) (arrays zeroed here) [T102, T103]:
    Hlam = ∂(Φ_qᵀλ)/∂q (n×n), Dacc = ∂(Φ_q q̈)/∂q, Dvel = ∂(Φ_q q̇)/∂q, Gq = ∂γ/∂q,
    Gqd = ∂γ/∂q̇ (m×n), gt = −Φ_tt (m) for the drivers (∂Φ_t/∂t = −α)."""
    Hlam[:, :] = 0.0
    Dacc[:, :] = 0.0
    Dvel[:, :] = 0.0
    Gq[:, :] = 0.0
    Gqd[:, :] = 0.0
    gt[:] = 0.0
    Hs = np.zeros((6, 6))
    gq = np.zeros(6)
    for k in range(cint.shape[0]):
        typ = cint[k, TYPE]
        bi = cint[k, BODY_I]
        bj = cint[k, BODY_J]
        r = cint[k, ROW]
        if typ == REVOLUTE:
            pix, piy, six, siy, vix, viy = point_kinematics(q, qd, bi, creal[k, XI_I], creal[k, ETA_I])
            pjx, pjy, sjx, sjy, vjx, vjy = point_kinematics(q, qd, bj, creal[k, XI_J], creal[k, ETA_J])
            wi = body_state(q, qd, bi)[5]
            wj = body_state(q, qd, bj)[5]
            for row in range(2):
                si = six if row == 0 else siy
                sj = sjx if row == 0 else sjy
                Hs[:, :] = 0.0
                gq[:] = 0.0
                Hs[2, 2] = -si  # ∂²(A s′)/∂φ² = −A s′  [T102]
                Hs[5, 5] = sj
                # γ = ω_i² s_i − ω_j² s_j: ∂/∂φ = ω² ẑ × s  [T102]
                gq[2] = wi * wi * (-siy if row == 0 else six)
                gq[5] = -wj * wj * (-sjy if row == 0 else sjx)
                _add_row(Hs, gq, r + row, bi, bj, lam[r + row], qdd, qd, Hlam, Dacc, Dvel, Gq, Gqd)
        elif typ == TRANSLATIONAL:
            six, siy, sjx, sjy, wi, wj, nx, ny, bnx, bny, dx, dy, ddx, ddy = translational_frame(
                q, qd, bi, bj, creal[k]
            )
            zsix, zsiy = -siy, six  # ẑ × s_i
            zsjx, zsjy = -sjy, sjx
            Hs[:, :] = 0.0
            # Hessian of Φ₁ = nᵀd over (r_i, φ_i, r_j, φ_j)  [T103]
            Hs[3, 2] = Hs[2, 3] = bnx
            Hs[4, 2] = Hs[2, 4] = bny
            Hs[0, 2] = Hs[2, 0] = -bnx
            Hs[1, 2] = Hs[2, 1] = -bny
            Hs[5, 5] = -(nx * sjx + ny * sjy)
            Hs[2, 5] = Hs[5, 2] = bnx * zsjx + bny * zsjy
            Hs[2, 2] = -(nx * dx + ny * dy) - 2.0 * (bnx * zsix + bny * zsiy) + (nx * six + ny * siy)
            # ∂γ₁/∂q  [T103]
            gq[0] = -wi * wi * nx
            gq[1] = -wi * wi * ny
            gq[3] = wi * wi * nx
            gq[4] = wi * wi * ny
            gq[5] = (wi * wi + wj * wj) * (nx * zsjx + ny * zsjy) + 2.0 * wi * wj * (bnx * sjx + bny * sjy)
            gq[2] = (
                wi * wi * (bnx * dx + bny * dy)
                - 2.0 * wi * wi * (nx * zsix + ny * zsiy)
                + 2.0 * wi * (nx * ddx + ny * ddy)
                - 3.0 * wi * wi * (bnx * six + bny * siy)
            )
            _add_row(Hs, gq, r, bi, bj, lam[r], qdd, qd, Hlam, Dacc, Dvel, Gq, Gqd)
        elif typ == ANGLE_DRIVER:
            gt[r] = creal[k, ALPHA]  # −Φ_tt = α  [T7]


@njit(cache=True)
def system_jacobian(t, y, f0, mem, P, Jm, ft, work, fw):
    """Exact Jm = ∂f/∂y (2n×2n) and ft = ∂f/∂t at (t, y) [T101–T104]; same signature and meaning
    as ``integrators.rodas4.jacobian`` (f0, work, fw are unused/scratch). Costs one force
    evaluation (for λ, q̈) plus the element Jacobians. Returns a status (0 = ok)."""
    minv, cint, creal, fint, freal, tables = P.minv, P.cint, P.creal, P.fint, P.freal, P.tables
    m = P.n_rows
    stab = P.stab
    nn = y.shape[0]
    n = nn // 2
    q = y[:n].copy()
    qd = y[n:].copy()
    qdd = np.empty(n)
    lam = np.zeros(max(m, 1))
    eout = np.zeros((fint.shape[0], NOUT))
    status = accelerations(t, q, qd, mem, P, qdd, lam, eout)
    if status != 0:
        return status
    dQdq = np.empty((n, n))
    dQdqd = np.empty((n, n))
    dQdt = np.empty(n)
    force_jacobian(t, q, qd, mem, fint, freal, tables, dQdq, dQdqd, dQdt, P.kinds)
    # G = [∂Q/∂q + ∂(Φ_qᵀλ)/∂q, ∂Q/∂q̇, ∂Q/∂t]  (n × (2n+1))
    G = np.zeros((n, nn + 1))
    G[:, :n] = dQdq
    G[:, n:nn] = dQdqd
    G[:, nn] = dQdt
    if m > 0:
        Phi = np.empty(m)
        J = np.empty((m, n))
        Phit = np.empty(m)
        gam = np.empty(m)
        eval_constraints(t, q, qd, cint, creal, Phi, J, Phit, gam)
        Hlam = np.empty((n, n))
        Dacc = np.empty((m, n))
        Dvel = np.empty((m, n))
        Gq = np.empty((m, n))
        Gqd = np.empty((m, n))
        gt = np.empty(m)
        constraint_derivatives(t, q, qd, qdd, lam, cint, creal, Hlam, Dacc, Dvel, Gq, Gqd, gt)
        G[:, :n] += Hlam
        # Hc = ∂γ̂ − ∂(Φ_q q̈)/∂q dq, γ̂ = γ − 2a(Φ_q q̇ + Φ_t) − a²Φ  [T104]
        a = stab[0]
        Hc = np.zeros((m, nn + 1))
        for r in range(m):
            for c in range(n):
                Hc[r, c] = Gq[r, c] - 2.0 * a * Dvel[r, c] - a * a * J[r, c] - Dacc[r, c]
                Hc[r, n + c] = Gqd[r, c] - 2.0 * a * J[r, c]
            # ∂γ̂/∂t: γ = α is constant, −2a ∂Φ_t/∂t = 2aα, −a² ∂Φ/∂t = −a²Φ_t
            Hc[r, nn] = 2.0 * a * gt[r] - a * a * Phit[r]
        S = np.empty((m, m))
        for i in range(m):
            for j in range(i, m):
                s = 0.0
                for c in range(n):
                    s += J[i, c] * minv[c] * J[j, c]
                S[i, j] = s
                S[j, i] = s
        if not cholesky_factor(S):
            return 1
        rhs_c = np.empty(m)
        for col in range(nn + 1):
            for r in range(m):
                s = Hc[r, col]
                for c in range(n):
                    s -= J[r, c] * minv[c] * G[c, col]
                rhs_c[r] = s
            cholesky_substitute(S, rhs_c)
            for c in range(n):
                s = G[c, col]
                for r in range(m):
                    s += J[r, c] * rhs_c[r]
                G[c, col] = s
    for i in range(nn):
        for j in range(nn):
            Jm[i, j] = 0.0
    for i in range(n):
        Jm[i, n + i] = 1.0
        ft[i] = 0.0
        for j in range(nn):
            Jm[n + i, j] = minv[i] * G[i, j]
        ft[n + i] = minv[i] * G[i, nn]
    return 0
