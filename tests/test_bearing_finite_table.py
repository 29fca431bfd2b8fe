"""The ``finite`` film's Reynolds-condition table [T80]: the compiled kernel reproduces direct
Swift–Stieber solves at the table nodes and is homogeneous of degree 1 in (A, B)."""

import math

import numpy as np
import pytest

from jointdyn.film import field as fm
from jointdyn.film.finite import XI_MAX, build_table, finite_force

NO_PARAMS = np.zeros(1)  # the finite model's own parameter block (none)
MU, R, C, LD = 0.4, 0.01, 5e-4, 1.0


@pytest.fixture(scope="module")
def table():
    return build_table(LD, n_xi=5, n_psi=9, cache=False, cavitation="reynolds")


def test_kernel_equals_direct_solve_at_nodes(table):
    """At table nodes the bicubic interpolation returns the node value: kernel vs a direct FV
    solve on the builder's mesh agree to 1e-12 (rounding)."""
    u = np.linspace(0.0, -math.log(1 - XI_MAX), 5)
    for xi in 1 - np.exp(-u[1:4]):
        for psi in (-math.pi / 2, 0.0, math.pi / 4):
            A, B = math.sin(psi), math.cos(psi)
            fr, ft = finite_force(xi, A, B * (2 + xi * xi), MU, R, 2 * R * LD, C, NO_PARAMS, table)
            f = fm.solve(float(xi), LD, A, B, "reynolds", False, (96, 12))
            dr, dt = fm.forces(f)
            s = 6 * MU * R**4 / C**2
            assert fr == pytest.approx(s * dr, rel=1e-12, abs=1e-12 * s)
            assert ft == pytest.approx(s * dt, rel=1e-12, abs=1e-12 * s)


def test_reynolds_lcp_is_homogeneous():
    """LCP(s·b) = s·LCP(b) for s > 0 (the basis of the table): 1e-12."""
    f1 = fm.solve(0.5, 1.0, 0.3, 0.7, "reynolds")
    f2 = fm.solve(0.5, 1.0, 3.0, 7.0, "reynolds")
    assert np.allclose(f2.P, 10 * f1.P, rtol=1e-12, atol=1e-12 * f2.P.max())


def test_reynolds_carries_more_load_than_gumbel_steady():
    """Steady wedge: the Swift–Stieber film extends past the minimum film and carries more load
    than the half-Sommerfeld film on the same mesh (a qualitative check of both branches)."""
    g = fm.forces(fm.solve(0.6, 1.0, 0.0, 1.0, "gumbel"))
    r = fm.forces(fm.solve(0.6, 1.0, 0.0, 1.0, "reynolds"))
    assert math.hypot(*r) > math.hypot(*g)


def test_bad_cavitation_name():
    with pytest.raises(ValueError, match="cavitation = 'elrod': must be one of gumbel, reynolds"):
        build_table(1.0, cavitation="elrod", cache=False)
