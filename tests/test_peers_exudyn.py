"""Exudyn peer model of the slider-crank (benchmarks/peers_exudyn.py) against the analytic
inverse dynamics. Slow; needs the optional ``exudyn`` package (the [peers] extra)."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

pytestmark = pytest.mark.slow


def _skip_without_exudyn():
    pytest.importorskip(
        "exudyn",
        reason="exudyn not installed: pip install -e .[peers] to run the Exudyn peer-benchmark tests",
    )


@pytest.fixture(autouse=True)
def _needs_exudyn():
    """Only the slow tier runs these; they need the optional [peers] extra."""
    _skip_without_exudyn()


ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from benchmarks.peers_exudyn import exudyn_dry, exudyn_perfect  # noqa: E402

OMEGA = 5000 * 2 * math.pi / 60
T_END = 4 * 2 * math.pi / OMEGA
R, L = 0.05, 0.12
M1, M2, M3 = 0.30, 0.21, 0.14
I2 = 2.5e-4
G = 9.81


def power_balance_moment(t):
    """Crank moment T = [sum m v.a + I_rod beta' beta'' + g sum m v_y] / omega at constant crank
    speed (crank inertia does no work at constant omega; slider does not rotate).

    Kinematics by hand: crank angle th = omega t; rod angle beta with l sin(beta) = -r sin(th);
    crank pin A = r(cos th, sin th); slider B = (r cos th + l cos beta, 0); CoMs at mid-lengths.
    """
    w = OMEGA
    th = w * np.asarray(t, dtype=float)
    sth, cth = np.sin(th), np.cos(th)
    sb = -R * sth / L
    cb = np.sqrt(1.0 - sb * sb)
    # differentiate l sin(beta) = -r sin(th):  l cos(beta) beta' = -r w cos(th)
    bd = -R * w * cth / (L * cb)
    # again: l cos(beta) beta'' - l sin(beta) beta'^2 = r w^2 sin(th)
    bdd = (R * w * w * sth + L * sb * bd * bd) / (L * cb)
    # crank pin A
    vAx, vAy = -R * w * sth, R * w * cth
    aAx, aAy = -R * w * w * cth, -R * w * w * sth
    # slider B (x only)
    vB = -R * w * sth - L * sb * bd
    aB = -R * w * w * cth - L * cb * bd * bd - L * sb * bdd
    # crank CoM = A/2; rod CoM = (A + B)/2
    p_crank = M1 * (vAx * aAx + vAy * aAy) / 4.0 + G * M1 * vAy / 2.0
    p_rod = M2 * ((vAx + vB) * (aAx + aB) + vAy * aAy) / 4.0 + I2 * bd * bdd + G * M2 * vAy / 2.0
    p_slider = M3 * vB * aB
    return (p_crank + p_rod + p_slider) / w


def test_analytic_reference_self_consistent():
    # the reference itself reproduces the benchmark's numbers [T160] (peak +138.62, min -138.42)
    t = np.linspace(0.0, 2 * math.pi / OMEGA, 200001)
    T = power_balance_moment(t)
    assert abs(T.max() - 138.62) < 0.02 and abs(T.min() + 138.42) < 0.02


@pytest.fixture(scope="module")
def perfect_1e5():
    _skip_without_exudyn()  # a module fixture runs before the autouse skip: skip here too
    return exudyn_perfect(1e-5, T_END, 1441)


def test_perfect_output_contract(perfect_1e5):
    r = perfect_1e5
    assert r["t"].shape == (1441,) and r["crank_moment"].shape == (1441,)
    assert r["t"][0] == 0.0 and math.isclose(r["t"][-1], T_END, rel_tol=1e-12)
    assert r["steps"] == round(T_END / 1e-5)
    assert r["wall_s"] > 0 and r["build_s"] >= 0
    assert r["max_penetration"] is None and r["impacts"] is None


def test_perfect_peak_matches_reference(perfect_1e5):
    Mc = perfect_1e5["crank_moment"]
    assert abs(Mc.max() - 138.62) < 0.1
    assert abs(Mc.min() - (-138.42)) < 0.1


def test_perfect_matches_power_balance(perfect_1e5):
    r = perfect_1e5
    ref = power_balance_moment(r["t"])
    err = np.abs(r["crank_moment"] - ref).max() / np.abs(ref).max()
    assert err < 1e-3, err


def test_dry_one_revolution_runs_and_stays_in_clearance():
    r = exudyn_dry(1e-5, T_END / 4, 361)
    assert r["impacts"] >= 1
    # penetration is a small fraction of the 0.5 mm clearance; the moment has impact spikes
    assert 0.0 < r["max_penetration"] < 0.5e-3 * 0.5
    assert np.all(np.isfinite(r["crank_moment"]))
    assert np.abs(r["crank_moment"]).max() > 138.62
