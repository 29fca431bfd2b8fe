"""Compiled Radau IIA (order 5) [T113]: order of one step, dense output, the film slider-crank
against a tight reference, slicing invariance."""

import math

import numpy as np
import pytest
from test_integrators import exact, oscillator

from jointdyn import post
from jointdyn.integrators.common import fd_jacobian
from jointdyn.integrators.driver import new_work, start
from jointdyn.integrators.radau5 import RADAU5, attempt_radau5, dense
from jointdyn.models import slider_crank as sc
from jointdyn.models.slider_crank import slider_crank_config
from jointdyn.simulation.simulate import simulate

K_, D_, MASS, X0 = 1e4, 5.0, 0.2, 1e-3  # ω = 223.6 rad/s, ζ = 0.056


def one_step(h):
    """x(h) − exact after one radau5 step from rest at x0, and the midpoint of the dense output."""
    system = oscillator(K_, D_, MASS, X0)
    P = system.packed(0.0)
    t_out = np.array([0.0, 0.5 * h, h])
    w = new_work(RADAU5, system.y0, system.mem0, 0.0, t_out, h)
    assert start(RADAU5, P, True, w) == 0
    fd_jacobian(0.0, w.y, w.f0, w.mem, P, w.Jm, w.ft, w.work, w.fw)
    res, en = attempt_radau5(0.0, h, P, w, 1e-13, 1e-18)  # Newton converged to round-off
    assert res == 0
    # collocation polynomial, outputs at h/2 and h
    assert dense(0.0, h, w.y, w.f0, w.y1, w.K, w.mem, w.ctl, w.ictl, t_out, 1, w.Y, w.MEM) == 3
    x1 = w.y1[0] - 0.1
    xm = w.Y[1, 0] - 0.1
    ex = exact(np.array([0.5 * h, h]), K_, D_, MASS, X0)
    return abs(x1 - ex[1]), abs(xm - ex[0])


def test_local_order():
    """Radau IIA with 3 stages has order 5 at the step points (local error ∝ h⁶) and stage
    order 3 inside (collocation polynomial: local error ∝ h⁴); Hairer & Wanner II, §IV.5."""
    hs = [2e-3, 1e-3, 5e-4, 2.5e-4]
    errs = [one_step(h) for h in hs]
    p_end = [math.log2(a[0] / b[0]) for a, b in zip(errs, errs[1:])]
    p_mid = [math.log2(a[1] / b[1]) for a, b in zip(errs, errs[1:])]
    print(p_end, p_mid)
    # asymptotic slopes 6 and 4, approached from below as ωh = 0.45 → 0.06 (measured 5.67, 5.89,
    # 5.96 at the step end): the last slope within 0.1, every slope within 0.4
    assert abs(p_end[-1] - 6.0) < 0.1 and all(abs(p - 6.0) < 0.4 for p in p_end), p_end
    assert abs(p_mid[-1] - 4.0) < 0.1 and all(abs(p - 4.0) < 0.4 for p in p_mid), p_mid


def test_film_slider_crank_against_tight_reference():
    """π-film pin, c = 0.5 mm, 0.25 rev: radau5 at the default rtol 1e-8 against rodas4 at
    rtol 1e-11 (the paper's case)."""
    system = sc.slider_crank("alshaer2005").compile()
    ref = simulate(system, slider_crank_config("alshaer2005", 0.25, solver="rodas4", rtol=1e-11, atol=1e-14))
    res = simulate(system, slider_crank_config("alshaer2005", 0.25, solver="radau5"))
    M, Mr = post.driving_moment(res), post.driving_moment(ref)
    err = np.abs(M - Mr).max() / np.abs(Mr).max()
    print(f"radau5 rtol 1e-8: max|ΔM|/peak = {err:.3g}, {res.stats}")
    # measured 8.4e-7 with 1,605 RHS evaluations (exact Jacobian, rtol unmapped [T114]; with
    # RADAU5's mapping 2.7e-5); 2× margin
    assert err < 2e-6
    st = res.stats  # radau5's own counters: 3 stage RHS per Newton iteration, ≥ 1 per attempt
    assert st["newton_iterations"] >= st["accepted_steps"] + st["rejected_steps"] - st["newton_failures"]
    assert 3 * st["newton_iterations"] <= st["rhs_evaluations"]
    assert 1 <= st["lu_pairs"] <= st["accepted_steps"] + st["rejected_steps"]


@pytest.mark.parametrize("joint", ["alshaer2005", "dry"])
def test_radau5_slices_equal_one_call(joint):
    system = sc.slider_crank(joint).compile()
    cfg = slider_crank_config(joint, 0.1, solver="radau5")
    one = simulate(system, cfg, step_budget=10**12)
    many = simulate(system, cfg, step_budget=5)
    assert np.array_equal(one.y, many.y) and np.array_equal(one.mem, many.mem) and one.stats == many.stats


@pytest.mark.parametrize("sigma", [3.7e4, complex(2.9e4, 1.6e4), 0.8])
def test_reduced_solve_equals_the_full_system(sigma):
    """The iteration matrices are factorised in the reduced form σI − B − A/σ of a second-order
    system [T181]; the solution of (σI − J) z = r must equal numpy's dense solve of the full
    nn×nn system, J = [[0, I], [A, B]] with random A, B of a film's magnitudes (σ as γ̂/h and
    (α + iβ)/h at h ≈ 1e-4 s, and a small σ where A/σ dominates)."""
    from jointdyn.integrators.radau5 import _solve
    from jointdyn.integrators.rodas4 import lu_factor

    rng = np.random.default_rng(7)
    n = 9
    J = np.zeros((2 * n, 2 * n))
    J[:n, n:] = np.eye(n)
    J[n:, :n] = rng.normal(scale=1e8, size=(n, n))  # ∂q̈/∂q: film stiffness/mass [1/s²]
    J[n:, n:] = rng.normal(scale=1e4, size=(n, n))  # ∂q̈/∂q̇: film damping/mass [1/s]
    dt = np.complex128 if isinstance(sigma, complex) else np.float64
    W = (sigma * np.eye(n) - J[n:, n:] - J[n:, :n] / sigma).astype(dt)
    piv = np.zeros(n, dtype=np.int64)
    assert lu_factor(W, piv)
    r = (rng.normal(size=2 * n) + (1j * rng.normal(size=2 * n) if dt is np.complex128 else 0)).astype(dt)
    z = r.copy()
    _solve(J, W, piv, sigma, z)
    ref = np.linalg.solve(sigma * np.eye(2 * n) - J, r)
    # forward error of a backward-stable solve ≤ cond · u: cond(σI − J) ≤ 4.9e8 for these three
    # matrices (numpy.linalg.cond), u = 1.1e-16, so each solve is within 5.4e-8 and the two agree to
    # 1.1e-7 (measured: ≤ 2.2e-15)
    cond = np.linalg.cond(sigma * np.eye(2 * n) - J)
    assert np.linalg.norm(z - ref) <= 2.0 * cond * 1.12e-16 * np.linalg.norm(ref)
