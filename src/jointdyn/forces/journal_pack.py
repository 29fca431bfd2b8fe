"""Packing of the journal elements' rows (slots, parameter blocks and tables [T14–T16, T311, T315])
and the capabilities that depend on the pieces an element uses (memory, outputs [T306])."""

from __future__ import annotations

import math

from jointdyn.core.layout import params_of
from jointdyn.film.models import NONE as NO_FILM
from jointdyn.forces import jfo_film
from jointdyn.forces.contact_laws import NONE as NO_CONTACT
from jointdyn.forces.friction_laws import NONE as NO_FRICTION


def _viscosity(el, thermal) -> float:
    """μ [Pa·s] packed into the element row: the constant one, or with ``thermal`` μ(T_in) of
    its oil at T(t₀) (the kernel then reads μ(T) from memory [T311])."""
    mu = getattr(el, "viscosity", None)
    if mu is None:
        return thermal.memory0()["viscosity"] if thermal is not None else 0.0
    return mu


def pack_journal(el, tables: list, body_index) -> tuple[dict, dict, dict]:
    """Element-specific slots (ints, reals, blocks) of a journal element's declared layouts; film
    and asperity tables are appended to ``tables`` and referenced by index."""
    film = el._film()
    table = 0
    if film is not None and hasattr(film, "table") and not getattr(film, "transient", False):
        tables.append(film.table(el.length, el.journal_radius))
        table = len(tables) - 1
    thermal = getattr(el, "thermal", None)
    asperity = getattr(el, "asperity", None)
    jfo = jfo_of(el)
    jfo_slot = 0
    if jfo is not None:  # the film's mesh [T306]; no force table
        table = 0
        jfo_slot = len(tables)
        tables.extend(jfo_film.pack(jfo, el.length, el.journal_radius, el.viscosity, el.clearance))
    asp_table = 0
    if asperity is not None:  # two consecutive tables: radial resultant and normal load [T315]
        tables.extend(asperity.tables(el.journal_radius, el.length, el.clearance))
        asp_table = len(tables) - 2
    ints = {
        "thermal": int(thermal is not None),
        "asperity": asp_table,
        "jfo": jfo_slot,
        "film": film.code if film is not None else NO_FILM,
        "contact": el.contact.code if el.contact is not None else NO_CONTACT,
        "friction": el.friction.code if el.friction is not None else NO_FRICTION,
        "table": table,
        "shear": int(getattr(el, "shear", False)),
    }
    reals = {
        "bearing_radius": el.bearing_radius,
        "journal_radius": el.journal_radius,
        "length": getattr(el, "length", 0.0),
        "viscosity": _viscosity(el, thermal),
        "clearance": el.clearance,
        "asperity_height": getattr(el, "asperity_height", 0.0),
        "onset_tolerance": el.onset_tolerance,
        "min_impact_velocity": el.min_impact_velocity,
    }
    laws = (("film", film), ("contact", el.contact), ("friction", el.friction), ("asperity", asperity))
    blocks = {name: params_of(law) for name, law in laws if law is not None}
    if thermal is not None:
        blocks["thermal"] = thermal.params()
    return ints, reals, blocks


def jfo_of(el):
    """The transient jfo film of a journal element (``Finite`` with a mass-conserving
    cavitation), or None [T306]."""
    film = el._film()
    return film if getattr(film, "transient", False) else None


def check_jfo(el) -> None:
    """ValueError unless the pieces of a bearing with a transient jfo film go together [T306]."""
    if jfo_of(el) is not None and getattr(el, "thermal", None) is not None:
        raise ValueError(
            f"{type(el).__name__}.thermal: the transient jfo film (film cavitation 'jfo') runs at a "
            "constant viscosity; omit thermal or use cavitation 'reynolds' [T306]"
        )


def _split(names: dict, start: int, stop: int) -> dict:
    keys = list(names)[start:stop]
    return {k: names[k] for k in keys}


def memory_slots(el) -> dict[str, str]:
    """The memory slots a bearing uses: the journal element's, the oil temperature's only with
    ``thermal`` [T311], the jfo film's only with a transient film [T306]."""
    mem = type(el).MEMORY
    base, jfo = jfo_film.BASE, jfo_film.BASE + len(jfo_film.MEMORY)
    return (
        _split(mem, 0, 4)
        | (_split(mem, 4, base) if el.thermal is not None else {})
        | (_split(mem, base, jfo) if jfo_of(el) is not None else {})
    )


def output_slots(el) -> dict[str, str]:
    """The outputs a bearing writes, in slot order (the first slots of the class's ``OUTPUTS``):
    the jfo film's (content, flows, then the flow of each supply feature under its own name,
    :func:`~jointdyn.forces.jfo_film.feature_names`) only with a transient film [T306, T376]."""
    outs = type(el).OUTPUTS
    base = len(outs) - len(jfo_film.OUTPUTS)
    jfo = jfo_of(el)
    if jfo is None:
        return _split(outs, 0, base)
    return _split(outs, 0, base + len(jfo_film.FILM_OUTPUTS)) | dict.fromkeys(
        jfo_film.feature_names(jfo), "m³/s"
    )


def memory_width(el) -> int:
    """Memory slots of the element's row: the named ones, then the jfo film's cells [T306]."""
    jfo = jfo_of(el)
    return len(type(el).MEMORY) + (jfo_film.cells(jfo) if jfo is not None else 0)


def memory0(el) -> dict[str, float]:
    """Initial memory: the oil temperature's [T311]; the jfo film's commit time NaN (its contents
    start full at the first accepted-step hook, the run's start) [T307]."""
    m0 = el.thermal.memory0() if el.thermal is not None else {}
    return m0 | ({"film_time": math.nan} if jfo_of(el) is not None else {})


def failure_hint(el, name: str, out: dict) -> str:
    """Capability: what this element's outputs ``out`` (name -> value) at a failed run's last
    state say about the failure, or ''. Near the wall (ξ > 0.99) the film is stiff: the usual
    cause of a step-size collapse; a film without a contact law cannot carry the load there."""
    if not out["xi"] > 0.99:
        return ""
    advice = (
        "; the film alone cannot carry the load there — give the bearing a contact law (mixed regime)"
        if el._film() is not None and el.contact is None
        else ""
    )
    return f"element {name!r} was at ξ = {out['xi']:.6f} (h_min = {out['h_min']:.3g} m){advice}"
