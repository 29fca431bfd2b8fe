"""Force-element dispatch: one compiled loop over the system's element table.

Element tables (built by :mod:`jointdyn.model`): ``fint[k] = [type, body_i, body_j, a, b, c, d,
e]`` (type-specific integer codes) and ``freal[k, :]`` = [ξ_i, η_i, ξ_j, η_j, p₄ …] (local
points [m], then type-specific parameters in SI). ``mem[k, :]`` is the element's memory (e.g.
contact onset velocity); it changes only in :func:`advance_memory`, after accepted steps.

Output columns per element (``OUT_COLUMNS``), all world frame, force on body j.
"""

from __future__ import annotations

from numba import njit

from .springs import SPRING_DAMPER, SpringDamper, spring_damper

NOUT = 8
OUT_COLUMNS = ("ex", "ey", "xi", "h_min", "Fx", "Fy", "power", "contact_force")
NMEM = 4
NREAL = 24
NINT = 8

FORCE_ELEMENTS = {"spring_damper": SpringDamper}


@njit(cache=True)
def eval_forces(t, q, qd, mem, fint, freal, tables, Q, out):
    """Add all element forces to Q; fill ``out`` (nf, NOUT). Returns a status code (0 = ok)."""
    status = 0
    for k in range(fint.shape[0]):
        typ = fint[k, 0]
        if typ == SPRING_DAMPER:
            spring_damper(q, qd, fint[k, 1], fint[k, 2], freal[k], Q, out[k])
    return status


@njit(cache=True)
def advance_memory(t, q, qd, mem, fint, freal, tables):
    """Update element memory after an accepted step. Returns a status code (0 = ok)."""
    return 0


@njit(cache=True)
def onset_fraction(q0, qd0, q1, qd1, mem, fint, freal):
    """Fraction of a trial step after which a contact onset happens, or 1.0 if none."""
    return 1.0


@njit(cache=True)
def step_limit(q, qd, mem, fint, freal):
    """Largest step that cannot skip a contact event [s] (inf if none)."""
    return 1e300


def element_tables(elements, body_index, point_of):
    """Flatten force-element dataclasses into (fint, freal, tables, mem0)."""
    import numpy as np

    fint = np.zeros((len(elements), NINT), dtype=np.int64)
    freal = np.zeros((len(elements), NREAL))
    mem0 = np.zeros((len(elements), NMEM))
    tables = np.zeros((1, 1, 1))
    for k, e in enumerate(elements):
        fint[k, 0] = e.code
        fint[k, 1] = body_index(e.body_i)
        fint[k, 2] = body_index(e.body_j)
        ints = e.int_params() if hasattr(e, "int_params") else ()
        fint[k, 3:3 + len(ints)] = ints
        freal[k, 0:2] = point_of(e.body_i, e.point_i)
        freal[k, 2:4] = point_of(e.body_j, e.point_j)
        p = e.params()
        freal[k, 4:4 + len(p)] = p
    return fint, freal, tables, mem0
