"""System Jacobian ∂f/∂y of the first-order equations of motion, exact (compiled) [T101–T104].

f(t, y) = [q̇, q̈] with q̈ from M q̈ = Q + Φ_qᵀλ, Φ_q q̈ = γ̂ (:mod:`jointdyn.multibody.dynamics`). Differentiating
the saddle-point system at fixed (q̈, λ) gives [T101]

    M dq̈ − Φ_qᵀ dλ = dQ + (∂(Φ_qᵀλ)/∂q) dq,     Φ_q dq̈ = dγ̂ − (∂(Φ_q q̈)/∂q) dq,

solved with the same Schur complement S = Φ_q M⁻¹ Φ_qᵀ as the accelerations. ∂Q comes from the
force elements (:mod:`jointdyn.forces.element_jacobians`), the constraint terms from the row
Hessians of [T102, T103] (revolute, translational; angle rows are linear).
:func:`system_jacobian` has the signature and meaning of ``integrators.common.fd_jacobian``.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from jointdyn.core.constraints import (
    ALPHA,
    ANGLE_DRIVER,
    REVOLUTE,
    ROW,
    TRANSLATIONAL,
    eval_constraints_into,
    translational_frame,
)
from jointdyn.core.kinematics import body_state, point_kinematics
from jointdyn.core.layout import BODY_I, BODY_J, ETA_I, ETA_J, TYPE, XI_I, XI_J
from jointdyn.forces.elements import NOUT
from jointdyn.forces.kernel_set import call_jacobian
from jointdyn.multibody.dynamics import accelerations, cholesky_factor, cholesky_substitute


@njit(cache=True)
def _coord(a, bi, bj):
    """Global coordinate of local index a ∈ 0..5 over (q_i, q_j); −1 for the ground."""
    b = bi if a < 3 else bj
    return 3 * b + a % 3 if b >= 0 else -1


@njit(cache=True)
def _add_row(Hs, gq, row, bi, bj, lam_r, qdd, qd, Hlam, Dacc, Dvel, Gq, Gqd):
    """Accumulate one constraint row with local Hessian Hs (6×6 over (q_i, q_j)) and ∂γ/∂q_local
    gq (6): Φ_qᵀλ, Φ_q q̈, Φ_q q̇ derivatives and ∂γ/∂q̇ = −2 Hs q̇ [T102]."""
    for a in range(6):
        ia = _coord(a, bi, bj)
        if ia < 0:
            continue
        Gq[row, ia] += gq[a]
        for b in range(6):
            ib = _coord(b, bi, bj)
            if ib < 0 or Hs[a, b] == 0.0:
                continue
            Hlam[ia, ib] += lam_r * Hs[a, b]
            Dacc[row, ib] += qdd[ia] * Hs[a, b]
            Dvel[row, ib] += qd[ia] * Hs[a, b]
            Gqd[row, ib] += -2.0 * qd[ia] * Hs[a, b]


@njit(cache=True)
def constraint_derivatives(t, q, qd, qdd, lam, cint, creal, Hlam, Dacc, Dvel, Gq, Gqd, gt, Hs, gq):
    """Second-order constraint terms at (q, q̇) (arrays zeroed here) [T102, T103]:
    Hlam = ∂(Φ_qᵀλ)/∂q (n×n), Dacc = ∂(Φ_q q̈)/∂q, Dvel = ∂(Φ_q q̇)/∂q, Gq = ∂γ/∂q,
    Gqd = ∂γ/∂q̇ (m×n), gt = −Φ_tt (m) for the drivers (∂Φ_t/∂t = −α); Hs (6×6), gq (6):
    scratch."""
    Hlam[:, :] = 0.0
    Dacc[:, :] = 0.0
    Dvel[:, :] = 0.0
    Gq[:, :] = 0.0
    Gqd[:, :] = 0.0
    gt[:] = 0.0
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
def jacobian_work_size(n, m, nf):
    """Length of the float scratch array of :func:`system_jacobian_into` (n coordinates, m
    constraint rows, nf force elements)."""
    tail = 4 * m + 5 * m * n + 2 * m * (2 * n + 1) + m * m + 42  # constraint terms, Hs, gq
    return 4 * n + max(m, 1) + nf * NOUT + 3 * n * n + n * (2 * n + 1) + tail


@njit(cache=True)
def system_jacobian(t, y, f0, mem, P, Jm, ft, work, fw):
    """Exact Jm = ∂f/∂y (2n×2n) and ft = ∂f/∂t at (t, y) [T101–T104]; same signature and meaning
    as ``integrators.common.fd_jacobian`` (f0, work, fw are unused). Allocates its scratch; the
    integrators call :func:`system_jacobian_into` with a scratch array they keep. Returns a status
    (0 = ok)."""
    n = y.shape[0] // 2
    return system_jacobian_into(
        t, y, mem, P, Jm, ft, np.empty(jacobian_work_size(n, P.n_rows, P.fint.shape[0]))
    )


@njit(cache=True)
def system_jacobian_into(t, y, mem, P, Jm, ft, jw):
    """:func:`system_jacobian` with the scratch array ``jw`` (length ≥
    :func:`jacobian_work_size`; a shorter one is replaced by a new array). Costs one force
    evaluation (for λ, q̈) plus the element Jacobians; on return jw[2n:3n] holds q̈(t, y), the
    same numbers as ``dynamics.rhs`` (the integrators use it as f(t, y)). Returns a status
    (0 = ok)."""
    minv, cint, creal, fint, freal, tables = P.minv, P.cint, P.creal, P.fint, P.freal, P.tables
    m = P.n_rows
    stab = P.stab
    nn = y.shape[0]
    n = nn // 2
    nf = fint.shape[0]
    need = jacobian_work_size(n, m, nf)
    if jw.shape[0] < need:
        jw = np.empty(need)
    # scratch arrays carved from jw (views, no allocation)
    q = jw[0:n]
    qd = jw[n : 2 * n]
    qdd = jw[2 * n : 3 * n]
    o = 3 * n
    lam = jw[o : o + max(m, 1)]
    o += max(m, 1)
    eout = jw[o : o + nf * NOUT].reshape((nf, NOUT))
    o += nf * NOUT
    dQdq = jw[o : o + n * n].reshape((n, n))
    o += n * n
    dQdqd = jw[o : o + n * n].reshape((n, n))
    o += n * n
    Hlam = jw[o : o + n * n].reshape((n, n))
    o += n * n
    dQdt = jw[o : o + n]
    o += n
    G = jw[o : o + n * (nn + 1)].reshape((n, nn + 1))
    o += n * (nn + 1)
    for i in range(n):
        q[i] = y[i]
        qd[i] = y[n + i]
    lam[:] = 0.0
    status = accelerations(t, q, qd, mem, P, qdd, lam, eout)
    if status != 0:
        return status
    call_jacobian(P.kernels, (t, q, qd, mem, fint, freal, tables, dQdq, dQdqd, dQdt))
    # G = [∂Q/∂q + ∂(Φ_qᵀλ)/∂q, ∂Q/∂q̇, ∂Q/∂t]  (n × (2n+1))
    for i in range(n):
        for j in range(n):
            G[i, j] = dQdq[i, j]
            G[i, n + j] = dQdqd[i, j]
        G[i, nn] = dQdt[i]
    if m > 0:
        Phi = jw[o : o + m]
        Phit = jw[o + m : o + 2 * m]
        gam = jw[o + 2 * m : o + 3 * m]
        gt = jw[o + 3 * m : o + 4 * m]
        o += 4 * m
        J = jw[o : o + m * n].reshape((m, n))
        Dacc = jw[o + m * n : o + 2 * m * n].reshape((m, n))
        Dvel = jw[o + 2 * m * n : o + 3 * m * n].reshape((m, n))
        Gq = jw[o + 3 * m * n : o + 4 * m * n].reshape((m, n))
        Gqd = jw[o + 4 * m * n : o + 5 * m * n].reshape((m, n))
        o += 5 * m * n
        Hc = jw[o : o + m * (nn + 1)].reshape((m, nn + 1))
        o += m * (nn + 1)
        Xt = jw[o : o + m * (nn + 1)].reshape((nn + 1, m))
        o += m * (nn + 1)
        S = jw[o : o + m * m].reshape((m, m))
        o += m * m
        Hs = jw[o : o + 36].reshape((6, 6))
        gq = jw[o + 36 : o + 42]
        cs = P.ws[P.ws.shape[0] - n :]  # the workspace's trig scratch (dynamics._trig_scratch) [T223]
        eval_constraints_into(t, q, qd, cint, creal, Phi, J, Phit, gam, cs)
        constraint_derivatives(t, q, qd, qdd, lam, cint, creal, Hlam, Dacc, Dvel, Gq, Gqd, gt, Hs, gq)
        for i in range(n):
            for j in range(n):
                G[i, j] += Hlam[i, j]
        # Hc = ∂γ̂ − ∂(Φ_q q̈)/∂q dq, γ̂ = γ − 2a(Φ_q q̇ + Φ_t) − a²Φ  [T104]
        a = stab[0]
        for r in range(m):
            for c in range(n):
                Hc[r, c] = Gq[r, c] - 2.0 * a * Dvel[r, c] - a * a * J[r, c] - Dacc[r, c]
                Hc[r, n + c] = Gqd[r, c] - 2.0 * a * J[r, c]
            # ∂γ̂/∂t: γ = α is constant, −2a ∂Φ_t/∂t = 2aα, −a² ∂Φ/∂t = −a²Φ_t
            Hc[r, nn] = 2.0 * a * gt[r] - a * a * Phit[r]
        for i in range(m):
            for j in range(i, m):
                s = 0.0
                for c in range(n):
                    s += J[i, c] * minv[c] * J[j, c]
                S[i, j] = s
                S[j, i] = s
        if not cholesky_factor(S):
            return 1
        # X = S⁻¹(Hc − Φ_q M⁻¹ G), stored transposed (one contiguous row per column of G); then
        # G += Φ_qᵀ X. Rows of Φ_q touch ≤ 6 coordinates: zeros are skipped
        # (the sums keep their order, so the result is the same to the bit).
        for r in range(m):
            for col in range(nn + 1):
                Xt[col, r] = Hc[r, col]
        for r in range(m):
            for c in range(n):
                jm = J[r, c] * minv[c]
                if jm != 0.0:
                    for col in range(nn + 1):
                        Xt[col, r] -= jm * G[c, col]
        for col in range(nn + 1):
            cholesky_substitute(S, Xt[col])
        for c in range(n):
            for r in range(m):
                jrc = J[r, c]
                if jrc != 0.0:
                    for col in range(nn + 1):
                        G[c, col] += jrc * Xt[col, r]
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
