"""Normal contact laws (compiled kernels) and their registry ``CONTACT_LAWS``.

Each law is a frozen dataclass (its fields are the model-file schema) registered with its integer
``code``, its compiled ``kernel(delta, delta_dot, delta_dot0, p) -> F_n ≥ 0`` and its ``PARAMS``
(the fields packed, in order, into the parameter block p that the kernel reads through named
slots): penetration δ [m] (> 0 in contact), its rate δ̇ [m/s], the rate at contact onset δ̇⁻
[m/s]. Damped laws are clamped to F_n ≥ 0 (no adhesive pull while separating).
The compiled dispatch by code is generated from the registry (``contact_dispatch``,
``contact_jac_dispatch`` [T229]); ``contact_force(code, …)`` is its Python-level entry.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from numba import njit

from jointdyn.core.dispatch import all_laws, law_switch
from jointdyn.core.layout import Layout, block_width, check_codes, check_finite

HERTZ, LANKARANI_NIKRAVESH, HUNT_CROSSLEY, FLORES, KELVIN_VOIGT = 0, 1, 2, 3, 4
NONE = -1  # no contact law


@njit(cache=True)
def _damped(fe, chi, delta_dot, delta_dot0):
    """Kδⁿ(1 + χ δ̇/δ̇⁻) clamped ≥ 0 (no adhesive pull while separating)."""
    f = fe * (1.0 + chi * delta_dot / delta_dot0)
    return f if f > 0.0 else 0.0


@njit(cache=True)
def hertz_force(delta, delta_dot, delta_dot0, p):
    """F = Kδⁿ [T51]."""
    return p[STIFFNESS] * delta ** p[EXPONENT]


@njit(cache=True)
def lankarani_nikravesh_force(delta, delta_dot, delta_dot0, p):
    """F = Kδⁿ[1 + 3(1 − c_r²)/4 · δ̇/δ̇⁻] [T52]."""
    cr = p[RESTITUTION]
    return _damped(p[STIFFNESS] * delta ** p[EXPONENT], 0.75 * (1.0 - cr * cr), delta_dot, delta_dot0)


@njit(cache=True)
def hunt_crossley_force(delta, delta_dot, delta_dot0, p):
    """F = Kδⁿ[1 + 3(1 − c_r)/2 · δ̇/δ̇⁻] [T53]."""
    cr = p[RESTITUTION]
    return _damped(p[STIFFNESS] * delta ** p[EXPONENT], 1.5 * (1.0 - cr), delta_dot, delta_dot0)


@njit(cache=True)
def flores_force(delta, delta_dot, delta_dot0, p):
    """F = Kδⁿ[1 + 8(1 − c_r)/(5c_r) · δ̇/δ̇⁻] [T54]."""
    cr = p[RESTITUTION]
    chi = 8.0 * (1.0 - cr) / (5.0 * cr)
    return _damped(p[STIFFNESS] * delta ** p[EXPONENT], chi, delta_dot, delta_dot0)


@njit(cache=True)
def kelvin_voigt_force(delta, delta_dot, delta_dot0, p):
    """F = Kδ + Dδ̇ clamped ≥ 0 [T55]."""
    f = p[KV_STIFFNESS] * delta + p[KV_DAMPING] * delta_dot
    return f if f > 0.0 else 0.0


@dataclass(frozen=True)
class _PowerLaw:
    stiffness: float
    """K [N/m^n], > 0"""
    exponent: float = 1.5
    """n [-], > 0 (1.5 for Hertzian cylinder-in-hole approximations)"""
    restitution: float = 1.0
    """coefficient of restitution c_r [-] in (0, 1]"""
    PARAMS: ClassVar[tuple[str, ...]] = ("stiffness", "exponent", "restitution")
    """the fields packed, in this order, into the kernel's parameter block"""

    def __post_init__(self):
        o = type(self).__name__
        check_finite(o, "stiffness", self.stiffness, "N/m^n", "> 0", lambda v: v > 0)
        check_finite(o, "exponent", self.exponent, "-", "> 0", lambda v: v > 0)
        check_finite(o, "restitution", self.restitution, "-", "in (0, 1]", lambda v: 0 < v <= 1)

    @classmethod
    def example(cls):
        """A typical instance (steel pin in a steel bushing, c = 0.5 mm) for tests and docs."""
        return cls(stiffness=6.9e10)


@dataclass(frozen=True)
class Hertz(_PowerLaw):
    """Hertz, F = Kδⁿ (elastic, no dissipation) [T51]."""

    code: ClassVar[int] = HERTZ
    kernel: ClassVar = hertz_force


@dataclass(frozen=True)
class LankaraniNikravesh(_PowerLaw):
    """Lankarani–Nikravesh (1990), F = Kδⁿ[1 + 3(1−c_r²)/4 · δ̇/δ̇⁻] [T52]; for c_r near 1."""

    restitution: float = 0.9
    code: ClassVar[int] = LANKARANI_NIKRAVESH
    kernel: ClassVar = lankarani_nikravesh_force


@dataclass(frozen=True)
class HuntCrossley(_PowerLaw):
    """Hunt–Crossley (1975), F = Kδⁿ[1 + 3(1−c_r)/2 · δ̇/δ̇⁻] [T53]."""

    restitution: float = 0.9
    code: ClassVar[int] = HUNT_CROSSLEY
    kernel: ClassVar = hunt_crossley_force


@dataclass(frozen=True)
class Flores(_PowerLaw):
    """Flores et al. (2011), F = Kδⁿ[1 + 8(1−c_r)/(5c_r) · δ̇/δ̇⁻] [T54]; any c_r in (0, 1]."""

    restitution: float = 0.9
    code: ClassVar[int] = FLORES
    kernel: ClassVar = flores_force


@dataclass(frozen=True)
class KelvinVoigt:
    """Linear spring–damper contact F = Kδ + Dδ̇, clamped ≥ 0 [T55]."""

    stiffness: float
    """K [N/m], > 0"""
    damping: float = 0.0
    """D [N·s/m], ≥ 0"""
    code: ClassVar[int] = KELVIN_VOIGT
    kernel: ClassVar = kelvin_voigt_force
    PARAMS: ClassVar[tuple[str, ...]] = ("stiffness", "damping")

    def __post_init__(self):
        check_finite("KelvinVoigt", "stiffness", self.stiffness, "N/m", "> 0", lambda v: v > 0)
        check_finite("KelvinVoigt", "damping", self.damping, "N·s/m", "≥ 0", lambda v: v >= 0)

    @classmethod
    def example(cls):
        """A typical instance for tests and docs."""
        return cls(stiffness=1e8, damping=1e3)


CONTACT_LAWS = {
    "hertz": Hertz,
    "lankarani_nikravesh": LankaraniNikravesh,
    "hunt_crossley": HuntCrossley,
    "flores": Flores,
    "kelvin_voigt": KelvinVoigt,
}
check_codes(CONTACT_LAWS, "contact law")
CONTACT_WIDTH = block_width(CONTACT_LAWS)
STIFFNESS, EXPONENT, RESTITUTION = Layout(_PowerLaw.PARAMS).slots(*_PowerLaw.PARAMS)
KV_STIFFNESS, KV_DAMPING = Layout(KelvinVoigt.PARAMS).slots(*KelvinVoigt.PARAMS)


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
        check_finite("journal_bearing_stiffness", name, v, unit, "> 0", lambda x: x > 0)
    for name, v in (("nu_bearing", nu_bearing), ("nu_journal", nu_journal)):
        check_finite("journal_bearing_stiffness", name, v, "-", "in (-1, 0.5)", lambda x: -1 < x < 0.5)
    check_finite(
        "journal_bearing_stiffness",
        "R_journal",
        R_journal,
        "m",
        f"in (0, R_bearing = {R_bearing})",
        lambda x: 0 < x < R_bearing,
    )
    s = (1 - nu_bearing**2) / E_bearing + (1 - nu_journal**2) / E_journal
    return (4.0 / 3.0) / s * math.sqrt(R_bearing * R_journal / (R_bearing - R_journal))


# -- optional capability: exact Jacobians [T96] ----------------------------------------------------
# ``jacobian(delta, delta_dot, delta_dot0, p) -> (F, ∂F/∂δ, ∂F/∂δ̇)``; a law without one is
# differentiated by central differences of its kernel (``FD_JAC`` [T229]).


@njit(cache=True)
def _damped_jac(p, chi, delta, delta_dot, delta_dot0):
    """Kδⁿ(1 + χδ̇/δ̇⁻) clamped ≥ 0 and its derivatives [T96]."""
    K = p[STIFFNESS]
    n = p[EXPONENT]
    fe = K * delta**n
    fac = 1.0 + chi * delta_dot / delta_dot0
    f = fe * fac
    if f > 0.0:
        return f, n * K * delta ** (n - 1.0) * fac, fe * chi / delta_dot0
    return 0.0, 0.0, 0.0


@njit(cache=True)
def hertz_jac(delta, delta_dot, delta_dot0, p):
    """Hertz [T51]: (Kδⁿ, nKδ^{n−1}, 0) [T96]."""
    K = p[STIFFNESS]
    n = p[EXPONENT]
    return K * delta**n, n * K * delta ** (n - 1.0), 0.0


@njit(cache=True)
def lankarani_nikravesh_jac(delta, delta_dot, delta_dot0, p):
    """Lankarani–Nikravesh [T52], χ = 3(1 − c_r²)/4 [T96]."""
    cr = p[RESTITUTION]
    return _damped_jac(p, 0.75 * (1.0 - cr * cr), delta, delta_dot, delta_dot0)


@njit(cache=True)
def hunt_crossley_jac(delta, delta_dot, delta_dot0, p):
    """Hunt–Crossley [T53], χ = 3(1 − c_r)/2 [T96]."""
    return _damped_jac(p, 1.5 * (1.0 - p[RESTITUTION]), delta, delta_dot, delta_dot0)


@njit(cache=True)
def flores_jac(delta, delta_dot, delta_dot0, p):
    """Flores et al. [T54], χ = 8(1 − c_r)/(5c_r) [T96]."""
    cr = p[RESTITUTION]
    return _damped_jac(p, 8.0 * (1.0 - cr) / (5.0 * cr), delta, delta_dot, delta_dot0)


@njit(cache=True)
def kelvin_voigt_jac(delta, delta_dot, delta_dot0, p):
    """Kelvin–Voigt [T55]: (Kδ + Dδ̇, K, D), 0 where clamped [T96]."""
    f = p[KV_STIFFNESS] * delta + p[KV_DAMPING] * delta_dot
    if f > 0.0:
        return f, p[KV_STIFFNESS], p[KV_DAMPING]
    return 0.0, 0.0, 0.0


Hertz.jacobian = hertz_jac  # type: ignore[attr-defined]
LankaraniNikravesh.jacobian = lankarani_nikravesh_jac  # type: ignore[attr-defined]
HuntCrossley.jacobian = hunt_crossley_jac  # type: ignore[attr-defined]
Flores.jacobian = flores_jac  # type: ignore[attr-defined]
KelvinVoigt.jacobian = kelvin_voigt_jac  # type: ignore[attr-defined]


FD_JAC = """
f_ = KERNEL(delta, delta_dot, delta_dot0, p)
h_ = 6.055454452393343e-06 * delta
fp_ = KERNEL(delta + h_, delta_dot, delta_dot0, p)
fm_ = KERNEL(delta - h_, delta_dot, delta_dot0, p)
s_ = 6.055454452393343e-06 * max(abs(delta_dot), abs(delta_dot0))
vp_ = KERNEL(delta, delta_dot + s_, delta_dot0, p)
vm_ = KERNEL(delta, delta_dot - s_, delta_dot0, p)
return f_, (fp_ - fm_) / (2.0 * h_), (vp_ - vm_) / (2.0 * s_)
"""
"""(F, ∂F/∂δ, ∂F/∂δ̇) of a contact ``KERNEL`` without an exact Jacobian by central differences
[T229] (δ > 0; steps ε^{1/3}·δ and ε^{1/3}·max(|δ̇|, δ̇⁻)): source lines for the generated dispatch."""


# -- the dispatch by code, generated from CONTACT_LAWS when a caller is compiled [T229] ------------
_ARGS = ("delta", "delta_dot", "delta_dot0", "p")
contact_dispatch = law_switch("contact_dispatch", 1, CONTACT_LAWS, _ARGS, None, "math.nan")
"""compiled only: ``contact_dispatch(laws, code, δ, δ̇, δ̇⁻, p) -> F_n`` over the laws present in
``laws`` (δ > 0: the caller tests contact); nan for another code"""
contact_jac_dispatch = law_switch(
    "contact_jac_dispatch",
    1,
    CONTACT_LAWS,
    _ARGS,
    FD_JAC,
    "(math.nan, math.nan, math.nan)",
)
"""compiled only: (F_n, ∂F_n/∂δ, ∂F_n/∂δ̇) from ``jacobian`` or central differences of the kernel"""


@njit(cache=True)
def _contact_force(laws, code, delta, delta_dot, delta_dot0, p):
    if delta <= 0.0:
        return 0.0
    return contact_dispatch(laws, code, delta, delta_dot, delta_dot0, p)


@njit(cache=True)
def _contact_jac(laws, code, delta, delta_dot, delta_dot0, p):
    if delta <= 0.0:
        return 0.0, 0.0, 0.0
    return contact_jac_dispatch(laws, code, delta, delta_dot, delta_dot0, p)


def contact_force(code, delta, delta_dot, delta_dot0, p):
    """F_n ≥ 0 [N] of the law with registry code ``code`` (p: its ``PARAMS`` block) through the
    compiled dispatch over every registered law; 0 for δ ≤ 0, nan for an unknown code
    [T50–T55, T229]."""
    return _contact_force(all_laws(CONTACT_LAWS, 1), code, delta, delta_dot, delta_dot0, p)


def contact_jac(code, delta, delta_dot, delta_dot0, p):
    """F_n and ∂F_n/∂(δ, δ̇) of the law ``code``: its ``jacobian``, or central differences of its
    kernel; zeros for δ ≤ 0, NaNs for an unknown code [T96, T229]."""
    return _contact_jac(all_laws(CONTACT_LAWS, 1), code, delta, delta_dot, delta_dot0, p)
