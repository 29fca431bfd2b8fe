"""Friction laws (compiled kernels) and their registry.

Kernel: ``friction_coefficient(code, vt, p) -> μ_eff`` with the sign of the slip velocity
v_t [m/s], so that the tangential force is −μ_eff·F_n (opposing slip).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from numba import njit

NONE, COULOMB, AMBROSIO = 0, 1, 2


@njit(cache=True)
def friction_coefficient(code, vt, p):
    """μ_eff(v_t) [-] of law ``code``, p = [μ_d, v_reg or v0, v1, 0] [T60–T62]."""
    if code == COULOMB:
        return p[0] * math.tanh(vt / p[1])  # [T61]
    if code == AMBROSIO:
        a = abs(vt)
        v0 = p[1]
        v1 = p[2]
        if a <= v0:
            cd = 0.0
        elif a >= v1:
            cd = 1.0
        else:
            x = (a - v0) / (v1 - v0)  # [T62]
            cd = x * x * (3.0 - 2.0 * x)
        return p[0] * cd * (1.0 if vt > 0 else -1.0)
    return 0.0


def _check(owner, name, v, unit, rule, ok):
    if not (isinstance(v, (int, float)) and math.isfinite(v) and ok(v)):
        raise ValueError(f"{owner}.{name} = {v!r} [{unit}]: must be {rule}")


@dataclass(frozen=True)
class Coulomb:
    """Regularised Coulomb friction μ_eff = μ tanh(v_t/v_reg) [T61]."""

    coefficient: float
    """μ [-], ≥ 0"""
    regularization_velocity: float = 1e-4
    """v_reg [m/s], > 0"""
    code: ClassVar[int] = COULOMB

    def __post_init__(self):
        _check("Coulomb", "coefficient", self.coefficient, "-", "≥ 0", lambda v: v >= 0)
        _check(
            "Coulomb", "regularization_velocity", self.regularization_velocity, "m/s", "> 0", lambda v: v > 0
        )

    def params(self):
        return (float(self.coefficient), float(self.regularization_velocity), 0.0, 0.0)


@dataclass(frozen=True)
class Ambrosio:
    """Ambrósio's modified Coulomb law (2002): no friction below v0, full above v1, smooth
    ramp between [T62]."""

    coefficient: float
    """μ [-], ≥ 0"""
    v0: float = 1e-4
    """v0 [m/s], ≥ 0"""
    v1: float = 1e-3
    """v1 [m/s], > v0"""
    code: ClassVar[int] = AMBROSIO

    def __post_init__(self):
        _check("Ambrosio", "coefficient", self.coefficient, "-", "≥ 0", lambda v: v >= 0)
        _check("Ambrosio", "v0", self.v0, "m/s", "≥ 0", lambda v: v >= 0)
        _check("Ambrosio", "v1", self.v1, "m/s", f"> v0 = {self.v0}", lambda v: v > self.v0)

    def params(self):
        return (float(self.coefficient), float(self.v0), float(self.v1), 0.0)


FRICTION_LAWS = {"coulomb": Coulomb, "ambrosio": Ambrosio}
