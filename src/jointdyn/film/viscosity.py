"""Viscosity–temperature laws of lubricating oils and a registry of oil grades [T273–T275].

* Walther / ASTM D341 [T273]: log₁₀ log₁₀(ν + 0.7) = A − B log₁₀ T (ν in mm²/s, T in K), A and B
  from the kinematic viscosities at 40 °C and 100 °C; μ = ρ(T)·ν with ρ(T) = ρ₁₅(1 − α(T − 15 °C)).
  The 0.7 form of D341 holds for ν ≥ 2 mm²/s.
* Vogel [T274]: μ = a·exp(b/(T + c)) (T in °C). Shigley's SAE grades (Seireg & Dandage's fits,
  Shigley's Mechanical Engineering Design, Table 12-1: μ = μ₀ exp(b/(T_F + 95)) in μreyn) are
  Vogel laws with a = 6.894757·10⁻³ μ₀ Pa·s, b/1.8, c = 95/1.8 + 160/9 ≈ 70.56 °C.

ISO VG grades (ISO 3448): ν₄₀ the grade's midpoint, ν₁₀₀ the typical values of a mineral oil of
viscosity index ≈ 95–105 (lubesolut.com ISO VG reference table, "typ. 100 °C"), ρ₁₅ = 870 kg/m³,
α = 6.5·10⁻⁴ 1/K, c_p = 1880 J/(kg·K) (typical mineral oil). The SAE grades carry Shigley's
heat-balance constants ρ = 861 kg/m³, c_p = 1760 J/(kg·K).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

#: ISO VG grade → (ν₄₀, ν₁₀₀) [mm²/s]
ISO_VG = {
    22: (22.0, 4.5),
    32: (32.0, 5.5),
    46: (46.0, 6.5),
    68: (68.0, 8.5),
    100: (100.0, 11.4),
    150: (150.0, 14.5),
    220: (220.0, 19.0),
}
#: SAE grade → (μ₀ [μreyn], b [°F]) of Seireg's fit (Shigley Table 12-1)
SAE = {
    10: (0.0158, 1157.5),
    20: (0.0136, 1271.6),
    30: (0.0141, 1360.0),
    40: (0.0121, 1474.4),
    50: (0.0170, 1509.6),
    60: (0.0187, 1564.0),
}
MICROREYN = 6.894757e-3  # 1 μreyn in Pa·s


@dataclass(frozen=True)
class Walther:
    """ASTM D341 law from ν₄₀, ν₁₀₀ [mm²/s] [T273]; valid T range [°C] and ν ≥ 2 mm²/s."""

    nu40: float
    nu100: float
    t_min: float = -10.0
    t_max: float = 150.0

    def __post_init__(self):
        if not (math.isfinite(self.nu40) and math.isfinite(self.nu100) and self.nu40 > self.nu100 >= 2.0):
            raise ValueError(f"nu40 = {self.nu40!r}, nu100 = {self.nu100!r} [mm²/s]: need nu40 > nu100 >= 2")

    def _AB(self):
        y40 = math.log10(math.log10(self.nu40 + 0.7))
        y100 = math.log10(math.log10(self.nu100 + 0.7))
        x40, x100 = math.log10(313.15), math.log10(373.15)
        B = (y40 - y100) / (x100 - x40)
        return y40 + B * x40, B

    def kinematic(self, t: float) -> float:
        """ν [mm²/s] at t [°C] (no range check)."""
        A, B = self._AB()
        return 10.0 ** (10.0 ** (A - B * math.log10(t + 273.15))) - 0.7


@dataclass(frozen=True)
class Vogel:
    """μ = a·exp(b/(t + c)) [Pa·s], t in °C [T274]."""

    a: float
    b: float
    c: float
    t_min: float = 0.0
    t_max: float = 150.0

    def dynamic(self, t: float) -> float:
        return self.a * math.exp(self.b / (t + self.c))


@dataclass(frozen=True)
class Oil:
    """A lubricant: viscosity law, density ρ₁₅ [kg/m³] and expansion α [1/K], specific heat c_p
    [J/(kg·K)]."""

    name: str
    law: Walther | Vogel
    density15: float = 870.0
    expansion: float = 6.5e-4
    specific_heat: float = 1880.0

    def density(self, t: float) -> float:
        """ρ(t) = ρ₁₅(1 − α(t − 15)) [kg/m³] at t [°C]."""
        return self.density15 * (1.0 - self.expansion * (t - 15.0))

    def raw_viscosity(self, t: float) -> float:
        """μ [Pa·s] at t [°C] without the range check (for root finding)."""
        if isinstance(self.law, Walther):
            return self.density(t) * self.law.kinematic(t) * 1e-6
        return self.law.dynamic(t)

    def viscosity(self, t: float) -> float:
        """Dynamic viscosity μ [Pa·s] at t [°C]; ValueError outside the law's range [T273–T274]."""
        lo, hi = self.law.t_min, self.law.t_max
        if not (math.isfinite(t) and lo <= t <= hi):
            raise ValueError(
                f"temperature = {t!r} [°C]: the viscosity law of {self.name} holds for {lo:g}…{hi:g} °C"
            )
        return self.raw_viscosity(t)

    def temperature_of(self, mu: float) -> float:
        """The temperature [°C] at which μ(t) = μ [Pa·s] (μ falls monotonically with t); may lie
        outside the law's range (callers check)."""
        from scipy.optimize import brentq

        lo, hi = self.law.t_min - 60.0, self.law.t_max + 150.0
        f = lambda t: math.log(self.raw_viscosity(t) / mu)  # noqa: E731
        if f(lo) < 0.0:
            return lo
        if f(hi) > 0.0:
            return hi
        return brentq(f, lo, hi, xtol=1e-10)


WALTHER, VOGEL = 0, 1  # law kinds of :func:`law_params`


def law_params(oil: Oil) -> tuple[float, ...]:
    """The oil's viscosity law as (kind, p1, p2, p3, ρ₁₅, α) for :func:`viscosity_of` [T273–T274]:
    Walther (A, B, 0), Vogel (a, b, c)."""
    if isinstance(oil.law, Walther):
        A, B = oil.law._AB()
        return (float(WALTHER), A, B, 0.0, oil.density15, oil.expansion)
    return (float(VOGEL), oil.law.a, oil.law.b, oil.law.c, oil.density15, oil.expansion)


@njit(cache=True)
def viscosity_of(p, t):
    """μ [Pa·s] at t [°C] of the law ``p`` = :func:`law_params` (compiled; no range check)."""
    if p[0] == VOGEL:
        return p[1] * math.exp(p[2] / (t + p[3]))
    nu = 10.0 ** (10.0 ** (p[1] - p[2] * math.log10(t + 273.15))) - 0.7  # [mm²/s]
    return p[4] * (1.0 - p[5] * (t - 15.0)) * nu * 1e-6


def _registry() -> dict[str, Oil]:
    oils = {f"ISO_VG{g}": Oil(f"ISO_VG{g}", Walther(*nu)) for g, nu in ISO_VG.items()}
    for g, (mu0, b) in SAE.items():
        law = Vogel(MICROREYN * mu0, b / 1.8, 95.0 / 1.8 + 160.0 / 9.0)
        oils[f"SAE_{g}"] = Oil(f"SAE_{g}", law, 861.0, 0.0, 1760.0)
    return oils


OILS = _registry()


def oil_by_name(name: str) -> Oil:
    """The registered oil ``name`` (e.g. ISO_VG46, SAE_30); ValueError listing the valid ones."""
    key = str(name).upper().replace(" ", "_").replace("-", "_")
    if key not in OILS:
        raise ValueError(f"oil = {name!r}: unknown grade; valid: {', '.join(OILS)}")
    return OILS[key]
