"""Short-bearing π-film [T40–T44], 2-D Reynolds solver [T45–T46] and the tabulated finite-length
bearing [T47–T49]: closed form vs high-precision quadrature of its own pressure, the classic
steady Ocvirk load, mesh convergence, LCP cross-check, short and long limits, homogeneity,
table accuracy and periodicity.

Print the measured numbers with ``python -m pytest tests/test_film_short_finite.py -q -s``.
"""

import math
import warnings

import mpmath as mp
import numpy as np
import pytest

from jointdyn.errors import PhysicsWarning
from jointdyn.forces.film_finite import build_finite_table, finite_force, table_grid
from jointdyn.forces.film_short import short_force, short_validity_warning
from jointdyn.reynolds_fd import assemble, fd_force, psor, solve_lcp, unit_coefficients

MU, R, C = 0.4, 0.01, 5e-4
TAB = np.zeros((1, 1, 2))


def rel(a, b):
    return float(np.linalg.norm(np.subtract(a, b)) / np.linalg.norm(b))


# ----------------------------------------------------------------------------- references
def short_quadrature(xi, xd, xo, L, dps=30):
    """Independent: mpmath quadrature (30 digits) of the z-integrated short-bearing pressure
    P(θ) = −μL³g/(2c²H³), g = 2ξ̇cosθ − ξΩ sinθ, over the arc where g < 0, located by
    root finding on g (not by the closed-form θ₁); F = R∫P(cosθ, sinθ)dθ (spec §1)."""
    mp.mp.dps = dps
    x, a, b = mp.mpf(xi), 2 * mp.mpf(xd), mp.mpf(xo)
    g = lambda t: a * mp.cos(t) - b * mp.sin(t)  # noqa: E731
    P = lambda t: -MU * mp.mpf(L) ** 3 * g(t) / (2 * mp.mpf(C) ** 2 * (1 + x * mp.cos(t)) ** 3)  # noqa: E731
    grid = [2 * mp.pi * k / 64 for k in range(65)]
    roots = [mp.findroot(g, (lo, hi), solver="anderson") for lo, hi in zip(grid[:-1], grid[1:]) if g(lo) * g(hi) < 0]
    edges = sorted([mp.mpf(0), *roots, 2 * mp.pi, mp.pi])  # split at the minimum film θ = π
    fr = ft = mp.mpf(0)
    for lo, hi in zip(edges[:-1], edges[1:]):
        if hi - lo > 0 and P((lo + hi) / 2) > 0:
            fr += R * mp.quad(lambda t: P(t) * mp.cos(t), [lo, hi])
            ft += R * mp.quad(lambda t: P(t) * mp.sin(t), [lo, hi])
    return float(fr), float(ft)


def long_pi_film(xi, xd, xo, L):
    """Long-bearing π-film, spec §3.3 (written here independently of film_models)."""
    k = MU * L * R**3 / C**2
    A, B = xd, xo / (2 + xi * xi)
    rho, w = math.hypot(A, B), (1 - xi) * (1 + xi)
    dd = 2 * math.atan2(rho * math.sqrt(w), -xi * A)
    return np.array([-6 * k * (A * dd / w**1.5 + 2 * xi * rho / w), 6 * k * B * dd / math.sqrt(w)])


def state(xi, psi, rho=20.0):
    """(ξ, ξ̇, ξΩ) with (A, B) = ρ(sin ψ, cos ψ)."""
    return xi, rho * math.sin(psi), rho * math.cos(psi) * (2 + xi * xi)


# ----------------------------------------------------------------------------- short model
def test_short_matches_high_precision_quadrature_of_its_own_pressure():
    L = 0.005
    rng = np.random.default_rng(7)
    states = [(0.5, 0.0, 300.0), (0.5, 0.0, -300.0), (0.5, 25.0, 0.0), (0.5, -25.0, 0.0), (0.0, 10.0, 0.0)]
    for i in range(45):
        xi = rng.uniform(0, 0.99) if i % 3 else 1 - 10 ** rng.uniform(-7, -1)  # incl. near the wall
        xd = 0.0 if i % 7 == 0 else rng.normal() * 30
        xo = 0.0 if i % 5 == 0 else rng.normal() * 400 * xi
        if xd or xo:
            states.append((xi, xd, xo))
    worst = max(rel(short_force(*s, MU, R, L, C, TAB), short_quadrature(*s, L)) for s in states)
    print(f"\nshort π-film vs 30-digit quadrature, {len(states)} states: max rel {worst:.1e}")
    # closed form is exact; measured 5.5e-15 over 200 states up to 1−ξ = 1e-8 (double rounding
    # of ~20 operations, amplified ≤ 10× by the surviving O(1/w) terms) — 1e-12 leaves margin
    assert worst < 1e-12


def test_short_steady_ocvirk_load():
    """Hamrock, *Fundamentals of Fluid Film Lubrication* (2nd ed., short-width journal bearing):
    W_r = μωRL³ξ²/(c²(1−ξ²)²) toward the centre, W_t = πμωRL³ξ/(4c²(1−ξ²)^{3/2}),
    i.e. W = μωRL³ξ/(4c²(1−ξ²)²)·√(16ξ² + π²(1−ξ²)) (Ocvirk 1952)."""
    L = 0.005
    for xi in (0.0, 0.1, 0.5, 0.9, 0.999):
        om = 523.6
        fr, ft = short_force(xi, 0.0, xi * om, MU, R, L, C, TAB)
        w = 1 - xi * xi
        assert fr == pytest.approx(-MU * om * R * L**3 * xi**2 / (C**2 * w**2), rel=1e-13, abs=1e-300)
        assert ft == pytest.approx(math.pi * MU * om * R * L**3 * xi / (4 * C**2 * w**1.5), rel=1e-13, abs=1e-300)
        W = MU * om * R * L**3 * xi / (4 * C**2 * w**2) * math.sqrt(16 * xi**2 + math.pi**2 * w)
        assert math.hypot(fr, ft) == pytest.approx(W, rel=1e-13, abs=1e-300)  # rounding only


def test_short_continuity_branches_and_rest():
    L = 0.005
    assert short_force(0.5, 0.0, 0.0, MU, R, L, C, TAB) == (0.0, 0.0)
    for xi in (0.0, 0.3, 0.9, 0.999):
        for xd, xo in ((0.0, 300.0), (0.0, -300.0), (20.0, 0.0), (-20.0, 0.0)):
            a = np.array(short_force(xi, xd, xo, MU, R, L, C, TAB))
            for dx, do in ((1e-9, 0), (-1e-9, 0), (0, 1e-7), (0, -1e-7)):
                b = np.array(short_force(xi, xd + dx, xo + do, MU, R, L, C, TAB))
                assert rel(b, a) < 1e-8  # perturbation 1e-9 relative → Lipschitz change only
    # the guarded (y < 1) and general forms meet at y = r√w/(ξ|a|) = 1
    xi = 0.9
    a = -20.0 * 2
    b_at = math.sqrt(((xi * a) ** 2 / (1 - xi * xi)) - a * a)  # makes y = 1
    lo = np.array(short_force(xi, a / 2, b_at * (1 - 1e-12), MU, R, L, C, TAB))
    hi = np.array(short_force(xi, a / 2, b_at * (1 + 1e-12), MU, R, L, C, TAB))
    assert rel(lo, hi) < 1e-10  # both forms are the same function: only rounding differs


def test_short_validity_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert short_validity_warning(0.01, 0.02) is False  # L/D = 0.5: no warning
    with pytest.warns(PhysicsWarning, match="L/D = 1"):
        assert short_validity_warning(0.02, 0.02) is True
    with pytest.raises(ValueError, match=r"L \[m\]"):
        short_validity_warning(-1.0, 0.02)


# ----------------------------------------------------------------------------- FD solver
@pytest.mark.parametrize("cav", ["gumbel", "reynolds"])
def test_fd_mesh_convergence_second_order(cav):
    psi = np.array([-2.0, -0.6, 0.0, 1.0])
    f = [unit_coefficients(0.7, 1.0, psi, cav, 36 * 2**m, 4 * 2**m) for m in range(4)]
    d = [np.max(np.linalg.norm(f[m + 1] - f[m], axis=1) / np.linalg.norm(f[3], axis=1)) for m in range(3)]
    order = math.log2(d[1] / d[2])
    print(f"\n{cav}: successive differences {['%.2e' % x for x in d]}, observed order {order:.2f}")
    assert 1.7 < order < 2.3  # second-order FV; measured 2.0 (gumbel) / 2.0 (reynolds)
    # error of the default mesh (144×16) ≈ difference to the next finer mesh: measured 1.1e-3
    assert d[2] < 3e-3


def test_lcp_active_set_matches_projected_sor_and_complementarity():
    pr = assemble(0.6, 1.0, 72, 8)
    b = 0.3 * pr.bA + 0.9 * pr.bB
    P, cav, it = solve_lcp(pr.M, b)
    Q, sweeps = psor(pr.M, b)
    w = pr.M @ P - b
    assert P.min() >= 0 and w.min() > -1e-12 * np.abs(b).max()  # feasibility to rounding
    assert np.abs(P * w).max() < 1e-12 * P.max() * np.abs(b).max()  # complementarity
    # two different algorithms for one LCP: PSOR stops at a 1e-13 step, measured 5e-13
    assert np.abs(P - Q).max() < 1e-9 * P.max()


@pytest.mark.parametrize("cav", ["gumbel", "reynolds"])
def test_fd_is_positively_homogeneous(cav):
    for xi, xd, xo in ((0.6, 12.0, -150.0), (0.9, -5.0, 80.0)):
        L = 2 * R * 1.0
        f1 = np.array(fd_force(xi, xd, xo, MU, R, L, C, cav, 72, 8))
        for s in (0.01, 7.0):
            fs = np.array(fd_force(xi, s * xd, s * xo, MU, R, L, C, cav, 72, 8))
            # the active set is scale-invariant: only LU rounding differs (measured 1e-15)
            assert rel(fs, s * f1) < 1e-11


LIMIT_STATES = [(0.5, 0.0), (0.5, 0.6), (0.5, -0.6), (0.5, math.pi / 2), (0.8, 2.5)]  # (ξ, ψ)


def test_limits_short_and_long_reported():
    """Measured relative differences |F_fd − F_model|/|F_model| at L/D = 0.25, 1, 2, 8 (printed).

    Short limit: F_fd(Gümbel) → short π-film as L/D → 0 (the short π-film *is* the Gümbel film of
    the short equation), error O((L/D)²). Long limit: for the wedge state ψ = 0 the Gümbel film
    → the long π-film (= half-Sommerfeld) with end leakage O(D/L); for squeeze states the two
    models differ even at L/D → ∞ (Gümbel clips the full film whose level is fixed by the
    ambient ends; the π-film re-levels it to vanish at θ₁, θ₁+π, spec §2.3), so only ψ = 0 is
    asserted there."""
    print("\nL/D   state(ξ,ψ)     gumbel-vs-short  gumbel-vs-long  reynolds-vs-short  reynolds-vs-long")
    table = {}
    for LD in (0.25, 1.0, 2.0, 8.0):
        L = 2 * R * LD
        for xi, psi in LIMIT_STATES:
            s = state(xi, psi)
            sh, lo = np.array(short_force(*s, MU, R, L, C, TAB)), long_pi_film(*s, L)
            g = fd_force(*s, MU, R, L, C, "gumbel")
            r = fd_force(*s, MU, R, L, C, "reynolds")
            table[LD, xi, psi] = (rel(g, sh), rel(g, lo), rel(r, sh), rel(r, lo))
            print(f"{LD:4}  ({xi}, {psi:+.2f})  " + "  ".join(f"{v:15.3f}" for v in table[LD, xi, psi]))
    # short limit at L/D = 0.25: measured 6.1–7.8 % (ξ = 0.5) and 17 % (ξ = 0.8, ψ = 2.5)
    assert all(table[0.25, 0.5, p][0] < 0.09 for _, p in LIMIT_STATES[:4])
    for LD_small in (0.05,):  # O((L/D)²): measured 0.45 % at L/D = 0.05
        L = 2 * R * LD_small
        for cav in ("gumbel", "reynolds"):
            s = state(0.5, 0.6)
            assert rel(fd_force(*s, MU, R, L, C, cav), short_force(*s, MU, R, L, C, TAB)) < 0.01
    # long limit, wedge: measured 42 % (L/D 2), 10.8 % (8), 2.7 % (32): ∝ D/L end leakage
    L32 = 2 * R * 32.0
    d32 = rel(fd_force(*state(0.5, 0.0), MU, R, L32, C, "gumbel", 144, 32), long_pi_film(*state(0.5, 0.0), L32))
    print(f"wedge ψ = 0, ξ = 0.5, L/D = 32: gumbel vs long π-film {d32:.3f}")
    assert table[8.0, 0.5, 0.0][1] < 0.13 and d32 < 0.035 and d32 < table[8.0, 0.5, 0.0][1] / 3


# ----------------------------------------------------------------------------- table
@pytest.fixture(scope="module")
def gumbel_table(tmp_path_factory):
    import os

    os.environ["JOINTDYN_CACHE"] = str(tmp_path_factory.mktemp("cache"))
    tab = build_finite_table(1.0, "gumbel")
    return tab, build_finite_table.last_build_seconds


def check_table(tab, LD, cav, n, seed):
    rng = np.random.default_rng(seed)
    L = 2 * R * LD
    errs = []
    for _ in range(n):
        xi = -math.expm1(-rng.uniform(0, -math.log1p(-0.98)))
        s = state(xi, rng.uniform(-math.pi, math.pi), rho=rng.uniform(0.1, 100))
        errs.append(rel(finite_force(*s, MU, R, L, C, tab), fd_force(*s, MU, R, L, C, cav)))
    return max(errs), float(np.median(errs))


def test_table_layout_cache_and_homogeneity(gumbel_table):
    tab, secs = gumbel_table
    xi, psi, meta = table_grid(tab)
    assert tab.shape == (1 + 48, 128, 2) and meta["L_over_D"] == 1.0 and meta["cavitation"] == "gumbel"
    assert xi[0] == 0 and abs(xi[-1] - 0.98) < 1e-14 and np.all(np.diff(np.diff(-np.log1p(-xi))) < 1e-12)
    print(f"\ngumbel table 48×128 at L/D = 1 built in {secs:.2f} s")
    again = build_finite_table(1.0, "gumbel")  # from the disk cache
    np.testing.assert_array_equal(again, tab)
    for s in (state(0.3, 1.0), state(0.97, -2.0)):
        f1 = np.array(finite_force(*s, MU, R, 0.02, C, tab))
        f5 = np.array(finite_force(s[0], 5 * s[1], 5 * s[2], MU, R, 0.02, C, tab))
        assert rel(f5, 5 * f1) < 1e-14  # the kernel scales by ρ exactly
        flat = np.array(finite_force(*s, MU, R, 0.02, C, tab.reshape(-1, 2)))  # simulator form
        np.testing.assert_array_equal(flat, f1)
    assert finite_force(0.5, 0.0, 0.0, MU, R, 0.02, C, tab) == (0.0, 0.0)
    assert all(math.isnan(v) for v in finite_force(0.5, 1.0, 1.0, MU, R, 0.02, C, np.zeros((3, 2))))


def test_table_accuracy_gumbel(gumbel_table):
    worst, med = check_table(gumbel_table[0], 1.0, "gumbel", 40, 3)
    print(f"\ngumbel table (L/D = 1) vs direct solves, 40 random states: max {worst:.2e}, median {med:.1e}")
    # bicubic Catmull–Rom (O(h³)) on 48×128: measured max 1.1e-3 (L/D 1), 2.6e-3 (L/D 0.25);
    # the largest errors sit where the force is small against the (1−ξ²)^{-3/2} scale
    assert worst < 5e-3


def test_table_periodic_in_psi(gumbel_table):
    tab = gumbel_table[0]
    for xi in (0.2, 0.9):
        a = np.array(finite_force(*state(xi, math.pi - 1e-10), MU, R, 0.02, C, tab))
        b = np.array(finite_force(*state(xi, -math.pi + 1e-10), MU, R, 0.02, C, tab))
        assert rel(a, b) < 1e-8  # C¹ interpolant: the jump is O(Δψ·f′) = O(1e-10)
        d = fd_force(*state(xi, math.pi), MU, R, 0.02, C, "gumbel")
        assert rel(a, d) < 5e-3  # and it is correct there (table accuracy above)


def test_table_reynolds_small():
    """A coarse Reynolds table (fast): plumbing and accuracy trend; the default one is slow."""
    tab = build_finite_table(0.5, "reynolds", n_xi=12, n_psi=32, mesh=(72, 8), cache=False, workers=1)
    rng = np.random.default_rng(5)
    errs = []
    for _ in range(10):
        xi = -math.expm1(-rng.uniform(0, -math.log1p(-0.98)))
        s = state(xi, rng.uniform(-math.pi, math.pi))
        errs.append(rel(finite_force(*s, MU, R, 0.01, C, tab), fd_force(*s, MU, R, 0.01, C, "reynolds", 72, 8)))
    # 12×32 table: Catmull–Rom error with Δu = 0.36, Δψ = 0.2; measured 2.1e-2
    assert max(errs) < 0.05


@pytest.mark.slow
def test_table_accuracy_reynolds_default(tmp_path, monkeypatch):
    monkeypatch.setenv("JOINTDYN_CACHE", str(tmp_path))
    tab = build_finite_table(2.0, "reynolds")
    worst, med = check_table(tab, 2.0, "reynolds", 30, 4)
    print(f"\nreynolds table 32×96 (L/D = 2): build {build_finite_table.last_build_seconds:.1f} s, "
          f"max {worst:.2e}, median {med:.1e}")
    assert worst < 5e-3  # measured 1.0e-3 (40 states, unit ρ)
