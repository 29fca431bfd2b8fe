"""What a study takes from a model when the user does not say: the revolution (period
2π/|ω| of an angle driver [T7]) and the journal element whose orbit is studied.

Every function ends a missing quantity with one ``ValueError`` line naming what to give
instead; nothing here knows a particular mechanism.
"""

from __future__ import annotations

import math

import numpy as np

from jointdyn.core.constraints import AngleDriver


def angle_drivers(system) -> list[str]:
    """Names of the angle drivers of a System, in model order."""
    return [n for n, c in zip(system.constraint_names, system.constraints) if isinstance(c, AngleDriver)]


def journal_elements(system) -> list[str]:
    """Names of the elements with an orbit (declared outputs ``ex``, ``ey`` and a clearance)."""
    return [
        n
        for n, e in zip(system.element_names, system.elements)
        if {"ex", "ey"} <= set(type(e).OUTPUTS) and hasattr(e, "clearance")
    ]


def driver(system, name: str | None = None, option: str = "--driver") -> AngleDriver:
    """The angle driver ``name``, or the model's first one; a one-line error when absent."""
    names = angle_drivers(system)
    if name is None:
        if not names:
            raise ValueError(
                f"model {system.name!r} has no angle driver, so no revolution: give the period "
                "explicitly (--period [s]) or add a joint of type angle_driver"
            )
        name = names[0]
    if name not in names:
        raise ValueError(f"{option} {name!r}: not an angle driver of the model; valid: {names}")
    return system.constraints[system.constraint_names.index(name)]


def driver_name(system, name: str | None = None, option: str = "--driver") -> str:
    """Name of the angle driver ``name`` or of the model's first one (checked as :func:`driver`)."""
    d = driver(system, name, option)
    return system.constraint_names[system.constraints.index(d)]


def driver_period(system, name: str | None = None, option: str = "--driver") -> float:
    """Period of one revolution of an angle driver, T = 2π/|ω| [s] [T7]; an error when the
    driver does not turn at a constant speed (ω = 0 or α ≠ 0)."""
    d = driver(system, name, option)
    if d.alpha != 0 or not (math.isfinite(d.omega) and d.omega != 0):
        raise ValueError(
            f"angle driver {driver_name(system, name, option)!r} (omega = {d.omega!r} rad/s, alpha = "
            f"{d.alpha!r} rad/s²) does not turn at a constant speed: give the period explicitly"
        )
    return 2 * math.pi / abs(d.omega)


def driver_angle(res, name: str) -> np.ndarray:
    """Relative angle φ_j − φ_i of an angle driver's bodies at the samples, unwrapped [rad]."""
    s = res.system
    d = s.constraints[s.constraint_names.index(name)]
    ang = [res.coordinate(b, "phi") if b != "ground" else np.zeros_like(res.t) for b in (d.body_i, d.body_j)]
    return ang[1] - ang[0]


def journal(system, name: str | None = None, option: str = "--element") -> str:
    """The journal element ``name`` or the model's first one; a one-line error when absent."""
    names = journal_elements(system)
    if name is None:
        if not names:
            raise ValueError(
                f"model {system.name!r} has no journal element (dry clearance joint or lubricated "
                "bearing): nothing has an orbit to study"
            )
        return names[0]
    if name not in names:
        raise ValueError(f"{option} {name!r}: not a journal element of the model; valid: {names}")
    return name


def per_revolution_config(system, config, revs: float, samples_per_rev: int, period: float | None = None):
    """``config`` with ``t_end`` = ``revs`` revolutions of the model's first angle driver (or of
    ``period`` [s]) and ``samples_per_rev`` output samples per revolution (sample 0 at t = 0)."""
    import dataclasses

    from jointdyn.core.checks import check

    check("revs", revs, "revolutions", "> 0")
    check("samples_per_rev", samples_per_rev, "-", ">= 2", integer=True)
    T = driver_period(system) if period is None else period
    return dataclasses.replace(config, t_end=revs * T, n_out=int(round(revs * samples_per_rev)) + 1)
