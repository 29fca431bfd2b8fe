"""Effective film temperature of a steady journal bearing from the classical heat balance
[T276–T277].

All friction power 2πN·T_J is carried away by the oil: the side flow Q_s leaves at the mean
rise ΔT/2, the rest of the inlet flow Q at ΔT (Shigley, Mechanical Engineering Design, §12-9):

    2πN T_J = ρ c_p Q (1 − ½ Q_s/Q) ΔT,   T_eff = T_in + ΔT/2,

i.e. ΔT = 4πP·(R/c)f / (ρc_p(1 − ½Q_s/Q)·Q/(RcNL)) in the Raimondi–Boyd variables [T276]. The
textbook iterates T_eff by hand; here the fixed point is one equation in ε [T277]: at each ε the
film gives S(ε), (R/c)f, Q/(RcNL), Q_s/Q; S gives the viscosity μ = S·P/((R/c)²N), the oil's law
the temperature T(μ), and the root of T(μ(ε)) − T_in − ΔT(ε)/2 is found by Brent's method.
"""

from __future__ import annotations

import math

from jointdyn.bearing.design import (
    EPS_MAX,
    _check_model,
    _row,
    check_positive,
    equilibrium,
    steady_quantities,
)
from jointdyn.film.fv import DEFAULT_MESH
from jointdyn.film.viscosity import Oil


def effective_temperature(
    load: float,
    speed: float,
    radius: float,
    length: float,
    clearance: float,
    oil: Oil,
    inlet_temp: float,
    model: str = "finite",
    cavitation: str | None = "reynolds",
    mesh=DEFAULT_MESH,
) -> dict:
    """Steady operating point at the effective temperature [T276–T277].

    load, speed, radius, length, clearance  W [N], N [rev/s], R, L, c [m] (as :func:`equilibrium`)
    oil         the lubricant (:func:`jointdyn.film.viscosity.oil_by_name`)
    inlet_temp  T_in [°C], inside the oil law's range
    Returns the :func:`equilibrium` dict at T_eff plus t_eff, delta_t [°C / K], viscosity [Pa·s].
    """
    check_positive(
        ("load", load, "N"),
        ("speed", speed, "rev/s"),
        ("radius", radius, "m"),
        ("length", length, "m"),
        ("clearance", clearance, "m"),
    )
    model, cavitation = _check_model(model, cavitation)  # film-name aliases, None: the default
    oil.viscosity(inlet_temp)  # range check of the inlet temperature
    ld = length / (2.0 * radius)
    P = load / (2.0 * radius * length)
    k = (radius / clearance) ** 2 * speed / P  # S = k·μ

    def parts(eps):
        r = _row(eps, ld, steady_quantities(model, cavitation, ld, eps, mesh))
        mu = r["sommerfeld"] / k
        t = oil.temperature_of(mu)
        rho_cp = oil.density(t) * oil.specific_heat
        dT = (
            4.0
            * math.pi
            * P
            * r["friction_variable"]
            / (rho_cp * (1.0 - 0.5 * r["side_flow_ratio"]) * r["flow_variable"])
        )
        return t, dT, mu

    def g(u):
        t, dT, _ = parts(1.0 - math.exp(-u))
        return t - inlet_temp - 0.5 * dT

    from scipy.optimize import brentq

    lo, hi = 1e-3, -math.log(1.0 - EPS_MAX)
    if g(lo) > 0.0:
        raise ValueError(
            f"load = {load!r} [N]: too light for the heat balance (eps < 1e-3 at T_in = {inlet_temp} °C)"
        )
    if g(hi) < 0.0:
        raise ValueError(
            f"load = {load!r} [N]: the bearing cannot carry it at its effective temperature (eps > {EPS_MAX})"
        )
    u = brentq(g, lo, hi, xtol=1e-12, rtol=1e-12)
    t, dT, mu = parts(1.0 - math.exp(-u))
    oil.viscosity(t)  # the effective temperature must lie in the law's range
    op = equilibrium(load, speed, radius, length, clearance, mu, model, cavitation, mesh)
    op.update({"t_eff": t, "delta_t": dT, "viscosity": mu})
    return op
