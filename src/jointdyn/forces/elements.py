"""Force-element dispatch: one compiled loop over the system's element table.

Element tables (built by :mod:`jointdyn.model`): ``fint[k] = [type, body_i, body_j, a, b, c, d,
e]`` (type-specific integer codes) and ``freal[k, :]`` = [ξ_i, η_i, ξ_j, η_j, p₄ …] (local
points [m], then type-specific parameters in SI). ``mem[k, :]`` is the element's memory (e.g.
contact onset velocity); it changes only in :func:`advance_memory`, after accepted steps.

Output columns per element (``OUT_COLUMNS``), all world frame, force on body j.
"""

from __future__ import annotations

from numba import njit

from .film_models import FILM_MODELS
from .journal import (
    CONTACT,
    IN_CONTACT,
    JOURNAL,
    ONSET_TOL,
    ONSET_VEL,
    TABLE,
    V_MIN,
    ClearanceJoint,
    JournalBearing,
    journal_element,
    penetration,
)
from .springs import SPRING_DAMPER, SpringDamper, spring_damper
from .tabulated import TABULATED_FORCE, TabulatedForce, tabulated_force

NOUT = 8
OUT_COLUMNS = ("ex", "ey", "xi", "h_min", "Fx", "Fy", "power", "contact_force")
NMEM = 4
NREAL = 24
NINT = 8

FORCE_ELEMENTS = {
    "spring_damper": SpringDamper,
    "clearance_joint": ClearanceJoint,
    "journal_bearing": JournalBearing,
    "tabulated_force": TabulatedForce,
}

MAX_PEN = 3  # mem column: largest penetration at an accepted step [m] (0 if none)
FILM_BREAKDOWN = 10  # status: ξ ≥ 1 in a bearing without a contact law


@njit(cache=True)
def eval_forces(t, q, qd, mem, fint, freal, tables, Q, out):
    """Add all element forces to Q; fill ``out`` (nf, NOUT). Returns a status code (0 = ok;
    probing inadmissible states is allowed and evaluated guarded, see ``journal_element``)."""
    for k in range(fint.shape[0]):
        typ = fint[k, 0]
        if typ == SPRING_DAMPER:
            spring_damper(q, qd, fint[k, 1], fint[k, 2], freal[k], Q, out[k])
        elif typ == JOURNAL:
            journal_element(q, qd, mem[k], fint[k, 1], fint[k, 2], fint[k], freal[k], tables, Q, out[k])
        elif typ == TABULATED_FORCE:
            tabulated_force(t, q, qd, fint[k, 2], fint[k], freal[k], tables[fint[k, 3]], Q, out[k])
    return 0


@njit(cache=True)
def advance_memory(t, q, qd, mem, fint, freal, tables):
    """After an accepted step: record contact onsets (δ̇⁻) and separations [T16]; stop on
    film breakdown. Returns 0 or FILM_BREAKDOWN + element index."""
    for k in range(fint.shape[0]):
        if fint[k, 0] != JOURNAL:
            continue
        delta, dd = penetration(q, qd, fint[k, 1], fint[k, 2], freal[k])
        if fint[k, CONTACT] < 0:
            if delta >= 0.0:  # ξ ≥ 1 with no contact law (c_c = c here)
                return FILM_BREAKDOWN + k
            continue
        mem[k, MAX_PEN] = max(mem[k, MAX_PEN], delta)
        if mem[k, IN_CONTACT] < 0.5 and delta > 0.0:
            mem[k, IN_CONTACT] = 1.0
            mem[k, ONSET_VEL] = max(dd, freal[k, V_MIN])
            mem[k, 2] += 1.0  # impact counter (mem column 2)
        elif mem[k, IN_CONTACT] > 0.5 and delta <= 0.0:
            mem[k, IN_CONTACT] = 0.0
    return 0


@njit(cache=True)
def onset_fraction(q0, qd0, q1, qd1, mem, fint, freal):
    """If a trial step ends with an unresolved contact onset (penetration above the element's
    onset tolerance while not in contact), the fraction of the step to retry with; else 1.0."""
    frac = 1.0
    for k in range(fint.shape[0]):
        if fint[k, 0] != JOURNAL or fint[k, CONTACT] < 0 or mem[k, IN_CONTACT] > 0.5:
            continue
        d1, _ = penetration(q1, qd1, fint[k, 1], fint[k, 2], freal[k])
        tol = freal[k, ONSET_TOL]
        if d1 > tol:
            d0, _ = penetration(q0, qd0, fint[k, 1], fint[k, 2], freal[k])
            f = (0.5 * tol - d0) / (d1 - d0) if d1 > d0 else 0.5
            frac = min(frac, max(0.01, min(0.95, f)))
    return frac


@njit(cache=True)
def step_limit(q, qd, mem, fint, freal):
    """Largest step that cannot carry a free journal through its gap at the current approach
    speed [s]: (gap + tol)/δ̇ for elements not in contact (inf if none)."""
    h = 1e300
    for k in range(fint.shape[0]):
        if fint[k, 0] != JOURNAL or fint[k, CONTACT] < 0 or mem[k, IN_CONTACT] > 0.5:
            continue
        delta, dd = penetration(q, qd, fint[k, 1], fint[k, 2], freal[k])
        if dd > 0.0 and delta < 0.0:
            h = min(h, (-delta + freal[k, ONSET_TOL]) / dd)
    return h


def element_tables(elements, body_index, point_of):
    """Flatten force-element dataclasses into (fint, freal, tables, mem0)."""
    import numpy as np

    fint = np.zeros((len(elements), NINT), dtype=np.int64)
    freal = np.zeros((len(elements), NREAL))
    mem0 = np.zeros((len(elements), NMEM))
    tabs = [np.zeros((1, 2))]  # table 0: unused placeholder; tables are (rows, 2) slices
    for k, e in enumerate(elements):
        fint[k, 0] = e.code
        fint[k, 1] = body_index(e.body_i)
        fint[k, 2] = body_index(e.body_j)
        freal[k, 2:4] = point_of(e.body_j, e.point_j)
        if isinstance(e, TabulatedForce):
            tabs.append(np.column_stack([e.x, e.y]).astype(float))
            d = np.asarray(e.direction, float)
            fint[k, 3] = len(tabs) - 1
            fint[k, 4] = -2 if e.argument == "time" else body_index(e.argument)
            fint[k, 5] = len(e.x)
            freal[k, 4:7] = (*(d / np.hypot(*d)), e.period)
            continue
        ints = e.int_params() if hasattr(e, "int_params") else ()
        fint[k, 3 : 3 + len(ints)] = ints
        if isinstance(e, JournalBearing) and hasattr(FILM_MODELS[e.film], "table"):
            tabs.append(FILM_MODELS[e.film].table(e.length, e.journal_radius))
            fint[k, TABLE] = len(tabs) - 1
        freal[k, 0:2] = point_of(e.body_i, e.point_i)
        p = e.params()
        freal[k, 4 : 4 + len(p)] = p
    rows = max(t.shape[0] for t in tabs)
    tables = np.zeros((len(tabs), rows, 2))
    for i, t in enumerate(tabs):
        tables[i, : t.shape[0]] = t
    return fint, freal, tables, mem0
