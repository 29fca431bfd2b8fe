"""Equations of motion in absolute coordinates (compiled hot path).

For n coordinates q (x, y, φ per body) and m constraint rows:

    M q̈ = Q(t, q, q̇) + Φ_qᵀ λ,    Φ_q q̈ = γ − 2a Φ̇ − a² Φ        [T3, T4, T10]

M is diagonal (centre-of-mass frames), so λ comes from the m×m Schur complement
(Φ_q M⁻¹ Φ_qᵀ) λ = γ̂ − Φ_q M⁻¹ Q, solved by Cholesky, and q̈ = M⁻¹(Q + Φ_qᵀ λ) [T10].
a ≥ 0 is the Baumgarte rate [1/s] (critically damped form, α = a, β = a). The compiled
integrators also project (q, q̇) onto Φ = 0, Φ̇ = 0 after every accepted step [T11].

The packed system ``P`` is a :class:`jointdyn.multibody.system.Packed` named tuple (minv, q0_force, cint,
creal, fint, freal, tables, n_rows, stab, ws) read by field name; ``ws`` is a preallocated
workspace (see :func:`workspace_size`) so that the right-hand side allocates nothing.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from jointdyn.core.arrays import copy_vector
from jointdyn.core.borrowed import borrowed
from jointdyn.core.constraints import eval_constraints, eval_constraints_into
from jointdyn.forces.elements import NOUT
from jointdyn.forces.kernel_set import call_forces
from jointdyn.multibody.cholesky import cholesky_factor, cholesky_solve, cholesky_substitute  # noqa: F401

OK = 0
SINGULAR = 1  # constraint Jacobian lost rank (lock-up or redundant joint)
NONFINITE = 2  # NaN or inf in the accelerations


def workspace_size(n: int, m: int, nf: int) -> int:
    """Length of the float workspace used by :func:`accelerations` and :func:`rhs`; its last n
    entries are the bodies' cos φ, sin φ of a constraint evaluation (:func:`_trig_scratch`)."""
    return n + 3 * m + m * n + m * m + max(m, 1) + nf * NOUT + n


@njit(inline="always")
def _constraint_views(ws, n, m):
    """The workspace's constraint slots (after Q, n entries): Φ, Φ_t, γ (m each), Φ_q (m×n),
    the Schur complement S (m×m) and the m entries after it (λ in :func:`rhs`, scratch in
    :func:`project`) — the one place the layout of :func:`workspace_size` is carved."""
    o = n
    Phi = ws[o : o + m]
    Phit = ws[o + m : o + 2 * m]
    gam = ws[o + 2 * m : o + 3 * m]
    o += 3 * m
    J = ws[o : o + m * n].reshape((m, n))
    o += m * n
    S = ws[o : o + m * m].reshape((m, m))
    o += m * m
    return Phi, Phit, gam, J, S, ws[o : o + m]


@njit(inline="always")
def _trig_scratch(ws, n):
    """The workspace's last n entries: scratch of ``eval_constraints_into`` [T223], which
    nothing reads after the evaluation that wrote it."""
    return ws[ws.shape[0] - n :]


@njit(cache=True)
def _schur_into(S, J, minv, m, n):
    for a in range(m):
        for b in range(a, m):
            s = 0.0
            for c in range(n):
                s += J[a, c] * minv[c] * J[b, c]
            S[a, b] = s
            S[b, a] = s
    return S


@njit(cache=True)
def _schur(J, minv, m, n):
    return _schur_into(np.empty((m, m)), J, minv, m, n)


@njit(cache=True)
def accelerations(t, q, qd, mem, P, qdd, lam, eout):
    """Solve the equations of motion for q̈ and λ at (t, q, q̇) [T10]; fill element outputs.
    Returns OK, SINGULAR or NONFINITE."""
    return _accelerations(t, q, qd, mem, P, qdd, lam, eout)


@njit(inline="always")
def _baumgarte(gam, Phi, Phit, J, qd, a, m, n):
    """γ ← γ − 2αΦ̇ − α²Φ (Baumgarte stabilisation with α [1/s], [T10])."""
    for r in range(m):
        phid = Phit[r]
        for c in range(n):
            phid += J[r, c] * qd[c]
        gam[r] -= 2.0 * a * phid + a * a * Phi[r]


@njit(inline="always")
def _multiplier_rhs(lam, gam, J, minv, Q, m, n):
    """lam ← γ − Φ_q M⁻¹Q: the right-hand side of (Φ_q M⁻¹Φ_qᵀ)λ = … [T10]."""
    for r in range(m):
        s = gam[r]
        for c in range(n):
            s -= J[r, c] * minv[c] * Q[c]
        lam[r] = s


@njit(inline="always")
def _qdd_of(qdd, Q, J, lam, minv, m, n):
    """q̈ = M⁻¹(Q + Φ_qᵀλ) [T10]."""
    for c in range(n):
        s = Q[c]
        for r in range(m):
            s += J[r, c] * lam[r]
        qdd[c] = minv[c] * s


@njit(cache=True, inline="always")
def _accelerations(t, q, qd, mem, P, qdd, lam, eout):
    """:func:`accelerations`, inlined into :func:`rhs` (a call with the packed system and the
    workspace views as arguments cost ≈ 0.19 µs of a 1.16 µs RHS [T192])."""
    minv, q0_force, cint, creal, fint, freal, tables, m, stab, ws, kernels = P
    n = q.shape[0]
    Q = ws[:n]
    copy_vector(Q, q0_force)
    if fint.shape[0] > 0:  # the call alone costs ≈ 0.13 µs, 12 % of an element-free RHS [T192]
        call_forces(kernels, (t, q, qd, mem, fint, freal, tables, Q, eout))
    if m > 0:
        Phi, Phit, gam, J, S, _ = _constraint_views(ws, n, m)
        eval_constraints_into(t, q, qd, cint, creal, Phi, J, Phit, gam, _trig_scratch(ws, n))
        a = stab[0]
        if a > 0.0:
            _baumgarte(gam, Phi, Phit, J, qd, a, m, n)
        _schur_into(S, J, minv, m, n)
        _multiplier_rhs(lam, gam, J, minv, Q, m, n)
        if not cholesky_solve(S, lam):
            return SINGULAR
        _qdd_of(qdd, Q, J, lam, minv, m, n)
    else:
        for c in range(n):
            qdd[c] = minv[c] * Q[c]
    for c in range(n):
        if not np.isfinite(qdd[c]):
            return NONFINITE
    return OK


@njit(cache=True)
def rhs(t, y, mem, P, ydot):
    """First-order form y = [q, q̇], ẏ = [q̇, q̈]. Returns a status code (0 = ok)."""
    n = y.shape[0] // 2
    m = P.n_rows
    ws = P.ws
    nf = P.fint.shape[0]
    o = n + 3 * m + m * n + m * m
    lam = ws[o : o + max(m, 1)]
    o += max(m, 1)
    eout = ws[o : o + nf * NOUT].reshape((nf, NOUT))
    qdd = ydot[n:]
    copy_vector(ydot, y[n:])
    return _accelerations(t, y[:n], y[n:], mem, P, qdd, lam, eout)


@njit(inline="always")
def _max_abs(v, m):
    """max |v_r| over the first m entries (0 for m = 0)."""
    res = 0.0
    for r in range(m):
        res = max(res, abs(v[r]))
    return res


@njit(inline="always")
def _correct(x, J, lam, minv, m, n):
    """x ← x − M⁻¹Φ_qᵀλ, in place: the M-weighted minimal correction of [T11]."""
    for c in range(n):
        s = 0.0
        for r in range(m):
            s += J[r, c] * lam[r]
        x[c] -= minv[c] * s


@njit(inline="always")
def _velocity_residual(out, J, Phit, qd, m, n):
    """out ← Φ̇ = Φ_t + Φ_q q̇ (m rows) [T11]."""
    for r in range(m):
        s = Phit[r]
        for c in range(n):
            s += J[r, c] * qd[c]
        out[r] = s


@njit(cache=True)
def project_positions(t, q, qd, minv, cint, creal, m, tol, max_iter):
    """Gauss–Newton projection of q onto Φ(q, t) = 0, M-weighted minimal correction
    q ← q − M⁻¹Φ_qᵀ(Φ_q M⁻¹Φ_qᵀ)⁻¹Φ, in place [T11]. Returns max |Φ| [m or rad] at the last
    evaluation (≤ tol when converged, else after ``max_iter`` corrections); −1.0 if the Schur
    complement is singular."""
    n = q.shape[0]
    Phi = np.empty(m)
    J = np.empty((m, n))
    Phit = np.empty(m)
    gam = np.empty(m)
    res = 0.0
    for _ in range(max_iter):
        eval_constraints(t, q, qd, cint, creal, Phi, J, Phit, gam)
        res = _max_abs(Phi, m)
        if res <= tol:
            break
        S = _schur(J, minv, m, n)
        x = Phi.copy()
        if not cholesky_solve(S, x):
            return -1.0
        _correct(q, J, x, minv, m, n)
    return res


@njit(cache=True)
def project_velocities(t, q, qd, minv, cint, creal, m):
    """M-weighted projection of q̇ onto Φ_q q̇ + Φ_t = 0, in place [T11]. Returns False if the
    Schur complement is singular."""
    n = q.shape[0]
    Phi = np.empty(m)
    J = np.empty((m, n))
    Phit = np.empty(m)
    gam = np.empty(m)
    eval_constraints(t, q, qd, cint, creal, Phi, J, Phit, gam)
    v = np.empty(m)
    _velocity_residual(v, J, Phit, qd, m, n)
    S = _schur(J, minv, m, n)
    if not cholesky_solve(S, v):
        return False
    _correct(qd, J, v, minv, m, n)
    return True


@njit(cache=True)
def project(t, y, P, tol):
    """Project y = [q, q̇] onto Φ = 0 (at most 6 Gauss–Newton corrections) and Φ̇ = 0 [T11];
    the one projection used by the integrators, the output samples and model assembly.

    The same arithmetic as :func:`project_positions` followed by :func:`project_velocities`,
    except that the velocity projection re-uses Φ_q, Φ_t of the last position iterate when that
    iterate converged (they depend on (q, t) only) and nothing is allocated per correction [T191].

    Its scratch is the packed system's workspace ``P.ws``, in the slots :func:`rhs` uses for
    Φ, Φ_t, γ, Φ_q, the Schur complement and λ (both overwrite them before reading them): no
    allocation per call [T209].

    Returns the max |Φ| after projection [m or rad]; −1.0 if the Jacobian is singular."""
    m = P.n_rows
    if m == 0:
        return 0.0
    n = y.shape[0] // 2
    q = y[:n]
    qd = y[n:]
    minv, cint, creal, ws = P.minv, P.cint, P.creal, P.ws
    Phi, Phit, gam, J, S, x = _constraint_views(ws, n, m)
    cs = _trig_scratch(ws, n)
    res = 0.0
    fresh = False  # Φ_q, Φ_t evaluated at the current q
    for _ in range(6):
        eval_constraints_into(t, q, qd, cint, creal, Phi, J, Phit, gam, cs)
        res = _max_abs(Phi, m)
        if res <= tol:
            fresh = True
            break
        _schur_into(S, J, minv, m, n)
        copy_vector(x, Phi)
        if not cholesky_solve(S, x):
            return -1.0
        _correct(q, J, x, minv, m, n)
    if not fresh:  # six corrections without convergence: Φ_q at the last corrected q
        eval_constraints_into(t, q, qd, cint, creal, Phi, J, Phit, gam, cs)
    _velocity_residual(x, J, Phit, qd, m, n)
    _schur_into(S, J, minv, m, n)
    if not cholesky_solve(S, x):
        return -1.0
    _correct(qd, J, x, minv, m, n)
    return res


@njit(cache=True)
def constraint_residuals(t, y, P):
    """max |Φ| [m or rad] and max |Φ̇| [m/s or rad/s] at y (the drift report)."""
    cint, creal, m = P.cint, P.creal, P.n_rows
    if m == 0:
        return 0.0, 0.0
    n = y.shape[0] // 2
    Phi = np.empty(m)
    J = np.empty((m, n))
    Phit = np.empty(m)
    gam = np.empty(m)
    eval_constraints(t, y[:n], y[n:], cint, creal, Phi, J, Phit, gam)
    p = 0.0
    v = 0.0
    for r in range(m):
        p = max(p, abs(Phi[r]))
        s = Phit[r]
        for c in range(n):
            s += J[r, c] * y[n + c]
        v = max(v, abs(s))
    return p, v


@njit(cache=True, inline="always")
def _sample(t, q, qd, mem, P, do_project, tol, Phi, J, Phit, gam, S, Q, cs, qdd, lam, eout, drift):
    """One output sample (see :func:`outputs`), in place; scratch Phi, J, Phit, gam, S (m rows),
    Q, cs (n).

    The Schur complement Φ_q M⁻¹Φ_qᵀ at the final q is factored once and serves both the velocity
    projection and the multipliers [T190]; Φ, Φ_q are evaluated once per Gauss–Newton iterate."""
    minv, cint, creal, m = P.minv, P.cint, P.creal, P.n_rows
    n = q.shape[0]
    factored = False
    if m > 0:
        eval_constraints_into(t, q, qd, cint, creal, Phi, J, Phit, gam, cs)
        res = _max_abs(Phi, m)
        if do_project:
            it = 0
            ok = True
            while res > tol and it < 6:  # Gauss–Newton, M-weighted minimal correction [T11]
                _schur_into(S, J, minv, m, n)
                for r in range(m):
                    lam[r] = Phi[r]
                if not cholesky_solve(S, lam):
                    ok = False
                    break
                _correct(q, J, lam, minv, m, n)
                eval_constraints_into(t, q, qd, cint, creal, Phi, J, Phit, gam, cs)
                res = _max_abs(Phi, m)
                it += 1
            if ok:  # q̇ onto Φ̇ = Φ_t + Φ_q q̇ = 0 with Φ_q at the final q [T11]
                _schur_into(S, J, minv, m, n)
                factored = cholesky_factor(S)
                if factored:
                    _velocity_residual(lam, J, Phit, qd, m, n)
                    cholesky_substitute(S, lam)
                    _correct(qd, J, lam, minv, m, n)
                    # γ depends on q̇: evaluate it at the projected velocities (Φ, Φ_q, Φ_t are
                    # functions of (q, t) only and come out unchanged) [T190]
                    eval_constraints_into(t, q, qd, cint, creal, Phi, J, Phit, gam, cs)
        v = 0.0
        for r in range(m):
            s = Phit[r]
            for c in range(n):
                s += J[r, c] * qd[c]
            v = max(v, abs(s))
        drift[0] = res
        drift[1] = v
    # accelerations at the final (q, q̇): the same arithmetic as :func:`accelerations` [T10]
    copy_vector(Q, P.q0_force)
    if P.fint.shape[0] > 0:  # no call without elements [T192]
        call_forces(P.kernels, (t, q, qd, mem, P.fint, P.freal, P.tables, Q, eout))
    if m > 0:
        a = P.stab[0]
        if a > 0.0:
            _baumgarte(gam, Phi, Phit, J, qd, a, m, n)
        if not factored:
            _schur_into(S, J, minv, m, n)
        _multiplier_rhs(lam, gam, J, minv, Q, m, n)
        if not factored:
            if not cholesky_factor(S):
                return SINGULAR
        cholesky_substitute(S, lam)
        _qdd_of(qdd, Q, J, lam, minv, m, n)
    else:
        for c in range(n):
            qdd[c] = minv[c] * Q[c]
    return OK


@njit(cache=True)
def outputs(ts, ys, mems, P, do_project):
    """Accelerations, multipliers and element outputs at saved states (post-processing).

    With ``do_project`` the (interpolated) output states are first projected on Φ = 0,
    Φ̇ = 0 in place [T11], as the integrator does with its step states: the same iteration as
    :func:`project` (Gauss–Newton until max |Φ| ≤ 1e-12, at most 6 steps, then q̇), fused with
    the drift report and the accelerations so that Φ, Φ_q are evaluated once per iterate, the
    Schur complement at the final q is factored once, and nothing is allocated per sample
    [T112, T190]. Returns (q̈ (nt, n), λ (nt, m), element outputs (nt, nf, NOUT), drift (nt, 2):
    max |Φ| [m or rad], max |Φ̇| [m/s or rad/s])."""
    nt = ts.shape[0]
    n = ys.shape[1] // 2
    m = P.n_rows
    nf = P.fint.shape[0]
    qdd = np.zeros((nt, n))
    lam = np.zeros((nt, max(m, 1)))
    eout = np.zeros((nt, nf, NOUT))
    drift = np.zeros((nt, 2))
    # the loop works on borrowed views (no reference counting [T208]): of the arguments (owned
    # by the caller), of the results (returned, hence alive) and of the scratch, which is the
    # workspace of rhs (Q, Φ, Φ_t, γ, Φ_q, S: written before read)
    bts, bys, bmems, bP = borrowed((ts, ys, mems, P))
    bqdd, blam, beout, bdrift = borrowed((qdd, lam, eout, drift))
    ws = bP.ws
    Q = ws[:n]
    Phi, Phit, gam, J, S, _ = _constraint_views(ws, n, m)
    cs = _trig_scratch(ws, n)
    for i in range(nt):
        _sample(
            bts[i], bys[i, :n], bys[i, n:], bmems[i], bP, do_project, 1e-12,
            Phi, J, Phit, gam, S, Q, cs, bqdd[i], blam[i], beout[i], bdrift[i],
        )  # fmt: skip
    return qdd, lam[:, :m], eout, drift
