"""Packing of the journal elements' rows: slots, parameter blocks and tables [T14–T16, T311, T315]."""

from __future__ import annotations

from jointdyn.core.layout import params_of
from jointdyn.film.models import NONE as NO_FILM
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
    if film is not None and hasattr(film, "table"):
        tables.append(film.table(el.length, el.journal_radius))
        table = len(tables) - 1
    thermal = getattr(el, "thermal", None)
    asperity = getattr(el, "asperity", None)
    asp_table = 0
    if asperity is not None:  # two consecutive tables: radial resultant and normal load [T315]
        tables.extend(asperity.tables(el.journal_radius, el.length, el.clearance))
        asp_table = len(tables) - 2
    ints = {
        "thermal": int(thermal is not None),
        "asperity": asp_table,
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
