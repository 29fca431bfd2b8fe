"""Normal contact laws (compiled kernels) and their registry.

Kernel: ``contact_force(code, delta, delta_dot, delta_dot0, p) -> F_n ≥ 0`` with penetration
δ [m] (> 0 in contact), its rate δ̇ [m/s], the rate at contact onset δ̇⁻ [m/s] and the law's
four parameters p. Damped laws are clamped to F_n ≥ 0 (no adhesive pull while separating).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from numba import njit

HERTZ, LANKARANI_NIKRAVESH, HUNT_CROSSLEY, FLORES, KELVIN_VOIGT = 0, 1, 2, 3, 4


@njit(cache=True)
def contact_force(code, delta, delta_dot, delta_dot0, p):
    """F_n [N] of law ``code`` (p = [K, n, c_r or D, 0]) [T50–T55]."""
    if delta <= 0.0:
        return 0.0
    K = p[0]
    if code == KELVIN_VOIGT:
        f = K * delta + p[2] * delta_dot  # [T55]
        return f if f > 0.0 else 0.0
    fe = K * delta ** p[1]
    cr = p[2]
    if code == HERTZ:
        return fe  # [T51]
    if code == LANKARANI_NIKRAVESH:
        chi = 0.75 * (1.0 - cr * cr)  # [T52]
    elif code == HUNT_CROSSLEY:
        chi = 1.5 * (1.0 - cr)  # [T53]
    elif code == FLORES:
        chi = 8.0 * (1.0 - cr) / (5.0 * cr)  # [T54]
    else:
        return math.nan
    f = fe * (1.0 + chi * delta_dot / delta_dot0)
    return f if f > 0.0 else 0.0


def _check(owner, name, v, unit, rule, ok):
    if not (isinstance(v, (int, float)) and math.isfinite(v) and ok(v)):
        raise ValueError(f"{owner}.{name} = {v!r} [{unit}]: must be {rule}")


@dataclass(frozen=True)
class _PowerLaw:
    stiffness: float
    """K [N/m^n], > 0"""
    exponent: float = 1.5
    """n [-], > 0 (1.5 for Hertzian cylinder-in-hole approximations)"""
    restitution: float = 1.0
    """coefficient of restitution c_r [-] in (0, 1]"""

    def __post_init__(self):
        o = type(self).__name__
        _check(o, "stiffness", self.stiffness, "N/m^n", "> 0", lambda v: v > 0)
        _check(o, "exponent", self.exponent, "-", "> 0", lambda v: v > 0)
        _check(o, "restitution", self.restitution, "-", "in (0, 1]", lambda v: 0 < v <= 1)

    def params(self):
        return (float(self.stiffness), float(self.exponent), float(self.restitution), 0.0)


@dataclass(frozen=True)
class Hertz(_PowerLaw):
    """Hertz, F = Kδⁿ (elastic, no dissipation) [T51]."""

    code: ClassVar[int] = HERTZ


@dataclass(frozen=True)
class LankaraniNikravesh(_PowerLaw):
    """Lankarani–Nikravesh (1990), F = Kδⁿ[1 + 3(1−c_r²)/4 · δ̇/δ̇⁻] [T52]; for c_r near 1."""

    restitution: float = 0.9
    code: ClassVar[int] = LANKARANI_NIKRAVESH


@dataclass(frozen=True)
class HuntCrossley(_PowerLaw):
    """Hunt–Crossley (1975), F = Kδⁿ[1 + 3(1−c_r)/2 · δ̇/δ̇⁻] [T53]."""

    restitution: float = 0.9
    code: ClassVar[int] = HUNT_CROSSLEY


@dataclass(frozen=True)
class Flores(_PowerLaw):
    """Flores et al. (2011), F = Kδⁿ[1 + 8(1−c_r)/(5c_r) · δ̇/δ̇⁻] [T54]; any c_r in (0, 1]."""

    restitution: float = 0.9
    code: ClassVar[int] = FLORES


@dataclass(frozen=True)
class KelvinVoigt:
    """Linear spring–damper contact F = Kδ + Dδ̇, clamped ≥ 0 [T55]."""

    stiffness: float
    """K [N/m], > 0"""
    damping: float = 0.0
    """D [N·s/m], ≥ 0"""
    code: ClassVar[int] = KELVIN_VOIGT

    def __post_init__(self):
        _check("KelvinVoigt", "stiffness", self.stiffness, "N/m", "> 0", lambda v: v > 0)
        _check("KelvinVoigt", "damping", self.damping, "N·s/m", "≥ 0", lambda v: v >= 0)

    def params(self):
        return (float(self.stiffness), 1.0, float(self.damping), 0.0)


CONTACT_LAWS = {
    "hertz": Hertz,
    "lankarani_nikravesh": LankaraniNikravesh,
    "hunt_crossley": HuntCrossley,
    "flores": Flores,
    "kelvin_voigt": KelvinVoigt,
}


def law_from_name(name: str, **kwargs):
    """Instantiate a contact law by registry name."""
    if name not in CONTACT_LAWS:
        raise ValueError(f"contact law {name!r} is unknown; valid: {sorted(CONTACT_LAWS)}")
    return CONTACT_LAWS[name](**kwargs)


def journal_bearing_stiffness(R_bearing, R_journal, E_bearing, nu_bearing, E_journal, nu_journal):
    """K = (4/3)/(σ_i + σ_j)·√(R_i R_j/(R_i − R_j)), σ = (1−ν²)/E [N/m^1.5] [T56].

    Hertz's relation for two cylinders with the effective radius of internal contact, as used
    for clearance joints by Lankarani & Nikravesh (1990) and Flores et al. (2006); an
    approximation for conformal contact (it overestimates K for large contact arcs)."""
    for name, v, unit in (("E_bearing", E_bearing, "Pa"), ("E_journal", E_journal, "Pa")):
        _check("journal_bearing_stiffness", name, v, unit, "> 0", lambda x: x > 0)
    for name, v in (("nu_bearing", nu_bearing), ("nu_journal", nu_journal)):
        _check("journal_bearing_stiffness", name, v, "-", "in (-1, 0.5)", lambda x: -1 < x < 0.5)
    _check(
        "journal_bearing_stiffness",
        "R_journal",
        R_journal,
        "m",
        f"in (0, R_bearing = {R_bearing})",
        lambda x: 0 < x < R_bearing,
    )
    s = (1 - nu_bearing**2) / E_bearing + (1 - nu_journal**2) / E_journal
    return (4.0 / 3.0) / s * math.sqrt(R_bearing * R_journal / (R_bearing - R_journal))
