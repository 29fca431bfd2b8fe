"""Lumped oil temperature of a journal bearing in the dynamics [T310–T313].

One temperature T per bearing (the oil in the film and the bushing as one heat capacity C):

    C dT/dt = P_loss − ṁc_p (T − T_in) − hA (T − T_amb)            [T310]

P_loss is the film's dissipation (``power_loss`` of the element: pressure and Couette shear
[T282]); the film's viscosity is μ(T) of the oil's law [T273–T274] and follows T. T is element
memory advanced in lock-step on accepted steps [T311]: over a step h from t_a to t_b, with μ(T_a)
held during the step, the heat generated G = h(P_a + P_b)/2 (trapezoid) and the removal by the
implicit trapezoid, so that C(T_b − T_a) = G − R holds for every step to rounding [T312].
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from numba import njit

from jointdyn.core.layout import check_finite
from jointdyn.film.viscosity import law_params, oil_by_name, viscosity_of

LUMPED = 1
#: memory slots appended to the journal bearing's own (name -> unit), from slot ``BASE`` on
MEMORY = {
    "oil_temperature": "K",
    "heat_generated": "J",
    "heat_removed": "J",
    "viscosity": "Pa·s",
    "last_time": "s",
    "last_loss": "W",
}
BASE = 4
OIL_T, Q_GEN, Q_REM, VISC, T_LAST, P_LAST = range(BASE, BASE + len(MEMORY))
# parameter block: C, ṁc_p, hA, T_in, T_amb [K], t_min, t_max [°C], law (kind, p1, p2, p3, ρ₁₅, α)
C_HEAT, K_FLOW, K_WALL, T_IN, T_AMB, T_MIN, T_MAX, LAW0 = range(8)
WIDTH = LAW0 + 6
KELVIN = 273.15
OUT_OF_RANGE = 1  # status of :func:`thermal_step`: T left the viscosity law's range
DT_STEP = 0.01  # largest change of the oil temperature per step [K] [T312]


@dataclass(frozen=True)
class LumpedOil:
    """Lumped oil temperature of one bearing [T310]: heat capacity, supply flow and a wall
    conductance to ambient; the film viscosity follows the oil's law."""

    oil: str
    """registered oil grade (``jointdyn.film.viscosity.OILS``, e.g. "ISO_VG46", "SAE_30")"""
    inlet_temp: float
    """T_in [°C], inside the oil law's range"""
    heat_capacity: float
    """C [J/K] of the oil and bushing, > 0"""
    mass_flow: float = 0.0
    """ṁ [kg/s] of the oil supply, ≥ 0 (removes ṁc_p(T − T_in))"""
    h_A: float = 0.0
    """hA [W/K] from the bearing to ambient, ≥ 0"""
    ambient_temp: float = 20.0
    """T_amb [°C]"""
    initial_temp: float | None = None
    """T(t₀) [°C] (None: inlet_temp)"""
    code: ClassVar[int] = LUMPED
    PARAMS: ClassVar[tuple[str, ...]] = ()

    def validate(self) -> None:
        o = type(self).__name__
        law = oil_by_name(self.oil).law  # unknown grade: ValueError naming oil
        rng = f"in the viscosity law's range {law.t_min:g}…{law.t_max:g} °C of {self.oil}"
        for name in ("inlet_temp", "initial_temp"):
            v = getattr(self, name)
            if v is not None:
                check_finite(o, name, v, "°C", rng, lambda t: law.t_min <= t <= law.t_max)
        check_finite(o, "heat_capacity", self.heat_capacity, "J/K", "> 0", lambda v: v > 0)
        check_finite(o, "mass_flow", self.mass_flow, "kg/s", ">= 0", lambda v: v >= 0)
        check_finite(o, "h_A", self.h_A, "W/K", ">= 0", lambda v: v >= 0)
        check_finite(o, "ambient_temp", self.ambient_temp, "°C", "> -273.15", lambda v: v > -KELVIN)

    def start_temp(self) -> float:
        """T(t₀) [°C]."""
        return self.inlet_temp if self.initial_temp is None else self.initial_temp

    def params(self) -> tuple[float, ...]:
        """The parameter block (``WIDTH`` values) [SI, temperatures in K, range in °C]."""
        oil = oil_by_name(self.oil)
        return (
            self.heat_capacity,
            self.mass_flow * oil.specific_heat,
            self.h_A,
            self.inlet_temp + KELVIN,
            self.ambient_temp + KELVIN,
            oil.law.t_min,
            oil.law.t_max,
            *law_params(oil),
        )

    def memory0(self) -> dict[str, float]:
        """Initial memory: T(t₀) [K], μ(T(t₀)), no heat yet; last_time NaN (set at the start)."""
        t0 = self.start_temp()
        mu = oil_by_name(self.oil).viscosity(t0)
        return {"oil_temperature": t0 + KELVIN, "viscosity": mu, "last_time": math.nan}


THERMAL_MODELS = {"lumped": LumpedOil}


@njit(cache=True)
def thermal_step(mem, p, t, loss):
    """Advance the oil temperature of one bearing to the accepted time t [s] [T311–T312]; ``loss``
    [W] is the film's dissipation at the accepted state with μ = mem[VISC]. Returns 0, or
    ``OUT_OF_RANGE`` if T leaves the viscosity law's range (T is then not advanced)."""
    t_a = mem[T_LAST]
    if not (t_a == t_a) or t <= t_a:  # start of the run (NaN) or a repeated call at t
        mem[T_LAST] = t
        mem[P_LAST] = loss
        return 0
    h = t - t_a
    C = p[C_HEAT]
    K = p[K_FLOW] + p[K_WALL]
    S = p[K_FLOW] * p[T_IN] + p[K_WALL] * p[T_AMB]  # removal = K·T − S
    Ta = mem[OIL_T]
    G = 0.5 * h * (mem[P_LAST] + loss)
    Tb = (Ta * (C - 0.5 * h * K) + G + h * S) / (C + 0.5 * h * K)
    tc = Tb - KELVIN
    if not (p[T_MIN] <= tc <= p[T_MAX]):
        return OUT_OF_RANGE
    mu_a = mem[VISC]
    mu_b = viscosity_of(p[LAW0:], tc)
    mem[OIL_T] = Tb
    mem[Q_GEN] += G
    mem[Q_REM] += h * (0.5 * K * (Ta + Tb) - S)
    mem[VISC] = mu_b
    mem[T_LAST] = t
    mem[P_LAST] = loss * mu_b / mu_a  # the film's loss is linear in μ at a given state [T311]
    return 0


@njit(cache=True)
def thermal_step_limit(mem, p):
    """Largest step [s] over which the oil temperature changes by at most ``DT_STEP`` at its
    current rate, and at most 0.1·C/(ṁc_p + hA) [T312]."""
    K = p[K_FLOW] + p[K_WALL]
    rate = abs(mem[P_LAST] - K * mem[OIL_T] + p[K_FLOW] * p[T_IN] + p[K_WALL] * p[T_AMB]) / p[C_HEAT]
    h = DT_STEP / rate if rate > 0.0 else 1e300
    return min(h, 0.1 * p[C_HEAT] / K) if K > 0.0 else h
