"""Steady journal-bearing engineering: 2-D Reynolds solver with cavitation conditions, design
quantities, the Raimondi–Boyd table, equilibrium for a load, film outputs, shear torque
[T70–T83]; mixed lubrication and the Stribeck curve (:mod:`.mixed`, [T260–T272]); the effective
temperature (:mod:`.thermal`, [T276–T277]). The names below are imported lazily, so importing
``jointdyn.cli`` (which registers ``bearing-table``) does not load the solver."""

from __future__ import annotations

__all__ = ["CAVITATION", "COLUMNS", "MODELS", "bearing_table", "equilibrium"]


def __getattr__(name: str):
    if name in ("COLUMNS", "MODELS", "bearing_table", "equilibrium"):
        from jointdyn.bearing import design

        return getattr(design, name)
    if name == "CAVITATION":
        from jointdyn.film.cavitation import names

        return names()
    raise AttributeError(f"module 'jointdyn.bearing' has no attribute {name!r}")
