"""Journal-bearing / clearance-joint force element: action–reaction, frame invariance,
kinematics by finite differences, consistency with the film-model front, error on ξ ≥ 1."""

import math

import numpy as np
import pytest

from jointdyn.errors import SimulationError
from jointdyn.film.models import film_forces
from jointdyn.forces.contact_laws import LankaraniNikravesh
from jointdyn.forces.elements import NOUT, eval_forces
from jointdyn.forces.journal import ClearanceJoint, JournalBearing
from jointdyn.models.slider_crank import slider_crank
from jointdyn.multibody.model import Model
from jointdyn.simulation.simulate import SimConfig, simulate

RB, RJ, L, MU = 0.0105, 0.0100, 0.04, 0.4
C = RB - RJ


def two_body_model(element):
    m = Model("pair", gravity=(0.0, 0.0))
    m.add_body("a", 1.0, 1e-3, points={"hole": (0.03, -0.01)})
    m.add_body("b", 1.0, 1e-3, points={"pin": (-0.02, 0.015)})
    m.add("el", element)
    return m


def forces(sysm, q, qd, mem=None):
    Q = np.zeros(6)
    out = np.zeros((1, NOUT))
    # in contact since an onset at δ̇⁻ = 5 m/s (faster than any |δ̇| drawn below): F_n > 0
    mem = np.array([[1.0, 5.0, 0.0, 0.0]]) if mem is None else mem
    eval_forces(0.0, q, qd, mem, sysm.fint, sysm.freal, sysm.tables, Q, out)
    return Q, out[0]


def state_with_eccentricity(rng, xi, phi_a=None, phi_b=None):
    """Random body states such that the pin centre sits at eccentricity ξ·c from the hole."""
    pa = rng.normal(size=2) * 0.1
    fa = rng.uniform(-3, 3) if phi_a is None else phi_a
    fb = rng.uniform(-3, 3) if phi_b is None else phi_b
    A = lambda f: np.array([[math.cos(f), -math.sin(f)], [math.sin(f), math.cos(f)]])
    hole = pa + A(fa) @ [0.03, -0.01]
    ang = rng.uniform(0, 2 * math.pi)
    pin = hole + xi * C * np.array([math.cos(ang), math.sin(ang)])
    pb = pin - A(fb) @ [-0.02, 0.015]
    q = np.array([pa[0], pa[1], fa, pb[0], pb[1], fb])
    qd = rng.normal(size=6) * np.array([0.2, 0.2, 10, 0.2, 0.2, 10])
    return q, qd


ELEMENTS = {
    "alshaer2005": JournalBearing("a", "hole", "b", "pin", RB, RJ, L, MU, film="alshaer2005"),
    "ott": JournalBearing("a", "hole", "b", "pin", RB, RJ, L, MU, film="ott"),
    "dry": ClearanceJoint(
        "a",
        "hole",
        "b",
        "pin",
        RB,
        RJ,
        contact=LankaraniNikravesh(stiffness=6.9e10, exponent=1.5, restitution=0.9),
    ),
}


@pytest.mark.parametrize("name", list(ELEMENTS))
def test_newton_third_law_and_no_net_moment(name):
    sysm = two_body_model(ELEMENTS[name]).compile()
    rng = np.random.default_rng(1)
    for _ in range(50):
        xi = rng.uniform(1.0005, 1.002) if name == "dry" else rng.uniform(0.0, 0.95)
        q, qd = state_with_eccentricity(rng, xi)
        Q, out = forces(sysm, q, qd)
        F = np.hypot(*out[4:6])
        assert F > 0
        # ΣF = 0 and Σ moments about the world origin = 0 (collinear pair) to round-off
        assert abs(Q[0] + Q[3]) <= 1e-12 * F and abs(Q[1] + Q[4]) <= 1e-12 * F
        mom = sum(Q[3 * k + 2] + q[3 * k] * Q[3 * k + 1] - q[3 * k + 1] * Q[3 * k] for k in range(2))
        assert abs(mom) <= 1e-12 * F * (1 + np.abs(q[[0, 1, 3, 4]]).max())
        np.testing.assert_allclose(out[4:6], Q[3:5], rtol=1e-13, atol=1e-13 * F)


@pytest.mark.parametrize("name", list(ELEMENTS))
def test_rotating_the_whole_system_rotates_the_forces(name):
    sysm = two_body_model(ELEMENTS[name]).compile()
    rng = np.random.default_rng(2)
    for _ in range(20):
        xi = rng.uniform(1.0005, 1.002) if name == "dry" else rng.uniform(0.05, 0.95)
        q, qd = state_with_eccentricity(rng, xi)
        Q, _ = forces(sysm, q, qd)
        a = rng.uniform(-math.pi, math.pi)
        R = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        q2, qd2 = q.copy(), qd.copy()
        for k in range(2):
            q2[3 * k : 3 * k + 2] = R @ q[3 * k : 3 * k + 2]
            q2[3 * k + 2] += a
            qd2[3 * k : 3 * k + 2] = R @ qd[3 * k : 3 * k + 2]
        Q2, _ = forces(sysm, q2, qd2)
        scale = np.abs(Q).max()
        for k in range(2):
            # forces rotate with the frame, moments are invariant (round-off of |F|·|q|)
            np.testing.assert_allclose(Q2[3 * k : 3 * k + 2], R @ Q[3 * k : 3 * k + 2], atol=1e-10 * scale)
            np.testing.assert_allclose(Q2[3 * k + 2], Q[3 * k + 2], atol=1e-10 * scale)


@pytest.mark.parametrize("film", ["alshaer2005", "ott"])
def test_element_matches_film_front_with_rotating_bearing(film):
    """The element's kinematics (ξ̇, γ̇ by finite differences of e(t), Ω = ω_J + ω_B − 2γ̇)
    fed to the film-model front give the same force as the element [T14, T15]."""
    sysm = two_body_model(ELEMENTS[film]).compile()
    rng = np.random.default_rng(3)
    for _ in range(30):
        q, qd = state_with_eccentricity(rng, rng.uniform(0.05, 0.9))
        Q, out = forces(sysm, q, qd)
        h = 1e-8

        def ecc(s):
            qq = q + s * qd
            _, o = forces(sysm, qq, qd)
            return o[0], o[1]

        (exm, eym), (exp_, eyp) = ecc(-h), ecc(h)
        ex, ey = out[0], out[1]
        xi_dot = (math.hypot(exp_, eyp) - math.hypot(exm, eym)) / (2 * h) / C
        gdot = (math.atan2(eyp, exp_) - math.atan2(eym, exm)) / (2 * h)
        ref = film_forces(
            film, math.hypot(ex, ey) / C, xi_dot, math.atan2(ey, ex), gdot, qd[5], qd[2], MU, L, RJ, C
        )
        F = math.hypot(ref["Fx"], ref["Fy"])
        # central difference of e(t) with h = 1e-8 s: relative error ~1e-7 in ξ̇, γ̇
        assert abs(out[4] - ref["Fx"]) < 1e-5 * F and abs(out[5] - ref["Fy"]) < 1e-5 * F


def test_dry_joint_has_no_force_inside_the_clearance():
    sysm = two_body_model(ELEMENTS["dry"]).compile()
    rng = np.random.default_rng(4)
    for _ in range(50):
        q, qd = state_with_eccentricity(rng, rng.uniform(0.0, 0.9999))
        Q, out = forces(sysm, q, qd)
        assert np.all(Q == 0.0) and out[7] == 0.0


def test_film_breakdown_without_contact_law_stops_with_clear_error():
    """A bearing with a vanishing viscosity cannot carry the 5000 rpm inertia load: the
    journal runs into the wall (ξ → 1) and, without a contact law, the run stops with an error
    that names the element and the remedy, keeping what was computed."""
    sysm = slider_crank("alshaer2005", viscosity=1e-5).compile()
    with pytest.raises(SimulationError, match=r"piston_pin.*ξ = 0\.99.*contact law") as err:
        simulate(
            sysm, SimConfig(t_end=0.012, n_out=121, solver="rodas4", rtol=1e-6, atol=1e-10, max_steps=20_000)
        )
    part = err.value.results
    assert part is not None and 0 < len(part.t) < 121  # what was computed is kept
    assert np.all(part.eout[:, 0, 2] < 1.0)


@pytest.mark.parametrize(
    "kw,pattern",
    [
        (dict(journal_radius=0.0105), r"journal_radius = 0.0105 \[m\]: must be in \(0, bearing_radius"),
        (dict(journal_radius=0.011), r"journal_radius.*\[m\]"),
        (dict(viscosity=0.0), r"viscosity = 0.0 \[Pa·s\]: must be > 0"),
        (dict(length=-0.01), r"length = -0.01 \[m\]: must be > 0"),
        (dict(film="sommerfeld"), r"film = 'sommerfeld'.*valid: .*'alshaer2005'.*'ott'"),
        (dict(viscosity=float("nan")), r"viscosity = nan"),
    ],
)
def test_bad_bearing_parameters_are_named(kw, pattern):
    from jointdyn.errors import ModelError

    args = dict(bearing_radius=RB, journal_radius=RJ, length=L, viscosity=MU, film="alshaer2005") | kw
    m = two_body_model(JournalBearing("a", "hole", "b", "pin", **args))
    with pytest.raises(ModelError, match=pattern):
        m.compile()


def test_rosenbrock_w_agrees_with_rodas4_on_the_lubricated_slider_crank():
    """One revolution, π-film, c = 0.5 mm: both stiff integrators against a rodas4 rtol 1e-10
    reference; measured max |ΔM|/peak: ros34pw2 1.2e-5, rodas4 9.6e-6 at rtol 1e-8."""
    from jointdyn import post

    sysm = slider_crank("alshaer2005").compile()
    cfg = dict(t_end=0.012, n_out=361)
    ref = post.driving_moment(simulate(sysm, SimConfig(solver="rodas4", rtol=1e-10, atol=1e-14, **cfg)))
    for solver in ("rodas4", "ros34pw2"):
        M = post.driving_moment(simulate(sysm, SimConfig(solver=solver, rtol=1e-8, atol=1e-12, **cfg)))
        assert np.abs(M - ref).max() < 1e-4 * np.abs(ref).max()
