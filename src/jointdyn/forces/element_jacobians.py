"""Exact Jacobians of the force elements, ∂Q/∂(q, q̇) and ∂Q/∂t (compiled) [T98–T100, T118].

The journal element (film and/or contact) is differentiated through its kinematics by the chain
rule over the 12 local variables z = (q_i, q_j, q̇_i, q̇_j) [T98]; spring–damper, torsional spring,
harmonic torque and tabulated force in closed form [T118]; a law of a journal element without
an exact Jacobian is differenced inside the element's Jacobian [T229]; an element without an
analytic Jacobian (a kind without a ``JACOBIAN_KERNELS`` entry, a spring at zero length, a journal
at e = 0) is differentiated by central differences of its own contribution [T100], so every
element is covered and the fallback is checked against the same references.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from jointdyn.core.arrays import copy_matrix, copy_vector
from jointdyn.core.dispatch import law_gate
from jointdyn.core.layout import BODY_I, BODY_J, TYPE
from jointdyn.film.models import film_jac_dispatch
from jointdyn.forces.contact_laws import KELVIN_VOIGT, contact_jac_dispatch
from jointdyn.forces.elements import NOUT, eval_forces
from jointdyn.forces.friction_laws import friction_jac_dispatch
from jointdyn.forces.journal import (
    ASPERITY,
    CLR,
    CONTACT,
    CONTACT_P0,
    CONTACT_P1,
    FILM,
    FILM_P0,
    FILM_P1,
    FRICTION,
    FRICTION_P0,
    FRICTION_P1,
    H_ASP,
    IN_CONTACT,
    JFO,
    JOURNAL,
    LEN,
    MU,
    NO_CONTACT,
    NO_FILM,
    NO_FRICTION,
    ONSET_VEL,
    R_B,
    R_J,
    SHEAR,
    TABLE,
    THERMAL,
    V_MIN,
    XI_GUARD,
    journal_kinematics,
)
from jointdyn.forces.journal_pieces import JFO_PIECE, asperity_on, film_viscosity, jfo_jac
from jointdyn.forces.kinds import kind_switch
from jointdyn.forces.simple_jacobians import (
    harmonic_torque_dt,
    spring_damper_jacobian,
    tabulated_force_jacobian,
    torsion_spring_jacobian,
)
from jointdyn.forces.springs import SPRING_DAMPER
from jointdyn.forces.tabulated import TABLE as TAB_TABLE
from jointdyn.forces.tabulated import TABULATED_FORCE
from jointdyn.forces.torsion import HARMONIC_TORQUE, TORSION_SPRING
from jointdyn.forces.transfer import pair_jac, pair_rates


@njit(inline="always")
def _jfo_block(mem, tables, slot, q, bi, ex, ey, edx, edy, wi, wj, mu, R, c, cap, De, Ded, F, DF, G):
    """The jfo film's force F (2,) [N] and ∂F/∂z (2, 12) into F, DF [T346], its gas Couette
    integral [-] and ∂/∂z into G (13,) [T375]; returns 1 where its active set does not settle,
    else 0."""
    Fj, DFj, gas, Dgas, bad = jfo_jac(
        mem, tables, slot, q, bi, ex, ey, edx, edy, wi, wj, mu, R, c, cap, De, Ded
    )
    copy_vector(F, Fj)
    copy_matrix(DF, DFj)
    G[0] = gas
    for k in range(12):
        G[1 + k] = Dgas[k]
    return bad


jfo_block = law_gate(
    "jfo_block",
    JFO_PIECE,
    _jfo_block,
    "mem, tables, slot, q, bi, ex, ey, edx, edy, wi, wj, mu, R, c, cap, De, Ded, F, DF, G".split(", "),
    "1",
)
""":func:`_jfo_block` where the laws hold the jfo piece, else the constant 1 (never reached: the
element's jfo slot is 0). Tiny where absent: an ``if`` on a gate's constant is still typed and
compiled, and an inlined gate's body is compiled once more on its own to type it [T357]."""


@njit(cache=True)
def journal_jacobian(q, qd, mem, bi, bj, ip, r, tables, DQ, laws):
    """∂(Q_i, Q_j)/∂z of one journal element into DQ (6, 12), z = (q_i, q_j, q̇_i, q̇_j) [T98],
    with the laws' exact Jacobians or, for a law without one, central differences of its kernel
    [T229] (``laws`` as in ``journal_element``).

    Returns 0, or 1 where the element is not differentiable analytically (e = 0): the caller
    then uses finite differences of the element."""
    ex, ey, edx, edy, six, siy, sjx, sjy, wi, wj = journal_kinematics(q, qd, bi, bj, r)
    c = r[CLR]
    e = np.sqrt(ex * ex + ey * ey)
    if e == 0.0 or asperity_on(laws, ip[ASPERITY]):  # [T315]: differenced
        return 1
    ux = ex / e
    uy = ey / e
    tx = -uy
    ty = ux
    # ∂e/∂z and ∂ė/∂z [T14, T98]
    De, Ded = pair_rates(six, siy, sjx, sjy, wi, wj)
    tde = tx * De[0] + ty * De[1]
    ude = ux * De[0] + uy * De[1]
    Du = np.empty((2, 12))  # du = t (t·de)/e
    Dt = np.empty((2, 12))  # dt = −u (t·de)/e
    for k in range(12):
        Du[0, k] = tx * tde[k] / e
        Du[1, k] = ty * tde[k] / e
        Dt[0, k] = -ux * tde[k] / e
        Dt[1, k] = -uy * tde[k] / e
    ue = ux * edx + uy * edy
    te = tx * edx + ty * edy
    uded = ux * Ded[0] + uy * Ded[1]
    tded = tx * Ded[0] + ty * Ded[1]
    Dwsum = np.zeros(12)
    Dwsum[8] = 1.0
    Dwsum[11] = 1.0
    # arms: ∂s_i/∂z, ∂s_j/∂z
    Dsi = np.zeros((2, 12))
    Dsi[0, 2] = -siy
    Dsi[1, 2] = six
    Dsj = np.zeros((2, 12))
    Dsj[0, 5] = -sjy
    Dsj[1, 5] = sjx
    F = np.empty(2)
    DF = np.empty((2, 12))
    G = np.zeros(13)  # the jfo film's gas Couette integral and its derivatives [T375]
    xi = e / c
    mu_f = film_viscosity(laws, ip[THERMAL], mem, r[MU])  # μ(T) frozen between accepted steps [T311]
    if ip[FILM] != NO_FILM:
        xi_cap = (c - r[H_ASP]) / c if ip[CONTACT] != NO_CONTACT else XI_GUARD
        xi_f = min(xi, xi_cap, XI_GUARD)
        Dxi = ude / c if xi < xi_cap and xi < XI_GUARD else np.zeros(12)
        xid = ue / c
        xi_om = xi_f * (wj + wi) - 2.0 * te / c
        Dxid = (te * tde / e + uded) / c
        DX = Dxi * (wj + wi) + xi_f * Dwsum - 2.0 * (-ue * tde / e + tded) / c
        if ip[JFO] != 0:  # the film's block in the bushing frame, chained [T346]
            cap = min(xi_cap, XI_GUARD)
            slot = ip[JFO]
            if jfo_block(
                laws,
                mem,
                tables,
                slot,
                q,
                bi,
                ex,
                ey,
                edx,
                edy,
                wi,
                wj,
                mu_f,
                r[R_J],
                c,
                cap,
                De,
                Ded,
                F,
                DF,
                G,
            ):
                return 1
            ft = F[0] * tx + F[1] * ty
            Dft = np.empty(12)
            for k in range(12):
                Dft[k] = tx * DF[0, k] + ty * DF[1, k] + F[0] * Dt[0, k] + F[1] * Dt[1, k]
        else:
            fr, ft, frx, fra, fro, ftx, fta, fto = film_jac_dispatch(
                laws,
                ip[FILM],
                xi_f,
                xid,
                xi_om,
                mu_f,
                r[R_J],
                r[LEN],
                c,
                r[FILM_P0:FILM_P1],
                tables[ip[TABLE]],
            )
            Dfr = frx * Dxi + fra * Dxid + fro * DX
            Dft = ftx * Dxi + fta * Dxid + fto * DX
            F[0] = fr * ux + ft * tx
            F[1] = fr * uy + ft * ty
            for k in range(12):
                DF[0, k] = ux * Dfr[k] + fr * Du[0, k] + tx * Dft[k] + ft * Dt[0, k]
                DF[1, k] = uy * Dfr[k] + fr * Du[1, k] + ty * Dft[k] + ft * Dt[1, k]
        # film force at the journal centre: a_j = s_j, a_i = s_i + e [T8, T15]
        pair_jac(DQ, F, DF, sjx, sjy, Dsj, six + ex, siy + ey, Dsi + De)
        if ip[SHEAR] != 0:
            # shear torques M_J = −M_C − (e/2)F_t, M_B' = M_C + (e/2)F_t with
            # M_C = K(ω_J − ω_B)/√(1−ξ_f²), K = 2πμR³L/c [T75]
            kc = 2.0 * np.pi * mu_f * r[R_J] ** 3 * r[LEN] / c
            sq = np.sqrt((1.0 - xi_f) * (1.0 + xi_f))
            dw = wj - wi
            Dmc = kc * dw * xi_f / sq**3 * Dxi
            Dmc[11] += kc / sq
            Dmc[8] -= kc / sq
            # a jfo film's gas carries no Couette shear: M_C − μ(ω_J − ω_B)R⁴/c·gas [T375]
            kg = mu_f * r[R_J] ** 4 / c
            for k in range(12):
                Dmc[k] -= kg * dw * G[1 + k]
            Dmc[11] -= kg * G[0]
            Dmc[8] += kg * G[0]
            Dhalf = 0.5 * (ude * ft + e * Dft)
            for k in range(12):
                DQ[5, k] += -Dmc[k] - Dhalf[k]
                DQ[2, k] += Dmc[k] + Dhalf[k]
    if ip[CONTACT] != NO_CONTACT:
        delta = e - (c - r[H_ASP])
        if delta > 0.0:
            in_c = mem[IN_CONTACT] > 0.5
            v0 = mem[ONSET_VEL] if in_c else max(ue, r[V_MIN])
            fn, fnd, fndd = contact_jac_dispatch(laws, ip[CONTACT], delta, ue, v0, r[CONTACT_P0:CONTACT_P1])
            if not in_c and ue > r[V_MIN] and ip[CONTACT] != KELVIN_VOIGT:
                fndd = 0.0  # δ̇⁻ = δ̇ at an unrecorded onset: F = Kδⁿ(1 + χ) [T16]
            Dfn = fnd * ude + fndd * (te * tde / e + uded)
            vt = te + wj * r[R_J] - wi * r[R_B]
            mu = 0.0
            dmu = 0.0
            if ip[FRICTION] != NO_FRICTION:
                mu, dmu = friction_jac_dispatch(laws, ip[FRICTION], vt, r[FRICTION_P0:FRICTION_P1])
            Dvt = -ue * tde / e + tded
            Dvt[11] += r[R_J]
            Dvt[8] -= r[R_B]
            Dmfn = mu * Dfn + fn * dmu * Dvt
            F[0] = -fn * ux - mu * fn * tx
            F[1] = -fn * uy - mu * fn * ty
            for k in range(12):
                DF[0, k] = -ux * Dfn[k] - fn * Du[0, k] - tx * Dmfn[k] - mu * fn * Dt[0, k]
                DF[1, k] = -uy * Dfn[k] - fn * Du[1, k] - ty * Dmfn[k] - mu * fn * Dt[1, k]
            cx = r[R_J] * ux
            cy = r[R_J] * uy
            Dc = r[R_J] * Du
            pair_jac(DQ, F, DF, sjx + cx, sjy + cy, Dsj + Dc, six + ex + cx, siy + ey + cy, Dsi + De + Dc)
    return 0


@njit(cache=True)
def _scatter(DQ, bi, bj, dQdq, dQdqd):
    """Add the local (6, 12) block of bodies (i, j) to the global ∂Q/∂q, ∂Q/∂q̇ (ground skipped)."""
    for a in range(2):
        ba = bi if a == 0 else bj
        if ba < 0:
            continue
        for b in range(2):
            bb = bi if b == 0 else bj
            if bb < 0:
                continue
            for r in range(3):
                for s in range(3):
                    dQdq[3 * ba + r, 3 * bb + s] += DQ[3 * a + r, 3 * b + s]
                    dQdqd[3 * ba + r, 3 * bb + s] += DQ[3 * a + r, 6 + 3 * b + s]


@njit(cache=True)
def _element_q(t, q, qd, mem, fint, freal, tables, k, Qk, out, kinds):
    Qk[:] = 0.0
    eval_forces(t, q, qd, mem[k : k + 1], fint[k : k + 1], freal[k : k + 1], tables, Qk, out, kinds)


@njit(cache=True)
def _fd_element(t, q, qd, mem, fint, freal, tables, k, dQdq, dQdqd, dQdt, kinds):
    """Central differences of element k's generalised force [T100] (the fallback)."""
    n = q.shape[0]
    Qp = np.zeros(n)
    Qm = np.zeros(n)
    out = np.zeros((1, NOUT))
    qw = q.copy()
    qdw = qd.copy()
    for col in range(n):  # every coordinate: an element may read other bodies (a tabulated force)
        for which in range(2):
            base = q[col] if which == 0 else qd[col]
            h = 6.055454452393343e-06 * max(abs(base), 1e-3 if which == 0 else 1.0)  # ε^(1/3)
            if which == 0:
                qw[col] = base + h
                _element_q(t, qw, qd, mem, fint, freal, tables, k, Qp, out, kinds)
                qw[col] = base - h
                _element_q(t, qw, qd, mem, fint, freal, tables, k, Qm, out, kinds)
                qw[col] = base
                for i in range(n):
                    dQdq[i, col] += (Qp[i] - Qm[i]) / (2.0 * h)
            else:
                qdw[col] = base + h
                _element_q(t, q, qdw, mem, fint, freal, tables, k, Qp, out, kinds)
                qdw[col] = base - h
                _element_q(t, q, qdw, mem, fint, freal, tables, k, Qm, out, kinds)
                qdw[col] = base
                for i in range(n):
                    dQdqd[i, col] += (Qp[i] - Qm[i]) / (2.0 * h)
    h = 6.055454452393343e-06 * max(abs(t), 1e-3)
    _element_q(t + h, q, qd, mem, fint, freal, tables, k, Qp, out, kinds)
    _element_q(t - h, q, qd, mem, fint, freal, tables, k, Qm, out, kinds)
    for i in range(n):
        dQdt[i] += (Qp[i] - Qm[i]) / (2.0 * h)


# One compiled Jacobian kernel per element code, all with the signature
# (t, q, q̇, k, mem, fint, freal, tables, DQ, ∂Q/∂q, ∂Q/∂q̇, ∂Q/∂t) -> 0 (element k's derivatives added
# to the global arrays) or 1 (not differentiable here: the caller uses the finite-difference
# fallback [T100]). DQ is a zeroed (6, 12) local block for kernels that scatter with
# :func:`_scatter`. A code without an entry is always differentiated by the fallback.


@njit(inline="always")
def _harmonic_torque_jac(t, q, qd, k, mem, fint, freal, tables, DQ, dQdq, dQdqd, dQdt):
    harmonic_torque_dt(t, fint[k, BODY_J], freal[k], dQdt)  # M(t) only: no q, q̇ terms [T118]
    return 0


@njit(inline="always")
def _tabulated_force_jac(t, q, qd, k, mem, fint, freal, tables, DQ, dQdq, dQdqd, dQdt):
    tab = tables[fint[k, TAB_TABLE]]
    tabulated_force_jacobian(t, q, qd, fint[k, BODY_J], fint[k], freal[k], tab, dQdq, dQdt)
    return 0


@njit(inline="always")
def _torsion_spring_jac(t, q, qd, k, mem, fint, freal, tables, DQ, dQdq, dQdqd, dQdt):
    bi = fint[k, BODY_I]
    bj = fint[k, BODY_J]
    torsion_spring_jacobian(q, bi, bj, freal[k], DQ)
    _scatter(DQ, bi, bj, dQdq, dQdqd)
    return 0


@njit(inline="always")
def _spring_damper_jac(t, q, qd, k, mem, fint, freal, tables, DQ, dQdq, dQdqd, dQdt):
    bi = fint[k, BODY_I]
    bj = fint[k, BODY_J]
    if spring_damper_jacobian(q, qd, bi, bj, freal[k], DQ) != 0:
        return 1
    _scatter(DQ, bi, bj, dQdq, dQdqd)
    return 0


@njit(inline="always")
def _journal_jac(t, q, qd, k, mem, fint, freal, tables, DQ, dQdq, dQdqd, dQdt, laws):
    bi = fint[k, BODY_I]
    bj = fint[k, BODY_J]
    if journal_jacobian(q, qd, mem[k], bi, bj, fint[k], freal[k], tables, DQ, laws) != 0:
        return 1
    _scatter(DQ, bi, bj, dQdq, dQdqd)
    return 0


JACOBIAN_KERNELS = {
    SPRING_DAMPER: _spring_damper_jac,
    JOURNAL: (_journal_jac, "t, q, qd, k, mem, fint, freal, tables, DQ, dQdq, dQdqd, dQdt, kind"),
    TABULATED_FORCE: _tabulated_force_jac,
    TORSION_SPRING: _torsion_spring_jac,
    HARMONIC_TORQUE: _harmonic_torque_jac,
}
"""element code -> compiled exact Jacobian kernel, or (kernel, its argument list) with ``kind`` the
element's entry of the kinds (optional: without one, finite differences)"""

_element_jacobian = kind_switch(
    "element_jacobian",
    JACOBIAN_KERNELS,
    ("t", "q", "qd", "k", "mem", "fint", "freal", "tables", "DQ", "dQdq", "dQdqd", "dQdt"),
    default="1",
)


@njit(cache=True)
def force_jacobian(t, q, qd, mem, fint, freal, tables, dQdq, dQdqd, dQdt, kinds=None):
    """∂Q/∂q, ∂Q/∂q̇ (n, n) and ∂Q/∂t (n,) of all force elements (zeroed here; gravity is
    constant). ``kinds`` as in :func:`~jointdyn.forces.elements.eval_forces` [T175]. Returns the
    number of elements differentiated by the fallback [T98–T100]."""
    dQdq[:, :] = 0.0
    dQdqd[:, :] = 0.0
    dQdt[:] = 0.0
    DQ = np.empty((6, 12))
    n_fd = 0
    for k in range(fint.shape[0]):
        DQ[:, :] = 0.0
        if (
            _element_jacobian(
                kinds, fint[k, TYPE], t, q, qd, k, mem, fint, freal, tables, DQ, dQdq, dQdqd, dQdt
            )
            != 0
        ):
            _fd_element(t, q, qd, mem, fint, freal, tables, k, dQdq, dQdqd, dQdt, kinds)
            n_fd += 1
    return n_fd


def fallback_elements(system) -> list[str]:
    """Names of the elements of a compiled system whose Jacobian comes from the finite-difference
    fallback [T100] (journal elements use it additionally at e = 0 only, spring–dampers at zero
    length [T118]): kinds without a ``JACOBIAN_KERNELS`` entry, for a one-time notice."""
    return [
        name
        for name, e in zip(system.element_names, system.elements, strict=True)
        if type(e).code not in JACOBIAN_KERNELS
    ]


def differenced_laws(system) -> list[str]:
    """``"element: family law"`` for each law of a journal element of a compiled system that has
    no exact ``jacobian`` and is differenced by central differences of its kernel [T229]."""
    from jointdyn.film.models import film_model, film_name

    out = []
    for name, e in zip(system.element_names, system.elements, strict=True):
        laws = [("contact law", getattr(e, "contact", None)), ("friction law", getattr(e, "friction", None))]
        if getattr(e, "film", None) is not None:
            laws.insert(0, ("film model", film_model(e.film)))
        for family, law in laws:
            if law is not None and getattr(type(law), "jacobian", None) is None:
                label = film_name(law) if family == "film model" else type(law).__name__
                out.append(f"{name}: {family} {label}")
    return out
