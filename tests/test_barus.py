"""Barus pressure–viscosity in the steady film [T317]: the reduced-pressure transform against a
direct integration of the variable-viscosity Reynolds equation, and its effect on the mixed
operating point."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from jointdyn.bearing.mixed import Bearing, operating_point
from jointdyn.film.asperity import GreenwoodTripp
from jointdyn.film.mixed import barus_pressure, mixed_steady


def test_transform_solves_the_variable_viscosity_reynolds_equation():
    """Long full (Sommerfeld) film, nondimensional: dP/dθ = e^{ᾱP}(1/H² − H*/H³), P(0) = P(2π) = 0.
    Integrated directly (DOP853, H* by shooting) against −ln(1 − ᾱq)/ᾱ of Sommerfeld's closed form
    q = ε sin θ(2 + ε cos θ)/((2 + ε²)(1 + ε cos θ)²)."""
    eps = 0.6
    th = np.linspace(0.0, 2 * math.pi, 721)
    q = eps * np.sin(th) * (2 + eps * np.cos(th)) / ((2 + eps**2) * (1 + eps * np.cos(th)) ** 2)
    bar = 0.9 / q.max()  # ᾱ·q_max = 0.9: viscosity ×10 at the peak

    def shoot(hs, t_eval=None):
        f = lambda t, p: [
            math.exp(bar * p[0]) * (1 / (1 + eps * math.cos(t)) ** 2 - hs / (1 + eps * math.cos(t)) ** 3)
        ]  # noqa: E731
        return solve_ivp(f, (0, 2 * math.pi), [0.0], method="DOP853", rtol=1e-12, atol=1e-14, t_eval=t_eval)

    hs0 = 2 * (1 - eps**2) / (2 + eps**2)
    hs = brentq(lambda h: shoot(h).y[0, -1], 0.95 * hs0, 1.05 * hs0, xtol=1e-14)
    assert hs == pytest.approx(hs0, rel=1e-9)  # the same H*: the transform keeps the flow
    P, visc = barus_pressure(q, bar)
    np.testing.assert_allclose(shoot(hs, th).y[0], P, atol=1e-7 * P.max())
    np.testing.assert_allclose(visc, np.exp(bar * P), rtol=1e-12)
    with pytest.raises(ValueError, match="pressure_viscosity: α·p_iso,max = 1.1 >= 1"):
        barus_pressure(q, 1.1 / q.max())


def test_zero_coefficient_is_the_isoviscous_film():
    a, b = mixed_steady(0.8, 1.0), mixed_steady(0.8, 1.0, barus=0.0)
    assert (a["Fr"], a["Ft"], a["torque"]) == (b["Fr"], b["Ft"], b["torque"])
    c = mixed_steady(0.8, 1.0, barus=0.05)
    assert math.hypot(c["Fr"], c["Ft"]) > math.hypot(a["Fr"], a["Ft"]) and c["torque"] > a["torque"]


def test_operating_point_with_barus_and_bad_input():
    def bearing(alpha):
        return Bearing(0.025, 0.025, 25e-6, 0.02, GreenwoodTripp(1.5e-6), flow=None, pressure_viscosity=alpha)

    iso, bar = operating_point(bearing(0.0), 3000.0, 16.0), operating_point(bearing(2e-8), 3000.0, 16.0)
    # measured: ε 0.7508 → 0.7441, torque +1.9 % (the film stiffens and its shear rises) [T317]
    assert bar["eps"] < iso["eps"] - 5e-3
    assert 1.005 < bar["friction_torque"] / iso["friction_torque"] < 1.05
    assert abs(bar["load_residual"]) < 1e-8
    with pytest.raises(ValueError, match=r"pressure_viscosity = -1e-08 \[1/Pa\]"):
        bearing(-1e-8)
    # α = 1e-7 1/Pa: the Barus pressure diverges (α·p_iso = 1) at ε = 0.775 carrying 6.5 kN
    with pytest.raises(ValueError, match=r"load = 30000.0 \[N\]: beyond the Barus film's range"):
        operating_point(bearing(1e-7), 30000.0, 16.0)
