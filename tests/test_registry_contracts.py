"""Contracts every registry entry must honour, parametrized over the registries themselves: a
newly registered film model, contact or friction law, force element, constraint or solver is
tested the moment it is registered (nothing here names an entry).

References: properties that hold for any Reynolds film (homogeneity, zero force at rest,
dissipation in the frame rotating at the mean surface speed), for any normal contact law
(no force apart, no tension, hysteresis dissipates), for any friction law (opposes slip), for
any pair force (Newton 3, frame invariance), and finite differences for constraint Jacobians.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import pytest
from numba import njit

from jointdyn.core.constraints import CONSTRAINTS, constraint_table, eval_constraints
from jointdyn.core.layout import params_of
from jointdyn.errors import PhysicsWarning
from jointdyn.film.models import FILM_MODELS, FILM_WIDTH, film_force, film_jac, pi_film_force
from jointdyn.forces.contact_laws import CONTACT_LAWS, CONTACT_WIDTH, contact_force, contact_jac
from jointdyn.forces.elements import FORCE_ELEMENTS, NINT, NMEM, NOUT, NREAL, eval_forces
from jointdyn.forces.friction_laws import FRICTION_LAWS, FRICTION_WIDTH, friction_coefficient, friction_jac
from jointdyn.forces.journal import ClearanceJoint, JournalBearing
from jointdyn.integrators import SOLVERS
from jointdyn.multibody.model import Model
from jointdyn.simulation.simulate import SimConfig, simulate

MU, R, L, C = 0.4, 0.01, 0.02, 5e-4  # benchmark pin, L/D = 1 (inside every model's domain)
NO_TABLE = np.zeros((1, 2))


def _film(name):
    m = FILM_MODELS[name]()
    p = np.zeros(FILM_WIDTH)
    p[: len(m.PARAMS)] = params_of(m)
    tab = m.table(L, R) if hasattr(m, "table") else NO_TABLE
    return m, p, tab


def _states(rng, n, xi_max=0.99):
    """(ξ, ξ̇ [1/s], ξΩ [rad/s]) drawn over signs and magnitudes of the benchmark (ω ~ 500 rad/s)."""
    xi = rng.uniform(0.0, xi_max, n)
    a = rng.normal(size=n) * 10.0 ** rng.uniform(-1, 3, n)
    b = rng.normal(size=n) * 10.0 ** rng.uniform(-1, 3, n)
    return xi, a, b


# ---------------------------------------------------------------------------------- films
@pytest.mark.parametrize("name", list(FILM_MODELS))
def test_film_dispatcher_is_the_kernel_and_declares_its_layout(name):
    m, p, tab = _film(name)
    assert len(m.PARAMS) <= FILM_WIDTH and isinstance(m.tag, str)
    rng = np.random.default_rng(1)
    for xi, a, b in zip(*_states(rng, 200)):
        args = (xi, a, b, MU, R, L, C, p, tab)
        assert film_force(m.code, *args) == type(m).kernel(*args)


@pytest.mark.parametrize("name", list(FILM_MODELS))
def test_film_zero_at_rest_and_homogeneous(name):
    """No squeeze and no wedge → no force; F is homogeneous of degree 1 in (ξ̇, ξΩ) for an
    isoviscous film (Reynolds' equation is linear in the surface velocities) [T20]."""
    m, p, tab = _film(name)
    rng = np.random.default_rng(2)
    for xi, a, b in zip(*_states(rng, 300)):
        assert film_force(m.code, xi, 0.0, 0.0, MU, R, L, C, p, tab) == (0.0, 0.0)
        f1 = np.array(film_force(m.code, xi, a, b, MU, R, L, C, p, tab))
        f3 = np.array(film_force(m.code, xi, 3.7 * a, 3.7 * b, MU, R, L, C, p, tab))
        # a few ulps of the cancelling terms of the closed forms; the table is exactly homogeneous
        np.testing.assert_allclose(f3, 3.7 * f1, rtol=1e-9, atol=1e-12 * np.abs(f3).max())


@pytest.mark.parametrize("name", list(FILM_MODELS))
def test_film_dissipates_in_the_mean_surface_frame(name):
    """In the frame rotating at (ω_J + ω_B)/2 the surfaces' speeds cancel in the wedge term, the
    film is a pure squeeze film and its pressure can only absorb power:
    P' = F_r c ξ̇ − F_t c ξΩ/2 ≤ 0 [T20]. Measured margins: max P'/(|F|·|v|) ≈ −0.07 (short) …
    −0.36 (finite) over these states; the bound allows round-off only."""
    m, p, tab = _film(name)
    rng = np.random.default_rng(3)
    for xi, a, b in zip(*_states(rng, 1000)):
        fr, ft = film_force(m.code, xi, a, b, MU, R, L, C, p, tab)
        power = fr * a - ft * b / 2.0
        assert power <= 1e-12 * math.hypot(fr, ft) * math.hypot(a, b / 2.0)


@pytest.mark.parametrize("name", list(FILM_MODELS))
def test_film_finite_near_the_wall_and_at_the_centre(name):
    m, p, tab = _film(name)
    for gap in (1e-3, 1e-6, 1e-9, 1e-12):
        for a, b in ((-50.0, 300.0), (50.0, 300.0), (0.0, 300.0), (-50.0, 0.0), (50.0, -300.0), (1e-9, 0.0)):
            f = film_force(m.code, 1.0 - gap, a, b, MU, R, L, C, p, tab)
            assert all(math.isfinite(v) for v in f), (gap, a, b, f)
    for a, b in ((1.0, 0.0), (0.0, 1.0), (-3.0, 2.0)):
        f = film_force(m.code, 0.0, a, b, MU, R, L, C, p, tab)
        assert all(math.isfinite(v) for v in f)


@pytest.mark.parametrize("name", list(FILM_MODELS))
def test_film_continuous_through_sign_changes(name):
    """The squeeze and wedge terms change sign twice per revolution in a slider-crank pin: the
    force must not jump there (a jump makes stiff solvers fail, docs/theory.md T24)."""
    m, p, tab = _film(name)
    rng = np.random.default_rng(4)

    def force(xi, a, b):
        return np.array(film_force(m.code, xi, a, b, MU, R, L, C, p, tab))

    for _ in range(200):
        xi = rng.uniform(0.0, 0.95)
        a, b = rng.normal(size=2) * 100
        e = 1e-6 * math.hypot(a, b)
        for f in (lambda s: force(xi, s, b), lambda s: force(xi, a, s)):
            across = np.abs(f(e) - f(-e)).max()  # a step of 2e through the sign change
            beside = max(np.abs(f(3 * e) - f(e)).max(), np.abs(f(-e) - f(-3 * e)).max())  # 2e on one side
            # a jump would be O(|F|) while the steps are O(e·slope): allow a kink, not a jump
            assert across <= 10.0 * beside + 1e-12 * np.abs(force(xi, a, b)).max()


# ----------------------------------------------------------------------- contact, friction
@pytest.mark.parametrize("name", list(CONTACT_LAWS))
def test_contact_law_contract(name):
    law = CONTACT_LAWS[name].example()
    p = np.zeros(CONTACT_WIDTH)
    p[: len(law.PARAMS)] = params_of(law)
    assert len(law.PARAMS) <= CONTACT_WIDTH
    rng = np.random.default_rng(5)
    for _ in range(300):
        d = 10.0 ** rng.uniform(-9, -4)
        v = 10.0 ** rng.uniform(-3, 1)
        v0 = 10.0 ** rng.uniform(-2, 1)
        assert contact_force(law.code, d, v, v0, p) == type(law).kernel(d, v, v0, p)
        assert contact_force(law.code, -d, v, v0, p) == 0.0  # apart: no force
        load, unload = contact_force(law.code, d, v, v0, p), contact_force(law.code, d, -v, v0, p)
        assert load >= unload >= 0.0  # no tension; hysteresis dissipates (equality if elastic)
        assert math.isfinite(load)
    # continuous at first touch at rest: the elastic force vanishes with the penetration (a
    # damper term may jump with δ̇ at onset: Kelvin–Voigt does, by Dδ̇, docs/theory.md T55)
    assert contact_force(law.code, 1e-15, 0.0, 1.0, p) < 1e-6 * contact_force(law.code, 1e-6, 0.0, 1.0, p)


@pytest.mark.parametrize("name", list(FRICTION_LAWS))
def test_friction_law_contract(name):
    law = FRICTION_LAWS[name].example()
    p = np.zeros(FRICTION_WIDTH)
    p[: len(law.PARAMS)] = params_of(law)
    for vt in np.concatenate([-np.logspace(-6, 1, 50), [0.0], np.logspace(-6, 1, 50)]):
        mu = friction_coefficient(law.code, vt, p)
        assert mu == type(law).kernel(vt, p)
        assert mu * vt >= 0.0  # opposes slip: the tangential force −μF_n t dissipates
        assert abs(mu) <= law.coefficient
        if vt != 0.0:
            assert friction_coefficient(law.code, -vt, p) == -mu  # odd in the slip velocity
    assert abs(friction_coefficient(law.code, 1.0, p)) == pytest.approx(law.coefficient, rel=1e-6)


# ------------------------------------------------------------------------- force elements
def _element_examples():
    out = []
    for name, cls in FORCE_ELEMENTS.items():
        if cls is JournalBearing:
            out += [(f"{name}[{f}]", cls.example(film=f)) for f in FILM_MODELS]
        else:
            out.append((name, cls.example()))
    return out


ELEMENT_EXAMPLES = _element_examples()


def _pair_model(element):
    m = Model("pair", gravity=(0.0, 0.0))
    m.add_body("a", 1.0, 1e-3, position=(0.0, 0.0), points={"A": (0.03, -0.01)})
    m.add_body("b", 1.0, 1e-3, position=(0.05, -0.035), points={"B": (-0.02, 0.015)})
    m.add("el", element)
    return m


def _compiled(element):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PhysicsWarning)  # short at L/D = 2: outside its domain
        return _pair_model(element).compile(centre_imperfect=False)


@pytest.mark.parametrize("label,element", ELEMENT_EXAMPLES, ids=[n for n, _ in ELEMENT_EXAMPLES])
def test_element_layout_pack_round_trip(label, element):
    cls = type(element)
    assert cls.REAL.width <= NREAL and cls.INT.width <= NINT
    assert len(cls.MEMORY) <= NMEM and len(cls.OUTPUTS) <= NOUT
    assert all(isinstance(u, str) and u for u in {**cls.OUTPUTS, **cls.MEMORY}.values())
    sysm = _compiled(element)
    ints, reals, blocks = element.pack([np.zeros((1, 2))], sysm.body_index)
    row = cls.REAL.unpack(sysm.freal[0])
    for k, v in reals.items():
        assert row[k] == v
    for k, vals in blocks.items():
        np.testing.assert_array_equal(row[k][: len(vals)], vals)
    irow = cls.INT.unpack(sysm.fint[0])
    assert irow["type"] == cls.code
    for k, v in ints.items():
        if k != "table":  # table indices depend on the other elements of the model
            assert irow[k] == v
    # and the packed row drives the kernel: every output is finite at the assembled state
    Q = np.zeros(sysm.n)
    out = np.zeros((1, NOUT))
    eval_forces(
        0.01, sysm.y0[: sysm.n], sysm.y0[sysm.n :], sysm.mem0, sysm.fint, sysm.freal, sysm.tables, Q, out
    )
    assert np.all(np.isfinite(out)) and np.all(np.isfinite(Q))


def _random_state(rng, element):
    """Body states with the element's two points ~ a clearance apart (journals: ξ < 1, or in
    contact for a dry joint), random velocities of the benchmark's magnitude."""
    fa, fb = rng.uniform(-3, 3, 2)
    A = lambda f: np.array([[math.cos(f), -math.sin(f)], [math.sin(f), math.cos(f)]])
    pa = rng.normal(size=2) * 0.1
    hole = pa + A(fa) @ [0.03, -0.01]
    c = getattr(element, "clearance", None)
    if c is None:  # a point-to-point element: 2 cm apart
        dist = 0.02
    elif element.contact is not None:  # dry joint: in contact, δ ≤ 1e-6 m
        dist = rng.uniform(1.0005, 1.002) * c
    else:
        dist = rng.uniform(0.05, 0.95) * c
    ang = rng.uniform(0, 2 * math.pi)
    pin = hole + dist * np.array([math.cos(ang), math.sin(ang)])
    pb = pin - A(fb) @ [-0.02, 0.015]
    q = np.array([pa[0], pa[1], fa, pb[0], pb[1], fb])
    qd = rng.normal(size=6) * np.array([0.2, 0.2, 10, 0.2, 0.2, 10])
    return q, qd


def _forces(sysm, q, qd, t=0.01):
    Q = np.zeros(6)
    out = np.zeros((1, NOUT))
    mem = np.zeros((1, NMEM))
    if "onset_velocity" in type(sysm.elements[0]).MEMORY:  # in contact since a fast onset
        mem[0, list(type(sysm.elements[0]).MEMORY).index("in_contact")] = 1.0
        mem[0, list(type(sysm.elements[0]).MEMORY).index("onset_velocity")] = 5.0
    eval_forces(t, q, qd, mem, sysm.fint, sysm.freal, sysm.tables, Q, out)
    return Q


PAIRS = [(n, e) for n, e in ELEMENT_EXAMPLES if getattr(type(e), "body_i", None) != "ground"]


@pytest.mark.parametrize("label,element", PAIRS, ids=[n for n, _ in PAIRS])
def test_element_newton_third_law_and_frame_invariance(label, element):
    """An internal force pair: ΣF = 0 and Σ moments about the origin = 0 (collinear pair) [T8];
    rotating the whole system rotates the forces and leaves the moments unchanged."""
    sysm = _compiled(element)
    rng = np.random.default_rng(6)
    for _ in range(30):
        q, qd = _random_state(rng, element)
        Q = _forces(sysm, q, qd)
        F = np.hypot(Q[3], Q[4])
        assert F > 0 or Q[5] != 0  # a force pair, or a pure couple (torsion spring: F = 0 exactly)
        assert abs(Q[0] + Q[3]) <= 1e-12 * F and abs(Q[1] + Q[4]) <= 1e-12 * F
        mom = sum(Q[3 * k + 2] + q[3 * k] * Q[3 * k + 1] - q[3 * k + 1] * Q[3 * k] for k in range(2))
        assert abs(mom) <= 1e-12 * F * (1 + np.abs(q[[0, 1, 3, 4]]).max())
        a = rng.uniform(-math.pi, math.pi)
        Rm = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        q2, qd2 = q.copy(), qd.copy()
        for k in range(2):
            q2[3 * k : 3 * k + 2] = Rm @ q[3 * k : 3 * k + 2]
            q2[3 * k + 2] += a
            qd2[3 * k : 3 * k + 2] = Rm @ qd[3 * k : 3 * k + 2]
        Q2 = _forces(sysm, q2, qd2)
        scale = np.abs(Q).max()
        for k in range(2):
            # round-off of |F|·|q| in the arms and of the rotation
            np.testing.assert_allclose(Q2[3 * k : 3 * k + 2], Rm @ Q[3 * k : 3 * k + 2], atol=1e-10 * scale)
            np.testing.assert_allclose(Q2[3 * k + 2], Q[3 * k + 2], atol=1e-10 * scale)


# ----------------------------------------------------------------------------- constraints
PTS = {"a": {"A": (0.3, -0.2)}, "b": {"B": (-0.1, 0.25)}}
INDEX = {"ground": -1, "a": 0, "b": 1}


def _evaluate(c, t, q, qd):
    point_of = lambda b, p: PTS[b][p]
    cint, creal, m = constraint_table([c], INDEX.__getitem__, point_of, lambda b: 0.1 * INDEX[b])
    Phi, J, Phit, gam = np.empty(m), np.empty((m, 6)), np.empty(m), np.empty(m)
    eval_constraints(t, q, qd, cint, creal, Phi, J, Phit, gam)
    return Phi, J, Phit, gam


@pytest.mark.parametrize("name", list(CONSTRAINTS))
def test_constraint_jacobian_and_gamma_by_finite_differences(name):
    c = CONSTRAINTS[name].example()
    assert c.rows == _evaluate(c, 0.0, np.zeros(6), np.zeros(6))[0].shape[0]
    rng = np.random.default_rng(8)
    for _ in range(5):
        q, qd, qdd = rng.normal(size=6), rng.normal(size=6) * 3, rng.normal(size=6) * 10
        t = rng.uniform(0, 1)
        Phi, J, Phit, gam = _evaluate(c, t, q, qd)
        h = 1e-6
        Jfd = np.array(
            [
                (_evaluate(c, t, q + h * e, qd)[0] - _evaluate(c, t, q - h * e, qd)[0]) / (2 * h)
                for e in np.eye(6)
            ]
        ).T
        # central differences, h = 1e-6: truncation ~h² and round-off ~1e-16/h ≈ 1e-10
        np.testing.assert_allclose(J, Jfd, atol=1e-8)
        np.testing.assert_allclose(
            Phit, (_evaluate(c, t + h, q, qd)[0] - _evaluate(c, t - h, q, qd)[0]) / (2 * h), atol=1e-8
        )
        s = 1e-4
        phi_at = lambda sv: _evaluate(c, t + sv, q + qd * sv + 0.5 * qdd * sv * sv, qd)[0]
        phidd = (phi_at(s) - 2 * phi_at(0.0) + phi_at(-s)) / s**2
        # Φ̈ = Φ_q q̈ − γ along q(s) [T4]; second difference: truncation ~1e-6, round-off ~1e-8
        np.testing.assert_allclose(phidd, J @ qdd - gam, atol=1e-5 * (1 + np.abs(J @ qdd).max()))


# --------------------------------------------------------------------------------- solvers
@pytest.mark.parametrize("name", list(SOLVERS))
def test_solver_integrates_a_pendulum(name):
    """A rigid pendulum released horizontally: energy is conserved (no dissipative element) and
    the constraint holds; period-scale run, tolerance 1e-8."""
    m = Model("pendulum")
    m.add_body("bar", 2.0, 0.02, position=(0.25, 0.0), points={"pin": (-0.25, 0.0)})
    m.add_ground_point("O", (0.0, 0.0))
    from jointdyn.core.constraints import Revolute

    m.add("pin", Revolute("ground", "O", "bar", "pin"))
    sysm = m.compile()
    res = simulate(sysm, SimConfig(t_end=1.0, n_out=51, solver=name, rtol=1e-8, atol=1e-10))
    mass = 1.0 / sysm.minv
    energy = 0.5 * (mass * res.qd**2).sum(1) - (res.q * sysm.q0_force).sum(1)
    scale = 2.0 * 9.81 * 0.25  # m g ℓ_cm [J]
    assert np.abs(energy - energy[0]).max() < 1e-5 * scale  # tolerance-level energy error
    assert res.drift.max() < 1e-6  # projection: ~1e-12 m; Baumgarte (scipy path): ~1e-8 m


# ------------------------------------------------------------------------ jacobians (optional)
# Laws registered from this file (plugins, no ``jacobian``): the compiled dispatch includes them
# and differences their kernels [T229]; they run through every Jacobian contract below.
@njit(cache=True)
def _plugin_film_force(xi, xi_dot, xi_Omega, mu, R, L, c, p, table):
    fr, ft = pi_film_force(xi, xi_dot, xi_Omega, mu, R, L, c, p, table)
    return 1.5 * fr, 1.5 * ft


@njit(cache=True)
def _plugin_contact_force(delta, delta_dot, delta_dot0, p):
    f = p[0] * delta**1.5 * (1.0 + 0.3 * delta_dot / delta_dot0)  # Hunt–Crossley-like, χ = 0.3
    return f if f > 0.0 else 0.0


@njit(cache=True)
def _plugin_friction(vt, p):
    return p[0] * vt / math.sqrt(vt * vt + 1e-8)  # μ v/√(v² + v_reg²), v_reg = 1e-4 m/s


@dataclass(frozen=True)
class PluginFilm:
    code: ClassVar[int] = max(c.code for c in FILM_MODELS.values()) + 1
    kernel: ClassVar = _plugin_film_force
    tag: ClassVar[str] = "T21"
    PARAMS: ClassVar[tuple[str, ...]] = ()


@dataclass(frozen=True)
class PluginContact:
    stiffness: float = 6.9e10
    code: ClassVar[int] = max(c.code for c in CONTACT_LAWS.values()) + 1
    kernel: ClassVar = _plugin_contact_force
    PARAMS: ClassVar[tuple[str, ...]] = ("stiffness",)

    @classmethod
    def example(cls):
        return cls()


@dataclass(frozen=True)
class PluginFriction:
    coefficient: float = 0.1
    code: ClassVar[int] = max(c.code for c in FRICTION_LAWS.values()) + 1
    kernel: ClassVar = _plugin_friction
    PARAMS: ClassVar[tuple[str, ...]] = ("coefficient",)

    @classmethod
    def example(cls):
        return cls()


@pytest.fixture()
def plugins(monkeypatch):
    """The three plugin laws registered for one test (removed after it)."""
    monkeypatch.setitem(FILM_MODELS, "plugin_film", PluginFilm)
    monkeypatch.setitem(CONTACT_LAWS, "plugin_contact", PluginContact)
    monkeypatch.setitem(FRICTION_LAWS, "plugin_friction", PluginFriction)


def _central(f, x, h):
    return (np.array(f(x + h)) - np.array(f(x - h))) / (2 * h)


@pytest.mark.parametrize("name", [*FILM_MODELS, "plugin_film"])
def test_film_jacobian_contract(name, plugins):
    """The compiled Jacobian path of every film model (its ``jacobian``, or central differences
    of its kernel [T229]): forces bit-identical to the kernel; derivatives = central differences
    at interior states (h = 1e-6 of the scale: truncation ~1e-12, round-off ~1e-10 relative;
    bound 1e-6 of the row's scale, the issue's criterion)."""
    m, p, tab = _film(name)
    jac = getattr(type(m), "jacobian", None)
    rng = np.random.default_rng(9)
    for xi, a, b in zip(*_states(rng, 60, xi_max=0.9)):
        args = (MU, R, L, C, p, tab)
        J = film_jac(m.code, xi, a, b, *args)
        assert J[:2] == film_force(m.code, xi, a, b, *args) == type(m).kernel(xi, a, b, *args)
        assert jac is None or J == jac(xi, a, b, *args)
        dxi = _central(lambda x: film_force(m.code, x, a, b, *args), xi, 1e-6)
        da = _central(lambda x: film_force(m.code, xi, x, b, *args), a, 1e-6 * math.hypot(a, b))
        db = _central(lambda x: film_force(m.code, xi, a, x, *args), b, 1e-6 * math.hypot(a, b))
        exact = np.array([[J[2], J[3], J[4]], [J[5], J[6], J[7]]])
        fd = np.column_stack([dxi, da, db])
        scale = np.abs(fd).max(axis=1, keepdims=True) * np.array([1.0, math.hypot(a, b), math.hypot(a, b)])
        assert np.all(
            np.abs((exact - fd) * np.array([1.0, math.hypot(a, b), math.hypot(a, b)]))
            <= 1e-6 * scale + 1e-300
        )


@pytest.mark.parametrize("name", [*CONTACT_LAWS, "plugin_contact"])
def test_contact_jacobian_contract(name, plugins):
    law = CONTACT_LAWS[name].example()
    jac = getattr(type(law), "jacobian", None)
    p = np.zeros(CONTACT_WIDTH)
    p[: len(law.PARAMS)] = params_of(law)
    rng = np.random.default_rng(10)
    for _ in range(60):
        d, v, v0 = 10.0 ** rng.uniform(-7, -5), 10.0 ** rng.uniform(-2, 0), 10.0 ** rng.uniform(-1, 0)
        F, dd, dv = contact_jac(law.code, d, v, v0, p)
        assert F == contact_force(law.code, d, v, v0, p) == type(law).kernel(d, v, v0, p)
        assert jac is None or (F, dd, dv) == jac(d, v, v0, p)
        fd_d = _central(lambda x: contact_force(law.code, x, v, v0, p), d, 1e-6 * d)
        fd_v = _central(lambda x: contact_force(law.code, d, x, v0, p), v, 1e-6 * v)
        # central differences at h = 1e-6 of the argument: ~1e-10 relative
        assert abs(dd - fd_d) <= 1e-6 * abs(fd_d) + 1e-9 * abs(F) / d
        assert abs(dv - fd_v) <= 1e-6 * abs(fd_v) + 1e-9 * abs(F) / v


@pytest.mark.parametrize("name", [*FRICTION_LAWS, "plugin_friction"])
def test_friction_jacobian_contract(name, plugins):
    law = FRICTION_LAWS[name].example()
    jac = getattr(type(law), "jacobian", None)
    p = np.zeros(FRICTION_WIDTH)
    p[: len(law.PARAMS)] = params_of(law)
    for vt in np.concatenate([-np.logspace(-5, 0, 20), np.logspace(-5, 0, 20)]):
        mu, dmu = friction_jac(law.code, vt, p)
        assert mu == friction_coefficient(law.code, vt, p) == type(law).kernel(vt, p)
        assert jac is None or (mu, dmu) == jac(vt, p)
        h = 1e-7 * abs(vt)
        fd = (friction_coefficient(law.code, vt + h, p) - friction_coefficient(law.code, vt - h, p)) / (2 * h)
        assert abs(dmu - fd) <= 1e-5 * abs(fd) + 1e-6 * law.coefficient / abs(vt)


# ------------------------------------------------------------------ element Jacobians (all)
@pytest.mark.parametrize("label,element", ELEMENT_EXAMPLES, ids=[n for n, _ in ELEMENT_EXAMPLES])
def test_element_jacobian_contract(label, element):
    """Every registered element has a Jacobian in ``force_jacobian`` (exact [T98, T118] or the
    finite-difference fallback [T100]) that matches central differences [T95] of its own force,
    and ``fallback_elements`` names it exactly when it takes the fallback."""
    _check_element_jacobian(label, element)


@pytest.mark.parametrize("which", ["film", "contact", "friction"])
def test_plugin_law_element_jacobian(which, plugins):
    """A journal element with a plugin law (no ``jacobian``): the system Jacobian, with the law
    differenced inside the element's exact Jacobian [T229], matches central differences of the
    element's force, with the system's kinds (the plugin in the type) and without fallback."""
    from jointdyn.forces.element_jacobians import differenced_laws

    if which == "film":
        element, named = JournalBearing.example(film=PluginFilm()), ["el: film model plugin_film"]
    elif which == "contact":
        element, named = (
            ClearanceJoint("a", "A", "b", "B", 0.0105, 0.01, PluginContact()),
            ["el: contact law PluginContact"],
        )
    else:
        element = ClearanceJoint("a", "A", "b", "B", 0.0105, 0.01, PluginContact(), PluginFriction())
        named = ["el: contact law PluginContact", "el: friction law PluginFriction"]
    assert differenced_laws(_compiled(element)) == named  # the warning of ``simulate`` names them
    _check_element_jacobian(f"plugin {which}", element)


def _check_element_jacobian(label, element):
    from fd_reference import central

    from jointdyn.forces.element_jacobians import fallback_elements, force_jacobian
    from jointdyn.forces.elements import kinds_of

    sysm = _compiled(element)
    kinds = kinds_of(sysm.fint)
    mem = np.zeros((1, NMEM))
    if "onset_velocity" in type(element).MEMORY:  # as in _forces: in contact since a fast onset
        mem[0, list(type(element).MEMORY).index("in_contact")] = 1.0
        mem[0, list(type(element).MEMORY).index("onset_velocity")] = 5.0
    rng = np.random.default_rng(8)
    t = 0.01
    worst = 0.0
    for _ in range(8):
        q, qd = _random_state(rng, element)
        dq, dqd, dt = np.empty((6, 6)), np.empty((6, 6)), np.empty(6)
        n_fd = force_jacobian(t, q, qd, mem, sysm.fint, sysm.freal, sysm.tables, dq, dqd, dt, kinds)
        assert n_fd == (1 if fallback_elements(sysm) else 0)
        Ja = np.hstack([dq, dqd, dt[:, None]])

        def Q(tt, qq, vv):
            out = np.zeros(6)
            eval_forces(tt, qq, vv, mem, sysm.fint, sysm.freal, sysm.tables, out, np.zeros((1, NOUT)), kinds)
            return out

        Jf = np.empty((6, 13))
        for j in range(6):
            # largest steps [m, rad], ≪ the clearance of the journal examples; the reference
            # searches 7 steps down to 4^-6 of these (in contact, δ ≥ 5e-4 c: steps below δ)
            hq = (1e-7 if j % 3 != 2 else 3e-6) * (1.0 if getattr(element, "contact", None) is None else 1e-2)
            Jf[:, j] = central(lambda v, j=j: Q(t, np.where(np.arange(6) == j, v, q), qd), q[j], hq)
            hv = 1e-6 * max(1.0, abs(qd[j]))
            Jf[:, 6 + j] = central(lambda v, j=j: Q(t, q, np.where(np.arange(6) == j, v, qd)), qd[j], hv)
        Jf[:, 12] = central(lambda tt: Q(tt, q, qd), t, 1e-6)
        # column measure of tests/test_jacobians_system.py (floor 1e-9 of the largest column)
        floor = 1e-9 * max(np.abs(Ja).max(), np.abs(Jf).max(), 1e-300)
        sc = np.maximum(np.maximum(np.abs(Ja).max(axis=0), np.abs(Jf).max(axis=0)), floor)
        worst = max(worst, float((np.abs(Ja - Jf).max(axis=0) / sc).max()))
    assert worst <= 1e-6, f"{label}: {worst:.3g}"  # the goal for every force law
