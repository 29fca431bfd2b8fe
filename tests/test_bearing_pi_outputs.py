"""Compiled π-film outputs [T81, T82] against quadrature of the models' own pressure."""

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import minimize_scalar

from jointdyn.film.pi_outputs import long_pi_outputs, short_pi_outputs

MU, R, L, C = 0.4, 0.01, 0.04, 5e-4
# states of the reference table [T164]: steady, approach, separation, whirl, Ω < 0, squeeze
STATES = [
    (0.5, 0.0, 523.6),
    (0.5, 20.0, 523.6),
    (0.5, -20.0, 523.6),
    (0.5, 20.0, 323.6),
    (0.9, -5.0, 423.6),
    (0.5, 20.0, -276.4),
    (0.5, 20.0, 0.0),
    (0.1, -100.0, -76.4),
]


@pytest.mark.parametrize("xi, xd, Om", STATES)
def test_long_pi_film_peak_against_quadrature(xi, xd, Om):
    """p(θ) = ∫_{θ₁}^{θ} p′ by adaptive quadrature of Reynolds' first integral (no closed form),
    maximised numerically: p_max and θ_pmax agree to 1e-9 relative and 1e-6 rad (measured
    ≤ 1e-15 and ≤ 1.7e-8 rad: the latter is the maximiser's resolution on a flat peak)."""
    C1 = -12 * MU * R * R * Om * C * (1 - xi * xi) / (2 + xi * xi)

    def dp(t):
        h = C * (1 + xi * math.cos(t))
        return (6 * MU * R * R * (Om * h + 2 * C * xd * math.sin(t)) + C1) / h**3

    pm, tm, t1, t2 = long_pi_outputs(xi, xd, xi * Om, MU, R, C)
    assert t2 == pytest.approx(t1 + math.pi) and t1 <= tm <= t2
    res = minimize_scalar(
        lambda t: -quad(dp, t1, t, epsabs=0, epsrel=1e-13)[0],
        bounds=(t1, t2),
        method="bounded",
        options={"xatol": 1e-10},
    )
    assert pm == pytest.approx(-res.fun, rel=1e-9)
    assert tm == pytest.approx(res.x, abs=1e-6)
    assert quad(dp, t1, t2, epsabs=1e-9 * pm, epsrel=1e-12)[0] == pytest.approx(
        0.0, abs=1e-8 * pm
    )  # p(θ₁+π) = 0


@pytest.mark.parametrize("xi, xd, Om", STATES)
def test_short_pi_film_peak_and_side_flow(xi, xd, Om):
    """Mid-plane peak vs a dense-grid maximum of the Ocvirk pressure refined by a bounded
    scalar search, and the side flow vs quadrature of −(h³/12μ)∂p/∂z at z = ±L/2 over the film:
    measured ≤ 9e-16 and ≤ 2.2e-16 (bounds 1e-10)."""
    pm, tm, ts, te, qs = short_pi_outputs(xi, xd, xi * Om, MU, R, L, C)

    def p_mid(t):
        g = 2 * xd * math.cos(t) - xi * Om * math.sin(t)
        return 3 * MU * L * L / (4 * C * C) * (-g) / (1 + xi * math.cos(t)) ** 3

    grid = np.linspace(ts, te, 20001)
    k = int(np.argmax([p_mid(t) for t in grid]))
    res = minimize_scalar(
        lambda t: -p_mid(t),
        bounds=(grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]),
        method="bounded",
        options={"xatol": 1e-12},
    )
    assert pm == pytest.approx(-res.fun, rel=1e-10)

    def q_end(t):  # −(h³/12μ)∂p/∂z at z = L/2 per unit length R dθ, p = −(3μ/h³)(L²/4 − z²)c g
        g = 2 * xd * math.cos(t) - xi * Om * math.sin(t)
        return -(L / 2) * C * g / 2 * R

    q = 2 * quad(q_end, ts, te, epsabs=0, epsrel=1e-13)[0]
    assert qs == pytest.approx(q, rel=1e-10)


def test_no_film_at_rest():
    assert long_pi_outputs(0.5, 0.0, 0.0, MU, R, C)[0] == 0.0
    assert short_pi_outputs(0.5, 0.0, 0.0, MU, R, L, C)[4] == 0.0
