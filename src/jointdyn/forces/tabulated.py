"""Tabulated external force on a body point (e.g. a gas-pressure force on a piston)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from numba import njit

from ..kinematics import body_state, point_kinematics

TABULATED_FORCE = 3


@dataclass(frozen=True)
class TabulatedForce:
    """Force F(s)·d on ``point_j`` of ``body_j`` along the fixed world direction ``direction``;
    F from the table (``x``, ``y``) by linear interpolation [T17]. The argument s is the time
    [s] (``argument = "time"``) or the angle of a body [rad] (``argument`` = its name), wrapped
    into [0, ``period``) when ``period`` > 0 (e.g. 4π for a four-stroke cycle). Outside the
    table the end values hold. The reaction goes to the ground (an external force)."""

    body_j: str
    """body carrying point_j (the journal/pin side; ``"ground"`` allowed)"""
    point_j: str
    """name of a point of body_j (coordinates in the body frame)"""
    x: tuple[float, ...]
    """table abscissae, strictly increasing [s or rad]"""
    y: tuple[float, ...]
    """force values [N]"""
    direction: tuple[float, float] = (-1.0, 0.0)
    """world direction of the force (normalised on compile) [-]"""
    argument: str = "time"
    """``"time"`` or the name of the body whose angle is the argument"""
    period: float = 0.0
    """wrap the argument into [0, period) if > 0 [s or rad]"""
    code: ClassVar[int] = TABULATED_FORCE
    OUTPUTS: ClassVar[dict[str, str]] = {
        "px": "m",
        "py": "m",
        "argument": "s or rad",
        "Fx": "N",
        "Fy": "N",
        "power": "W",
    }
    """output columns written by the kernel (name -> unit), world frame"""
    MEMORY: ClassVar[dict[str, str]] = {}
    body_i: ClassVar[str] = "ground"
    point_i: ClassVar[None] = None

    def validate(self):
        o = "TabulatedForce"
        x, y = np.asarray(self.x, float), np.asarray(self.y, float)
        if x.ndim != 1 or x.size < 2 or x.shape != y.shape:
            raise ValueError(f"{o}.x/y: need two 1-D arrays of equal length ≥ 2; got {x.shape} and {y.shape}")
        if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
            raise ValueError(f"{o}.x/y [s or rad, N]: values must be finite")
        if np.any(np.diff(x) <= 0):
            raise ValueError(f"{o}.x [s or rad]: must be strictly increasing")
        d = np.asarray(self.direction, float)
        if d.shape != (2,) or not np.all(np.isfinite(d)) or np.hypot(*d) == 0:
            raise ValueError(f"{o}.direction = {self.direction!r} [-]: must be a non-zero 2-vector")
        if not (math.isfinite(self.period) and self.period >= 0):
            raise ValueError(f"{o}.period = {self.period!r} [s or rad]: must be ≥ 0")

    @classmethod
    def from_csv(cls, path, body_j, point_j, **kw):
        """Read the table from a two-column CSV (header line, then x, y rows)."""
        data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
        return cls(body_j, point_j, tuple(map(float, data[:, 0])), tuple(map(float, data[:, 1])), **kw)


@njit(cache=True)
def tabulated_force(t, q, qd, bj, ip, r, tab, Q, out):
    """Apply the tabulated force [T17]: ip = [type, −1, j, table, arg body (−2 = time), n];
    r = [0, 0, ξ_j, η_j, d_x, d_y, period]; tab rows (x, y)."""
    n = ip[5]
    if ip[4] == -2:
        s = t
    else:
        s = body_state(q, qd, ip[4])[2]
    if r[6] > 0.0:
        s = s - r[6] * math.floor(s / r[6])
    if s <= tab[0, 0]:
        f = tab[0, 1]
    elif s >= tab[n - 1, 0]:
        f = tab[n - 1, 1]
    else:
        lo = 0
        hi = n - 1
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if tab[mid, 0] <= s:
                lo = mid
            else:
                hi = mid
        w = (s - tab[lo, 0]) / (tab[hi, 0] - tab[lo, 0])
        f = (1.0 - w) * tab[lo, 1] + w * tab[hi, 1]
    fx = f * r[4]
    fy = f * r[5]
    px, py, sx, sy, vx, vy = point_kinematics(q, qd, bj, r[2], r[3])
    if bj >= 0:
        k = 3 * bj
        Q[k] += fx
        Q[k + 1] += fy
        Q[k + 2] += sx * fy - sy * fx
    out[0] = px
    out[1] = py
    out[2] = s
    out[3] = fx
    out[4] = fy
    out[5] = fx * vx + fy * vy
