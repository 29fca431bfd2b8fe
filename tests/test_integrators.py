"""Integrators against closed forms: a stiff damped oscillator and a pure drift."""

import math

import numpy as np
import pytest

from jointdyn.forces.springs import SpringDamper
from jointdyn.multibody.model import Model
from jointdyn.simulation.simulate import SimConfig, simulate


def oscillator(k, d, mass=0.2, x0=1e-3):
    m = Model("oscillator", gravity=(0.0, 0.0))
    m.add_ground_point("O", (0.0, 0.0))
    m.add_body("b", mass, 1e-3, position=(0.1 + x0, 0.0), points={"c": (0.0, 0.0)})
    m.add("spring", SpringDamper("ground", "O", "b", "c", stiffness=k, damping=d, free_length=0.1))
    return m.compile()


def exact(t, k, d, mass, x0):
    """Underdamped or overdamped free response x(t) with x(0) = x0, ẋ(0) = 0."""
    wn = math.sqrt(k / mass)
    z = d / (2 * math.sqrt(k * mass))
    if z < 1:
        wd = wn * math.sqrt(1 - z * z)
        return x0 * np.exp(-z * wn * t) * (np.cos(wd * t) + z * wn / wd * np.sin(wd * t))
    r1 = -wn * (z - math.sqrt(z * z - 1))
    r2 = -wn * (z + math.sqrt(z * z - 1))
    return x0 * (r2 * np.exp(r1 * t) - r1 * np.exp(r2 * t)) / (r2 - r1)


@pytest.mark.parametrize("solver", ["dopri5", "rodas4", "ros34pw2", "radau5", "scipy-radau"])
def test_oscillator_closed_form(solver):
    k, d, mass, x0 = 1e4, 5.0, 0.2, 1e-3
    res = simulate(
        oscillator(k, d, mass, x0), SimConfig(t_end=0.2, n_out=201, solver=solver, rtol=1e-9, atol=1e-13)
    )
    x = res.coordinate("b", "x") - 0.1
    # rtol 1e-9 on a state of size 1e-3 m: global error well below 1e-9 m
    np.testing.assert_allclose(x, exact(res.t, k, d, mass, x0), atol=1e-9)


@pytest.mark.parametrize("solver", ["rodas4", "ros34pw2", "radau5"])
def test_rosenbrock_handles_stiff_damping_in_few_steps(solver):
    """Damping time constant m/d = 2e-8 s (the c = 0.05 mm film class): both stay cheap."""
    k, d, mass, x0 = 1e4, 1e7, 0.2, 1e-3
    res = simulate(
        oscillator(k, d, mass, x0), SimConfig(t_end=1e-3, n_out=101, solver=solver, rtol=1e-8, atol=1e-12)
    )
    x = res.coordinate("b", "x") - 0.1
    np.testing.assert_allclose(x, exact(res.t, k, d, mass, x0), atol=1e-9)
    # explicit methods would need t_end/(2·2e-8) ≈ 25,000 steps; a stiff method needs ≪ 1,000
    assert res.stats["accepted_steps"] < 500
