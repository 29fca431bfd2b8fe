"""Planar kinematics of a point fixed in a body (pure, compiled).

A body k has absolute coordinates q_k = (x, y, φ) [m, m, rad]. A point with local coordinates
s' = (ξ, η) [m] is at r + A(φ) s' [T1]; A = [[cos φ, −sin φ], [sin φ, cos φ]] and
B = dA/dφ, so that B s' = ẑ × (A s') [T2]. Body index −1 is the ground (fixed, q = 0).
"""

from __future__ import annotations

import math

from numba import njit


@njit(cache=True)
def body_state(q, qd, b):
    """Coordinates and velocities of body ``b`` (−1 = ground): x, y, φ, ẋ, ẏ, φ̇."""
    if b < 0:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    k = 3 * b
    return q[k], q[k + 1], q[k + 2], qd[k], qd[k + 1], qd[k + 2]


@njit(cache=True)
def point_kinematics(q, qd, b, xi, eta):
    """World position p, body-fixed arm s = A s', and velocity of a body point [T1, T2].

    Returns (px, py, sx, sy, vx, vy) [m, m, m, m, m/s, m/s].
    """
    phi = body_state(q, qd, b)[2]
    return point_kinematics_trig(q, qd, b, xi, eta, math.cos(phi), math.sin(phi))


@njit(inline="always")
def point_kinematics_trig(q, qd, b, xi, eta, c, s):
    """:func:`point_kinematics` with c = cos φ_b, s = sin φ_b given (evaluated once per body and
    evaluation, :func:`body_trig`)."""
    x, y, _, xd, yd, phid = body_state(q, qd, b)
    sx = c * xi - s * eta
    sy = s * xi + c * eta
    return x + sx, y + sy, sx, sy, xd - phid * sy, yd + phid * sx


@njit(inline="always")
def body_trig(q, cs):
    """cs[3b] = cos φ_b, cs[3b + 1] = sin φ_b for every body b (cs has the length of q)."""
    for k in range(2, q.shape[0], 3):
        cs[k - 2] = math.cos(q[k])
        cs[k - 1] = math.sin(q[k])


@njit(inline="always")
def trig_of(cs, b):
    """(cos φ_b, sin φ_b) from :func:`body_trig`'s array; (1, 0) for the ground (b = −1)."""
    if b < 0:
        return 1.0, 0.0
    return cs[3 * b], cs[3 * b + 1]
