"""Force-element registry and dispatch: one compiled loop over the system's element table.

Element tables (built by :func:`element_tables` from each element's declared layouts):
``fint[k]`` holds the element's ``INT`` layout (registry code, body indices, then its own integer
slots) and ``freal[k]`` its ``REAL`` layout (point_i, point_j in body frames [m], then its own
parameters in SI, then parameter blocks of the laws it uses). ``mem[k]`` is the element's
``MEMORY`` (e.g. contact onset velocity); it changes only in :func:`advance_memory`, after
accepted steps. ``out[k]`` receives its ``OUTPUTS``. The table widths are the widest
declarations over ``FORCE_ELEMENTS``.
"""

from __future__ import annotations

import numpy as np
from numba import njit, types

from jointdyn.core.dispatch import generated, generated_overload, identity, law_gate, law_tuple
from jointdyn.core.layout import BODY_I, BODY_J, TYPE
from jointdyn.film.models import FILM_MODELS
from jointdyn.forces.contact_laws import CONTACT_LAWS
from jointdyn.forces.friction_laws import FRICTION_LAWS
from jointdyn.forces.journal import (
    ASPERITY,
    CONTACT,
    FILM,
    FRICTION,
    IMPACTS,
    IN_CONTACT,
    JFO,
    JOURNAL,
    MAX_PEN,
    O_LOSS,
    ONSET_TOL,
    ONSET_VEL,
    R_J,
    THERMAL,
    THERMAL_P0,
    THERMAL_P1,
    V_MIN,
    ClearanceJoint,
    JournalBearing,
    journal_element,
    penetration,
)
from jointdyn.forces.journal import CLR as _CLR
from jointdyn.forces.journal import H_ASP as _H_ASP
from jointdyn.forces.journal import NO_CONTACT as _NO_CONTACT
from jointdyn.forces.journal import XI_GUARD as _XI_GUARD
from jointdyn.forces.journal_geometry import journal_kinematics
from jointdyn.forces.journal_pieces import (
    ASPERITY_PIECE,
    JFO_PIECE,
    THERMAL_PIECE,
    jfo_commit_gate,
    jfo_limit,
    thermal_limit,
)
from jointdyn.forces.kinds import kind_gate, kind_loop, kinds_tuple
from jointdyn.forces.springs import SPRING_DAMPER, SpringDamper, spring_damper
from jointdyn.forces.tabulated import TABLE as TAB_TABLE
from jointdyn.forces.tabulated import TABULATED_FORCE, TabulatedForce, tabulated_force
from jointdyn.forces.thermal import thermal_step
from jointdyn.forces.torsion import (
    HARMONIC_TORQUE,
    TORSION_SPRING,
    HarmonicTorque,
    TorsionSpring,
    harmonic_torque,
    torsion_spring,
)

FORCE_ELEMENTS = {
    "spring_damper": SpringDamper,
    "clearance_joint": ClearanceJoint,
    "journal_bearing": JournalBearing,
    "tabulated_force": TabulatedForce,
    "torsion_spring": TorsionSpring,
    "harmonic_torque": HarmonicTorque,
}
NREAL = max(cls.REAL.width for cls in FORCE_ELEMENTS.values())
NINT = max(cls.INT.width for cls in FORCE_ELEMENTS.values())
NMEM = max([1, *(len(cls.MEMORY) for cls in FORCE_ELEMENTS.values())])
NOUT = max(len(cls.OUTPUTS) for cls in FORCE_ELEMENTS.values())

FILM_BREAKDOWN = 10  # status: ξ ≥ 1 in a bearing without a contact law (+ element index)
THERMAL_RANGE = 1_000_000  # status: a bearing's oil temperature left its viscosity law (+ element index)
JFO_FAILED = 2_000_000  # status: a jfo film's active set did not settle on an accepted step (+ index)


# One compiled kernel per element code. A kernel with the element signature
# (t, q, q̇, k, mem, fint, freal, tables, Q, out) is registered as itself (k: the element's row of
# the tables mem, fint, freal, out); a kernel with a signature of its own as (kernel, its argument
# list), written in those names, the slot constants below and ``kind`` (the element's entry of
# the kinds: for a journal element the laws it uses [T229]). A new element type registers its
# kernel here (and its class above).
FORCE_KERNELS = {
    SPRING_DAMPER: (spring_damper, "q, qd, fint[k, BODY_I], fint[k, BODY_J], freal[k], Q, out[k]"),
    JOURNAL: (
        journal_element,
        "t, q, qd, mem[k], fint[k, BODY_I], fint[k, BODY_J], fint[k], freal[k], tables, Q, out[k], kind",
    ),
    TABULATED_FORCE: (
        tabulated_force,
        "t, q, qd, fint[k, BODY_J], fint[k], freal[k], tables[fint[k, TAB_TABLE]], Q, out[k]",
    ),
    TORSION_SPRING: (torsion_spring, "q, qd, fint[k, BODY_I], fint[k, BODY_J], freal[k], Q, out[k]"),
    HARMONIC_TORQUE: (harmonic_torque, "t, qd, fint[k, BODY_J], freal[k], Q, out[k]"),
}
"""element code -> compiled kernel adding element k's force to Q (or (kernel, argument list))"""

_force_loop = kind_loop(
    "force_loop",
    FORCE_KERNELS,
    ("t", "q", "qd", "mem", "fint", "freal", "tables", "Q", "out"),
    {"BODY_I": BODY_I, "BODY_J": BODY_J, "TAB_TABLE": TAB_TABLE},
)


def journal_laws(fint: np.ndarray) -> tuple:
    """The laws of the journal rows of an element table as the type-level tuple (film, contact,
    friction, oil temperature, asperity contact): the laws the rows use
    (:func:`jointdyn.core.dispatch.law_tuple`) [T229] and 1/None for the optional pieces
    (``forces.journal_pieces``) [T322]. Only these are compiled; a command running several
    models compiles one set for all of them (:func:`jointdyn.multibody.system.shared_kinds`)."""
    rows = fint[fint[:, TYPE] == JOURNAL]

    def family(registry, column):
        return law_tuple(registry, sorted(set(rows[:, column].tolist())))

    pieces = tuple(1 if (rows[:, column] != 0).any() else None for column in (THERMAL, ASPERITY, JFO))
    laws = (family(FILM_MODELS, FILM), family(CONTACT_LAWS, CONTACT), family(FRICTION_LAWS, FRICTION))
    assert (THERMAL_PIECE, ASPERITY_PIECE, JFO_PIECE) == (len(laws), len(laws) + 1, len(laws) + 2)
    return (*laws, *pieces)


def kinds_of(fint: np.ndarray) -> tuple:
    """The ``kinds`` argument of :func:`eval_forces` for an element table: at each code it
    contains the kind's identity (for journal elements the laws they use), None elsewhere
    [T175, T229]."""
    codes = fint[:, TYPE].tolist()
    ids = {c: identity(k[0] if isinstance(k, tuple) else k) for c, k in FORCE_KERNELS.items() if c in codes}
    if JOURNAL in codes:
        ids[JOURNAL] = journal_laws(fint)
    return kinds_tuple(codes, tuple(FORCE_KERNELS), ids)


def _either(x, y):
    return x if y is None or x == y else (y if x is None else x)


def _laws_union(a: tuple, b: tuple) -> tuple:
    """The journal laws of two systems together (:func:`journal_laws`): per family the laws of
    either, per optional piece present in either [T322]."""
    if len(a) != len(b):
        return a
    return tuple(
        tuple(_either(u, v) for u, v in zip(x, y, strict=True))
        if isinstance(x, tuple) and isinstance(y, tuple) and len(x) == len(y)
        else _either(x, y)
        for x, y in zip(a, b, strict=True)
    )


def kinds_union(a: tuple, b: tuple) -> tuple:
    """The kinds of two systems together, entry by entry (:func:`kinds_of`): a kernel set that
    serves both [T341]; for journal elements the laws of both [T322]. Where both have a kind or
    law with different identities (from user code), ``a``'s is kept: the second system then
    compiles its own set, as without the union."""
    if len(a) != len(b):
        return a
    return tuple(
        _laws_union(x, y) if c == JOURNAL and isinstance(x, tuple) and isinstance(y, tuple) else _either(x, y)
        for c, (x, y) in enumerate(zip(a, b, strict=True))
    )


@njit(cache=True)
def eval_forces(t, q, qd, mem, fint, freal, tables, Q, out, kinds=None):
    """Add all element forces to Q; fill ``out`` (nf, NOUT). ``kinds`` (:func:`kinds_of`) selects
    the element kinds compiled into this specialisation; None: every registered kind [T175].
    Probing inadmissible states is allowed and evaluated guarded (see ``journal_element``);
    breakdown is reported by :func:`advance_memory` on accepted steps."""
    _force_loop(kinds, t, q, qd, mem, fint, freal, tables, Q, out)


def _build_journal_kind(kinds):
    expr = f"kinds[{JOURNAL}]" if isinstance(kinds, types.BaseTuple) else "None"
    return generated("journal_kind", ["def journal_kind(kinds):", f"    return {expr}"], {})


_journal_kind = generated_overload("journal_kind", "kinds", _build_journal_kind)  # its laws [T229]


@njit(inline="always")
def _heat_oil(t, q, qd, mem, k, fint, freal, tables, laws):
    """The film's loss at the accepted state heats the oil of element k [T311]."""
    scratch = np.zeros(q.shape[0])
    out = np.zeros(NOUT)
    bi, bj = fint[k, BODY_I], fint[k, BODY_J]
    journal_element(t, q, qd, mem[k], bi, bj, fint[k], freal[k], tables, scratch, out, laws)
    return thermal_step(mem[k], freal[k, THERMAL_P0:THERMAL_P1], t, out[O_LOSS])


_heat_gate = law_gate(
    "heat_oil",
    THERMAL_PIECE,
    _heat_oil,
    ("t", "q", "qd", "mem", "k", "fint", "freal", "tables", "laws_"),
    "0",
)


@njit(inline="always")
def _commit_film(t, q, qd, mem, k, fint, freal, tables, laws):
    """Commit the jfo film of element k at the accepted state [T307]."""
    r = freal[k]
    ex, ey, edx, edy, six, siy, sjx, sjy, wi, wj = journal_kinematics(
        q, qd, fint[k, BODY_I], fint[k, BODY_J], r
    )
    c = r[_CLR]
    cap = min((c - r[_H_ASP]) / c if fint[k, CONTACT] != _NO_CONTACT else _XI_GUARD, _XI_GUARD)
    bi = fint[k, BODY_I]
    return jfo_commit_gate(laws, t, mem[k], tables, fint[k, JFO], q, bi, ex, ey, wi, wj, r[R_J], c, cap)


@njit(inline="always")
def _journal_memory(t, q, qd, mem, fint, freal, tables, kinds):
    laws = _journal_kind(kinds)
    for k in range(fint.shape[0]):
        if fint[k, TYPE] != JOURNAL:
            continue
        if fint[k, THERMAL] != 0 and _heat_gate(laws, t, q, qd, mem, k, fint, freal, tables, laws) != 0:
            return THERMAL_RANGE + k
        if fint[k, JFO] != 0 and _commit_film(t, q, qd, mem, k, fint, freal, tables, laws) != 0:
            return JFO_FAILED + k
        delta, dd = penetration(q, qd, fint[k, BODY_I], fint[k, BODY_J], freal[k])
        if fint[k, CONTACT] == _NO_CONTACT:
            if delta >= 0.0:  # ξ ≥ 1 with no contact law (c_c = c here)
                return FILM_BREAKDOWN + k
            continue
        mem[k, MAX_PEN] = max(mem[k, MAX_PEN], delta)
        if mem[k, IN_CONTACT] < 0.5 and delta > 0.0:
            mem[k, IN_CONTACT] = 1.0
            mem[k, ONSET_VEL] = max(dd, freal[k, V_MIN])
            mem[k, IMPACTS] += 1.0
        elif mem[k, IN_CONTACT] > 0.5 and delta <= 0.0:
            mem[k, IN_CONTACT] = 0.0
    return 0


@njit(cache=True)
def onset_fraction(q0, qd0, q1, qd1, mem, fint, freal):
    """If a trial step ends with an unresolved contact onset (penetration above the element's
    onset tolerance while not in contact), the fraction of the step to retry with; else 1.0.
    Independent of the model's kinds: part of the step loop, not of a kernel set [T383]."""
    frac = 1.0
    for k in range(fint.shape[0]):
        if fint[k, TYPE] != JOURNAL or fint[k, CONTACT] == _NO_CONTACT or mem[k, IN_CONTACT] > 0.5:
            continue
        d1, _ = penetration(q1, qd1, fint[k, BODY_I], fint[k, BODY_J], freal[k])
        tol = freal[k, ONSET_TOL]
        if d1 > tol:
            d0, _ = penetration(q0, qd0, fint[k, BODY_I], fint[k, BODY_J], freal[k])
            f = (0.5 * tol - d0) / (d1 - d0) if d1 > d0 else 0.5
            frac = min(frac, max(0.01, min(0.95, f)))
    return frac


@njit(inline="always")
def _journal_step_limit(q, qd, mem, fint, freal, kinds):
    laws = _journal_kind(kinds)
    h = 1e300
    for k in range(fint.shape[0]):
        if fint[k, TYPE] == JOURNAL and fint[k, THERMAL] != 0:
            h = min(h, thermal_limit(laws, mem[k], freal[k, THERMAL_P0:THERMAL_P1]))
        if fint[k, TYPE] == JOURNAL and fint[k, JFO] != 0:
            h = min(h, jfo_limit(laws, mem[k]))  # [T308]
        if fint[k, TYPE] != JOURNAL or fint[k, CONTACT] == _NO_CONTACT or mem[k, IN_CONTACT] > 0.5:
            continue
        delta, dd = penetration(q, qd, fint[k, BODY_I], fint[k, BODY_J], freal[k])
        if dd > 0.0 and delta < 0.0:
            h = min(h, (-delta + freal[k, ONSET_TOL]) / dd)
    return h


# The accepted-step hooks of journal elements, compiled only for a model that has one [T175].
_memory_gate = kind_gate(
    "memory_gate", JOURNAL, _journal_memory, ("t", "q", "qd", "mem", "fint", "freal", "tables", "kinds_"), "0"
)
_step_gate = kind_gate(
    "step_gate", JOURNAL, _journal_step_limit, ("q", "qd", "mem", "fint", "freal", "kinds_"), "1e300"
)


@njit(cache=True)
def advance_memory(t, q, qd, mem, fint, freal, tables, kinds=None):
    """After an accepted step: record contact onsets (δ̇⁻) and separations [T16]; advance oil
    temperatures [T311]; stop on film breakdown. Returns 0, FILM_BREAKDOWN or THERMAL_RANGE +
    element index. ``kinds`` as in :func:`eval_forces`."""
    return _memory_gate(kinds, t, q, qd, mem, fint, freal, tables, kinds)


@njit(cache=True)
def step_limit(q, qd, mem, fint, freal, kinds=None):
    """Largest step that cannot carry a free journal through its gap at the current approach
    speed [s]: (gap + tol)/δ̇ for elements not in contact, and the oil temperature's step limit
    [T312] (inf if none)."""
    return _step_gate(kinds, q, qd, mem, fint, freal, kinds)


def memory_slots(e) -> dict:
    """Memory slots element ``e`` uses: its ``memory_slots()`` if declared, else its ``MEMORY``."""
    return e.memory_slots() if hasattr(e, "memory_slots") else type(e).MEMORY


def output_slots(e) -> dict:
    """Outputs element ``e`` writes (name -> unit): its ``output_slots()`` if declared, else its
    class's ``OUTPUTS`` (a journal bearing's jfo film outputs only with the film [T306])."""
    return e.output_slots() if hasattr(e, "output_slots") else type(e).OUTPUTS


def element_tables(elements, body_index, point_of):
    """Pack force-element dataclasses into (fint, freal, tables, mem0) through their declared
    layouts: each element's ``pack(tables, body_index) -> (ints, reals, blocks)`` names its own
    slots; the header (code, bodies) and the two points are filled here for all."""
    fint = np.zeros((len(elements), NINT), dtype=np.int64)
    freal = np.zeros((len(elements), NREAL))
    width = max([NMEM, *(e.memory_width() for e in elements if hasattr(e, "memory_width"))])
    mem0 = np.zeros((len(elements), width))  # a jfo film's cells widen the rows [T306]
    tabs = [np.zeros((1, 2))]  # table 0: unused placeholder; tables are (rows, 2) slices
    for k, e in enumerate(elements):
        cls = type(e)
        ints, reals, blocks = e.pack(tabs, body_index)
        cls.INT.pack(
            fint[k], {"type": e.code, "body_i": body_index(e.body_i), "body_j": body_index(e.body_j), **ints}
        )
        pi = point_of(e.body_i, e.point_i) if e.point_i is not None else (0.0, 0.0)
        pj = point_of(e.body_j, e.point_j) if e.point_j is not None else (0.0, 0.0)  # couples: no point
        points = {"xi_i": pi[0], "eta_i": pi[1], "xi_j": pj[0], "eta_j": pj[1]}
        cls.REAL.pack(freal[k], {**points, **reals}, blocks)
        for name, v in (e.memory0() if hasattr(e, "memory0") else {}).items():  # [T307, T311]
            mem0[k, list(cls.MEMORY).index(name)] = v
    rows = max(t.shape[0] for t in tabs)
    tables = np.zeros((len(tabs), rows, 2))
    for i, t in enumerate(tabs):
        tables[i, : t.shape[0]] = t
    return fint, freal, tables, mem0


@njit(cache=True)
def film_gap_rows(q, qd, fint, freal, rtol, atol, qsc):
    """0, or FILM_BREAKDOWN + k for the first journal bearing without a contact law whose film
    is thinner than the change of |e| a state error at the tolerances can make [T115]
    (``integrators.accuracy.film_gap_unresolved``). Independent of the kinds [T383]."""
    for k in range(fint.shape[0]):
        if fint[k, TYPE] != JOURNAL or fint[k, CONTACT] != _NO_CONTACT:
            continue
        bi, bj = fint[k, BODY_I], fint[k, BODY_J]
        d0, _ = penetration(q, qd, bi, bj, freal[k])
        qp = q.copy()
        spread = 0.0
        for j in range(q.shape[0]):
            s = qsc[j] if j < qsc.shape[0] and qsc[j] > 0.0 else abs(q[j])
            qp[j] = q[j] + (atol + rtol * s)
            d1, _ = penetration(qp, qd, bi, bj, freal[k])
            spread += abs(d1 - d0)
            qp[j] = q[j]
        if -d0 <= spread:
            return FILM_BREAKDOWN + k
    return 0
