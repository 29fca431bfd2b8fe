"""The cavitation conditions are a registry [T88]: a condition registered from outside the package
reaches the design table, the pressure field and the dynamic ``finite`` film (hence the bearing
element) by its name alone. The plugin used here solves the Swift–Stieber problem by projected SOR
(Cryer 1971) instead of the active-set method: a different algorithm for the same discrete
problem, so it must reproduce ``reynolds`` to the solvers' tolerance."""

from __future__ import annotations

import numpy as np
import pytest

from jointdyn.bearing.design import bearing_table
from jointdyn.film import cavitation as cv
from jointdyn.film.field import pressure_field
from jointdyn.film.finite import build_table
from jointdyn.film.lcp import psor, residual
from jointdyn.film.models import Finite


class ProjectedSOR:
    """Swift–Stieber by projected SOR, from scratch each call (no warm start)."""

    name = "reynolds-psor"
    rupture_exponent = 2.0
    mass_conserving = False

    def solve(self, prob, A, B, fixed=None, warm=None):
        b = A * prob.bA + B * prob.bB
        P, sweeps = psor(prob.M, b, fixed)
        return cv.Solution(P, None, sweeps, residual(prob.M, b, P, fixed))


@pytest.fixture()
def plugin(monkeypatch):
    monkeypatch.setitem(cv.CAVITATION, "reynolds-psor", ProjectedSOR())  # removed after the test
    return "reynolds-psor"


def test_plugin_reaches_the_design_table(plugin):
    """Same discrete LCP, two algorithms: measured 7.5e-15 relative in every column (bound 1e-10:
    PSOR stops at an update of 1e-14 of max P per sweep, the active set is exact to rounding)."""
    a = bearing_table("finite", "reynolds", 0.5, [0.3, 0.8], mesh=(48, 6))
    b = bearing_table("finite", plugin, 0.5, [0.3, 0.8], mesh=(48, 6))
    for col in ("sommerfeld", "attitude_deg", "friction_variable", "flow_variable", "theta_end_deg"):
        assert np.allclose(a[col], b[col], rtol=1e-10, atol=0.0), col


def test_plugin_reaches_the_pressure_field(plugin):
    args = (0.6, 0.0, 300.0, 0.02, 0.01, 0.01, 5e-5)
    _, _, pa = pressure_field(*args, cavitation="reynolds", mesh=(48, 6))
    _, _, pb = pressure_field(*args, cavitation=plugin, mesh=(48, 6))
    assert np.max(np.abs(pa - pb)) <= 1e-10 * np.max(pa)  # same LCP (see above); measured 1.4e-14


def test_plugin_reaches_the_dynamic_film(plugin):
    """``Finite(cavitation=NAME)`` accepts the plugin and its table (the element's input) equals
    the ``reynolds`` table (small table: 3 × 5 entries; measured 2.0e-14 of the largest entry,
    bound as above)."""
    Finite(cavitation=plugin)  # accepted by name
    kw = {"n_xi": 3, "n_psi": 5, "cache": False}
    ta = build_table(1.0, cavitation="reynolds", **kw)
    tb = build_table(1.0, cavitation=plugin, **kw)
    n = 2 + 3 * 5  # the force block [T37]
    assert np.allclose(ta[2:n], tb[2:n], rtol=1e-10, atol=1e-10 * np.max(np.abs(ta[2:n])))


def test_unknown_and_malformed_conditions():
    with pytest.raises(ValueError, match="must be one of gumbel, reynolds, jfo"):
        cv.condition("elrod")
    with pytest.raises(ValueError, match="unknown; valid"):
        Finite(cavitation="elrod")
    with pytest.raises(ValueError, match="already registered"):
        cv.register(cv.Gumbel())

    class NoExponent:
        name = "x"
        mass_conserving = True

        def solve(self, prob, A, B, fixed=None, warm=None):
            raise AssertionError

    with pytest.raises(ValueError, match="rupture_exponent"):
        cv.register(NoExponent())
    assert "x" not in cv.names()


def test_closed_form_models_refuse_a_plugin(plugin):
    with pytest.raises(ValueError, match="model 'long'"):
        bearing_table("long", plugin, 1.0, [0.5])
    with pytest.raises(ValueError, match="model 'short'"):
        bearing_table("short", plugin, 1.0, [0.5])
