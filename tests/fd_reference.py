"""Step-size-robust finite differences used as the reference for the exact Jacobians.

Central differences with one Richardson extrapolation (error O(h⁴)), or one-sided differences
with two Richardson extrapolations (error O(h³)) next to a point where the function is only C¹
(a cell boundary of a table interpolant, ξ = 0). Each is evaluated on a geometric sequence of
steps h_max·4^−k and, per component, the estimate that agrees best with both its neighbours is
returned (the step
where truncation and rounding balance; the same idea as numdifftools). Steps are made exactly
representable ((x + h) − x), so the reference measures the derivative, not the rounding of x + h.
"""

from __future__ import annotations

import numpy as np


def _exact_step(x, h):
    return (x + h) - x


def _central1(f, x, h):
    h = _exact_step(x, h)
    h2 = _exact_step(x, h / 2)
    d1 = (np.asarray(f(x + h)) - np.asarray(f(x - h))) / (2 * h)
    d2 = (np.asarray(f(x + h2)) - np.asarray(f(x - h2))) / (2 * h2)
    return (4 * d2 - d1) / 3


def _one_sided1(f, x, h):
    f0 = np.asarray(f(x))
    d = []
    for s in (1.0, 0.5, 0.25):
        hs = _exact_step(x, h * s)
        d.append((np.asarray(f(x + hs)) - f0) / hs)
    r1 = 2 * d[1] - d[0]
    r2 = 2 * d[2] - d[1]
    return (4 * r2 - r1) / 3


def _best(rule, f, x, h_max, n):
    """Per component, the estimate that agrees best with both neighbours in the step sequence
    (two-sided, so two noise-dominated estimates agreeing by chance are not picked)."""
    est = np.array([np.atleast_1d(rule(f, x, h_max * 4.0**-k)) for k in range(n)])
    d = np.abs(np.diff(est, axis=0))  # d[k] = |D_k − D_{k+1}|
    score = np.full(est.shape, np.inf)
    score[1:-1] = np.maximum(d[:-1], d[1:])
    k = np.argmin(score, axis=0)
    return est[k, np.arange(est.shape[1])]


def central(f, x, h_max, n=7):
    """Derivative of f (vector-valued) at x by central differences with steps ≤ h_max."""
    return _best(_central1, f, x, h_max, n)


def one_sided(f, x, h_max, n=7):
    """One-sided derivative (h_max > 0: forward, < 0: backward) with steps ≤ |h_max|."""
    return _best(_one_sided1, f, x, h_max, n)


def element_jacobian_error(system, run, element: str, samples=(10, 20, 30), rows=None, check=None) -> float:
    """Largest relative difference [-] between the chained exact force Jacobian [T346] and plain
    central differences of one element's generalised force (steps 1e-8 m or rad in q, 1e-4 m/s or
    rad/s in q̇) at the given samples of ``run``, with the run's committed memory; over ``rows``
    (all when None). ``check(Q, t, q, qd, mem)`` runs extra assertions at each sample."""
    from jointdyn.forces.element_jacobians import _element_q, force_jacobian
    from jointdyn.forces.elements import NOUT, kinds_of

    P = system.packed()
    kinds = kinds_of(system.fint)
    n = system.n
    k = system.element_names.index(element)
    rows = slice(None) if rows is None else rows

    def Q(t, q, qd, mem):
        out = np.zeros(n)
        _element_q(t, q, qd, mem, P.fint, P.freal, P.tables, k, out, np.zeros((1, NOUT)), kinds)
        return out

    worst = 0.0
    for i in samples:
        y, mem, t = np.asarray(run.y[i]), np.ascontiguousarray(run.mem[i]), float(run.t[i])
        q, qd = y[:n].copy(), y[n:].copy()
        dq, dqd, dt = np.empty((n, n)), np.empty((n, n)), np.empty(n)
        assert force_jacobian(t, q, qd, mem, P.fint, P.freal, P.tables, dq, dqd, dt, kinds) == 0
        for exact, base, h, which in ((dq, q, 1e-8, 0), (dqd, qd, 1e-4, 1)):
            ref = np.empty((n, n))
            for j in range(n):
                a, b = base.copy(), base.copy()
                a[j] += h
                b[j] -= h
                qa, qb = (a, b) if which == 0 else (q, q)
                va, vb = (qd, qd) if which == 0 else (a, b)
                ref[:, j] = (Q(t, qa, va, mem) - Q(t, qb, vb, mem)) / (2.0 * h)
            worst = max(worst, float(np.abs(exact[rows] - ref[rows]).max() / np.abs(ref[rows]).max()))
        if check is not None:
            check(Q, t, q, qd, mem)
    return worst
