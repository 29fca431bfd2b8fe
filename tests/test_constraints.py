"""Finite-difference checks of every constraint type: Φ_q and the acceleration RHS γ."""

import numpy as np
import pytest

from jointdyn.core.constraints import (
    CONSTRAINTS,
    AngleDriver,
    Revolute,
    Translational,
    constraint_table,
    eval_constraints,
)

POINTS = {("a", "p"): (0.3, -0.2), ("b", "p"): (-0.1, 0.25), ("ground", "p"): (0.05, 0.4)}
INDEX = {"ground": -1, "a": 0, "b": 1}


MAKERS = {
    Revolute: lambda bi, bj: Revolute(bi, "p", bj, "p"),
    Translational: lambda bi, bj: Translational(bi, "p", bj, "p", axis=(0.6, 0.8), angle=0.3),
    AngleDriver: lambda bi, bj: AngleDriver(bi, bj, phi0=0.2, omega=3.0, alpha=-1.5),
}


def make(kind, bi, bj):
    if kind not in MAKERS:  # a new constraint type needs its own instance here (and an example())
        raise KeyError(f"no test instance for constraint type {kind.__name__}")
    return MAKERS[kind](bi, bj)


def evaluate(c, t, q, qd):
    cint, creal, m = constraint_table([c], INDEX.__getitem__, lambda b, p: POINTS[(b, p)], lambda b: 0.0)
    Phi, J, Phit, gam = np.empty(m), np.empty((m, 6)), np.empty(m), np.empty(m)
    eval_constraints(t, q, qd, cint, creal, Phi, J, Phit, gam)
    return Phi, J, Phit, gam


@pytest.mark.parametrize("kind", list(CONSTRAINTS.values()))
@pytest.mark.parametrize("pair", [("a", "b"), ("ground", "b"), ("a", "ground")])
def test_jacobian_and_gamma_by_finite_differences(kind, pair):
    rng = np.random.default_rng(7)
    c = make(kind, *pair)
    for _ in range(5):
        q = rng.normal(size=6)
        qd = rng.normal(size=6) * 3
        qdd = rng.normal(size=6) * 10
        t = rng.uniform(0, 1)
        Phi, J, Phit, gam = evaluate(c, t, q, qd)
        h = 1e-6
        Jfd = np.empty_like(J)
        for k in range(6):
            dq = np.zeros(6)
            dq[k] = h
            Jfd[:, k] = (evaluate(c, t, q + dq, qd)[0] - evaluate(c, t, q - dq, qd)[0]) / (2 * h)
        # central differences, h = 1e-6: truncation ~h² and round-off ~1e-16/h ≈ 1e-10
        np.testing.assert_allclose(J, Jfd, atol=1e-8)
        Phit_fd = (evaluate(c, t + h, q, qd)[0] - evaluate(c, t - h, q, qd)[0]) / (2 * h)
        np.testing.assert_allclose(Phit, Phit_fd, atol=1e-8)
        # along q(s) = q + qd s + ½ qdd s², Φ̈(0) = Φ_q q̈ − γ  [T4]
        s = 1e-4

        def phi_at(sv):
            return evaluate(c, t + sv, q + qd * sv + 0.5 * qdd * sv * sv, qd)[0]

        phidd = (phi_at(s) - 2 * phi_at(0.0) + phi_at(-s)) / s**2
        # second difference with s = 1e-4: truncation O(s²)·|Φ''''| ~ 1e-6, round-off ~1e-8
        np.testing.assert_allclose(phidd, J @ qdd - gam, atol=1e-5 * (1 + np.abs(J @ qdd).max()))


@pytest.mark.parametrize("kind", list(CONSTRAINTS.values()))
def test_scratch_trig_gives_the_same_numbers(kind):
    """eval_constraints_into (the bodies' cos φ, sin φ evaluated once into a scratch array [T223])
    writes what the wrapper writes, bit for bit, whatever the scratch held before; a revolute's
    Φ also against its closed form (numpy's sin/cos may differ from libm's in the last bit)."""
    from jointdyn.core.constraints import eval_constraints_into

    rng = np.random.default_rng(3)
    c = make(kind, "a", "b")
    cint, creal, m = constraint_table([c], INDEX.__getitem__, lambda b, p: POINTS[(b, p)], lambda b: 0.0)
    q, qd = rng.normal(size=6), rng.normal(size=6)
    first = [np.empty(m), np.empty((m, 6)), np.empty(m), np.empty(m)]
    second = [np.empty(m), np.empty((m, 6)), np.empty(m), np.empty(m)]
    eval_constraints(0.7, q, qd, cint, creal, *first)
    eval_constraints_into(0.7, q, qd, cint, creal, *second, np.full(6, np.nan))
    for a, b in zip(first, second):
        assert np.array_equal(a, b)
    if kind is Revolute:  # Φ = r_a + A(φ_a) s'_a − r_b − A(φ_b) s'_b  [T1, T5]

        def point(k, s):
            ca, sa = np.cos(q[3 * k + 2]), np.sin(q[3 * k + 2])
            return q[3 * k : 3 * k + 2] + np.array([ca * s[0] - sa * s[1], sa * s[0] + ca * s[1]])

        want = point(0, POINTS[("a", "p")]) - point(1, POINTS[("b", "p")])
        np.testing.assert_allclose(second[0], want, rtol=0, atol=1e-15)  # a few ulp of |q| ~ 1
