"""Normal contact laws (compiled kernels) and their registry [T50–T58].

Kernel: ``contact_force(code, delta, delta_dot, delta_dot0, p) -> F_n`` with penetration
δ [m] (> 0 in contact; F_n = 0 for δ ≤ 0), its rate δ̇ [m/s] (> 0 while approaching), the rate at
contact onset δ̇⁻ [m/s] (> 0; the caller stores it and floors it for grazing contacts) and the
law's four parameters ``p`` (from the law's ``params()``). The same compiled function runs in the
simulator (``journal.py``) and in the tests.

**Clamp.** Every law returns F_n ≥ 0. During restitution (δ̇ < 0) the damping term of the damped
laws lowers the force, and for large damping it could exceed the elastic term; a contact cannot
pull (no adhesion), so the force is clamped at 0 and the bodies then separate freely [T50]. For
the power laws [T52–T54] the clamp never acts in a single impact (their exact energy balance
[T57] keeps 1 + χδ̇/δ̇⁻ > 0); for Kelvin–Voigt [T55] it does, and it sets that law's restitution
[T58].

Each law is a frozen dataclass (fields = the model-file schema) with ``params()`` returning the
kernel's ``p``, a ``code`` and a ``theory`` tag, registered in ``CONTACT_LAWS``.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import ClassVar

from numba import njit

from ..errors import PhysicsWarning

HERTZ, LANKARANI_NIKRAVESH, HUNT_CROSSLEY, FLORES, KELVIN_VOIGT = 0, 1, 2, 3, 4

#: relative gap |e − c_r|/c_r between the restitution a damped power law actually gives [T57]
#: and the c_r it is given, beyond which the law warns (PhysicsWarning) that c_r is outside its
#: validity range [-]
RESTITUTION_WARN_GAP = 0.05


@njit(cache=True)
def contact_force(code, delta, delta_dot, delta_dot0, p):
    """Normal contact force F_n ≥ 0 [N] of law ``code`` [T50–T55].

    ``delta`` penetration δ [m]; ``delta_dot`` its rate δ̇ [m/s]; ``delta_dot0`` the rate at
    contact onset δ̇⁻ (> 0) [m/s]; ``p`` float64 array of four law parameters [-]:

    * HERTZ: p = [K, n, 0, 0], F = Kδⁿ [T51]
    * LANKARANI_NIKRAVESH: p = [K, n, c_r, 0], F = Kδⁿ[1 + 3(1−c_r²)/4 · δ̇/δ̇⁻] [T52]
    * HUNT_CROSSLEY: p = [K, n, c_r, 0], F = Kδⁿ[1 + 3(1−c_r)/2 · δ̇/δ̇⁻] [T53]
    * FLORES: p = [K, n, c_r, 0], F = Kδⁿ[1 + 8(1−c_r)/(5c_r) · δ̇/δ̇⁻] [T54]
    * KELVIN_VOIGT: p = [K, 1, D, 0], F = Kδ + Dδ̇ [T55]

    Returns 0 for δ ≤ 0 and clamps to F_n ≥ 0 (no adhesive pull while separating) [T50];
    NaN for an unknown code.
    """
    if delta <= 0.0:
        return 0.0
    K = p[0]
    if code == KELVIN_VOIGT:
        f = K * delta + p[2] * delta_dot  # [T55]
        return f if f > 0.0 else 0.0
    fe = K * delta ** p[1]
    if code == HERTZ:
        return fe  # [T51]
    cr = p[2]
    if code == LANKARANI_NIKRAVESH:
        chi = 0.75 * (1.0 - cr * cr)  # [T52]
    elif code == HUNT_CROSSLEY:
        chi = 1.5 * (1.0 - cr)  # [T53]
    elif code == FLORES:
        chi = 8.0 * (1.0 - cr) / (5.0 * cr)  # [T54]
    else:
        return math.nan
    f = fe * (1.0 + chi * delta_dot / delta_dot0)  # [T50]
    return f if f > 0.0 else 0.0  # clamp: no adhesion [T50]


def _check(owner, name, v, unit, rule, ok):
    if isinstance(v, bool) or not (isinstance(v, (int, float)) and math.isfinite(v) and ok(v)):
        raise ValueError(f"{owner}.{name} = {v!r} [{unit}]: must be {rule} (and finite)")


# -- exact restitution of the damped power laws [T57] ---------------------------------------------
def _x_minus_log1p(x: float) -> float:
    """x − ln(1 + x) without cancellation for small |x| (series below |x| = 0.1) [-]."""
    if abs(x) >= 0.1:
        return x - math.log1p(x)
    s, term, k = 0.0, -x, 1  # term = (−x)^k
    while True:  # Σ_{k≥2} (−1)^k x^k / k
        k += 1
        term *= -x
        s += term / k
        if abs(term) < 1e-18 * abs(s) or k > 60:
            return s


def effective_restitution(chi: float) -> float:
    """Actual restitution e [-] of F = Kδⁿ[1 + χ δ̇/δ̇⁻] in a single impact [T57].

    Exact energy balance along the impact (independent of K, n, the mass and the approach
    speed): χ − ln(1 + χ) = −χe − ln(1 − χe), solved for e by bisection on y = χe ∈ [0, 1).
    ``chi`` is the damping factor χ ≥ 0 [-]."""
    if not (math.isfinite(chi) and chi >= 0.0):
        raise ValueError(f"effective_restitution: chi = {chi!r} [-]: must be a finite number ≥ 0")
    if chi == 0.0:
        return 1.0
    target = _x_minus_log1p(chi)
    lo, hi = 0.0, 1.0
    for _ in range(300):  # f(−y) increases from 0 (y = 0) to ∞ (y → 1); to full precision
        y = 0.5 * (lo + hi)
        if y <= lo or y >= hi:
            break
        if _x_minus_log1p(-y) < target:
            lo = y
        else:
            hi = y
    return 0.5 * (lo + hi) / chi


# -- laws -----------------------------------------------------------------------------------------
@dataclass(frozen=True)
class _PowerLaw:
    stiffness: float
    """generalised stiffness K, > 0 (for a journal in a bearing see ``journal_bearing_stiffness``) [N/m^n]"""
    exponent: float = 1.5
    """exponent n, > 0 (1.5 for Hertzian contact; cylinder-in-hole approximations use it too) [-]"""

    def __post_init__(self):
        o = type(self).__name__
        _check(o, "stiffness", self.stiffness, "N/m^n", "> 0", lambda v: v > 0)
        _check(o, "exponent", self.exponent, "-", "> 0", lambda v: v > 0)


@dataclass(frozen=True)
class Hertz(_PowerLaw):
    """Hertz (1881), F = Kδⁿ: elastic, no dissipation (restitution 1) [T51]."""

    code: ClassVar[int] = HERTZ
    theory: ClassVar[str] = "T51"

    def params(self) -> tuple[float, float, float, float]:
        """Kernel parameters p = (K, n, 0, 0) [T51]."""
        return (float(self.stiffness), float(self.exponent), 0.0, 0.0)


@dataclass(frozen=True)
class _DampedPowerLaw(_PowerLaw):
    restitution: float = 0.9
    """coefficient of restitution c_r in (0, 1] (validity narrower, see the law's docstring) [-]"""

    #: c_r below which the law's actual restitution [T57] misses c_r by more than
    #: RESTITUTION_WARN_GAP (measured with ``effective_restitution``) [-]
    valid_from: ClassVar[float] = 0.0

    def __post_init__(self):
        super().__post_init__()
        o = type(self).__name__
        _check(o, "restitution", self.restitution, "-", "in (0, 1]", lambda v: 0 < v <= 1)
        e = self.effective_restitution()
        if abs(e - self.restitution) > RESTITUTION_WARN_GAP * self.restitution:
            warnings.warn(
                f"{o}: restitution = {self.restitution:g} is outside the law's validity range "
                f"(c_r ≥ {self.valid_from:g}); it gives an actual restitution of {e:.3f} [T57]"
                + ("" if isinstance(self, Flores) else "; Flores is meant for low c_r"),
                PhysicsWarning,
                stacklevel=3,
            )

    def chi(self) -> float:
        """Damping factor χ of F = Kδⁿ[1 + χ δ̇/δ̇⁻] [-] [T50]."""
        raise NotImplementedError

    def effective_restitution(self) -> float:
        """Restitution this law actually produces in a single impact [-] [T57]."""
        return effective_restitution(self.chi())

    def params(self) -> tuple[float, float, float, float]:
        """Kernel parameters p = (K, n, c_r, 0) [T50]."""
        return (float(self.stiffness), float(self.exponent), float(self.restitution), 0.0)


@dataclass(frozen=True)
class LankaraniNikravesh(_DampedPowerLaw):
    """Lankarani & Nikravesh (1990), F = Kδⁿ[1 + 3(1−c_r²)/4 · δ̇/δ̇⁻] [T52].

    Derived for c_r close to 1: the actual restitution [T57] is within 2 % of c_r for
    c_r ≥ 0.883 and within 5 % for c_r ≥ 0.816 (0.913 at 0.9, 0.796 at 0.7); a PhysicsWarning is
    issued below 0.816."""

    code: ClassVar[int] = LANKARANI_NIKRAVESH
    theory: ClassVar[str] = "T52"
    valid_from: ClassVar[float] = 0.816

    def chi(self) -> float:
        return 0.75 * (1.0 - self.restitution**2)


@dataclass(frozen=True)
class HuntCrossley(_DampedPowerLaw):
    """Hunt & Crossley (1975), F = Kδⁿ[1 + 3(1−c_r)/2 · δ̇/δ̇⁻] [T53].

    For c_r close to 1: actual restitution [T57] within 2 % of c_r for c_r ≥ 0.860 and within 5 %
    for c_r ≥ 0.781 (0.909 at 0.9, 0.768 at 0.7); a PhysicsWarning is issued below 0.781."""

    code: ClassVar[int] = HUNT_CROSSLEY
    theory: ClassVar[str] = "T53"
    valid_from: ClassVar[float] = 0.781

    def chi(self) -> float:
        return 1.5 * (1.0 - self.restitution)


@dataclass(frozen=True)
class Flores(_DampedPowerLaw):
    """Flores, Machado, Silva & Martins (2011), F = Kδⁿ[1 + 8(1−c_r)/(5c_r) · δ̇/δ̇⁻] [T54].

    Meant for the whole range of c_r; its actual restitution [T57] is within 2 % of c_r for
    c_r ≥ 0.738 and within 5 % for c_r ≥ 0.538 (0.894 at 0.9, 0.683 at 0.7, 0.470 at 0.5); a
    PhysicsWarning is issued below 0.538."""

    code: ClassVar[int] = FLORES
    theory: ClassVar[str] = "T54"
    valid_from: ClassVar[float] = 0.538

    def chi(self) -> float:
        return 8.0 * (1.0 - self.restitution) / (5.0 * self.restitution)


@dataclass(frozen=True)
class KelvinVoigt:
    """Linear spring–damper contact F = Kδ + Dδ̇, clamped at F ≥ 0 [T55].

    The damping D is a field, not c_r: the restitution of a linear dashpot depends on the
    effective mass of the impact [T58], which a contact law attached to a joint does not know
    (in a mechanism it changes with the configuration). ``from_restitution(K, c_r, mass)``
    converts for a stated mass. The force jumps by Dδ̇ at contact onset (δ = 0⁺)."""

    stiffness: float
    """contact stiffness K, > 0 [N/m]"""
    damping: float = 0.0
    """damping coefficient D, ≥ 0 [N·s/m]"""
    code: ClassVar[int] = KELVIN_VOIGT
    theory: ClassVar[str] = "T55"

    def __post_init__(self):
        _check("KelvinVoigt", "stiffness", self.stiffness, "N/m", "> 0", lambda v: v > 0)
        _check("KelvinVoigt", "damping", self.damping, "N·s/m", "≥ 0", lambda v: v >= 0)

    def params(self) -> tuple[float, float, float, float]:
        """Kernel parameters p = (K, 1, D, 0) [T55]."""
        return (float(self.stiffness), 1.0, float(self.damping), 0.0)

    def restitution(self, mass: float) -> float:
        """Restitution of a single impact of ``mass`` [kg] on this contact [-] [T58]."""
        return kelvin_voigt_restitution(self.stiffness, self.damping, mass)

    @classmethod
    def from_restitution(cls, stiffness: float, restitution: float, mass: float) -> KelvinVoigt:
        """The law whose single impact of ``mass`` [kg] rebounds with ``restitution`` c_r in
        (0, 1] [-]; ``stiffness`` K [N/m] [T58]. D by bisection on the closed form."""
        _check(
            "KelvinVoigt.from_restitution", "restitution", restitution, "-", "in (0, 1]", lambda v: 0 < v <= 1
        )
        _check("KelvinVoigt.from_restitution", "mass", mass, "kg", "> 0", lambda v: v > 0)
        _check("KelvinVoigt.from_restitution", "stiffness", stiffness, "N/m", "> 0", lambda v: v > 0)
        if restitution == 1.0:
            return cls(stiffness, 0.0)
        d_crit = 2.0 * math.sqrt(stiffness * mass)
        lo, hi = 0.0, d_crit
        while kelvin_voigt_restitution(stiffness, hi, mass) > restitution:
            lo, hi = hi, 2.0 * hi  # e(D) decreases monotonically towards 0
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if kelvin_voigt_restitution(stiffness, mid, mass) > restitution:
                lo = mid
            else:
                hi = mid
            if hi - lo <= 1e-15 * hi:
                break
        return cls(stiffness, 0.5 * (lo + hi))


def kelvin_voigt_restitution(stiffness: float, damping: float, mass: float) -> float:
    """Restitution e [-] of a mass m on F = Kδ + Dδ̇ clamped at F ≥ 0 [T58].

    Separation happens where the force reaches zero (δ > 0), not at δ = 0; then e = exp(−βt*)
    with β = D/(2m), ω₀² = K/m and, underdamped (ω = √(ω₀² − β²)),
    ωt* = π − atan2(2βω, ω₀² − 2β²); overdamped (s = √(β² − ω₀²)),
    st* = artanh(2βs/(2β² − ω₀²)); critical, t* = 2/ω₀ (Schwager & Pöschel 2007).
    ``stiffness`` K [N/m], ``damping`` D [N·s/m], ``mass`` m [kg]."""
    _check("kelvin_voigt_restitution", "stiffness", stiffness, "N/m", "> 0", lambda v: v > 0)
    _check("kelvin_voigt_restitution", "damping", damping, "N·s/m", "≥ 0", lambda v: v >= 0)
    _check("kelvin_voigt_restitution", "mass", mass, "kg", "> 0", lambda v: v > 0)
    w0sq = stiffness / mass
    beta = damping / (2.0 * mass)
    if beta == 0.0:
        return 1.0
    d = w0sq - beta * beta
    if d > 0.0:
        w = math.sqrt(d)
        t = (math.pi - math.atan2(2.0 * beta * w, w0sq - 2.0 * beta * beta)) / w
    elif d < 0.0:
        s = math.sqrt(-d)
        t = math.atanh(2.0 * beta * s / (2.0 * beta * beta - w0sq)) / s
    else:
        t = 2.0 / math.sqrt(w0sq)
    return math.exp(-beta * t)


CONTACT_LAWS = {
    "hertz": Hertz,
    "lankarani_nikravesh": LankaraniNikravesh,
    "hunt_crossley": HuntCrossley,
    "flores": Flores,
    "kelvin_voigt": KelvinVoigt,
}


def law_from_name(name: str, **kwargs):
    """Instantiate a contact law by its ``CONTACT_LAWS`` name with the law's fields as keywords."""
    if name not in CONTACT_LAWS:
        raise ValueError(f"contact law {name!r} is unknown; valid: {', '.join(sorted(CONTACT_LAWS))}")
    return CONTACT_LAWS[name](**kwargs)


def journal_bearing_stiffness(R_bearing, R_journal, E_bearing, nu_bearing, E_journal, nu_journal):
    """K = (4/3)/(σ_i + σ_j)·√(R_i R_j/(R_i − R_j)), σ = (1−ν²)/E [N/m^1.5] [T56].

    ``R_bearing`` R_i [m], ``R_journal`` R_j < R_i [m], ``E_bearing``/``E_journal`` Young's moduli
    [Pa], ``nu_bearing``/``nu_journal`` Poisson's ratios in (−1, 0.5) [-].

    Hertz's point-contact stiffness evaluated with the effective radius of internal contact
    R_i R_j/(R_i − R_j), as used for revolute clearance joints by Lankarani & Nikravesh (1990)
    and Flores et al. (2006). For conformal contact (small clearance, large contact arc) it is an
    approximation that overestimates the stiffness; the cylindrical laws (e.g. Johnson's, or
    Liu et al.'s) are nonlinear in δ and not of the form Kδⁿ."""
    o = "journal_bearing_stiffness"
    for name, v in (("E_bearing", E_bearing), ("E_journal", E_journal)):
        _check(o, name, v, "Pa", "> 0", lambda x: x > 0)
    for name, v in (("nu_bearing", nu_bearing), ("nu_journal", nu_journal)):
        _check(o, name, v, "-", "in (-1, 0.5)", lambda x: -1 < x < 0.5)
    _check(o, "R_bearing", R_bearing, "m", "> 0", lambda x: x > 0)
    _check(o, "R_journal", R_journal, "m", f"in (0, R_bearing = {R_bearing})", lambda x: 0 < x < R_bearing)
    s = (1 - nu_bearing**2) / E_bearing + (1 - nu_journal**2) / E_journal
    return (4.0 / 3.0) / s * math.sqrt(R_bearing * R_journal / (R_bearing - R_journal))
