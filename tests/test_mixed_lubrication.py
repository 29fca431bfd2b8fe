"""Mixed lubrication of the steady journal bearing: Greenwood–Tripp contact [T260–T263],
Patir–Cheng factors and the average Reynolds film [T264–T269], the mixed operating point and
the Stribeck curve [T270–T272]."""

import csv
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import quad

from jointdyn.bearing.design import equilibrium
from jointdyn.bearing.mixed import Bearing, operating_point, stribeck
from jointdyn.film import flow_factors as ff
from jointdyn.film.asperity import (
    GreenwoodTripp,
    asperity_load,
    composite_sigma,
    f52,
    f52_power_law,
    gt_integral,
)
from jointdyn.film.flow_factors import AverageFlow
from jointdyn.film.mixed import mixed_steady

DATA = Path(__file__).parent / "data" / "patir_cheng_1978_1979.csv"
MESH = (96, 12)


def _quad_F(n, H):
    v = quad(lambda s: (s - H) ** n * math.exp(-0.5 * s * s), H, np.inf, epsabs=0.0, epsrel=1e-12, limit=200)[
        0
    ]
    return v / math.sqrt(2.0 * math.pi)


@pytest.mark.parametrize("n", [1.0, 1.5, 2.5])
def test_gt_integral_closed_form_against_quadrature(n):
    for H in (-2.0, -0.5, 0.0, 0.7, 1.5, 3.0, 4.5, 6.0):
        assert gt_integral(n, H) == pytest.approx(_quad_F(n, H), rel=1e-9)
    assert gt_integral(1.0, 0.0) == pytest.approx(1.0 / math.sqrt(2.0 * math.pi), rel=1e-12)  # ∫s ϕ ds


def test_power_law_fit_fails_beyond_h_3():
    H = np.linspace(0.0, 2.0, 21)
    rel = f52_power_law(H) / f52(H) - 1.0
    assert np.all(np.abs(rel) < 0.15)  # a fair fit where the contact carries load
    assert f52(3.0) / f52_power_law(3.0) > 3.5  # …but a factor ≈ 3.9 low at H = 3
    assert f52(3.5) / f52_power_law(3.5) > 50.0
    assert f52_power_law(4.2) == 0.0 and f52(4.2) > 5e-7


def test_asperity_load_against_direct_quadrature():
    gt = GreenwoodTripp(composite_sigma(0.4e-6, 0.3e-6), 0.05, 2e-3, 1.2e11)
    R, L, c, xi = 0.02, 0.015, 2e-5, 0.98
    d = mixed_steady(xi, L / (2 * R), mesh=MESH)
    a = asperity_load(gt, xi, R, L, c, d["theta"], d["weights"])
    p = lambda t: float(gt.pressure(c * (1 + xi * math.cos(t))))  # noqa: E731
    ref_r = R * L * quad(lambda t: p(t) * math.cos(t), 0, 2 * math.pi, points=[math.pi], limit=400)[0]
    ref_n = R * L * quad(p, 0, 2 * math.pi, points=[math.pi], limit=400)[0]
    assert a["F_r"] == pytest.approx(ref_r, rel=1e-6)
    assert a["normal"] == pytest.approx(ref_n, rel=1e-6)
    assert abs(a["F_t"]) < 1e-9 * abs(a["F_r"])
    assert a["F_r"] < 0.0  # pushes the journal back toward the centre, as the film's F_r


def test_bad_contact_input_names_the_parameter():
    with pytest.raises(ValueError, match="sigma = 0"):
        GreenwoodTripp(0.0)
    with pytest.raises(ValueError, match="sigma1"):
        composite_sigma(-1e-6, 1e-6)
    with pytest.raises(ValueError, match="composite RMS roughness"):
        composite_sigma(0.0, 0.0)
    with pytest.raises(ValueError, match="gamma = 2"):
        ff.phi_x(3.0, 2.0)


def _table():
    with open(DATA) as fh:
        rows = list(csv.DictReader(line for line in fh if not line.startswith("#")))
    return [{k: float(v) for k, v in r.items()} for r in rows]


def test_fits_use_the_published_coefficients():
    for k, r in enumerate(_table()):
        assert ff.GAMMAS[k] == pytest.approx(r["gamma"], rel=1e-9)
        assert ff.PRESSURE[k] == (r["C"], r["r"])
        assert ff.SHEAR[k] == (r["A1"], r["alpha1"], r["alpha2"], r["alpha3"], r["A2"])
        assert ff.STRESS_FS[k] == (r["A3"], r["alpha4"], r["alpha5"], r["alpha6"])
        assert ff.STRESS_FP[k] == (r["D"], r["s"])


def test_pressure_flow_coefficients_against_a_regression_over_gamma():
    # an independent regression of Patir–Cheng's Table 1 over γ, as used in a public EHD code
    # (C = 0.89679 − 0.26591 ln γ, r = 0.43006 − 0.10828γ + 0.23821γ² for γ < 1; C = −0.10667 +
    # 0.1075γ, r = 1.5 for γ > 1): the transcribed coefficients lie within 0.02 of it
    for g in ff.GAMMAS:
        C, r = ff.PRESSURE[ff.gamma_index(g)]
        if g < 1.0:
            Cr, rr = 0.89679 - 0.26591 * math.log(g), 0.43006 - 0.10828 * g + 0.23821 * g * g
        elif g > 1.0:
            Cr, rr = -0.10667 + 0.1075 * g, 1.5
        else:
            Cr, rr = 0.89679, 0.43006 - 0.10828 + 0.23821
        assert abs(C - Cr) < 0.02 and abs(r - rr) < 0.02


def test_published_shear_flow_branches_meet_at_lambda_5():
    # an independent check of the transcribed table: Patir & Cheng fitted the two branches of Φ_s
    # separately; the published coefficients make them meet at Λ = 5 to < 0.1 %
    for g in ff.GAMMAS:
        A1, a1, a2, a3, A2 = ff.SHEAR[ff.gamma_index(g)]
        lo = A1 * 5**a1 * math.exp(-5 * a2 + 25 * a3)
        assert lo == pytest.approx(A2 * math.exp(-1.25), rel=1e-3)


def test_factors_stay_nonnegative_below_their_range():
    L = np.linspace(0.0, 10.0, 401)
    for g in ff.GAMMAS:
        assert np.all(ff.phi_x(L, g) > 0.0) and np.all(ff.phi_z(L, g) > 0.0)
        assert np.all(ff.phi_fp(L, g) >= 0.0) and np.all(ff.stress_fs(L, g) >= 0.0)
        assert np.all(ff.shear_flow(L, g) >= 0.0)
    assert np.all(ff.phi_f(L[1:]) > 0.0)


def test_phi_f_against_its_definition_and_branches():
    # φ_f = E[Λ/(Λ + 3x)], x with density (35/32)(1−x²)³ on [−1, 1], for Λ > 3 (no contact)
    dens = lambda x: 35 / 32 * (1 - x * x) ** 3  # noqa: E731
    for L in (3.5, 4.5, 6.0, 9.0, 20.0):
        ref = quad(lambda x: dens(x) * L / (L + 3 * x), -1, 1, epsabs=0, epsrel=1e-12)[0]
        assert ff.phi_f(L) == pytest.approx(ref, rel=1e-10)
    for z in (1.0, 2.0):  # the branches join continuously
        assert ff.phi_f(3 * z * (1 - 1e-9)) == pytest.approx(ff.phi_f(3 * z * (1 + 1e-9)), rel=1e-7)


def test_smooth_limits_and_symmetry():
    big = 1e4
    for g in ff.GAMMAS:
        assert ff.phi_x(big, g) == pytest.approx(1.0, abs=1e-5)
        assert ff.phi_z(big, g) == pytest.approx(1.0, abs=1e-5)
        assert ff.phi_fp(big, g) == pytest.approx(1.0, abs=1e-12)
        assert ff.shear_flow(big, g) == pytest.approx(0.0, abs=1e-12)
        assert ff.stress_fs(big, g) == 0.0
        assert ff.phi_z(2.0, g) == ff.phi_x(2.0, 1.0 / g)
    assert ff.phi_f(big) == pytest.approx(1.0 + 1.0 / big**2, rel=1e-12)  # 1 + E[δ²]/h²
    assert ff.mean_gap(big) == pytest.approx(big, rel=1e-15)
    # longitudinal roughness (γ < 1) blocks pressure flow along x, transverse (γ > 1) helps it
    assert ff.phi_x(2.0, 1 / 9) < ff.phi_x(2.0, 1.0) < 1.0 < ff.phi_x(2.0, 9.0)


@pytest.mark.parametrize("eps", [0.3, 0.8, 0.95])
def test_average_film_of_smooth_surfaces_is_the_smooth_film(eps):
    smooth = mixed_steady(eps, 0.5, None, mesh=MESH)
    fine = mixed_steady(eps, 0.5, AverageFlow(1e-5), mesh=MESH)  # Λ ≥ 5000 everywhere
    # the wedge source in flux form (average film) and at the nodes (smooth film) are two O(h²)
    # discretisations of the same integral: they differ by < 1e-3 and the gap closes with the mesh
    gap = [abs(fine[k] / smooth[k] - 1.0) for k in ("Fr", "Ft", "torque")]
    assert max(gap) < 1e-3
    fine2 = mixed_steady(eps, 0.5, AverageFlow(1e-5), mesh=(2 * MESH[0], MESH[1]))
    smooth2 = mixed_steady(eps, 0.5, None, mesh=(2 * MESH[0], MESH[1]))
    assert abs(fine2["Fr"] / smooth2["Fr"] - 1.0) < 0.5 * max(gap[0], 1e-6)
    # the friction torque by direct shear integration equals [T75]'s C + ξF̄_t/2
    assert smooth["torque"] == pytest.approx(smooth["couette"] + 0.5 * eps * smooth["Ft"], rel=2e-3)


def _bearing(flow=True, fb=0.1):
    R, L, c = 0.025, 0.025, 25e-6
    s1, s2 = 0.4e-6, 0.3e-6
    gt = GreenwoodTripp(composite_sigma(s1, s2), 0.04, 1e-3, 1.1e11)
    return Bearing(R, L, c, 0.02, gt, AverageFlow.of(s1, s2, c) if flow else None, fb)


def test_mixed_operating_point_balances_the_load():
    b = _bearing()
    op = operating_point(b, 3000.0, 0.1, MESH)
    assert abs(op["load_residual"]) < 1e-8
    assert 0.3 < op["asperity_load_fraction"] < 1.0
    assert op["boundary_torque"] > 0.0 and op["friction_torque"] > op["boundary_torque"]
    # the boundary torque is f_b R ∫p_a dA with the regularisation saturated (ωR ≫ v_s)
    assert op["friction_coefficient"] < b.boundary_friction * 1.2


def test_fast_mixed_point_is_the_smooth_hydrodynamic_point():
    b = _bearing()
    W, N = 3000.0, 50.0  # Λ_min ≈ 24: no contact, factors ≈ 1
    op = operating_point(b, W, N, (144, 16))
    ref = equilibrium(W, N, b.radius, b.length, b.clearance, b.viscosity, "finite", "reynolds")
    assert op["asperity_load_fraction"] < 1e-12
    assert op["eps"] == pytest.approx(ref["eps"], rel=2e-3)
    assert op["friction_torque"] == pytest.approx(ref["friction_torque"], rel=5e-3)


def test_stribeck_curve_has_a_minimum():
    out = stribeck(_bearing(), 3000.0, [1, 10, 100, 1000, 3000], MESH)
    f = np.array(out["friction_coefficient"])
    k = int(np.argmin(f))
    assert 0 < k < f.size - 1  # boundary/mixed on the left, hydrodynamic on the right
    assert np.all(np.diff(out["asperity_load_fraction"]) <= 0.0)  # the film lifts the journal
    assert np.all(np.diff(out["h_min"]) > 0.0)


def test_load_beyond_boundary_contact_is_an_error():
    with pytest.raises(
        ValueError, match=r"load = 100000000.0 \[N\]: the bearing cannot carry it even in boundary"
    ):
        operating_point(_bearing(), 1e8, 1.0, MESH)
