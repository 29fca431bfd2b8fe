"""Validation tier: the steady design table against the published Raimondi & Boyd (1958)
tables (tests/data/raimondi_boyd_1958.csv, citation in its header) for L/D = 1/4, 1/2, 1, ∞,
against Butenschön's (1976) finite-bearing table (tests/data/butenschoen_1976.csv) for
L/D = 1 … 1/8, and against his curve fit [T77, T78, T84, T85]."""

import math
from pathlib import Path

import numpy as np
import pytest

from jointdyn.bearing.design import bearing_table
from jointdyn.bearing.validation import compare, compare_butenschoen, load_butenschoen, load_published

DATA = Path(__file__).parent / "data" / "raimondi_boyd_1958.csv"


@pytest.fixture(scope="module")
def res():
    return compare(load_published(DATA), "reynolds")


# Tolerances: the acceptance bounds (S 3 %, attitude 1°, friction variable 3 %, flow
# variable 5 %). The published values have 3 significant digits (±0.5 % of the last digit at
# worst, e.g. 0.0101).
BOUNDS = {"sommerfeld": 0.03, "attitude_deg": 1.0, "friction_variable": 0.03, "flow_variable": 0.05}
# The one published point beyond 3 %: L/D = 1/4, ε = 0.97 (S +3.2 %, friction variable +3.1 %).
# There the 1958 table itself is off: Butenschön's (1976) finer solution lies 3.1 % above it and
# agrees with ours to 0.01 % (test_1958_outlier_is_in_the_table). S and the friction variable at
# this point are therefore compared with Butenschön, not with the 1958 numbers [T85].
OUTLIER = (0.25, 0.97)
BUT = Path(__file__).parent / "data" / "butenschoen_1976.csv"


@pytest.mark.parametrize("ld", [0.25, 0.5, 1.0])
@pytest.mark.parametrize("col", list(BOUNDS))
def test_finite_reynolds_matches_raimondi_boyd(res, ld, col):
    got, ref, err = res[ld][col]
    eps = load_published(DATA)[ld]["eps"]
    for e, x in zip(eps, err):
        if (ld, e) == OUTLIER and col in ("sommerfeld", "friction_variable"):
            continue  # the 1958 value is 3.1 % off the later solution: see the test below
        assert abs(x) <= BOUNDS[col], f"L/D={ld} eps={e} {col}: error {x:+.4f} > {BOUNDS[col]}"


def _half_unit(x, digits=3):
    """Half a unit of the last of ``digits`` significant digits, relative to x [-]."""
    return 0.5 * 10.0 ** (math.floor(math.log10(abs(x))) - digits + 1) / abs(x)


def _friction_full_film(S, eps, phi_deg):
    """(R/c)f with the Couette shear of a full film over 360° [T75]: 2π²S/√(1−ε²) + (ε/2) sin φ."""
    return 2 * math.pi**2 * S / math.sqrt(1 - eps * eps) + 0.5 * eps * math.sin(math.radians(phi_deg))


def _butenschoen_point(ld, eps):
    b = load_butenschoen(BUT)[ld]
    j = list(b["eps"]).index(eps)
    return 1.0 / (2.0 * math.pi * b["So"][j]), b["beta_deg"][j]  # S = 1/(2π So)


def test_1958_outlier_is_in_the_table(res):
    """At L/D = 1/4, ε = 0.97 Raimondi & Boyd's S = 0.0101 lies 3.10 % below Butenschön's
    S = 1/(2π·15.2697) = 0.010423 (3 printed digits: ±0.5 %). Ours: +0.01 % from Butenschön
    (bound 0.5 %: the grid error of his table, [T85]). The friction torque ∝ (R/c)f/S is
    load-independent: ours and the 1958 one agree to 0.11 % (bound: the rounding of RB's two
    3-digit numbers, 0.55 %), so the 3.1 % in the friction variable is the load, i.e. S."""
    ld, e = OUTLIER
    i = list(load_published(DATA)[ld]["eps"]).index(e)
    S_b, beta_b = _butenschoen_point(ld, e)
    S_here, S_rb = res[ld]["sommerfeld"][0][i], res[ld]["sommerfeld"][1][i]
    # beyond RB's rounding (0.5 %) plus Butenschön's grid error (0.5 %, BUT_BOUNDS) together
    assert S_rb / S_b - 1 < -0.01
    assert abs(S_here / S_b - 1) < 0.005
    assert abs(res[ld]["attitude_deg"][0][i] - beta_b) < 0.15  # measured 0.10°, 3 decimals printed
    fv_here, fv_rb = res[ld]["friction_variable"][0][i], res[ld]["friction_variable"][1][i]
    torque_ratio = (fv_here / S_here) / (fv_rb / S_rb)
    assert abs(torque_ratio - 1) < _half_unit(fv_rb) + _half_unit(S_rb)


def test_raimondi_boyd_friction_is_full_film_couette():
    """RB's friction variable is their own S and φ put into the full-film (360°) Couette shear
    [T75], within the rounding of their printed digits, at 20 of the 21 finite-L/D points: the
    convention used here (the cavitated region carries the Couette shear of a full film). The
    21st, L/D = 1, ε = 0.4 (−1.27 %), is where RB's printed S = 0.264 is itself 1.3 % off
    Butenschön's 0.2606; with Butenschön's S and β the same formula gives RB's 5.79 to 0.01 %."""
    pub = load_published(DATA)
    for ld in (0.25, 0.5, 1.0):
        d = pub[ld]
        for e, S, phi, fv in zip(d["eps"], d["sommerfeld"], d["attitude_deg"], d["friction_variable"]):
            if (ld, e) == (1.0, 0.4):
                S, phi = _butenschoen_point(ld, e)
                assert abs(fv / _friction_full_film(S, e, phi) - 1) < _half_unit(fv)
                continue
            err = fv / _friction_full_film(S, e, phi) - 1
            assert abs(err) <= _half_unit(fv) + _half_unit(S), (ld, e, err)


@pytest.fixture(scope="module")
def but():
    return compare_butenschoen(load_butenschoen(BUT))


# Bounds against Butenschön's table: the rounding of each printed value (half a unit of its last
# digit, column 4 of compare_butenschoen) plus 0.5 % (So, Q) / 0.15° (β): the difference of a
# mesh-refined solution here (288 × 32 cells) to his table grows to 0.43 % (So) and 0.48 % (Q)
# at L/D = 1, i.e. his grid error; measured on the default mesh: So ≤ 0.16 %, Q ≤ 0.39 % beyond
# the rounding, β ≤ 0.10° [T85].
BUT_BOUNDS = {"So": 0.005, "beta_deg": 0.15, "Q": 0.005}


@pytest.mark.parametrize("ld", [1.0, 0.5, 0.4, 1 / 3, 0.25, 0.2, 1 / 6, 0.125])
def test_finite_reynolds_matches_butenschoen_table(but, ld):
    """``finite`` + ``reynolds`` against Butenschön's (1976) table, ε = 0.1 … 0.99, L/D = 1 … 1/8."""
    eps = load_butenschoen(BUT)[ld]["eps"]
    for col, bound in BUT_BOUNDS.items():
        got, ref, err, rounding = but[ld][col]
        for e, x, r in zip(eps, err, rounding):
            assert abs(x) <= bound + r, f"L/D={ld:.4g} eps={e} {col}: error {x:+.5f} > {bound} + {r:.5f}"


def test_butenschoen_mean_errors(but):
    """Mean |error| over the 112 points: measured So 0.084 %, Q 0.071 %, β 0.0095°."""
    for col, bound in (("So", 0.002), ("Q", 0.002), ("beta_deg", 0.03)):
        assert np.mean(np.concatenate([np.abs(r[col][2]) for r in but.values()])) < bound, col


@pytest.mark.slow
def test_1958_outlier_richardson():
    """Mesh sequence 144×16, 288×32, 576×64 at L/D = 1/4, ε = 0.97: observed order p of S
    (measured 1.98) and the Richardson limit S∞ (measured 0.0104098): +3.07 % from RB's 0.0101,
    −0.13 % from Butenschön's 0.010423. Bounds: p within 0.2 of the scheme's 2 [T71]; S∞ within
    Butenschön's grid error (0.5 %) of his value, and off RB's by more than their rounding
    (0.5 %) plus that grid error."""
    ld, e = OUTLIER
    S = [
        bearing_table("finite", "reynolds", ld, [e], mesh=(144 * k, 16 * k))["sommerfeld"][0]
        for k in (1, 2, 4)
    ]
    p = math.log2((S[0] - S[1]) / (S[1] - S[2]))
    assert abs(p - 2) < 0.2, p
    S_inf = S[2] + (S[2] - S[1]) / (2**p - 1)
    S_b, _ = _butenschoen_point(ld, e)
    assert abs(S_inf / S_b - 1) < 0.005
    assert S_inf / 0.0101 - 1 > 0.005 + 0.005


def test_mean_errors_near_one_percent(res):
    """Mean |error| over L/D = 1/4, 1/2, 1: measured S 0.66 %, friction 0.56 %, flow 0.09 %,
    attitude 0.16°; bound 1 % / 0.25° (the issue's aim)."""
    for col, bound in (("sommerfeld", 0.01), ("friction_variable", 0.01), ("flow_variable", 0.01)):
        m = np.mean(np.concatenate([np.abs(res[ld][col][2]) for ld in (0.25, 0.5, 1.0)]))
        assert m < bound, (col, m)
    m = np.mean(np.concatenate([np.abs(res[ld]["attitude_deg"][2]) for ld in (0.25, 0.5, 1.0)]))
    assert m < 0.25


def test_side_flow_and_pressure_ratio(res):
    """Side-flow ratio measured ≤ 0.5 % (bound 1 %); pressure ratio ≤ 5.8 %, worst at ε = 0.97
    where the peak is narrowest (bound 6 %; 3 digits published)."""
    for ld in (0.25, 0.5, 1.0):
        assert np.max(np.abs(res[ld]["side_flow_ratio"][2])) < 0.01
        assert np.max(np.abs(res[ld]["pressure_ratio"][2])) < 0.06


def test_long_limit_against_raimondi_boyd_infinite(res):
    """The long bearing with Reynolds' condition [T78] (1-D quadrature + root finding, no FV)
    against RB's L/D = ∞ row: measured S ≤ 0.61 %, attitude ≤ 0.36°, friction ≤ 0.77 %; the
    flow variable ≤ 0.8 % up to ε = 0.6, 3.0 % and 5.4 % at ε = 0.8, 0.9 where the published
    flow (0.760, 0.411) is a small difference of large terms."""
    d = res[math.inf]
    assert np.max(np.abs(d["sommerfeld"][2])) < 0.01
    assert np.max(np.abs(d["attitude_deg"][2])) < 0.5
    assert np.max(np.abs(d["friction_variable"][2])) < 0.01
    assert np.max(np.abs(d["flow_variable"][2][:4])) < 0.01
    assert np.max(np.abs(d["flow_variable"][2])) < 0.06


def _butenschoen(eps, bd):
    """Butenschön (1976) approximation of his finite-bearing solutions, So = F ψ²/(B D μ ω)
    (ψ = c/R) and β [deg], coefficients as in MBDyn's hydrodynamic plain bearing module
    (github.com/alex-marinov/mbdyn, modules/module-hydrodynamic_plain_bearing/
    hydrodynamic_plain_bearing_force.f95)."""
    a1 = 1.1642 - 1.9456 * bd + 7.1161 * bd**2 - 10.1073 * bd**3 + 5.0141 * bd**4
    a2 = -1.000026 - 0.023634 * bd - 0.4215 * bd**2 - 0.038817 * bd**3 - 0.090551 * bd**4
    a = (1.152624 - 0.104565 * bd, -2.5905 + 0.798745 * bd, 8.73393 - 2.3291 * bd)
    a += (-13.3414 + 3.424337 * bd, 6.6294 - 1.591732 * bd)
    e2 = 1 - eps * eps
    So = bd**2 * eps / (2 * e2**2) * math.sqrt(math.pi**2 * e2 + 16 * eps**2) * a1 * (eps - 1) / (a2 + eps)
    poly = sum(c * eps**k for k, c in enumerate(a))
    return So, math.degrees(math.atan(math.pi * math.sqrt(e2) / (2 * eps)) * poly)


@pytest.mark.parametrize("bd", [0.25, 0.5, 1.0])
def test_butenschoen_approximation(bd):
    """Reynolds-condition table vs Butenschön's approximation for ε = 0.1…0.97: measured
    So within 5.5 % and β within 2.3° (B/D = 1/4, 1/2, 1); the approximation is a curve fit to
    his numerical solutions, so the bound is 6 % / 2.5°. (Gümbel misses it by up to 21 % and
    7.5°; beyond B/D = 1 the fit's polynomials are outside their range: not compared.)"""
    eps = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.97]
    tab = bearing_table("finite", "reynolds", bd, eps)
    for k, e in enumerate(eps):
        So, beta = _butenschoen(e, bd)
        So_here = 1.0 / (2.0 * math.pi * tab["sommerfeld"][k])  # S = 1/(2π So)
        assert abs(So_here / So - 1) < 0.06, (e, So_here / So)
        assert abs(tab["attitude_deg"][k] - beta) < 2.5, (e, tab["attitude_deg"][k] - beta)
