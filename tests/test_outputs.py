"""Output samples ([T112], [T190–T192]): the fused per-sample kernel against the separate
reference path (projection, then accelerations), and the equations of motion at the samples."""

import math

import numpy as np
import pytest

from jointdyn.core.constraints import eval_constraints
from jointdyn.forces.elements import NOUT
from jointdyn.integrators import SOLVERS
from jointdyn.integrators.driver import run
from jointdyn.models.slider_crank import SPEED, slider_crank
from jointdyn.multibody.dynamics import (
    accelerations,
    constraint_residuals,
    outputs,
    project,
    project_positions,
    project_velocities,
)

T1 = 2 * math.pi / SPEED  # one crank revolution [s]


def raw_samples(system, solver, n_out=121, rtol=1e-8):
    """Output states of a compiled solver before post-processing (interpolated, off Φ = 0)."""
    P = system.packed(0.0)
    ts = np.linspace(0.0, T1 / 4, n_out)
    Y, MEM, nw, _, status, *_ = run(
        SOLVERS[solver][0],
        P,
        system.y0,
        system.mem0,
        0.0,
        ts,
        rtol,
        rtol * 1e-2,
        0.0,
        np.inf,
        10**8,
        True,
        True,
    )
    assert status == 0 and nw == n_out
    return P, ts, Y, MEM


def reference(ts, Y, MEM, P, do_project):
    """The separate path: the integrator's projection [T11], then the drift report and the
    accelerations of the right-hand side [T10], sample by sample."""
    n = Y.shape[1] // 2
    m, nf = P.n_rows, P.fint.shape[0]
    Y = Y.copy()
    qdd, lam = np.zeros((len(ts), n)), np.zeros((len(ts), max(m, 1)))
    eout, drift = np.zeros((len(ts), nf, NOUT)), np.zeros((len(ts), 2))
    for i, t in enumerate(ts):
        if do_project:
            project(t, Y[i], P, 1e-12)
        drift[i] = constraint_residuals(t, Y[i], P)
        accelerations(t, Y[i, :n], Y[i, n:], MEM[i], P, qdd[i], lam[i], eout[i])
    return Y, qdd, lam[:, :m], eout, drift


@pytest.mark.parametrize(
    ("joint", "solver"), [("perfect", "dopri5"), ("dry", "dopri5"), ("alshaer2005", "radau5")]
)
def test_fused_samples_equal_the_separate_path(joint, solver):
    """One factorisation per sample [T190] changes no bit: both paths do the same arithmetic on
    the same Φ_q (a function of q only), so the comparison is exact equality."""
    system = slider_crank(joint).compile()
    P, ts, Y, MEM = raw_samples(system, solver)
    Yr, qdd_r, lam_r, eout_r, drift_r = reference(ts, Y, MEM, P, True)
    Yf = Y.copy()
    qdd, lam, eout, drift = outputs(ts, Yf, MEM, P, True)
    np.testing.assert_array_equal(Yf, Yr)
    np.testing.assert_array_equal(qdd, qdd_r)
    np.testing.assert_array_equal(lam, lam_r)
    np.testing.assert_array_equal(eout, eout_r)
    np.testing.assert_array_equal(drift, drift_r)


def test_unprojected_samples_with_baumgarte_equal_the_rhs():
    """Without projection (the scipy solvers, Baumgarte a = 1000 1/s) a sample costs one
    right-hand side and gives exactly its q̈, λ."""
    system = slider_crank("perfect").compile()
    _, ts, Y, MEM = raw_samples(system, "dopri5")
    Y = Y + 1e-9 * np.sin(np.arange(Y.size)).reshape(Y.shape)  # off the manifold: γ̂ ≠ γ
    P = system.packed(1000.0)
    Yr, qdd_r, lam_r, eout_r, drift_r = reference(ts, Y, MEM, P, False)
    Yf = Y.copy()
    qdd, lam, eout, drift = outputs(ts, Yf, MEM, P, False)
    np.testing.assert_array_equal(Yf, Y)  # not moved
    np.testing.assert_array_equal(qdd, qdd_r)
    np.testing.assert_array_equal(lam, lam_r)
    np.testing.assert_array_equal(drift, drift_r)


def test_samples_satisfy_the_equations_of_motion():
    """At every projected sample: Φ = 0 to the projection tolerance 1e-12 [T11], Φ_q q̇ + Φ_t = 0,
    Φ_q q̈ = γ and M q̈ = Q + Φ_qᵀλ (Q = gravity here), checked with an independent evaluation
    of the constraints (the identities hold to round-off: relative 1e-12 of their terms)."""
    system = slider_crank("perfect").compile()
    P, ts, Y, MEM = raw_samples(system, "dopri5", rtol=1e-5)  # loose: samples need ≥ 2 iterations
    qdd, lam, _, drift = outputs(ts, Y, MEM, P, True)
    n, m = system.n, system.n_rows
    Phi, J, Phit, gam = np.empty(m), np.empty((m, n)), np.empty(m), np.empty(m)
    M = 1.0 / system.minv
    for i, t in enumerate(ts):
        q, qd = Y[i, :n], Y[i, n:]
        eval_constraints(t, q, qd, system.cint, system.creal, Phi, J, Phit, gam)
        assert np.abs(Phi).max() <= 1e-12 and drift[i, 0] <= 1e-12
        assert np.abs(J @ qd + Phit).max() <= 1e-12 * np.abs(J).max() * np.abs(qd).max()
        scale = np.abs(J).max() * np.abs(qdd[i]).max()
        assert np.abs(J @ qdd[i] - gam).max() <= 1e-12 * scale
        force = system.q0_force + J.T @ lam[i]
        assert np.abs(M * qdd[i] - force).max() <= 1e-12 * np.abs(J.T).max() * np.abs(lam[i]).max()


def test_samples_on_the_manifold_are_not_moved():
    """A second pass over projected samples does no position iteration (max |Φ| ≤ 1e-12 is
    checked first [T112]): q is returned bit for bit, and q̈, λ agree to round-off (q̇ is
    projected again, a change of ≈ 1e-16 relative)."""
    system = slider_crank("perfect").compile()
    P, ts, Y, MEM = raw_samples(system, "dopri5")
    qdd1, lam1, _, _ = outputs(ts, Y, MEM, P, True)
    Y2 = Y.copy()
    qdd2, lam2, _, _ = outputs(ts, Y2, MEM, P, True)
    n = system.n
    np.testing.assert_array_equal(Y2[:, :n], Y[:, :n])
    # round-off of a re-projected q̇ through the multipliers: 1e-10 of the peak, far above the
    # 1e-16 relative change of q̇ and far below the 1e-6·peak accuracy goal of the moment
    assert np.abs(lam2 - lam1).max() <= 1e-10 * np.abs(lam1).max()
    assert np.abs(qdd2 - qdd1).max() <= 1e-10 * np.abs(qdd1).max()


def test_project_equals_positions_then_velocities():
    """The fused integrator projection [T191] against the two functions model assembly uses,
    from states 1e-4 off the manifold (several Gauss–Newton corrections): exact equality."""
    system = slider_crank("perfect").compile()
    P = system.packed(0.0)
    n = system.n
    rng = np.random.default_rng(7)
    for k in range(20):
        y = system.y0 + 1e-4 * rng.standard_normal(2 * n)
        t = 1e-4 * k
        a = y.copy()
        res_a = project(t, a, P, 1e-12)
        b = y.copy()
        res_b = project_positions(t, b[:n], b[n:], P.minv, P.cint, P.creal, P.n_rows, 1e-12, np.int64(6))
        assert project_velocities(t, b[:n], b[n:], P.minv, P.cint, P.creal, P.n_rows)
        np.testing.assert_array_equal(a, b)
        assert res_a == res_b and res_a <= 1e-12
