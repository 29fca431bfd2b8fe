"""Tabulated film outputs of the ``finite`` model [T83]: peak pressure, its angle, mid-plane
rupture angle and side flow, against direct solves (at table nodes and off-grid)."""

import math

import numpy as np
import pytest

from jointdyn.film import field as fm
from jointdyn.film.finite import (
    XI_MAX,
    _gumbel_outputs,
    build_table,
    finite_outputs,
    solve_unit_pressures,
)

NO_PARAMS = np.zeros(1)  # the finite model's own parameter block (none)
MU, R, C = 0.4, 0.01, 5e-4
SP = 6 * MU * R * R / C**2  # p = (6μR²/c²)·P
SQ = 0.5 * C * R * R  # Q_s = (cR²/2)·side flow


def test_reynolds_outputs_at_table_nodes():
    """At table nodes the kernel returns the direct FV values (rounding: 1e-12; angles through
    (cos, sin) and atan2)."""
    LD = 1.0
    tab = build_table(LD, n_xi=5, n_psi=9, cache=False, cavitation="reynolds")
    u = np.linspace(0.0, -math.log(1 - XI_MAX), 5)
    for xi in 1 - np.exp(-u[1:4]):
        for psi in (-math.pi / 2, 0.0, math.pi / 4):
            A, B = math.sin(psi), math.cos(psi)
            pm, tp, tr, qs = finite_outputs(xi, A, B * (2 + xi * xi), MU, R, 2 * R * LD, C, NO_PARAMS, tab)
            f = fm.solve(float(xi), LD, A, B, "reynolds", False, (96, 12))
            dpm, dtp = fm.peak(f)
            assert pm == pytest.approx(SP * dpm, rel=1e-12)
            assert math.remainder(tp - dtp, 2 * math.pi) == pytest.approx(0.0, abs=1e-12)
            assert math.remainder(tr - fm.rupture_angle(f), 2 * math.pi) == pytest.approx(0.0, abs=1e-12)
            assert qs == pytest.approx(SQ * fm.side_flow(f), rel=1e-12)


def test_gumbel_outputs_off_grid():
    """Full Gümbel table (L/D = 2) vs direct FD outputs at 25 random off-grid states: measured
    max p_max 9.0e-5, θ_pmax 5.6e-4 rad, rupture 3.4e-3 rad, side flow 2.3e-4 relative; bounds
    5e-4, 2e-3 rad, 1e-2 rad, 1e-3 (the rupture angle is the least smooth of the four)."""
    LD = 2.0
    tab = build_table(LD)
    rng = np.random.default_rng(2)
    for _ in range(25):
        xi, psi = rng.uniform(0.05, 0.93), rng.uniform(-math.pi, math.pi)
        A, B = math.sin(psi), math.cos(psi)
        pm, tp, tr, qs = finite_outputs(xi, A, B * (2 + xi * xi), MU, R, 2 * R * LD, C, NO_PARAMS, tab)
        th, z, PA, PB = solve_unit_pressures(xi, LD)
        o = _gumbel_outputs(xi, th, z, PA, PB, np.array([psi]))[0]
        assert abs(pm / (SP * o[0]) - 1) < 5e-4
        assert abs(math.remainder(tp - o[1], 2 * math.pi)) < 2e-3
        assert abs(math.remainder(tr - o[2], 2 * math.pi)) < 1e-2
        assert abs(qs / (SQ * o[3]) - 1) < 1e-3


def test_outputs_scale_with_the_rates_and_vanish_at_rest():
    tab = build_table(2.0)
    L = 4 * R
    a = np.array(finite_outputs(0.5, 0.3, 0.8, MU, R, L, C, NO_PARAMS, tab))
    b = np.array(finite_outputs(0.5, 3.0, 8.0, MU, R, L, C, NO_PARAMS, tab))
    np.testing.assert_allclose(b[[0, 3]], 10 * a[[0, 3]], rtol=1e-12)  # degree 1: p_max, Q_s
    np.testing.assert_allclose(b[[1, 2]], a[[1, 2]], rtol=1e-12)  # degree 0: angles
    assert finite_outputs(0.5, 0.0, 0.0, MU, R, L, C, NO_PARAMS, tab)[0] == 0.0


def test_table_without_output_blocks_gives_nan():
    old = build_table(2.0)[: 2 + 40 * 97].copy()
    old[1, 1] = 0.0  # the layout before the output blocks
    assert all(math.isnan(v) for v in finite_outputs(0.5, 0.3, 0.8, MU, R, 4 * R, C, NO_PARAMS, old))
