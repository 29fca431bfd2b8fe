"""Friction laws (compiled kernels) and their registry ``FRICTION_LAWS``.

Each law is a frozen dataclass registered with its integer ``code``, its compiled
``kernel(vt, p) -> μ_eff`` and its ``PARAMS`` (fields packed, in order, into the block p): μ_eff
carries the sign of the slip velocity v_t [m/s], so that the tangential force −μ_eff·F_n opposes
slip. The compiled dispatch by code is generated from the registry (``friction_dispatch``,
``friction_jac_dispatch`` [T229]); ``friction_coefficient(code, …)`` is its Python-level entry;
code −1 (``NONE``) is frictionless.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from numba import njit

from jointdyn.core.dispatch import all_laws, law_switch
from jointdyn.core.layout import Layout, block_width, check_codes, check_finite

COULOMB, AMBROSIO = 0, 1
NONE = -1  # frictionless


@njit(cache=True)
def coulomb_coefficient(vt, p):
    """μ_eff = μ tanh(v_t/v_reg) [T61]."""
    return p[C_MU] * math.tanh(vt / p[C_VREG])


@njit(cache=True)
def ambrosio_coefficient(vt, p):
    """μ_eff = μ·c_d(|v_t|)·sign(v_t), c_d a C¹ ramp from 0 at v0 to 1 at v1 [T62]."""
    a = abs(vt)
    v0 = p[A_V0]
    v1 = p[A_V1]
    if a <= v0:
        cd = 0.0
    elif a >= v1:
        cd = 1.0
    else:
        x = (a - v0) / (v1 - v0)  # [T62]
        cd = x * x * (3.0 - 2.0 * x)
    return p[A_MU] * cd * (1.0 if vt > 0 else -1.0)


@dataclass(frozen=True)
class Coulomb:
    """Regularised Coulomb friction μ_eff = μ tanh(v_t/v_reg) [T61]."""

    coefficient: float
    """μ [-], ≥ 0"""
    regularization_velocity: float = 1e-4
    """v_reg [m/s], > 0"""
    code: ClassVar[int] = COULOMB
    kernel: ClassVar = coulomb_coefficient
    PARAMS: ClassVar[tuple[str, ...]] = ("coefficient", "regularization_velocity")

    def __post_init__(self):
        check_finite("Coulomb", "coefficient", self.coefficient, "-", "≥ 0", lambda v: v >= 0)
        check_finite(
            "Coulomb", "regularization_velocity", self.regularization_velocity, "m/s", "> 0", lambda v: v > 0
        )

    @classmethod
    def example(cls):
        """A typical instance for tests and docs."""
        return cls(coefficient=0.1)


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
    kernel: ClassVar = ambrosio_coefficient
    PARAMS: ClassVar[tuple[str, ...]] = ("coefficient", "v0", "v1")

    def __post_init__(self):
        check_finite("Ambrosio", "coefficient", self.coefficient, "-", "≥ 0", lambda v: v >= 0)
        check_finite("Ambrosio", "v0", self.v0, "m/s", "≥ 0", lambda v: v >= 0)
        check_finite("Ambrosio", "v1", self.v1, "m/s", f"> v0 = {self.v0}", lambda v: v > self.v0)

    @classmethod
    def example(cls):
        """A typical instance for tests and docs."""
        return cls(coefficient=0.1)


FRICTION_LAWS = {"coulomb": Coulomb, "ambrosio": Ambrosio}
check_codes(FRICTION_LAWS, "friction law")
FRICTION_WIDTH = block_width(FRICTION_LAWS)
C_MU, C_VREG = Layout(Coulomb.PARAMS).slots(*Coulomb.PARAMS)
A_MU, A_V0, A_V1 = Layout(Ambrosio.PARAMS).slots(*Ambrosio.PARAMS)


# -- optional capability: exact Jacobians [T97] ----------------------------------------------------
# ``jacobian(vt, p) -> (μ_eff, dμ_eff/dv_t)``; a law without one is differentiated by central
# differences of its kernel (``FD_JAC`` [T229]).


@njit(cache=True)
def coulomb_jac(vt, p):
    """μ tanh(v_t/v_reg) [T61] and (μ/v_reg) sech²(v_t/v_reg), without 1 − tanh² cancellation [T97]."""
    x = vt / p[C_VREG]
    ch = math.cosh(min(abs(x), 700.0))
    return p[C_MU] * math.tanh(x), p[C_MU] / (ch * ch) / p[C_VREG]


@njit(cache=True)
def ambrosio_jac(vt, p):
    """Ambrósio's ramp [T62] and its derivative 6μx(1 − x)/(v₁ − v₀) on the ramp [T97]."""
    a = abs(vt)
    v0 = p[A_V0]
    v1 = p[A_V1]
    sg = 1.0 if vt > 0 else -1.0
    if a <= v0:
        return 0.0, 0.0
    if a >= v1:
        return p[A_MU] * 1.0 * sg, 0.0
    x = (a - v0) / (v1 - v0)
    cd = x * x * (3.0 - 2.0 * x)
    return p[A_MU] * cd * sg, p[A_MU] * 6.0 * x * (1.0 - x) / (v1 - v0)


Coulomb.jacobian = coulomb_jac  # type: ignore[attr-defined]
Ambrosio.jacobian = ambrosio_jac  # type: ignore[attr-defined]


FD_JAC = """
h_ = 6.055454452393343e-06 * max(abs(vt), 1e-9)
return KERNEL(vt, p), (KERNEL(vt + h_, p) - KERNEL(vt - h_, p)) / (2.0 * h_)
"""
"""(μ_eff, dμ_eff/dv_t) of a friction ``KERNEL`` without an exact Jacobian by central differences
[T229] (step ε^{1/3}·max(|v_t|, 1e-9 m/s)): source lines for the generated dispatch."""


# -- the dispatch by code, generated from FRICTION_LAWS when a caller is compiled [T229] -----------
friction_dispatch = law_switch("friction_dispatch", 2, FRICTION_LAWS, ("vt", "p"), None, "math.nan")
"""compiled only: ``friction_dispatch(laws, code, v_t, p) -> μ_eff`` over the laws present in
``laws``; nan for another code (the caller skips ``NONE``)"""
friction_jac_dispatch = law_switch(
    "friction_jac_dispatch",
    2,
    FRICTION_LAWS,
    ("vt", "p"),
    FD_JAC,
    "(math.nan, math.nan)",
)
"""compiled only: (μ_eff, dμ_eff/dv_t) from ``jacobian`` or central differences of the kernel"""


@njit(cache=True)
def _friction_coefficient(laws, code, vt, p):
    if code == NONE:
        return 0.0
    return friction_dispatch(laws, code, vt, p)


@njit(cache=True)
def _friction_jac(laws, code, vt, p):
    if code == NONE:
        return 0.0, 0.0
    return friction_jac_dispatch(laws, code, vt, p)


def friction_coefficient(code, vt, p):
    """μ_eff(v_t) [-] of the law with registry code ``code`` (p: its ``PARAMS`` block) through the
    compiled dispatch over every registered law; 0 for ``NONE``, nan for an unknown code
    [T60–T62, T229]."""
    return _friction_coefficient(all_laws(FRICTION_LAWS, 2), code, vt, p)


def friction_jac(code, vt, p):
    """μ_eff(v_t) and dμ_eff/dv_t of the law ``code``: its ``jacobian``, or central differences of
    its kernel; (0, 0) for ``NONE``, NaNs for an unknown code [T97, T229]."""
    return _friction_jac(all_laws(FRICTION_LAWS, 2), code, vt, p)
