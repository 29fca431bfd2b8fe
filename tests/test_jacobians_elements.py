"""Exact Jacobians of the spring–damper, torsional spring, harmonic torque and tabulated force
[T118] vs
step-size-robust central differences [T95] of the element's own generalised force, over 1,200
seeded states per element (random poses, velocities, parameters, either body the ground), and
the zero-length edge of the spring (finite-difference fallback [T100])."""

from __future__ import annotations

import numpy as np
import pytest
from fd_reference import central

from jointdyn.forces.element_jacobians import force_jacobian
from jointdyn.forces.elements import NOUT, element_tables, eval_forces
from jointdyn.forces.springs import SpringDamper
from jointdyn.forces.tabulated import TabulatedForce
from jointdyn.forces.torsion import HarmonicTorque, TorsionSpring

N_STATES = 1200  # the issue asks for ≥ 1,000 seeded states per element
# goal of the issue: 1e-6 relative (column measure). Measured on these states (python
# tests/test_jacobians_elements.py): harmonic 7.9e-10, tabulated 1.1e-9, torsion 2.5e-8, spring
# 2.3e-8 (1.2e-7 with ℓ ≤ 1 mm, where the reference's steps shrink with ℓ)
TOL = 1e-6
BODIES = {"a": 0, "b": 1, "ground": -1}


def pack(element, points):
    fint, freal, tables, mem = element_tables([element], BODIES.__getitem__, lambda b, p: points[p])
    return fint, freal, tables, mem


def element_q(t, q, qd, P):
    fint, freal, tables, mem = P
    Q = np.zeros(6)
    eval_forces(t, q, qd, mem, fint, freal, tables, Q, np.zeros((1, NOUT)))
    return Q


def exact(t, q, qd, P):
    fint, freal, tables, mem = P
    dq, dqd, dt = np.empty((6, 6)), np.empty((6, 6)), np.empty(6)
    n_fd = force_jacobian(t, q, qd, mem, fint, freal, tables, dq, dqd, dt)
    return np.hstack([dq, dqd, dt[:, None]]), n_fd


def reference(t, q, qd, P, hq):
    """Central differences of the element force in q (steps ≤ hq [m, rad], scalar or per
    coordinate), q̇ and t."""
    hq = np.broadcast_to(hq, 6)
    J = np.empty((6, 13))
    for j in range(6):

        def fq(v, j=j):
            qq = q.copy()
            qq[j] = v
            return element_q(t, qq, qd, P)

        def fv(v, j=j):
            vv = qd.copy()
            vv[j] = v
            return element_q(t, q, vv, P)

        J[:, j] = central(fq, q[j], hq[j])
        J[:, 6 + j] = central(fv, qd[j], 0.1 * max(1.0, abs(qd[j])))
    J[:, 12] = central(lambda tt: element_q(tt, q, qd, P), t, 1e-3)
    return J


def error(Ja, Jf):
    """max over columns of |ΔJ|∞ / |J|∞; a column is measured against at least 1e-9 of the
    largest column (columns that vanish exactly come out as rounding of the reference)."""
    floor = 1e-9 * max(np.abs(Ja).max(), np.abs(Jf).max(), 1e-300)
    sc = np.maximum(np.maximum(np.abs(Ja).max(axis=0), np.abs(Jf).max(axis=0)), floor)
    return float((np.abs(Ja - Jf).max(axis=0) / sc).max())


def pair_bodies(rng):
    u = rng.uniform()
    return ("ground", "b") if u < 0.15 else (("a", "ground") if u < 0.3 else ("a", "b"))


def spring_state(rng, k):
    bi, bj = pair_bodies(rng)
    points = {"A": tuple(rng.uniform(-0.05, 0.05, 2)), "B": tuple(rng.uniform(-0.05, 0.05, 2))}
    e = SpringDamper(
        bi, "A", bj, "B", stiffness=10 ** rng.uniform(2, 6), damping=rng.choice([0.0, 10 ** rng.uniform(0, 3)]),
        free_length=rng.choice([0.0, rng.uniform(0.0, 0.1)]),
    )  # fmt: skip
    q = np.concatenate(
        [rng.uniform(-0.1, 0.1, 2), [rng.uniform(-4, 4)], rng.uniform(-0.1, 0.1, 2), [rng.uniform(-4, 4)]]
    )
    qd = np.concatenate([rng.normal(0, 1, 2), [rng.normal(0, 20)], rng.normal(0, 1, 2), [rng.normal(0, 20)]])
    hq = 1e-4
    if k % 4 == 0:  # near the zero-length edge: ℓ from 1e-7 to 1e-3 m (the kernel's guard is at 0)
        P = pack(e, points)
        ell = 10 ** rng.uniform(-7, -3)
        ang = rng.uniform(0, 2 * np.pi)
        pi = _point(q, BODIES[bi], points["A"])
        sj = _arm(q, BODIES[bj], points["B"])
        if BODIES[bj] >= 0:
            q[3 * BODIES[bj] : 3 * BODIES[bj] + 2] = pi + ell * np.array([np.cos(ang), np.sin(ang)]) - sj
        else:  # move body i instead
            pj = _point(q, -1, points["B"])
            si = _arm(q, BODIES[bi], points["A"])
            q[3 * BODIES[bi] : 3 * BODIES[bi] + 2] = pj - ell * np.array([np.cos(ang), np.sin(ang)]) - si
        # steps well inside the 1/ℓ curvature of the direction: a point displacement ≤ ℓ/20
        arms = [np.hypot(*points["A"]), np.hypot(*points["B"])]
        hq = 0.05 * ell * np.array([1.0, 1.0, 1.0 / arms[0], 1.0, 1.0, 1.0 / arms[1]])
        return P, q, qd, hq, 0.0
    return pack(e, points), q, qd, hq, 0.0


def _arm(q, b, p):
    if b < 0:
        return np.zeros(2)
    c, s = np.cos(q[3 * b + 2]), np.sin(q[3 * b + 2])
    return np.array([c * p[0] - s * p[1], s * p[0] + c * p[1]])


def _point(q, b, p):
    return q[3 * b : 3 * b + 2] + _arm(q, b, p) if b >= 0 else np.array(p)


def torsion_state(rng, k):
    bi, bj = pair_bodies(rng)
    e = TorsionSpring(
        bi, bj, stiffness=10 ** rng.uniform(0, 3), cubic_stiffness=rng.uniform(-50, 50),
        damping=rng.uniform(0, 2), free_angle=rng.uniform(-1, 1),
    )  # fmt: skip
    q = rng.uniform(-1, 1, 6) * np.array([0.1, 0.1, 6.0, 0.1, 0.1, 6.0])
    qd = rng.normal(0, 5, 6)
    return pack(e, {}), q, qd, 1e-3, 0.0


def harmonic_state(rng, k):
    e = HarmonicTorque(
        rng.choice(["a", "b"]), amplitude=rng.uniform(-10, 10), frequency=10 ** rng.uniform(-1, 2),
        phase=rng.uniform(-3, 3),
    )  # fmt: skip
    q = rng.uniform(-1, 1, 6)
    qd = rng.normal(0, 5, 6)
    return pack(e, {}), q, qd, 1e-3, rng.uniform(0, 10)


def tabulated_state(rng, k):
    """A random table on point B of body b (or the ground), argument the time or either body's
    angle, with or without a period; states ≥ 5e-3 from a table node (the interpolant has a kink
    there) and from the period wrap, so the central differences stay in one cell."""
    nodes = np.sort(rng.uniform(0.5, 5.5, rng.integers(2, 9)))
    if np.diff(nodes).min(initial=1.0) < 0.02:
        nodes = np.linspace(0.5, 5.5, nodes.size)
    arg = str(rng.choice(["time", "a", "b"]))
    e = TabulatedForce(
        "ground" if rng.uniform() < 0.1 else "b", "B", x=tuple(nodes), y=tuple(rng.uniform(-1e3, 1e3, nodes.size)),
        direction=tuple(rng.normal(size=2)), argument=arg, period=float(rng.choice([0.0, 6.3])),
    )  # fmt: skip
    points = {"B": tuple(rng.uniform(-0.05, 0.05, 2))}
    qd = rng.normal(0, 5, 6)
    while True:
        q = rng.uniform(-1, 1, 6) * np.array([0.1, 0.1, 8.0, 0.1, 0.1, 8.0])
        t = rng.uniform(-1.0, 8.0)
        s = t if arg == "time" else q[3 * BODIES[arg] + 2]
        s = s - e.period * np.floor(s / e.period) if e.period > 0 else s
        if np.abs(s - np.concatenate([nodes, [0.0, e.period]])).min() > 5e-3:
            return pack(e, points), q, qd, 1e-3, t


STATES = {
    "spring_damper": spring_state,
    "torsion_spring": torsion_state,
    "harmonic_torque": harmonic_state,
    "tabulated_force": tabulated_state,
}


def errors(name, n=N_STATES, seed=0):
    rng = np.random.default_rng(seed)
    out = []
    for k in range(n):
        P, q, qd, hq, t = STATES[name](rng, k)
        Ja, n_fd = exact(t, q, qd, P)
        assert n_fd == 0, f"{name}: took the finite-difference fallback"
        out.append(error(Ja, reference(t, q, qd, P, hq)))
    return np.array(out)


@pytest.mark.parametrize("name", sorted(STATES))
def test_element_jacobian_matches_central_differences(name):
    err = errors(name)
    assert err.max() <= TOL, f"{name}: max {err.max():.3g} over {err.size} states"


def test_spring_at_zero_length_uses_the_fallback():
    """At ℓ = 0 the direction is undefined: the element is differenced numerically [T100]; for
    ℓ₀ = 0 and d = 0 the force −k(P_j − P_i) is linear, so the fallback gives exactly −k, +k."""
    e = SpringDamper("a", "A", "b", "B", stiffness=1e4)
    P = pack(e, {"A": (0.01, 0.0), "B": (0.0, 0.0)})
    q = np.array([0.0, 0.0, 0.0, 0.01, 0.0, 0.3])  # P_j = P_i
    Ja, n_fd = exact(0.0, q, np.zeros(6), P)
    assert n_fd == 1
    # central differences of a linear function: rounding only, ~ε^(2/3) ≈ 4e-11 relative
    np.testing.assert_allclose(Ja[3:5, 3:5], -1e4 * np.eye(2), rtol=1e-8)
    np.testing.assert_allclose(Ja[0:2, 3:5], 1e4 * np.eye(2), rtol=1e-8)


if __name__ == "__main__":  # the numbers of the report: python tests/test_jacobians_elements.py
    for name in sorted(STATES):
        err = errors(name)
        msg = f"{name}: {err.size} states, max {err.max():.2e}, median {np.median(err):.2e}"
        if name == "spring_damper":  # every 4th state near the zero-length edge
            msg += f" (ℓ ≤ 1 mm: {err[::4].max():.2e}, others {np.delete(err, np.s_[::4]).max():.2e})"
        print(msg)
