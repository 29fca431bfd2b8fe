"""The optional pieces of a journal element as type-level choices [T322]: the lumped oil
temperature (μ(T) of the film [T310–T312]) and Greenwood–Tripp asperity contact with boundary
friction [T314].

A journal element's entry of the kinds (``forces.elements.journal_laws``) holds, after its film,
contact and friction laws, one entry per piece: 1 where an element of the system uses it, None
where none does. The gates here (:func:`jointdyn.core.dispatch.law_gate`) compile the piece only
where it is present; elsewhere they are the constant of a bearing without it (μ = ``viscosity``,
no asperity load), so a plain bearing neither compiles nor evaluates the pieces. Where present,
each element still checks its own slot at run time (systems that share one kernel set [T341]).
"""

from __future__ import annotations

import math

from numba import njit

from jointdyn.core.dispatch import law_gate
from jointdyn.forces.mixed import asperity_loads
from jointdyn.forces.thermal import VISC, thermal_step_limit

THERMAL_PIECE = 3  # place of the oil temperature in a journal element's laws
ASPERITY_PIECE = 4  # place of the asperity contact


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
