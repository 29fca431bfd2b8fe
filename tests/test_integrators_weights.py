"""Error scales from the clearance [T186]: SimConfig.error_scale = "clearance"."""

import math
import warnings

import numpy as np
import pytest
from test_integrators import oscillator

from jointdyn import post
from jointdyn.integrators.accuracy import force_resolution
from jointdyn.integrators.common import error_norm, error_norm_scaled
from jointdyn.integrators.weights import AUTO_CLEARANCE_RATIO, clearance_scale
from jointdyn.models.slider_crank import CRANK_LENGTH, ROD_LENGTH, SPEED, slider_crank
from jointdyn.simulation.simulate import SimConfig, simulate


def _system(**kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return slider_crank(joint="alshaer2005", **kw).compile()


def test_clearance_scale_of_the_benchmark_slider_crank():
    """Y = c for translations, c/ℓ for rotations (ℓ = the rod's half length, its largest lever
    arm, as the rod's points sit at ±l/2 from its centre), times ω_ref = the crank speed (the
    fastest body of y0) for the velocities: the model's own numbers, exact up to rounding."""
    s = _system(clearance=2e-4)
    Y = clearance_scale(s, 1.0)
    ell = max(ROD_LENGTH / 2, CRANK_LENGTH / 2)
    pos = np.tile([2e-4, 2e-4, 2e-4 / ell], 3)
    np.testing.assert_allclose(Y, np.concatenate([pos, pos * SPEED]), rtol=1e-12)
    # a slow system (crank at 0.1 rad/s): ω_ref is 2π over the simulated span (1 s)
    slow = _system(clearance=2e-4, speed=0.1)
    assert clearance_scale(slow, 1.0)[9] == pytest.approx(2e-4 * 2 * math.pi, rel=1e-12)


def test_zero_scales_are_the_state_norm_bit_for_bit():
    rng = np.random.default_rng(1)
    err, y0, y1 = rng.normal(size=(3, 18))
    assert error_norm_scaled(err, y0, y1, 1e-6, 1e-9, np.zeros(18)) == error_norm(err, y0, y1, 1e-6, 1e-9)
    ysc = np.abs(rng.normal(size=18)) + 0.1
    expect = np.sqrt(np.mean((err / (1e-9 + 1e-6 * ysc)) ** 2))
    assert error_norm_scaled(err, y0, y1, 1e-6, 1e-9, ysc) == pytest.approx(expect, rel=1e-14)


def test_force_resolution_uses_the_fixed_scales():
    """The spring–damper closed form of test_integrators_accuracy with s_j = atol + rtol·Y_j."""
    k, d = 1e4, 5.0
    system = oscillator(k, d)
    P = system.packed(0.0)
    y = system.y0.copy()
    y[3] = 0.7
    rtol, atol = 1e-6, 1e-9
    ysc = np.full(y.shape[0], 2.0)
    dF = np.zeros(1)
    force_resolution(0.0, y, system.mem0, P, rtol, atol, dF, ysc)
    x = y[0]
    tension = k * (x - 0.1) + d * y[3]
    s = atol + rtol * 2.0
    # second-order terms ≈ k·s²/L ≈ 1e4·(2e-6)²/0.1 = 4e-7 N against 0.2 N
    assert dF[0] == pytest.approx(k * s + d * s + tension * s / x, rel=1e-5)


def test_auto_is_clearance_at_300_rtol_for_the_auto_solver_only():
    """error_scale="auto" (the default) = clearance scales at 300·rtol when solver="auto" picks
    radau5 [T188]: the same run step for step; an explicit solver keeps the state scales."""
    s = _system()
    t_end = 0.25 * 2 * math.pi / SPEED
    auto = simulate(s, SimConfig(t_end=t_end, n_out=181))
    clr = simulate(s, SimConfig(t_end=t_end, n_out=181, solver="radau5", rtol=3e-6, error_scale="clearance"))
    assert AUTO_CLEARANCE_RATIO * 1e-8 == pytest.approx(3e-6, rel=1e-15)
    assert auto.stats == clr.stats and np.array_equal(auto.y, clr.y)
    explicit = simulate(s, SimConfig(t_end=t_end, n_out=181, solver="radau5"))
    state = simulate(s, SimConfig(t_end=t_end, n_out=181, solver="radau5", error_scale="state"))
    assert explicit.stats == state.stats and np.array_equal(explicit.y, state.y)
    assert explicit.stats != auto.stats


def test_bad_error_scale_requests():
    with pytest.raises(ValueError, match="error_scale"):
        SimConfig(t_end=1.0, error_scale="origin")
    s = _system()
    with pytest.raises(ValueError, match="rodas4, ros34pw2 or radau5"):
        simulate(s, SimConfig(t_end=1e-3, solver="dopri5", error_scale="clearance"))
    perfect = slider_crank(joint="perfect").compile()
    with pytest.raises(ValueError, match="no journal element"):
        simulate(perfect, SimConfig(t_end=1e-3, solver="radau5", error_scale="clearance"))


@pytest.mark.parametrize("solver", ["radau5", "ros34pw2"])
def test_one_rtol_gives_similar_accuracy_at_both_clearances(solver):
    """The point of [T186]: with state scales the crank-moment error at c = 0.05 mm is many times
    that at c = 0.5 mm for the same rtol; with clearance scales the two are close. Measured over
    one revolution against radau5 at rtol 1e-11 (ratio error(0.05 mm)/error(0.5 mm)): radau5 state
    rtol 1e-8 1.43e-6 vs 4.04e-5, 28.3; clearance rtol 3e-6 1.08e-5 vs 2.45e-5, 2.26 (the same
    over 2 and 4 revolutions); ros34pw2 state 1.68e-6 vs 3.15e-5, 18.8; clearance 3.51e-5 vs
    2.29e-5, 0.65. The bound 5 lies ≥ 2.2× above every clearance ratio and ≥ 3.7× below every
    state ratio."""
    revs = 1.0
    t_end = revs * 2 * math.pi / SPEED
    n = int(revs * 720) + 1
    ratios = {}
    for scale, rtol in (("clearance", 3e-6), ("state", 1e-8)):
        errs = []
        for c in (5e-4, 5e-5):
            s = _system(clearance=c)
            ref = post.driving_moment(
                simulate(s, SimConfig(t_end=t_end, n_out=n, solver="radau5", rtol=1e-11, atol=1e-14))
            )
            cfg = SimConfig(t_end=t_end, n_out=n, solver=solver, rtol=rtol, atol=1e-10, error_scale=scale)
            M = post.driving_moment(simulate(s, cfg))
            errs.append(np.abs(M - ref).max() / np.abs(ref).max())
        ratios[scale] = errs[1] / errs[0]
        assert max(errs) < 1e-4  # the accuracy aim of the defaults [T116]
    assert ratios["clearance"] < 5.0 < ratios["state"], ratios


def test_results_record_the_error_scale_that_was_used():
    """The resolved error test is recorded like the resolved solver: the default lubricated run
    (auto → radau5) says clearance scales at AUTO_CLEARANCE_RATIO × rtol, the same run with the
    solver named says state scales at rtol — two runs that differ are told apart [T188]."""
    system = slider_crank("alshaer2005").compile()
    auto = simulate(system, SimConfig(t_end=2e-3, n_out=5))
    named = simulate(system, SimConfig(t_end=2e-3, n_out=5, solver="radau5"))
    assert auto.config["solver"] == named.config["solver"] == "radau5"
    assert (auto.config["error_scale"], auto.config["error_rtol"]) == (
        "clearance",
        AUTO_CLEARANCE_RATIO * 1e-8,
    )
    assert (named.config["error_scale"], named.config["error_rtol"]) == ("state", 1e-8)
    assert not np.array_equal(auto.y, named.y)  # they did run differently
