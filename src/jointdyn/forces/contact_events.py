"""Contact events of journal elements inside the compiled step loop [T200–T204].

Two pieces the step-control loop (``integrators.driver``) calls besides the existing onset
rejection (``elements.onset_fraction``) and linear step limit (``elements.step_limit``):

* :func:`onset_limit` — the step that *lands* on a predicted contact onset: δ(t) is extrapolated
  to second order from the step's start, δ + δ̇h + ½δ̈h² (δ̈ from the accelerations the method
  already has, f(t, y)), and the step is limited to reach half the onset tolerance [T201]. The
  linear limit of ``step_limit`` (gap/δ̇) overshoots a journal that accelerates towards the wall
  and lets a free-flight step grow into the contact, where the error test rejects it
  repeatedly.
* :func:`refine_peaks` — the largest penetration *between* two accepted step ends, from the
  cubic Hermite interpolant of δ(t) through (δ, δ̇) at both ends [T202]; the element's
  ``max_penetration`` memory thus measures the continuous trajectory instead of where the steps
  happen to end.

Penetration δ = |e| − c_c [m], δ̇ = u·ė [m/s], δ̈ = u·ë + (|ė|² − (u·ė)²)/|e| [m/s²] [T200].
"""

from __future__ import annotations

import math

from numba import njit

from jointdyn.core.layout import BODY_I, BODY_J, TYPE
from jointdyn.forces.journal import (
    CLR,
    CONTACT,
    H_ASP,
    IN_CONTACT,
    JOURNAL,
    MAX_PEN,
    NO_CONTACT,
    ONSET_TOL,
    journal_kinematics,
)


@njit(cache=True)
def _point_acc(qdd, b, sx, sy, w):
    """Acceleration of a body point with arm s = A s' [m]: r̈ + φ̈ ẑ×s − φ̇² s [m/s²] (ground: 0)."""
    if b < 0:
        return 0.0, 0.0
    k = 3 * b
    return qdd[k] - qdd[k + 2] * sy - w * w * sx, qdd[k + 1] + qdd[k + 2] * sx - w * w * sy


@njit(cache=True)
def penetration_rates(q, qd, qdd, bi, bj, r):
    """δ [m], δ̇ [m/s], δ̈ [m/s²] of a journal element [T200]; δ̈ = 0 at a centred journal."""
    ex, ey, edx, edy, six, siy, sjx, sjy, wi, wj = journal_kinematics(q, qd, bi, bj, r)
    e = math.sqrt(ex * ex + ey * ey)
    delta = e - (r[CLR] - r[H_ASP])
    if not e > 0.0:
        return delta, math.sqrt(edx * edx + edy * edy), 0.0
    ux = ex / e
    uy = ey / e
    dd = ux * edx + uy * edy
    aix, aiy = _point_acc(qdd, bi, six, siy, wi)
    ajx, ajy = _point_acc(qdd, bj, sjx, sjy, wj)
    ddd = ux * (ajx - aix) + uy * (ajy - aiy) + (edx * edx + edy * edy - dd * dd) / e
    return delta, dd, ddd


@njit(cache=True)
def first_root(a, b, c):
    """Smallest positive root of a·h² + b·h + c = 0 (c < 0: the target lies ahead) [s]; inf if
    none. Stable quadratic formula (Press et al., Numerical Recipes §5.6)."""
    if a == 0.0:
        return -c / b if b > 0.0 else math.inf
    disc = b * b - 4.0 * a * c
    if disc < 0.0:
        return math.inf
    qq = -0.5 * (b + math.copysign(math.sqrt(disc), b))
    best = math.inf
    if qq != 0.0:
        r1 = qq / a
        r2 = c / qq
        if r1 > 0.0:
            best = r1
        if 0.0 < r2 < best:
            best = r2
    return best


@njit(cache=True)
def onset_limit(q, qd, qdd, mem, fint, freal):
    """Step [s] that ends where the second-order prediction δ + δ̇h + ½δ̈h² reaches half the
    onset tolerance, for journal elements with a contact law that are not in contact [T201]
    (inf if no onset is predicted). Independent of the model's kinds: part of the step loop
    compiled at install, not of a kernel set [T383]."""
    h = math.inf
    for k in range(fint.shape[0]):
        if fint[k, TYPE] != JOURNAL or fint[k, CONTACT] == NO_CONTACT or mem[k, IN_CONTACT] > 0.5:
            continue
        d, dd, ddd = penetration_rates(q, qd, qdd, fint[k, BODY_I], fint[k, BODY_J], freal[k])
        target = 0.5 * freal[k, ONSET_TOL]
        if d >= target:
            continue  # already past the target: the onset rejection handles it
        h = min(h, first_root(0.5 * ddd, dd, d - target))
    return h


@njit(cache=True)
def hermite_peak(d0, v0, d1, v1, h):
    """Largest value of the cubic Hermite interpolant of δ(t) on a step of length h [s] through
    (d0, v0) and (d1, v1) [m, m/s], for v0 > 0 > v1 (one interior maximum) [T202]."""
    # p'(θ)/1 = Aθ² + Bθ + C with the derivatives of the Hermite basis
    a = 6.0 * (d0 - d1) + 3.0 * h * (v0 + v1)
    b = 6.0 * (d1 - d0) - h * (4.0 * v0 + 2.0 * v1)
    c = h * v0
    if abs(a) <= 1e-12 * (abs(b) + abs(c)):
        th = -c / b
    else:
        disc = max(b * b - 4.0 * a * c, 0.0)  # > 0: p'(0) > 0 > p'(1)
        qq = -0.5 * (b + math.copysign(math.sqrt(disc), b))
        th = qq / a
        if not 0.0 <= th <= 1.0:
            th = c / qq
    th = min(max(th, 0.0), 1.0)
    s = 1.0 - th
    p0 = (1.0 + 2.0 * th) * s * s * d0 + th * s * s * h * v0
    return p0 + th * th * (3.0 - 2.0 * th) * d1 + th * th * (th - 1.0) * h * v1


@njit(cache=True)
def refine_peaks(q0, qd0, q1, qd1, h, mem, fint, freal):
    """Raise ``max_penetration`` of every journal element with a contact law to the peak of δ
    inside an accepted step of length h [s] (Hermite interpolant of δ, [T202]); the step ends
    themselves are recorded by ``elements.advance_memory``. Independent of the kinds [T383]."""
    for k in range(fint.shape[0]):
        if fint[k, TYPE] != JOURNAL or fint[k, CONTACT] == NO_CONTACT:
            continue
        bi, bj = fint[k, BODY_I], fint[k, BODY_J]
        jk0 = journal_kinematics(q0, qd0, bi, bj, freal[k])
        jk1 = journal_kinematics(q1, qd1, bi, bj, freal[k])
        cc = freal[k, CLR] - freal[k, H_ASP]
        e0 = math.sqrt(jk0[0] * jk0[0] + jk0[1] * jk0[1])
        e1 = math.sqrt(jk1[0] * jk1[0] + jk1[1] * jk1[1])
        if not (e0 > 0.0 and e1 > 0.0):
            continue
        v0 = (jk0[0] * jk0[2] + jk0[1] * jk0[3]) / e0
        v1 = (jk1[0] * jk1[2] + jk1[1] * jk1[3]) / e1
        if v0 > 0.0 and v1 < 0.0:
            p = hermite_peak(e0 - cc, v0, e1 - cc, v1, h)
            if p > mem[k, MAX_PEN]:
                mem[k, MAX_PEN] = p
