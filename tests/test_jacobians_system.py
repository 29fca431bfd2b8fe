"""Exact system Jacobian ∂f/∂y, ∂f/∂t [T101–T104] vs step-size-robust central differences of
``dynamics.rhs`` on the slider-crank with every joint kind and on the lubricated four-bar, at
states along simulated trajectories (and with perturbed velocities)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from fd_reference import central

from jointdyn.forces.element_jacobians import force_jacobian
from jointdyn.io.modelfile import load_model
from jointdyn.models.slider_crank import JOINTS, slider_crank
from jointdyn.multibody.dynamics import rhs
from jointdyn.multibody.jacobian import system_jacobian
from jointdyn.simulation.simulate import SimConfig, simulate

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
# goal of the issue: 1e-6. Measured (this file's states): slider-crank ≤ 3.1e-8 for every joint
# kind, Baumgarte 1.6e-9, four-bar 1.3e-7, engine 4.8e-8; the reference's rounding noise,
# measured on the driven rows whose exact Jacobian is 0, is ≤ 5.7e-7 of a column
TOL = 1e-6


def fd_jacobian(t, y, mem, P, vel_step=0.1):
    nn = y.shape[0]
    n = nn // 2
    out = np.empty(nn)

    def f_of(j):
        def f(v):
            yy = y.copy()
            yy[j] = v
            rhs(t, yy, mem, P, out)
            return out.copy()

        return f

    Jf = np.empty((nn, nn))
    for j in range(nn):
        # largest steps [m], [rad], [m/s or rad/s]; 12 steps down to 4^-11 of these are searched
        h = (1e-6 if j % 3 != 2 else 1e-4) if j < n else vel_step * max(1.0, abs(y[j]))
        Jf[:, j] = central(f_of(j), y[j], h, n=12)

    def g(tt):
        rhs(tt, y, mem, P, out)
        return out.copy()

    ft = central(g, t, 1e-5, n=9)
    return Jf, ft


def states(system, n_states, rng, t_end, solver="auto"):
    """States along a trajectory (every other one with perturbed velocities). The method does not
    matter to the comparison; ``auto`` (and the model files' own rodas4) run kernel sets the rest
    of the suite compiles anyway [T373]."""
    res = simulate(system, SimConfig(t_end=t_end, n_out=n_states + 1, solver=solver, rtol=1e-7))
    ys = np.asarray(res.y)[1:]
    mems = np.asarray(res.mem)[1:]
    out = []
    for k, (y, mem) in enumerate(zip(ys, mems, strict=True)):
        y = y.copy()
        if k % 2:  # off the trajectory: perturbed velocities
            n = y.shape[0] // 2
            y[n:] *= 1.0 + 0.2 * rng.standard_normal(n)
        out.append((float(res.t[k + 1]), y, mem))
    return out


def driven_rows(system):
    """Rows of q̈ fixed by an angle driver against the ground (φ̈ = α exactly, [T7])."""
    from jointdyn.core.constraints import AngleDriver

    n = system.n
    return [
        n + 3 * system.body_index(c.body_j) + 2
        for c in system.constraints
        if isinstance(c, AngleDriver) and c.body_i == "ground"
    ]


def column_error(Ja, Jf, skip=()):
    """max over columns of |ΔJ|∞/|J|∞ on the q̈ rows; a column is measured against at least 1e-9
    of the largest column of its block (∂/∂q or ∂/∂q̇): columns that vanish exactly (e.g. a
    body's x for a perfect mechanism) come out as rounding of the Schur solve, ~1e-14 of it."""
    n = Ja.shape[0] // 2
    keep = [i for i in range(n, 2 * n) if i not in skip]
    Ja = Ja[keep + list(range(n))][: len(keep)]
    Jf = Jf[keep + list(range(n))][: len(keep)]
    Ja = np.vstack([np.zeros((n, Ja.shape[1])), Ja])[-(len(keep) + n) :]
    Jf = np.vstack([np.zeros((n, Jf.shape[1])), Jf])[-(len(keep) + n) :]
    err = 0.0
    for lo, hi in ((0, n), (n, 2 * n)):
        floor = 1e-9 * np.abs(Ja[n:, lo:hi]).max()
        for j in range(lo, hi):
            sc = max(np.abs(Ja[n:, j]).max(), np.abs(Jf[n:, j]).max(), floor)
            if sc > 0:
                err = max(err, np.abs(Ja[n:, j] - Jf[n:, j]).max() / sc)
    return err


def check(system, t_end, n_states=12, baumgarte=0.0, seed=0, vel_step=0.1, solver="auto"):
    P = system.packed(baumgarte, jacobian=True)
    nn = system.y0.shape[0]
    rng = np.random.default_rng(seed)
    worst = 0.0
    noise = 0.0
    for t, y, mem in states(system, n_states, rng, t_end, solver):
        Jm = np.empty((nn, nn))
        ft = np.empty(nn)
        f0 = np.empty(nn)
        rhs(t, y, mem, P, f0)
        assert system_jacobian(t, y, f0, mem, P, Jm, ft, np.empty(nn), np.empty(nn)) == 0
        # every element took an exact path [T98, T118] (no journal at e = 0 on these states)
        n = system.n
        dQ = np.empty((n, n))
        n_fd = force_jacobian(t, y[:n], y[n:], mem, P.fint, P.freal, P.tables, dQ, dQ.copy(), np.empty(n))
        assert n_fd == 0
        Jf, ftf = fd_jacobian(t, y, mem, P, vel_step)
        # a driven angle has φ̈ = α whatever the state: its Jacobian row vanishes up to rounding
        # (the reference there is pure rounding noise, eps·|Φ_qᵀλ|/(I h), so it is not compared)
        skip = driven_rows(system) if baumgarte == 0.0 else []
        for i in skip:
            assert np.abs(Jm[i]).max() <= 1e-9 * np.abs(Jm[system.n :]).max()
        worst = max(worst, column_error(Jm, Jf, skip))
        # the reference's rounding noise, measured where the exact value is 0: the driven rows
        n = system.n
        for j in range(2 * n):
            sc = np.abs(Jm[n:, j]).max()
            if sc > 0 and skip:
                noise = max(noise, max(abs(Jf[i, j]) for i in skip) / sc)
        sc = max(np.abs(ft).max(), np.abs(ftf).max())
        if sc > 0:
            worst = max(worst, np.abs(ft - ftf).max() / sc)
    return worst, noise


REV = 2 * np.pi / (5000 * 2 * np.pi / 60)  # one crank revolution at 5000 rpm [s]


@pytest.mark.filterwarnings("ignore:JournalBearing. film model 'short':jointdyn.errors.PhysicsWarning")
@pytest.mark.parametrize("joint", JOINTS)
def test_slider_crank_system_jacobian(joint):
    system = slider_crank(joint).compile()
    err, noise = check(system, 0.5 * REV if joint != "dry" else REV)
    assert err <= TOL, f"{joint}: {err:.3g} (reference noise {noise:.3g})"


@pytest.mark.parametrize("bushing", ["rod", "slider"])
def test_slider_crank_with_shear_torques(bushing):
    """The film's shear torques [T75] are differentiated too (either body carrying the bushing)."""
    system = slider_crank("alshaer2005", shear=True, bushing=bushing).compile()
    err, noise = check(system, 0.5 * REV)
    assert err <= TOL, f"shear, bushing in {bushing}: {err:.3g} (reference noise {noise:.3g})"


def test_dry_joint_states_in_contact_are_covered():
    system = slider_crank("dry").compile()
    P = system.packed(0.0, jacobian=True)
    pts = states(system, 60, np.random.default_rng(1), REV)
    inside = [s for s in pts if s[2][0, 0] > 0.5]
    assert len(inside) >= 3  # the dry joint is in contact at some sampled states
    nn = system.y0.shape[0]
    for t, y, mem in inside[:5]:
        Jm = np.empty((nn, nn))
        ft = np.empty(nn)
        system_jacobian(t, y, y, mem, P, Jm, ft, np.empty(nn), np.empty(nn))
        Jf, _ = fd_jacobian(t, y, mem, P)
        assert column_error(Jm, Jf) <= TOL
        n = nn // 2
        n_q = system.n
        dQ = np.empty((n_q, n_q))
        force_jacobian(
            t, y[:n], y[n:], mem, system.fint, system.freal, system.tables, dQ, dQ.copy(), np.empty(n_q)
        )
        assert np.abs(dQ).max() > 1e6  # contact stiffness present [N/m]


def test_baumgarte_terms():
    system = slider_crank("alshaer2005").compile()
    assert check(system, 0.25 * REV, n_states=4, baumgarte=1000.0)[0] <= TOL


def test_four_bar_lubricated():
    model, _ = load_model(EXAMPLES / "four_bar_lubricated.toml")
    system = model.compile()
    err, noise = check(system, 0.01, n_states=10, solver="rodas4")
    assert err <= TOL, f"{err:.3g} (reference noise {noise:.3g})"


def test_engine_with_two_bearings_and_a_tabulated_force():
    """Two film bearings and a tabulated gas force reading the crank angle (all exact [T118])."""
    model, _ = load_model(EXAMPLES / "engine_single_cylinder.toml")
    err, noise = check(model.compile(), 0.01, n_states=8, solver="rodas4")
    assert err <= TOL, f"{err:.3g} (reference noise {noise:.3g})"


def test_ueda_torsion_spring_and_harmonic_torque():
    """The rotor on a revolute joint, cubic torsion spring and harmonic moment: ∂f/∂y and ∂f/∂t
    (the moment's ∂M/∂t [T118]) through the constrained system [T101]."""
    model, _ = load_model(EXAMPLES / "ueda.toml")
    err, noise = check(model.compile(), 6.0, n_states=8)
    assert err <= TOL, f"{err:.3g} (reference noise {noise:.3g})"


def test_tabulated_force_of_another_body():
    """The gas force F(φ_crank) on the piston: the exact Jacobian [T118] (no fallback) has
    ∂Q_piston/∂φ_crank = F′(s)·d (F′ the table slope, d = (−1, 0))."""
    model, _ = load_model(EXAMPLES / "engine_single_cylinder.toml")
    system = model.compile()
    k = system.element_names.index("gas")
    gas = system.elements[k]
    n = system.n
    ic = 3 * system.body_index("crank") + 2
    ip = 3 * system.body_index("piston")
    x = np.asarray(gas.x)
    rng = np.random.default_rng(4)
    for _ in range(20):
        q = system.y0[:n].copy()
        q[ic] = rng.uniform(0.0, 4 * np.pi)
        i = np.searchsorted(x, q[ic]) - 1
        if min(abs(q[ic] - x[i]), abs(q[ic] - x[i + 1])) < 1e-3:
            continue  # the table is only piecewise linear
        slope = (gas.y[i + 1] - gas.y[i]) / (x[i + 1] - x[i])
        dQ = np.empty((n, n))
        dQd = np.empty((n, n))
        sl = slice(k, k + 1)
        n_fd = force_jacobian(
            0.0,
            q,
            system.y0[n:],
            system.mem0[sl],
            system.fint[sl],
            system.freal[sl],
            system.tables,
            dQ,
            dQd,
            np.empty(n),
        )
        assert n_fd == 0
        # the slope of the same table, computed two ways: rounding only
        assert abs(dQ[ip, ic] - (-slope)) <= 1e-8 * abs(slope) + 1e-9
        assert abs(dQ[ip + 1, ic]) <= 1e-9


def test_fallback_elements_are_named():
    from jointdyn.forces.element_jacobians import fallback_elements

    model, _ = load_model(EXAMPLES / "engine_single_cylinder.toml")
    assert fallback_elements(model.compile()) == []
    assert fallback_elements(slider_crank("alshaer2005").compile()) == []


@pytest.mark.parametrize("example", ["four_bar_lubricated", "engine_single_cylinder", "ueda"])
def test_model_files_run_without_the_fallback_warning(example):
    """With default settings (jacobian="exact" for the stiff solvers) a model-file run emits no
    "no exact Jacobian" warning: every element of these models is differentiated exactly."""
    import dataclasses
    import warnings

    model, cfg = load_model(EXAMPLES / f"{example}.toml")
    cfg = dataclasses.replace(cfg, t_end=min(cfg.t_end, 0.002), n_out=5, solver="rodas4")
    with warnings.catch_warnings():
        warnings.filterwarnings("error", message=".*no exact Jacobian.*")
        res = simulate(model.compile(), cfg)
    assert res.t[-1] == pytest.approx(cfg.t_end)


def test_simulate_with_the_exact_jacobian():
    """SimConfig(jacobian="exact") feeds the stiff solvers the exact system Jacobian: rodas4 needs
    far fewer RHS evaluations per accepted step (measured 25 → 7 on this case) at the accuracy of
    the finite-difference run (both within the tolerance-level error of a converged run)."""
    from jointdyn import post
    from jointdyn.simulation.simulate import SimConfig, simulate

    system = slider_crank("alshaer2005").compile()
    ref = simulate(system, SimConfig(t_end=0.25 * REV, n_out=181, rtol=1e-11, atol=1e-14))
    peak = np.abs(post.driving_moment(ref)).max()
    per_step = {}
    for jac in ("finite-differences", "exact"):
        cfg = SimConfig(t_end=0.25 * REV, n_out=181, solver="rodas4", rtol=1e-8, atol=1e-12, jacobian=jac)
        res = simulate(system, cfg)
        assert np.abs(post.driving_moment(res) - post.driving_moment(ref)).max() < 1e-4 * peak
        per_step[jac] = res.stats["rhs_evaluations"] / res.stats["accepted_steps"]
    assert per_step["exact"] < per_step["finite-differences"] / 3


def test_scratch_array_of_the_integrators_gives_the_same_jacobian():
    """``system_jacobian_into`` (the integrators' call, scratch kept between steps) returns the
    same bits as ``system_jacobian`` (fresh scratch), also with a stale scratch full of NaN and
    with one too short (then it makes its own); same arithmetic, so equality is exact."""
    from jointdyn.multibody.jacobian import jacobian_work_size, system_jacobian_into

    system = slider_crank("alshaer2005").compile()
    P = system.packed(0.0, jacobian=True)
    nn = system.y0.shape[0]
    size = jacobian_work_size(system.n, system.n_rows, system.fint.shape[0])
    for t, y, mem in states(system, 4, np.random.default_rng(3), REV):
        Jm, ft = np.empty((nn, nn)), np.empty(nn)
        assert system_jacobian(t, y, y, mem, P, Jm, ft, np.empty(nn), np.empty(nn)) == 0
        for jw in (np.full(size, np.nan), np.empty(3)):
            J2, ft2 = np.full((nn, nn), np.nan), np.full(nn, np.nan)
            assert system_jacobian_into(t, y, mem, P, J2, ft2, jw) == 0
            assert np.array_equal(J2, Jm) and np.array_equal(ft2, ft)


@pytest.mark.parametrize("joint", ["alshaer2005", "dry", "perfect"])
def test_jacobian_accelerations_are_the_right_hand_side(joint):
    """radau5 reads f(t, y) from the Jacobian's scratch when it takes a Jacobian after a step
    [T185]: q̈ there must be dynamics.rhs's, bit for bit (same arithmetic, so equality is exact)."""
    from jointdyn.multibody.jacobian import jacobian_work_size, system_jacobian_into

    system = slider_crank(joint).compile()
    P = system.packed(0.0, jacobian=True)
    nn = system.y0.shape[0]
    n = nn // 2
    jw = np.empty(jacobian_work_size(n, system.n_rows, system.fint.shape[0]))
    for t, y, mem in states(system, 4, np.random.default_rng(5), REV):
        f = np.empty(nn)
        assert rhs(t, y, mem, P, f) == 0
        assert system_jacobian_into(t, y, mem, P, np.empty((nn, nn)), np.empty(nn), jw) == 0
        assert np.array_equal(jw[2 * n : 3 * n], f[n:])
