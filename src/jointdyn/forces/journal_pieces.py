"""The optional pieces of a journal element as type-level choices [T322]: the lumped oil
temperature (μ(T) of the film [T310–T312]), Greenwood–Tripp asperity contact with boundary
friction [T314] and the transient mass-conserving film (``forces.jfo_film``) [T306].

A journal element's entry of the kinds (``forces.elements.journal_laws``) holds, after its film,
contact and friction laws, one entry per piece: 1 where an element of the system uses it, None
where none does. The gates here (:func:`jointdyn.core.dispatch.law_gate`) compile the piece only
where it is present; elsewhere they are the constant of a bearing without it (μ = ``viscosity``,
no asperity load), so a plain bearing neither compiles nor evaluates the pieces. Where present,
each element still checks its own slot at run time (systems that share one kernel set [T341]).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from jointdyn.core.dispatch import law_gate
from jointdyn.forces.jfo_film import feature_flows, jfo_commit, jfo_force, jfo_jacobian, jfo_step_limit
from jointdyn.forces.mixed import asperity_loads
from jointdyn.forces.thermal import VISC, thermal_step_limit

THERMAL_PIECE = 3  # place of the oil temperature in a journal element's laws
ASPERITY_PIECE = 4  # place of the asperity contact
JFO_PIECE = 5  # place of the transient jfo film


@njit(inline="always")
def _viscosity(flag, mem, mu):
    return mem[VISC] if flag != 0 else mu


@njit(inline="always")
def _asperity(slot, xi, dw, tables, rj, fb, vs):
    if slot == 0:
        return 0.0, 0.0
    fa, wa = asperity_loads(xi, tables[slot], tables[slot + 1])
    return fa, rj * fb * math.tanh(dw * rj / vs) * wa  # boundary friction couple [T270, T314]


@njit(inline="always")
def _nonzero(slot):
    return slot != 0


film_viscosity = law_gate("film_viscosity", THERMAL_PIECE, _viscosity, ("flag", "mem", "mu"), "mu")
"""μ of the film [Pa·s]: the oil temperature's μ(T) (memory slot VISC) if the element's thermal
slot ``flag`` is set, else ``mu``"""

thermal_limit = law_gate("thermal_limit", THERMAL_PIECE, thermal_step_limit, ("mem", "p"), "1e300")
"""the oil temperature's step limit [s] [T312] (1e300 where no element has one)"""

asperity_terms = law_gate(
    "asperity_terms",
    ASPERITY_PIECE,
    _asperity,
    ("slot", "xi", "dw", "tables", "rj", "fb", "vs"),
    "(0.0, 0.0)",
)
"""(asperity load F_a [N], boundary friction couple T_b [N·m]) of an element with asperity
tables at ``slot`` (0: none), relative rate ``dw`` = ω_J − ω_B [rad/s]"""

asperity_on = law_gate("asperity_on", ASPERITY_PIECE, _nonzero, ("slot",), "False")
"""whether the element's asperity slot is set"""


@njit(inline="always")
def bushing_frame(q, bi, ex, ey, edx, edy, wi, c):
    """(cos φ_i, sin φ_i) of the bushing and the journal's offset e and its rate in the bushing
    frame [c, c/s]: e_b = Aᵀe, ė_b = Aᵀė − ω_i S e_b (S the quarter turn) [T306]."""
    co = 1.0
    si = 0.0
    if bi >= 0:
        co = math.cos(q[3 * bi + 2])
        si = math.sin(q[3 * bi + 2])
    ebx = (co * ex + si * ey) / c
    eby = (-si * ex + co * ey) / c
    vbx = (co * edx + si * edy) / c + wi * eby
    vby = (-si * edx + co * edy) / c - wi * ebx
    return co, si, ebx, eby, vbx, vby


@njit(inline="always")
def _jfo(t, mem, tables, slot, q, bi, ex, ey, edx, edy, wi, wj, ux, uy, mu, R, c, cap, out, o):
    co, si, ebx, eby, vbx, vby = bushing_frame(q, bi, ex, ey, edx, edy, wi, c)
    fbx, fby, content, inflow, side, gas, net = jfo_force(
        t, mem, tables, slot, ebx, eby, vbx, vby, wj - wi, mu, R, c, cap
    )
    out[o] = content
    out[o + 1] = inflow
    out[o + 2] = side
    feature_flows(tables, slot, net, out, o + 3)
    fx = co * fbx - si * fby
    fy = si * fbx + co * fby
    dmc = mu * (wj - wi) * R**4 / c * gas  # the Couette torque the gas does not carry [T375]
    return fx * ux + fy * uy, fy * ux - fx * uy, dmc


jfo_terms = law_gate(
    "jfo_terms",
    JFO_PIECE,
    _jfo,
    (
        "t",
        "mem",
        "tables",
        "slot",
        "q",
        "bi",
        "ex",
        "ey",
        "edx",
        "edy",
        "wi",
        "wj",
        "ux",
        "uy",
        "mu",
        "R",
        "c",
        "cap",
        "out",
        "o",
    ),
    "(0.0, 0.0, 0.0)",
)
"""(F_r, F_t [N], the Couette torque its gas does not carry [N·m] [T375]) of the transient jfo
film of an element with its tables at ``slot`` [T306]; its content [m³], inflow, side outflow and
flow per supply feature [m³/s] into out[o], out[o + 1], … [T376]"""


@njit(inline="always")
def _commit(t, mem, tables, slot, q, bi, ex, ey, wi, wj, R, c, cap):
    co, si, ebx, eby, _, _ = bushing_frame(q, bi, ex, ey, 0.0, 0.0, wi, c)
    return jfo_commit(t, mem, tables, slot, ebx, eby, wj - wi, R, c, cap)


jfo_commit_gate = law_gate(
    "jfo_commit_gate",
    JFO_PIECE,
    _commit,
    ("t", "mem", "tables", "slot", "q", "bi", "ex", "ey", "wi", "wj", "R", "c", "cap"),
    "0",
)
"""commit the jfo film of an accepted step [T307]: 0, or 1 if its active set does not settle"""

jfo_limit = law_gate("jfo_limit", JFO_PIECE, jfo_step_limit, ("mem",), "1e300")
"""the jfo film's step limit [s] [T308] (1e300 where no element has one)"""


@njit(inline="always")
def jfo_jac(mem, tables, slot, q, bi, ex, ey, edx, edy, wi, wj, mu, R, c, cap, De, Ded):
    """Global film force F (2,) [N] on the journal and ∂F/∂z (2, 12) for z = (q_i, q_j, q̇_i, q̇_j)
    from ∂e/∂z, ∂ė/∂z (De, Ded): the film's derivatives in the bushing frame (``jfo_jacobian``)
    chained through e_b = Aᵀe/c, ė_b = Aᵀė/c − ω_i S e_b, ω = ω_J − ω_B and F = A F_b; the gas
    Couette integral [-] and its ∂/∂z (12,) [T375]; 1 if the film's active set does not settle
    else 0 [T346]. Called only where the laws hold the jfo piece
    (``forces.element_jacobians.film_jac_block``)."""
    co, si, ebx, eby, vbx, vby = bushing_frame(q, bi, ex, ey, edx, edy, wi, c)
    fbx, fby, gas, J, bad = jfo_jacobian(mem, tables, slot, ebx, eby, vbx, vby, wj - wi, mu, R, c, cap)
    Dx = np.zeros((5, 12))  # ∂(e_b, ė_b, ω)/∂z
    for k in range(12):
        Dx[0, k] = (co * De[0, k] + si * De[1, k]) / c
        Dx[1, k] = (-si * De[0, k] + co * De[1, k]) / c
        Dx[2, k] = (co * Ded[0, k] + si * Ded[1, k]) / c + wi * Dx[1, k]
        Dx[3, k] = (-si * Ded[0, k] + co * Ded[1, k]) / c - wi * Dx[0, k]
    if bi >= 0:  # the bushing's angle φ_i (z[2]) and rate ω_i (z[8]) in A and in ė_b
        Dx[0, 2] += eby
        Dx[1, 2] -= ebx
        Dx[2, 2] += vby
        Dx[3, 2] -= vbx
        Dx[2, 8] += eby
        Dx[3, 8] -= ebx
    Dx[4, 8] -= 1.0
    Dx[4, 11] += 1.0
    DFb = J[:2] @ Dx
    Dgas = J[2] @ Dx
    F = np.array([co * fbx - si * fby, si * fbx + co * fby])
    DF = np.empty((2, 12))
    for k in range(12):
        DF[0, k] = co * DFb[0, k] - si * DFb[1, k]
        DF[1, k] = si * DFb[0, k] + co * DFb[1, k]
    if bi >= 0:
        DF[0, 2] -= F[1]
        DF[1, 2] += F[0]
    return F, DF, gas, Dgas, bad
