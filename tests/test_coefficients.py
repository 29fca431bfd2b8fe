"""Dynamic coefficients, equilibrium locus and Lund's threshold [T105–T109] against closed forms
from the literature, finite differences of the force law and eigenvalues of the rotor."""

from __future__ import annotations

import math

import numpy as np
import pytest
from fd_reference import central, one_sided

from jointdyn.film.coefficients import (
    dynamic_coefficients,
    equilibrium,
    equilibrium_locus,
    stability_threshold,
)
from jointdyn.film.models import film_forces

EPS = np.round(np.arange(0.05, 0.96, 0.05), 2)
NAMES = ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy")
PI = math.pi


def short_closed_form(e):
    """Short (Ocvirk, π-film) bearing, x horizontal, load along −y: Friswell, Penny, Garvey & Lees,
    *Dynamics of Rotating Machines* (CUP 2010), ch. 5 short-bearing coefficients (the same
    expressions are in ROSS, ``ross/fluid_flow/fluid_flow_coefficients.py``)."""
    h0 = 1.0 / (PI**2 * (1 - e**2) + 16 * e**2) ** 1.5
    s = math.sqrt(1 - e**2)
    return {
        "kxx": h0 * 4 * (PI**2 * (2 - e**2) + 16 * e**2),
        "kxy": h0 * PI * (PI**2 * (1 - e**2) ** 2 - 16 * e**4) / (e * s),
        "kyx": -h0 * PI * (PI**2 * (1 - e**2) * (1 + 2 * e**2) + 32 * e**2 * (1 + e**2)) / (e * s),
        "kyy": h0 * 4 * (PI**2 * (1 + 2 * e**2) + 32 * e**2 * (1 + e**2) / (1 - e**2)),
        "cxx": h0 * 2 * PI * s * (PI**2 * (1 + 2 * e**2) - 16 * e**2) / e,
        "cxy": -h0 * 8 * (PI**2 * (1 + 2 * e**2) - 16 * e**2),
        "cyx": -h0 * 8 * (PI**2 * (1 + 2 * e**2) - 16 * e**2),
        "cyy": h0 * 2 * PI * (PI**2 * (1 - e**2) ** 2 + 48 * e**2) / (e * s),
    }


@pytest.mark.parametrize("e", EPS)
def test_short_bearing_coefficients_match_closed_form(e):
    d = dynamic_coefficients("short", 0.25, float(e))
    ref = short_closed_form(float(e))
    big = max(abs(v) for v in ref.values())
    for k in NAMES:
        # exact Jacobian of the same closed-form force: rounding only (issue goal 1e-6)
        assert abs(d[k] - ref[k]) <= 1e-9 * big, (k, d[k], ref[k])


@pytest.mark.parametrize("e", EPS)
def test_equilibrium_closed_forms(e):
    e = float(e)
    w = 1 - e * e
    # short: tan φ = π√(1−ε²)/(4ε), S(L/D)² = (1−ε²)²/(πε√(π²(1−ε²) + 16ε²))  (Hamrock,
    # *Fundamentals of Fluid Film Lubrication*, short-bearing theory)
    ld = 0.25
    q = equilibrium("short", ld, e)
    assert abs(math.tan(q["attitude"]) - PI * math.sqrt(w) / (4 * e)) <= 1e-12 * PI / (4 * e)
    S = w**2 / (PI * e * math.sqrt(PI**2 * w + 16 * e**2)) / ld**2
    assert abs(q["sommerfeld"] - S) <= 1e-12 * S
    # long (half-Sommerfeld, which both long models reproduce for steady load):
    # tan φ = π√(1−ε²)/(2ε), S = (2+ε²)(1−ε²)/(6πε√(π²(1−ε²) + 4ε²))  (Hamrock, long-bearing theory)
    S = (2 + e * e) * w / (6 * PI * e * math.sqrt(PI**2 * w + 4 * e * e))
    for model in ("alshaer2005", "ott"):
        q = equilibrium(model, 1.0, e)
        assert abs(math.tan(q["attitude"]) - PI * math.sqrt(w) / (2 * e)) <= 1e-12 * PI / (2 * e)
        assert abs(q["sommerfeld"] - S) <= 1e-12 * S


def fd_coefficients(model, ld, e):
    """K, C by central differences of the public ``film_forces`` in Cartesian variables (an
    independent path: γ, γ̇ and Ω are formed there, not by the chain rule of [T105])."""
    q = equilibrium(model, ld, e)
    g = q["gamma"]
    x0 = np.array([e * math.cos(g), e * math.sin(g), 0.0, 0.0])  # c = 1, ω = 1

    def F(z):
        x, y, xd, yd = z
        r = math.hypot(x, y)
        f = film_forces(
            model,
            r,
            (x * xd + y * yd) / r,
            math.atan2(y, x),
            (x * yd - y * xd) / r**2,
            1.0,
            0.0,
            1.0,
            2.0 * ld,
            1.0,
            1.0,
        )
        return np.array([float(f["Fx"]), float(f["Fy"])])

    J = np.empty((2, 4))
    for j in range(4):

        def fj(v, j=j):
            z = x0.copy()
            z[j] = v
            return F(z)

        if model in ("ott", "finite"):
            # only C¹ at the equilibrium: Ott's Φ has |ξ̇| (ξ̇ = 0 there) and the finite table's
            # ψ = atan2(ξ̇, B) = 0 is a grid node of the C¹ interpolant; one-sided limits agree
            J[:, j] = one_sided(fj, x0[j], 0.05 * (1 - e))
        else:
            J[:, j] = central(fj, x0[j], 0.05 * (1 - e))
    W = q["load"]
    return -J[:, :2] / W, -J[:, 2:] / W


@pytest.mark.parametrize("model,ld", [("ott", 1.0), ("alshaer2005", 1.0), ("short", 0.25), ("finite", 0.5)])
def test_coefficients_match_finite_differences_of_the_force_law(model, ld):
    worst = 0.0
    for e in np.round(np.arange(0.1, 0.91, 0.1), 1):
        d = dynamic_coefficients(model, ld, float(e))
        K, C = fd_coefficients(model, ld, float(e))
        ref = np.concatenate([K.ravel(), C.ravel()])
        got = np.array([d[k] for k in NAMES])
        worst = max(worst, np.abs(got - ref).max() / np.abs(ref).max())
    # issue goal: ≤ 1e-4 of the largest coefficient; the reference is O(h⁴)-accurate
    assert worst <= 1e-6, f"{model}: {worst:.3g}"


@pytest.mark.parametrize("e", [0.1, 0.3, 0.5, 0.7])
def test_threshold_is_where_the_rotor_eigenvalue_crosses(e):
    """m x'' + c x' + k x = 0 (τ = ωt, dimensionless): at M̄_crit one eigenvalue is ±iν/ω."""
    d = dynamic_coefficients("short", 0.25, e)
    k = np.array([[d["kxx"], d["kxy"]], [d["kyx"], d["kyy"]]])
    c = np.array([[d["cxx"], d["cxy"]], [d["cyx"], d["cyy"]]])
    m = d["critical_mass"]
    assert math.isfinite(m)

    def eig(mass):
        A = np.block([[np.zeros((2, 2)), np.eye(2)], [-k / mass, -c / mass]])
        return np.linalg.eigvals(A)

    lam = eig(m)
    i = np.argmax(lam.real)
    # eigenvalues of a 4×4 matrix: rounding ~1e-14 of |λ| ≈ 1
    assert abs(lam[i].real) <= 1e-10
    assert abs(abs(lam[i].imag) - d["whirl_ratio"]) <= 1e-10
    assert eig(0.999 * m).real.max() < 0 < eig(1.001 * m).real.max()


def test_short_bearing_threshold_limits():
    # ε → 0: half-frequency whirl (ν/ω → 1/2), the classic oil-whirl ratio (Lund 1987, review)
    assert abs(dynamic_coefficients("short", 0.25, 1e-3)["whirl_ratio"] - 0.5) < 1e-3
    # the short bearing is stable for any rotor mass at high eccentricity
    assert dynamic_coefficients("short", 0.25, 0.9)["critical_mass"] == math.inf


def test_stability_threshold_closed_form_inputs():
    # isotropic stiffness and damping, no cross coupling: no threshold
    assert stability_threshold(np.eye(2), np.eye(2))["critical_mass"] == math.inf


def test_locus_is_monotone():
    loc = equilibrium_locus("alshaer2005", 1.0, np.linspace(0.05, 0.95, 19))
    assert np.all(np.diff(loc["sommerfeld"]) < 0) and np.all(np.diff(loc["attitude"]) < 0)


@pytest.mark.parametrize(
    "args,word",
    [
        (("short", 0.25, 1.0), "eps"),
        (("short", 0.25, -0.1), "eps"),
        (("short", 0.25, 0.0), "eps"),
        (("short", 0.0, 0.5), "ld"),
        (("nope", 0.25, 0.5), "model"),
    ],
)
def test_bad_input(args, word):
    with pytest.raises(ValueError, match=word) as err:
        dynamic_coefficients(*args)
    assert "\n" not in str(err.value)


def _max_rel_diff(model_a, ld_a, model_b, ld_b, names):
    w = 0.0
    for e in np.round(np.arange(0.1, 0.91, 0.1), 1):
        a = dynamic_coefficients(model_a, ld_a, float(e))
        b = dynamic_coefficients(model_b, ld_b, float(e))
        ga = np.array([a[k] for k in names])
        gb = np.array([b[k] for k in names])
        w = max(w, np.abs(ga - gb).max() / np.abs(gb).max())
    return w


def test_finite_tends_to_short_as_length_vanishes():
    # measured (ε = 0.1 … 0.9, all 8 coefficients, of the largest): 5.2 % at L/D = 0.1,
    # 1.6 % at 0.05, 0.5 % at 0.025 — about (L/D)^1.7, end leakage dominating as L/D → 0
    d1 = _max_rel_diff("finite", 0.1, "short", 0.25, NAMES)
    d2 = _max_rel_diff("finite", 0.05, "short", 0.25, NAMES)
    assert d2 < d1 / 3 and d2 < 0.02


def test_finite_stiffness_tends_to_long_pi_film():
    # stiffness: 4.0 % at L/D = 8, 0.45 % at 32 (measured). Damping does not converge to the
    # π-film's (24 % at L/D = 32): the clipped finite full film tends to the clipped long film,
    # whose squeeze derivative of F_t is 2.5/(1 + 1.5ε²) times the π-film's ([T87];
    # all eight coefficients: tests/test_coefficients_long.py)
    k8 = _max_rel_diff("finite", 8.0, "alshaer2005", 1.0, NAMES[:4])
    k32 = _max_rel_diff("finite", 32.0, "alshaer2005", 1.0, NAMES[:4])
    assert k32 < k8 / 3 and k32 < 0.005


def test_columns_declared():
    from jointdyn.film.coefficients import COLUMNS

    assert set(dynamic_coefficients("ott", 1.0, 0.5)) == set(COLUMNS)


@pytest.mark.parametrize(
    "model,ld", [pytest.param("short", 0.25, marks=pytest.mark.slow, id="short-0.25"), ("alshaer2005", 1.0)]
)
def test_system_jacobian_of_a_rotor_on_the_bearing_gives_the_coefficients(model, ld):
    """A free rotor (mass m, spin ω) in a fixed bearing, loaded by gravity, sitting at the static
    equilibrium of ε = 0.6: the multibody system Jacobian [T101] (no constraints) must contain
    ∂ẍ/∂x = −K/m and ∂ẍ/∂ẋ = −C/m with K = k W/c, C = c̄ W/(cω) from [T107] — two independent
    paths (element chain rule vs the Cartesian linearisation). Each film compiles a system
    Jacobian of its own (≈ 20 s of CPU from a cold cache): the short film's case is ``slow``; its
    film Jacobian is checked against finite differences in the default tier
    (tests/test_jacobians_laws.py), and the path from it to the system Jacobian is the one the
    π-film case runs."""
    from jointdyn.forces.journal import JournalBearing
    from jointdyn.multibody.jacobian import system_jacobian
    from jointdyn.multibody.model import Model

    eps, R, c, mu, omega, g = 0.6, 0.01, 5e-5, 0.02, 300.0, 9.81
    L = 2 * R * ld
    d = dynamic_coefficients(model, ld, eps)
    # W from S = μ N L D (R/c)²/W, N = ω/2π
    W = mu * omega / (2 * PI) * L * 2 * R * (R / c) ** 2 / d["sommerfeld"]
    mass = W / g
    gam = d["attitude"] - PI / 2
    m = Model("rotor", gravity=(0.0, -g))
    m.add_ground_point("O", (0.0, 0.0))
    pos = (eps * c * math.cos(gam), eps * c * math.sin(gam))
    m.add_body(
        "rotor", mass, 1e-4, position=pos, angle=0.0, velocity=(0.0, 0.0, omega), points={"C": (0.0, 0.0)}
    )
    m.add("brg", JournalBearing("ground", "O", "rotor", "C", R + c, R, L, mu, film=model))
    s = m.compile(centre_imperfect=False)
    P = s.packed(0.0, jacobian=True)
    y = s.y0.copy()
    nn = y.size
    Jm = np.empty((nn, nn))
    ft = np.empty(nn)
    f0 = np.empty(nn)
    assert system_jacobian(0.0, y, f0, s.mem0, P, Jm, ft, np.empty(nn), np.empty(nn)) == 0
    from jointdyn.multibody.dynamics import rhs

    rhs(0.0, y, s.mem0, P, f0)
    assert np.abs(f0[3:5]).max() <= 1e-9 * g  # static equilibrium: film force balances gravity
    K = np.array([[d["kxx"], d["kxy"]], [d["kyx"], d["kyy"]]]) * W / c
    C = np.array([[d["cxx"], d["cxy"]], [d["cyx"], d["cyy"]]]) * W / (c * omega)
    # both exact: rounding only
    assert np.allclose(-Jm[3:5, 0:2] * mass, K, rtol=1e-9, atol=1e-9 * np.abs(K).max())
    assert np.allclose(-Jm[3:5, 3:5] * mass, C, rtol=1e-9, atol=1e-9 * np.abs(C).max())


def test_equilibrium_agrees_with_the_bearing_table():
    """The steady design table (``jointdyn.bearing``, its own closed forms) and the equilibrium
    found from the film kernels agree for short and long (half-Sommerfeld) bearings."""
    from jointdyn.bearing.design import bearing_table

    eps = [0.2, 0.5, 0.8]
    for table_model, film, ld in (("short", "short", 0.25), ("long", "alshaer2005", 1.0)):
        t = bearing_table(table_model, "gumbel", ld, eps)
        for i, e in enumerate(eps):
            q = equilibrium(film, ld, e)
            # two closed-form evaluations: rounding only (measured ≤ 2e-15)
            assert abs(q["sommerfeld"] - t["sommerfeld"][i]) <= 1e-12 * q["sommerfeld"]
            assert abs(math.degrees(q["attitude"]) - t["attitude_deg"][i]) <= 1e-10


if __name__ == "__main__":  # the numbers of the report: python tests/test_coefficients.py
    for model, ld in [("ott", 1.0), ("alshaer2005", 1.0), ("short", 0.25), ("finite", 0.5)]:
        worst = 0.0
        for e in np.round(np.arange(0.1, 0.91, 0.1), 1):
            d = dynamic_coefficients(model, ld, float(e))
            K, C = fd_coefficients(model, ld, float(e))
            ref = np.concatenate([K.ravel(), C.ravel()])
            worst = max(worst, np.abs(np.array([d[k] for k in NAMES]) - ref).max() / np.abs(ref).max())
        print(f"exact vs FD of film_forces, {model} (L/D = {ld:g}): {worst:.2e} of the largest")
    worst = max(
        abs(dynamic_coefficients("short", 0.25, float(e))[k] - short_closed_form(float(e))[k])
        / max(abs(v) for v in short_closed_form(float(e)).values())
        for e in EPS
        for k in NAMES
    )
    print(f"short vs Friswell et al. closed forms, ε = 0.05 … 0.95: {worst:.2e} of the largest")
    for ld in (0.25, 0.1, 0.05, 0.025):
        print(f"finite vs short, L/D = {ld:g}: {_max_rel_diff('finite', ld, 'short', 0.25, NAMES):.3g}")
    for ld in (2.0, 8.0, 32.0):
        k = _max_rel_diff("finite", ld, "alshaer2005", 1.0, NAMES[:4])
        c = _max_rel_diff("finite", ld, "alshaer2005", 1.0, NAMES[4:])
        print(f"finite vs alshaer2005, L/D = {ld:g}: stiffness {k:.3g}, damping {c:.3g}")


def test_bearing_table_carries_the_dynamic_coefficients_of_its_film():
    """The design table adds k, c and Lund's threshold where the table's film has a dynamic
    kernel (Gümbel films), from the same exact Jacobians; Swift–Stieber films have them by
    central differences ([T247], [T344]: tests/test_long_reynolds_coefficients.py)."""
    from jointdyn.bearing.design import COEFFICIENT_COLUMNS, bearing_table
    from jointdyn.film.coefficients import dynamic_coefficients

    tab = bearing_table("short", "gumbel", 0.25, [0.3, 0.7])
    for i, eps in enumerate((0.3, 0.7)):
        ref = dynamic_coefficients("short", 0.25, eps)
        for c in COEFFICIENT_COLUMNS:
            assert tab[c][i] == ref[c]
    assert set(COEFFICIENT_COLUMNS) <= set(bearing_table("long", "reynolds", 1.0, [0.5]))


def test_cross_damping_asymmetry_quoted_in_the_theory_is_current():
    """[T107] explains why c_xy ≠ c_yx for the π-film and the finite Gümbel film (and not for the
    short bearing) with numbers at ε = 0.6; a stale number fails here (issue 29)."""
    import re
    from pathlib import Path

    text = " ".join((Path(__file__).resolve().parents[1] / "docs" / "theory.md").read_text("utf-8").split())
    num = r"(−?\d+\.\d+)"
    m = re.search(
        rf"Measured at ε = 0\.6: alshaer2005 \(long π-film\) c_xy = {num}, c_yx = {num}; finite "
        rf"\(L/D = 1, Gümbel\) {num} and {num}\. .*? c_xy = c_yx = {num} \(L/D = 0\.25\)",
        text,
    )
    assert m, "the [T107] sentence moved: update this test"
    quoted = [float(g.replace("−", "-")) for g in m.groups()]
    a = dynamic_coefficients("alshaer2005", 1.0, 0.6)
    f = dynamic_coefficients("finite", 1.0, 0.6)
    s = dynamic_coefficients("short", 0.25, 0.6)
    now = [a["cxy"], a["cyx"], f["cxy"], f["cyx"], s["cxy"]]
    assert [round(x, 3) for x in now] == quoted, (now, quoted)
    assert s["cxy"] == pytest.approx(s["cyx"], rel=1e-9)  # the short bearing keeps the symmetry
