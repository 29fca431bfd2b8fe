"""Dynamic coefficients of the long bearing with Reynolds' film end [T344]: the 1-D free-boundary
film at the equilibrium carries the steady load of the closed form [T78], and the 2-D finite-volume
film with the same supply line [T247] converges to its coefficients as L/D grows (end effects
O(D/L))."""

from __future__ import annotations

import math

import pytest

from jointdyn.bearing.design import bearing_table
from jointdyn.bearing.grooved_table import numeric_coefficients
from jointdyn.film.long_dynamic import long_reynolds_coefficients, long_reynolds_force
from jointdyn.film.long_short import long_reynolds_end, long_steady

K = ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy")


@pytest.mark.parametrize("eps", [0.2, 0.6, 0.9])
def test_the_dynamic_film_at_rest_is_the_steady_closed_form(eps):
    st = long_steady(eps, 1.0, "reynolds")
    phi = math.atan2(st["Ft"], -st["Fr"])
    e = (eps * math.cos(phi), eps * math.sin(phi))
    F, ae = long_reynolds_force(1.0, e, (0.0, 0.0), phi + math.pi, phi + math.pi + long_reynolds_end(eps))
    assert F[0] == pytest.approx(-st["W"], rel=1e-10)  # against the load (load frame)
    assert abs(F[1]) <= 1e-10 * st["W"]
    assert ae - phi - math.pi == pytest.approx(long_reynolds_end(eps), abs=1e-10)


def test_the_finite_film_converges_to_the_long_coefficients():
    """Largest |k − k_long| over the eight coefficients, relative to the largest coefficient, at
    ε = 0.6 (measured: 0.061, 0.027, 0.012 at L/D = 4, 8, 16: halving with each doubling)."""
    long = long_reynolds_coefficients(1.0, 0.6)
    big = max(abs(float(long[k])) for k in K)
    diffs = []
    for lam in (4.0, 8.0, 16.0):
        c = numeric_coefficients("reynolds", lam, [0.6], "line", (180, 16))
        diffs.append(max(abs(float(c[k][0]) - float(long[k])) for k in K) / big)
    assert diffs[2] < 0.015
    assert diffs[0] / diffs[1] > 1.8 and diffs[1] / diffs[2] > 1.8  # first order in D/L


def test_bearing_table_long_reynolds_has_every_coefficient_column():
    tab = bearing_table("long", "reynolds", 1.0, [0.3, 0.7])
    direct = long_reynolds_coefficients(1.0, 0.7)
    for k in K:
        assert float(tab[k][1]) == pytest.approx(float(direct[k]), rel=1e-12)
    assert all(math.isfinite(float(v)) for v in tab["critical_mass"][:1])
