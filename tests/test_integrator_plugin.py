"""A compiled integrator added from outside the package [T230]: a Heun stepper (explicit
trapezoid, order 2, with the embedded Euler step as its error estimate) is defined in this file,
registered in ``SOLVERS`` with one line, and runs the solvers' pendulum contract of
``test_registry_contracts`` and a convergence test against the pendulum's closed form. Every
test undoes the registration (``heun`` fixture)."""

import math

import numpy as np
import pytest
import test_registry_contracts as contracts
from numba import njit
from scipy.special import ellipj

from jointdyn.core.constraints import Revolute
from jointdyn.integrators import SOLVERS
from jointdyn.integrators.common import error_norm
from jointdyn.integrators.driver import ATTEMPT_BAD, ATTEMPT_OK, Stepper, loop
from jointdyn.multibody.dynamics import rhs
from jointdyn.multibody.model import Model
from jointdyn.simulation.simulate import SimConfig, simulate


@njit(cache=True)
def attempt_heun(t, h, P, w, rtol, atol):
    """k₁ = f(t, y) (w.f0), k₂ = f(t + h, y + h k₁); y₁ = y + h(k₁ + k₂)/2; the error estimate is
    y₁ minus the Euler step y + h k₁ = h(k₂ − k₁)/2 (order 1)."""
    y, y1, yt, err, k1, k2 = w.y, w.y1, w.yt, w.err, w.f0, w.K[1]
    for i in range(y.shape[0]):
        yt[i] = y[i] + h * k1[i]
    bad = rhs(t + h, yt, w.mem, P, k2)
    w.stats[0] += 1
    if bad != 0:
        return ATTEMPT_BAD, np.inf
    for i in range(y.shape[0]):
        y1[i] = y[i] + 0.5 * h * (k1[i] + k2[i])
        err[i] = 0.5 * h * (k2[i] - k1[i])
    return ATTEMPT_OK, error_norm(err, y, y1, rtol, atol)


@njit(cache=True)
def heun_rejected(res, h, en, ctl, ictl, stats, reuse):
    """After a failed error test: h·max(0.2, 0.9‖err‖^(−1/2)) (the estimate is of order 1)."""
    if res == ATTEMPT_OK:
        h *= max(0.2, 0.9 * en**-0.5)
    return h


@njit(cache=True)
def heun_accepted(h, h_prop, hmax, en, ctl, ictl, stats, reuse):
    """The elementary controller, from the step proposed before landing on an output time."""
    return max(h, h_prop) * min(4.0, max(0.2, 0.9 * max(en, 1e-10) ** -0.5))


# no dense output (dense=None): every step lands on the next output time
HEUN = Stepper("heun", 2, attempt_heun, heun_rejected, heun_accepted)


@pytest.fixture
def heun():
    SOLVERS["heun"] = (HEUN, True, "compiled Heun 2(1), explicit trapezoid (a test's plugin)")
    try:
        yield HEUN
    finally:
        del SOLVERS["heun"]
    assert "heun" not in SOLVERS


def test_heun_runs_the_solvers_pendulum_contract(heun):
    """The contract every registered solver passes: energy conserved to the tolerance, the
    constraint kept (projection after every step)."""
    contracts.test_solver_integrates_a_pendulum("heun")


# the contract's pendulum: a bar of 2 kg, J = 0.02 kg·m² about its centre, pinned 0.25 m from it,
# released at rest horizontally (φ = 0; hanging: φ = −π/2)
MASS, J_CM, ARM, G = 2.0, 0.02, 0.25, 9.81


def pendulum():
    m = Model("pendulum")
    m.add_body("bar", MASS, J_CM, position=(ARM, 0.0), points={"pin": (-ARM, 0.0)})
    m.add_ground_point("O", (0.0, 0.0))
    m.add("pin", Revolute("ground", "O", "bar", "pin"))
    return m.compile()


def phi_exact(t):
    """Closed form of the large-amplitude pendulum: θ = φ + π/2 from the hanging position,
    θ(0) = θ₀ = π/2 at rest ⇒ sin(θ/2) = k·cd(ω₀t | k²), k = sin(θ₀/2), ω₀² = m g a/(J + m a²)."""
    k = math.sin(math.pi / 4)
    w0 = math.sqrt(MASS * G * ARM / (J_CM + MASS * ARM**2))
    sn, cn, dn, _ = ellipj(w0 * t, k * k)
    cd = cn / dn
    return 2.0 * np.arcsin(k * cd) - math.pi / 2


def test_heun_converges_at_its_order(heun):
    """Fixed steps h (max_step = h with a loose error test that never rejects, outputs on the
    step grid): the error of φ at t = 0.6 s against the closed form falls as h², and the stepper's
    loop is compiled under its own name. Slicing the run changes nothing (the resumable loop)."""
    system = pendulum()
    assert abs(phi_exact(0.0)) < 1e-15  # the closed form starts where the model does
    t_end, errors = 0.6, []
    for h in (4e-3, 2e-3, 1e-3, 5e-4):
        cfg = SimConfig(t_end=t_end, n_out=7, solver="heun", rtol=0.5, atol=0.5, max_step=h)
        res = simulate(system, cfg)
        assert res.stats["rejected_steps"] == 0
        assert res.stats["accepted_steps"] >= round(t_end / h)
        errors.append(np.abs(res.coordinate("bar", "phi") - phi_exact(res.t)).max())
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    # order 2 ⇒ 2 as h → 0: measured orders are printed on failure; ±0.1 is the asymptotic regime
    assert np.all(np.abs(orders - 2.0) < 0.1), (errors, orders)
    assert errors[-1] < 1e-5  # and the errors are those of the method, far above round-off
    assert loop(HEUN, 0).py_func.__qualname__.startswith("drive_heun_")
    cfg = SimConfig(t_end=0.3, n_out=31, solver="heun", rtol=1e-6, atol=1e-8)
    one, many = simulate(system, cfg), simulate(system, cfg, step_budget=7)
    assert np.array_equal(one.y, many.y) and one.stats == many.stats
    assert set(one.stats) == {"rhs_evaluations", "accepted_steps", "rejected_steps", "jacobians"}
