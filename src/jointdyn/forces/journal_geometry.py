"""Kinematics of a journal element's pair of points [T14] and its contact penetration [T16]."""

from __future__ import annotations

import math

from numba import njit

from jointdyn.core.kinematics import body_state, point_kinematics
from jointdyn.core.layout import ETA_I, ETA_J, XI_I, XI_J

# slots of the journal element's real row used here (``journal.REAL``: points, R_B, R_J, L, μ, c, h_a)
CLR, H_ASP = 8, 9


@njit(cache=True)
def journal_kinematics(q, qd, bi, bj, r):
    """e, ė [m, m/s], arms s_i, s_j [m] and body rates ω_i, ω_j [rad/s] [T14]."""
    pix, piy, six, siy, vix, viy = point_kinematics(q, qd, bi, r[XI_I], r[ETA_I])
    pjx, pjy, sjx, sjy, vjx, vjy = point_kinematics(q, qd, bj, r[XI_J], r[ETA_J])
    wi = body_state(q, qd, bi)[5]
    wj = body_state(q, qd, bj)[5]
    return pjx - pix, pjy - piy, vjx - vix, vjy - viy, six, siy, sjx, sjy, wi, wj


@njit(cache=True)
def penetration(q, qd, bi, bj, r):
    """Contact penetration δ = |e| − c_c [m] and its rate δ̇ [m/s] [T16]."""
    ex, ey, edx, edy, six, siy, sjx, sjy, wi, wj = journal_kinematics(q, qd, bi, bj, r)
    e = math.sqrt(ex * ex + ey * ey)
    ed = (ex * edx + ey * edy) / e if e > 0.0 else math.sqrt(edx * edx + edy * edy)
    return e - (r[CLR] - r[H_ASP]), ed
