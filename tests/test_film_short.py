"""Short-bearing (Ocvirk) π-film: closed form vs direct quadrature of its own pressure, the
classic steady load, continuity, symmetry, and the validity warning."""

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from jointdyn.errors import PhysicsWarning
from jointdyn.film.models import short_force
from jointdyn.forces.journal import JournalBearing
from jointdyn.multibody.model import Model

TAB = np.zeros((1, 2))
NO_PARAMS = np.zeros(1)  # the model's own parameter block (short has none)
MU, R, L, C = 0.4, 0.01, 0.005, 5e-4  # L/D = 0.25


def reference(xi, xd, xo):
    """Independent: integrate the z-integrated short-bearing pressure P(θ) = −μL³ g/(2c²w³),
    g = 2ξ̇cosθ − ξΩ sinθ, over the sub-interval(s) where P > 0 found by root finding."""
    g = lambda t: 2 * xd * math.cos(t) - xo * math.sin(t)
    P = lambda t: -MU * L**3 * g(t) / (2 * C**2 * (1 + xi * math.cos(t)) ** 3)
    grid = np.linspace(0.0, 2 * math.pi, 65)
    roots = [brentq(g, a, b, xtol=1e-15) for a, b in zip(grid[:-1], grid[1:]) if g(a) * g(b) < 0]
    edges = [0.0, *roots, 2 * math.pi]
    # absolute floor: components that nearly cancel cannot reach a relative epsrel
    tol = 1e-13 * R * 2 * math.pi * max(abs(P(t)) for t in np.linspace(0, 2 * math.pi, 721))
    fr = ft = 0.0
    for a, b in zip(edges[:-1], edges[1:]):
        if P(0.5 * (a + b)) > 0:
            fr += R * quad(lambda t: P(t) * math.cos(t), a, b, epsabs=tol, epsrel=1e-11, limit=200)[0]
            ft += R * quad(lambda t: P(t) * math.sin(t), a, b, epsabs=tol, epsrel=1e-11, limit=200)[0]
    return fr, ft


def test_matches_quadrature_of_its_own_pressure():
    rng = np.random.default_rng(11)
    worst = 0.0
    for i in range(300):
        xi = rng.uniform(0.0, 0.97)
        xd = 0.0 if i % 7 == 0 else rng.normal() * 30
        xo = 0.0 if i % 11 == 0 else rng.normal() * 400
        if xd == 0 and xo == 0:
            continue
        a, b = short_force(xi, xd, xo, MU, R, L, C, NO_PARAMS, TAB), reference(xi, xd, xo)
        worst = max(worst, math.hypot(a[0] - b[0], a[1] - b[1]) / math.hypot(*b))
    # closed form is exact; adaptive quadrature of smooth pieces at epsrel 1e-11, (1−ξ²)^-2.5 growth
    assert worst < 1e-9


def test_steady_ocvirk_load():
    """Hamrock, Fundamentals of Fluid Film Lubrication (short-bearing theory): W_r = μωRL³ξ²/(c²(1−ξ²)²),
    W_t = πμωRL³ξ/(4c²(1−ξ²)^{3/2}) for a fixed bearing, ξ̇ = 0, γ̇ = 0."""
    for xi in (0.1, 0.5, 0.9, 0.99):
        om = 523.6
        fr, ft = short_force(xi, 0.0, xi * om, MU, R, L, C, NO_PARAMS, TAB)
        assert fr == pytest.approx(-MU * om * R * L**3 * xi**2 / (C**2 * (1 - xi**2) ** 2), rel=1e-12)
        assert ft == pytest.approx(
            math.pi * MU * om * R * L**3 * xi / (4 * C**2 * (1 - xi**2) ** 1.5), rel=1e-12
        )


def test_continuity_and_zero_at_rest():
    assert short_force(0.5, 0.0, 0.0, MU, R, L, C, NO_PARAMS, TAB) == (0.0, 0.0)
    for xi in (0.0, 0.3, 0.9):
        for xd, xo in ((1e-9, 300.0), (-1e-9, 300.0), (20.0, 1e-7), (20.0, -1e-7)):
            a = np.array(short_force(xi, xd, xo, MU, R, L, C, NO_PARAMS, TAB))
            b = np.array(
                short_force(
                    xi,
                    0.0 if abs(xd) < 1e-6 else xd,
                    0.0 if abs(xo) < 1e-6 else xo,
                    MU,
                    R,
                    L,
                    C,
                    NO_PARAMS,
                    TAB,
                )
            )
            # F is homogeneous of degree 1 and continuous: a 1e-9 perturbation moves it ~1e-9 relative
            assert np.abs(a - b).max() <= 1e-6 * np.abs(b).max()


def test_pure_squeeze_does_no_positive_work():
    for xi in np.linspace(0, 0.95, 20):
        for xd in (-10.0, 10.0):
            fr, ft = short_force(xi, xd, 0.0, MU, R, L, C, NO_PARAMS, TAB)
            assert fr * xd <= 0 and ft == pytest.approx(0.0, abs=1e-12 * abs(fr))


def test_short_bearing_outside_its_validity_warns():
    m = Model("w", gravity=(0.0, 0.0))
    m.add_body("a", 1.0, 1e-3, points={"p": (0.0, 0.0)})
    m.add_body("b", 1.0, 1e-3, points={"p": (0.0, 0.0)})
    m.add("bearing", JournalBearing("a", "p", "b", "p", 0.0105, 0.01, 0.04, 0.4, film="short"))  # L/D = 2
    with pytest.warns(PhysicsWarning, match="L/D = 2"):
        m.compile()
    m.items["bearing"] = JournalBearing("a", "p", "b", "p", 0.0105, 0.01, 0.005, 0.4, film="short")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        m.compile()  # L/D = 0.25: no warning
