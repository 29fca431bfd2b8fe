"""Friction laws (compiled kernels) and their registry [T60–T63].

Kernel: ``friction_coefficient(code, vt, p) -> μ_eff`` [-], signed like the slip velocity
v_t [m/s], so that the tangential force is F_t = −μ_eff·F_n (opposing the slip) [T60]; ``p`` are
the law's four parameters (from its ``params()``). μ_eff(0) = 0 for every law, and every law is
continuous in v_t (the exact Coulomb sign function is replaced by a regularisation).

Each law is a frozen dataclass (fields = the model-file schema) with ``params()``, a ``code`` and
a ``theory`` tag, registered in ``FRICTION_LAWS``. Code 0 means "no friction": the journal
elements skip the friction branch for it (``friction=None`` or ``NoFriction()``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from numba import njit

NONE, COULOMB, AMBROSIO = 0, 1, 2


@njit(cache=True)
def friction_coefficient(code, vt, p):
    """Signed friction coefficient μ_eff(v_t) [-] of law ``code`` [T60–T63].

    ``vt`` slip velocity v_t [m/s]; ``p`` float64 array of four parameters [-]:

    * NONE: p unused, μ_eff = 0 [T63]
    * COULOMB: p = [μ, v_reg, 0, 0], μ_eff = μ tanh(v_t/v_reg) [T61]
    * AMBROSIO: p = [μ, v₀, v₁, 0], μ_eff = μ c_d(|v_t|) sgn(v_t), c_d = 0 below v₀, 1 above v₁,
      C¹ cubic ramp x²(3 − 2x), x = (|v_t| − v₀)/(v₁ − v₀), between [T62]

    NaN for an unknown code.
    """
    if code == NONE:
        return 0.0  # [T63]
    if code == COULOMB:
        return p[0] * math.tanh(vt / p[1])  # [T61]
    if code == AMBROSIO:
        a = abs(vt)
        v0 = p[1]
        v1 = p[2]
        if a <= v0:
            return 0.0
        if a >= v1:
            cd = 1.0
        else:
            x = (a - v0) / (v1 - v0)
            cd = x * x * (3.0 - 2.0 * x)  # [T62]
        return p[0] * cd if vt > 0.0 else -p[0] * cd
    return math.nan


def _check(owner, name, v, unit, rule, ok):
    if isinstance(v, bool) or not (isinstance(v, (int, float)) and math.isfinite(v) and ok(v)):
        raise ValueError(f"{owner}.{name} = {v!r} [{unit}]: must be {rule} (and finite)")


@dataclass(frozen=True)
class NoFriction:
    """Frictionless contact, μ_eff = 0 (same as ``friction=None``) [T63]."""

    code: ClassVar[int] = NONE
    theory: ClassVar[str] = "T63"

    def params(self) -> tuple[float, float, float, float]:
        """Kernel parameters p = (0, 0, 0, 0) [T63]."""
        return (0.0, 0.0, 0.0, 0.0)


@dataclass(frozen=True)
class Coulomb:
    """Regularised Coulomb friction μ_eff = μ tanh(v_t/v_reg) [T61].

    μ_eff = tanh(1) μ = 0.762 μ at |v_t| = v_reg and within 4.2e-9 μ of μ beyond 10 v_reg
    (1 − tanh 10); no true sticking (a slow creep of order v_reg replaces it)."""

    coefficient: float
    """dynamic friction coefficient μ, ≥ 0 [-]"""
    regularization_velocity: float = 1e-4
    """regularisation velocity v_reg, > 0 (small against the slip speeds of interest) [m/s]"""
    code: ClassVar[int] = COULOMB
    theory: ClassVar[str] = "T61"

    def __post_init__(self):
        _check("Coulomb", "coefficient", self.coefficient, "-", "≥ 0", lambda v: v >= 0)
        _check(
            "Coulomb", "regularization_velocity", self.regularization_velocity, "m/s", "> 0", lambda v: v > 0
        )

    def params(self) -> tuple[float, float, float, float]:
        """Kernel parameters p = (μ, v_reg, 0, 0) [T61]."""
        return (float(self.coefficient), float(self.regularization_velocity), 0.0, 0.0)


@dataclass(frozen=True)
class Ambrosio:
    """Ambrósio's modified Coulomb law (2002): no friction below v₀, full μ above v₁, a ramp
    between (C¹ cubic here instead of the original linear ramp; same end points and mid-point
    value μ/2) [T62]."""

    coefficient: float
    """dynamic friction coefficient μ, ≥ 0 [-]"""
    v0: float = 1e-4
    """slip speed v₀ below which there is no friction, ≥ 0 [m/s]"""
    v1: float = 1e-3
    """slip speed v₁ above which the full μ acts, > v₀ [m/s]"""
    code: ClassVar[int] = AMBROSIO
    theory: ClassVar[str] = "T62"

    def __post_init__(self):
        _check("Ambrosio", "coefficient", self.coefficient, "-", "≥ 0", lambda v: v >= 0)
        _check("Ambrosio", "v0", self.v0, "m/s", "≥ 0", lambda v: v >= 0)
        _check("Ambrosio", "v1", self.v1, "m/s", f"> v0 = {self.v0}", lambda v: v > self.v0)

    def params(self) -> tuple[float, float, float, float]:
        """Kernel parameters p = (μ, v₀, v₁, 0) [T62]."""
        return (float(self.coefficient), float(self.v0), float(self.v1), 0.0)


FRICTION_LAWS = {"none": NoFriction, "coulomb": Coulomb, "ambrosio": Ambrosio}


def friction_law_from_name(name: str, **kwargs):
    """Instantiate a friction law by its ``FRICTION_LAWS`` name with the law's fields as keywords."""
    if name not in FRICTION_LAWS:
        raise ValueError(f"friction law {name!r} is unknown; valid: {', '.join(sorted(FRICTION_LAWS))}")
    return FRICTION_LAWS[name](**kwargs)
