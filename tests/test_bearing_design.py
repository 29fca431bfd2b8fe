"""Bearing engineering: complementarity solver, design table, equilibrium, limits, shear torque,
film outputs, Reynolds-condition table of the ``finite`` film [T70–T80]."""

import math
import time

import numpy as np
import pytest

from jointdyn.bearing.design import bearing_table, equilibrium
from jointdyn.film import field as fm
from jointdyn.film.fv import assemble
from jointdyn.film.lcp import residual, solve_lcp
from jointdyn.film.long_short import long_steady, short_steady
from jointdyn.film.shear import film_power_loss
from jointdyn.film.shear_kernels import couette_torque, shear_torques


def test_lcp_complementarity_and_uniqueness():
    """Active set terminates with P ≥ 0, w ≥ 0, Pᵀw = 0 to rounding (measured residual ~1e-17)
    and the same solution from a cold start and a warm start."""
    prob = assemble(0.6, 1.0, 72, 8)
    b = 0.3 * prob.bA + 0.8 * prob.bB
    P, cav, it = solve_lcp(prob.M, b)
    w = prob.M @ P - b
    assert P.min() >= 0.0 and w.min() > -1e-12 * np.abs(b).max()  # rounding of a 576-unknown LU
    assert residual(prob.M, b, P) < 1e-12
    P2, _, it2 = solve_lcp(prob.M, b, cavitated=cav)
    assert it2 == 1 and np.array_equal(P, P2)


def test_banded_active_set_equals_the_sparse_lu_one():
    """The compiled banded solver [T89] runs the same active-set iteration as :func:`solve_lcp`
    (sparse LU of the reduced matrix): same final cavitated set and P to rounding over 30 seeded
    problems (ξ ∈ [0, 0.99), L/D 1/8 … 8, meshes 24…144 × 4…16, periodic and with a supply line),
    measured max |ΔP|/max P = 2.4e-14; bound 1e-12 (two factorisations of the same SPD matrix,
    condition number ≲ 1e4 on these meshes)."""
    from jointdyn.film.lcp import solve_lcp_banded

    rng = np.random.default_rng(0)
    for trial in range(30):
        xi = rng.uniform(0, 0.99)
        lam = rng.choice([0.125, 0.5, 1, 2, 8])
        nt, nz = rng.choice([24, 48, 96, 144]), rng.choice([4, 8, 12, 16])
        prob = assemble(xi, lam, nt, nz)
        b = rng.normal() * prob.bA + rng.normal() * prob.bB
        fixed = None
        if trial % 2:
            fixed = np.zeros(b.size, bool)
            fixed[:nz] = True
        P1, c1, _ = solve_lcp(prob.M, b, fixed)
        P2, c2, _ = solve_lcp_banded(prob, b, fixed)
        assert np.array_equal(c1, c2), trial
        assert np.max(np.abs(P1 - P2)) <= 1e-12 * max(np.max(P1), 1e-300), trial


def test_mesh_convergence_order_of_the_lcp():
    """S at L/D = 1, ε = 0.6 on meshes halved three times: error ratios ≈ 4 (second order;
    measured 4.04 and 3.94). The free boundary does not spoil the order of the integral."""
    S = [
        bearing_table("finite", "reynolds", 1.0, [0.6], mesh=(36 * 2**k, 4 * 2**k), coefficients=False)[
            "sommerfeld"
        ][0]
        for k in range(4)
    ]
    r1 = (S[1] - S[0]) / (S[2] - S[1])
    r2 = (S[2] - S[1]) / (S[3] - S[2])
    assert 3.0 < r1 < 5.5 and 3.0 < r2 < 5.5, (r1, r2)


def test_table_speed_50_eps():
    """50 values of ε at one L/D in ≤ 2 s warm (measured 0.8 s on the shared 2-core machine), the
    steady columns (with the numerical k/c of [T247] the same table took 2.8 s, measured once)."""
    bearing_table("finite", "reynolds", 1.0, [0.5], coefficients=False)
    t = time.perf_counter()
    tab = bearing_table("finite", "reynolds", 1.0, np.linspace(0.02, 0.98, 50), coefficients=False)
    assert time.perf_counter() - t < 2.0
    assert np.all(np.diff(tab["sommerfeld"]) < 0)  # S falls monotonically with ε


def test_long_limit_of_the_finite_solver():
    """Finite Reynolds S → long Reynolds S as L/D grows; the end leakage error decays like D/L
    (measured relative errors 26 %, 11.6 %, 5.5 % at L/D = 4, 8, 16: ratios 2.26, 2.12)."""
    eps = 0.6
    S_long = 2.0 / (math.pi * long_steady(eps, 1.0)["W"])
    e = [
        bearing_table("finite", "reynolds", ld, [eps], mesh=(144, 24), coefficients=False)["sommerfeld"][0]
        / S_long
        - 1
        for ld in (4, 8, 16)
    ]
    assert e[0] > e[1] > e[2] > 0
    assert 1.6 < e[0] / e[1] < 2.4 and 1.6 < e[1] / e[2] < 2.4, e


def test_short_limit_against_ocvirk():
    """Finite Gümbel S → Ocvirk as L/D → 0: measured relative S differences 1.38 %, 0.43 % at
    L/D = 0.1, 0.05 (ε = 0.5; ratio 3.2, the short theory's error ∝ (L/D)² gives 4)."""
    d = []
    for ld in (0.1, 0.05):
        S = bearing_table("finite", "gumbel", ld, [0.5], mesh=(144, 16))["sommerfeld"][0]
        So = bearing_table("short", "gumbel", ld, [0.5])["sommerfeld"][0]
        d.append(abs(S / So - 1))
    assert d[1] < d[0] < 0.02 and 3.0 < d[0] / d[1] < 5.0, d


def test_petroff_limit():
    """ε → 0: friction variable → 2π²S (Petroff) — the table to 1e-6 at ε = 1e-3 (measured
    6.8e-7: the remaining terms are O(ε²)); the kernel's journal torque equals −2πμωR³L/c to
    1e-12 at ξ = 0 and to 1e-6 at ξ = 1e-7."""
    t = bearing_table("finite", "reynolds", 1.0, [1e-3])
    assert abs(t["friction_variable"][0] / (2 * math.pi**2 * t["sommerfeld"][0]) - 1) < 1e-6
    mu, R, L, c, w = 0.05, 0.02, 0.03, 4e-5, 300.0
    mj, mb = shear_torques(0.0, 0.0, mu, R, L, c, w, 0.0)
    petroff = 2 * math.pi * mu * w * R**3 * L / c
    assert abs(mj / -petroff - 1) < 1e-12 and abs(mb / petroff - 1) < 1e-12
    assert abs(shear_torques(1e-7, 0.0, mu, R, L, c, w, 0.0)[0] / -petroff - 1) < 1e-6


def test_shear_torque_against_direct_integration():
    """M_J from the kernel (Couette closed form + (e/2)F_t identity) vs direct quadrature of the
    wall shear τ = −μU/h − (h/2)∂p/∂x over the FV film (∂p/∂θ by central differences):
    measured 2.1e-7 relative on 144×16 cells, 4.8e-8 on 288×32 (the Poiseuille part is 10 % of
    M_J here); bound 1e-6."""
    mu, R, L, c, w, xi = 0.05, 0.02, 0.04, 4e-5, 300.0, 0.7
    f = fm.solve(xi, L / (2 * R), 0.0, xi * w / (2 + xi * xi), "reynolds", False, (144, 16))
    p = 6 * mu * R * R / (c * c) * f.P
    th = f.prob.theta
    h = c * (1 + xi * np.cos(th))
    dth = np.mod(np.roll(th, -1) - np.roll(th, 1), 2 * np.pi)  # periodic central differences
    dp = (np.roll(p, -1, axis=0) - np.roll(p, 1, axis=0)) / dth[:, None]
    A = 2 * f.prob.area.reshape(f.P.shape) * R * R  # R dθ dz over both halves
    pois = -np.sum(A * (h / 2)[:, None] * dp / R) * R
    coue = couette_torque(xi, mu, R, L, c, w)
    fr, ft = fm.forces(f)
    Ft = 6 * mu * R**4 / c**2 * ft
    mj, _ = shear_torques(xi, Ft, mu, R, L, c, w, 0.0)
    assert abs((-coue + pois) / mj - 1) < 1e-6


def test_power_loss_is_work_of_the_film():
    """Steady journal (bearing fixed, no whirl): power loss = −M_J ω = friction torque × ω."""
    mj, mb = shear_torques(0.5, 123.0, 0.05, 0.02, 0.04, 4e-5, 300.0, 0.0)
    assert film_power_loss(0.5, -50.0, 123.0, 0.05, 0.02, 0.04, 4e-5, 300.0, 0.0, 0.0, 0.0) == pytest.approx(
        -mj * 300.0, rel=1e-15
    )


def test_equilibrium_round_trip():
    """equilibrium(W) returns ε whose table S reproduces W's S (1e-8), and the SI outputs follow
    from the table row (h_min, torque, power, peak pressure)."""
    W, N, R, L, c, mu = 2000.0, 30.0, 0.02, 0.04, 4e-5, 0.03
    op = equilibrium(W, N, R, L, c, mu)
    row = bearing_table("finite", "reynolds", L / (2 * R), [op["eps"]])
    assert row["sommerfeld"][0] == pytest.approx(op["sommerfeld"], rel=1e-8)
    assert op["h_min"] == pytest.approx(c * (1 - op["eps"]), rel=1e-15)
    assert op["power_loss"] == pytest.approx(op["friction_torque"] * 2 * math.pi * N, rel=1e-15)
    assert op["peak_pressure"] == pytest.approx(W / (2 * R * L) / row["pressure_ratio"][0], rel=1e-12)


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: bearing_table("finite", "reynolds", 1.0, [1.0]), r"eps = 1.0 \[-\]: must be in \(0, 1\)"),
        (lambda: bearing_table("finite", "reynolds", 1.0, [-0.1]), r"eps = -0.1"),
        (lambda: bearing_table("finite", "reynolds", 0.0, [0.5]), r"L/D = 0.0 \[-\]: must be finite and > 0"),
        (
            lambda: bearing_table("finite", "elrod", 1.0, [0.5]),
            r"cavitation = 'elrod': must be one of gumbel, reynolds, jfo",
        ),
        (lambda: bearing_table("short", "reynolds", 0.2, [0.5]), r"only gumbel"),
        (lambda: bearing_table("nope", "reynolds", 1.0, [0.5]), r"model = 'nope'"),
        (lambda: equilibrium(-1.0, 30, 0.02, 0.04, 4e-5, 0.03), r"load = -1.0 \[N\]: must be finite and > 0"),
        (lambda: equilibrium(2e7, 30, 0.02, 0.04, 4e-5, 0.03), r"cannot carry it below eps = 0.999"),
    ],
)
def test_bad_input_one_line(call, match):
    with pytest.raises(ValueError, match=match) as ei:
        call()
    assert "\n" not in str(ei.value)


def test_short_and_long_closed_forms_against_quadrature():
    """Ocvirk's closed-form forces vs quadrature of its own pressure P = ξ sin θ (λ² − ζ²)/(2H³)
    over the half film (1e-9), and the long Reynolds film ends where P = 0 and H = H*."""
    from scipy.integrate import dblquad

    eps, lam = 0.6, 0.3
    d = short_steady(eps, lam)

    def P(z, t):
        return eps * math.sin(t) * (lam * lam - z * z) / (2 * (1 + eps * math.cos(t)) ** 3)

    fr = 6 * dblquad(lambda z, t: P(z, t) * math.cos(t), 0, math.pi, -lam, lam, epsabs=0, epsrel=1e-12)[0]
    ft = 6 * dblquad(lambda z, t: P(z, t) * math.sin(t), 0, math.pi, -lam, lam, epsabs=0, epsrel=1e-12)[0]
    assert fr == pytest.approx(d["Fr"], rel=1e-9) and ft == pytest.approx(d["Ft"], rel=1e-9)
    dl = long_steady(eps, 1.0)
    assert math.pi < dl["theta_rupture"] < 2 * math.pi and dl["theta_peak"] < math.pi


def test_pressure_field_and_outputs_consistent():
    """pressure_field integrates to the forces of film_outputs (same solve, 1e-12), is symmetric
    in z, zero at the ends, ≥ 0; the peak lies before the minimum film for a steady journal."""
    mu, R, L, c = 0.05, 0.02, 0.04, 4e-5
    xi, xd, xo = 0.6, 0.0, 0.6 * 300.0
    th, z, p = fm.pressure_field(xi, xd, xo, mu, R, L, c)
    out = fm.film_outputs(xi, xd, xo, mu, R, L, c)
    assert p.min() >= 0 and np.all(p[:, 0] == 0) and np.all(p[:, -1] == 0)
    assert np.allclose(p, p[:, ::-1], rtol=0, atol=1e-9 * p.max())
    assert out["p_max"] == pytest.approx(p.max(), rel=0.02)  # parabola-refined peak vs nodes
    assert 0 < out["theta_pmax"] < math.pi < out["theta_rupture"] < 2 * math.pi
    assert out["side_flow"] > 0


def test_active_set_agrees_with_projected_sor():
    """Two different LCP algorithms on the same discrete problem (supply line at θ = 0, steady
    wedge and a squeeze state): max |ΔP| / max P measured 1.4e-14, 2.0e-14 (PSOR stopped at 1e-14 per
    sweep; bound 1e-9)."""
    from jointdyn.film.lcp import psor

    prob = assemble(0.7, 0.5, 48, 6)
    fixed = np.zeros(prob.bA.size, bool)
    fixed[:6] = True
    for A, B, fx in ((0.0, 1.0, fixed), (0.6, 0.4, None)):
        b = A * prob.bA + B * prob.bB
        P1, _, _ = solve_lcp(prob.M, b, fx)
        P2, sweeps = psor(prob.M, b, fx)
        assert np.max(np.abs(P1 - P2)) < 1e-9 * P1.max(), (np.max(np.abs(P1 - P2)) / P1.max(), sweeps)


def test_angles_tend_to_the_long_bearing():
    """θ_pmax and θ_end of the finite table at L/D = 16 vs the long Reynolds film [T78] (where
    P′ = 0 at H = H* on both sides of the minimum film): measured |Δθ_pmax| ≤ 0.017°,
    |Δθ_end| ≤ 0.25° (the rupture estimate is good to about one cell); bounds 0.05°, 0.4°."""
    for eps in (0.3, 0.6, 0.9):
        d = long_steady(eps, 1.0)
        t = bearing_table("finite", "reynolds", 16.0, [eps])
        assert abs(t["theta_pmax_deg"][0] - math.degrees(math.pi - d["theta_peak"])) < 0.05
        assert abs(t["theta_end_deg"][0] - math.degrees(d["theta_rupture"] - math.pi)) < 0.4


def test_finite_torques_use_the_table_force():
    """The compiled ``finite`` torque kernel = shear_torques with the kernel's own F_t (exact),
    and the pair's moment M_J + M_B + e·F_t vanishes (angular momentum of the film pair)."""
    from jointdyn.film.finite import build_table, finite_force
    from jointdyn.film.shear import finite_torques

    tab = build_table(1.0)
    mu, R, L, c = 0.05, 0.02, 0.04, 4e-5
    xi, xd, xo, wj, wb = 0.6, 3.0, 0.6 * 250.0, 300.0, 50.0
    noparams = np.zeros(1)
    fr, ft = finite_force(xi, xd, xo, mu, R, L, c, noparams, tab)
    mj, mb = finite_torques(xi, xd, xo, mu, R, L, c, noparams, tab, wj, wb)
    assert (mj, mb) == shear_torques(xi, ft, mu, R, L, c, wj, wb)
    assert abs(mj + mb + c * xi * ft) <= 1e-12 * abs(mj)


def test_pressure_figure_marks_the_peak():
    """The figure's peak marker sits at film_outputs' p_max in the bearing frame α = θ + γ + π."""
    import matplotlib

    matplotlib.use("Agg")
    from jointdyn.viz.bearing_plot import pressure_figure

    args = (0.7, 20.0, 0.7 * 300, 0.05, 0.02, 0.04, 4e-5)
    fig = pressure_figure(*args, gamma=0.5)
    out = fm.film_outputs(*args)
    x, y = fig.axes[0].lines[1].get_data()
    assert y[0] == pytest.approx(out["p_max"] / 1e6, rel=1e-12)
    assert x[0] == pytest.approx(
        math.degrees(math.fmod(out["theta_pmax"] + 0.5 + math.pi, 2 * math.pi)), rel=1e-12
    )


def test_poiseuille_torque_identity_for_the_long_pi_film():
    """For the long π-film with squeeze and whirl [T22], the Poiseuille shear torque on the
    journal −(R/2)L∫h p′ dθ over [θ₁, θ₁+π], by quadrature of the Reynolds first integral
    h³p′ = 6μR²[Ωh + 2cξ̇ sin θ] + C₁, equals −(e/2)F_t with F_t from the compiled π-film
    kernel: measured ≤ 2.4e-15 relative (bound 1e-10, quadrature at epsrel 1e-13)."""
    from scipy.integrate import quad

    from jointdyn.film.models import pi_film_force

    mu, R, L, c = 0.4, 0.01, 0.04, 5e-4
    for xi, xd, Om in ((0.5, 20.0, 323.6), (0.9, -5.0, 423.6), (0.3, 40.0, -200.0)):
        C1 = -12 * mu * R * R * Om * c * (1 - xi * xi) / (2 + xi * xi)

        def hdp(t):  # h·p′ = (6μR²[Ωh + 2cξ̇ sin θ] + C₁)/h²
            h = c * (1 + xi * math.cos(t))
            return (6 * mu * R * R * (Om * h + 2 * c * xd * math.sin(t)) + C1) / (h * h)

        th1 = math.atan2(xd, xi * Om / (2 + xi * xi))
        pois = -(R / 2) * L * quad(hdp, th1, th1 + math.pi, epsabs=0, epsrel=1e-13, limit=200)[0]
        _, ft = pi_film_force(xi, xd, xi * Om, mu, R, L, c, np.zeros(1), np.zeros((1, 2)))
        assert pois == pytest.approx(-0.5 * c * xi * ft, rel=1e-10)


@pytest.mark.parametrize("name", ["ott", "alshaer2005", "short", "finite"])
def test_film_torques_for_every_model(name):
    """film_torques(code, …) = shear_torques with that model's own F_t (exact); Petroff's torque
    at ξ = 0 (1e-12) for every registered film model."""
    from jointdyn.film.models import FILM_MODELS, film_force
    from jointdyn.film.shear import film_torques

    model = FILM_MODELS[name]()
    mu, R, L, c = 0.05, 0.02, 0.04, 4e-5
    tab = model.table(L, R) if hasattr(model, "table") else np.zeros((1, 2))
    p = np.zeros(max(1, len(model.PARAMS)))
    xi, xd, xo, wj, wb = 0.5, 2.0, 0.5 * 250.0, 300.0, 50.0
    _, ft = film_force(model.code, xi, xd, xo, mu, R, L, c, p, tab)
    assert film_torques(model.code, xi, xd, xo, mu, R, L, c, p, tab, wj, wb) == shear_torques(
        xi, ft, mu, R, L, c, wj, wb
    )
    mj, mb = film_torques(model.code, 0.0, 0.0, 0.0, mu, R, L, c, p, tab, wj, 0.0)
    assert mj == pytest.approx(-2 * math.pi * mu * wj * R**3 * L / c, rel=1e-12) and mb == -mj


def test_equilibrium_short_bearing_against_ocvirk():
    """Ocvirk's closed form S(ε) = (D/L)²(1−ε²)²/(πε√(π²(1−ε²) + 16ε²)) [T79] inverted by
    equilibrium(model='short') for a given load: the returned ε reproduces the load's S (1e-9)."""
    R, L, c, mu, N, W = 0.02, 0.01, 3e-5, 0.02, 20.0, 3000.0
    op = equilibrium(W, N, R, L, c, mu, model="short", cavitation="gumbel")
    e = op["eps"]
    S = (2 * R / L) ** 2 * (1 - e * e) ** 2 / (math.pi * e * math.sqrt(math.pi**2 * (1 - e * e) + 16 * e * e))
    assert S == pytest.approx((R / c) ** 2 * mu * N / (W / (2 * R * L)), rel=1e-9)


def test_film_names_are_table_aliases():
    # the π-film (alshaer2005) is the long bearing with Gümbel's condition [T21]: the same table
    eps = [0.2, 0.6, 0.9]
    a, b = bearing_table("alshaer2005", None, 1.0, eps), bearing_table("long", "gumbel", 1.0, eps)
    assert list(a) == list(b)
    for k in a:
        np.testing.assert_array_equal(a[k], b[k])
    with pytest.raises(ValueError, match=r"cavitation = 'reynolds' with model 'alshaer2005'.*'long'"):
        bearing_table("alshaer2005", "reynolds", 1.0, eps)
    with pytest.raises(ValueError, match=r"'ott' approximates 'alshaer2005'"):
        bearing_table("ott", None, 1.0, eps)
    # no cavitation given: Ocvirk's film takes the only one it has, the others Swift–Stieber
    np.testing.assert_array_equal(
        bearing_table("short", None, 0.25, eps)["sommerfeld"],
        bearing_table("short", "gumbel", 0.25, eps)["sommerfeld"],
    )
    np.testing.assert_array_equal(
        bearing_table("long", None, 1.0, eps)["sommerfeld"],
        bearing_table("long", "reynolds", 1.0, eps)["sommerfeld"],
    )
