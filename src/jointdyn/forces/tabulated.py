"""Tabulated external force on a body point (e.g. a gas-pressure force on a piston)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from numba import njit

from jointdyn.core.kinematics import body_state, point_kinematics
from jointdyn.core.layout import ETA_J, HEADER, POINTS, XI_J, Layout

TABULATED_FORCE = 3
TIME = -2  # "argument" slot value: the argument is the time
REAL = Layout(POINTS + ("direction_x", "direction_y", "period"))
INT = Layout(HEADER + ("table", "argument", "rows"))
OUTPUTS = {"px": "m", "py": "m", "argument": "s or rad", "Fx": "N", "Fy": "N", "power": "W"}
DIR_X, DIR_Y, PERIOD = REAL.slots("direction_x", "direction_y", "period")
TABLE, ARGUMENT, ROWS = INT.slots("table", "argument", "rows")
O_PX, O_PY, O_ARG, O_FX, O_FY, O_POWER = Layout(OUTPUTS).slots(*OUTPUTS)


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
    REAL: ClassVar[Layout] = REAL
    INT: ClassVar[Layout] = INT
    OUTPUTS: ClassVar[dict[str, str]] = OUTPUTS
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
    def example(cls):
        """A gas-force-like table on point "B" of body "b", argument the angle of body "a"."""
        return cls("b", "B", x=(0.0, 1.0, 2.5, 6.3), y=(0.0, 300.0, 50.0, 0.0), argument="a", period=6.3)

    def pack(self, tables: list, body_index) -> tuple[dict, dict, dict]:
        """Element-specific slots (ints, reals, blocks); the (x, y) table is appended to ``tables``."""
        tables.append(np.column_stack([self.x, self.y]).astype(float))
        d = np.asarray(self.direction, float)
        d = d / np.hypot(*d)
        arg = TIME if self.argument == "time" else body_index(self.argument)
        ints = {"table": len(tables) - 1, "argument": arg, "rows": len(self.x)}
        return ints, {"direction_x": d[0], "direction_y": d[1], "period": self.period}, {}

    @classmethod
    def from_csv(cls, path, body_j, point_j, **kw):
        """Read the table from a two-column CSV (header line, then x, y rows)."""
        data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
        return cls(body_j, point_j, tuple(map(float, data[:, 0])), tuple(map(float, data[:, 1])), **kw)


@njit(cache=True)
def table_value(t, q, qd, ip, r, tab):
    """(s, f(s), f′(s)) of a tabulated force [T17]: its argument s (time or a body's angle,
    wrapped by the period), the table linearly interpolated (held constant beyond its ends) and
    the slope of the cell s lies in (right-hand cell at a node, 0 beyond the ends) [T118]."""
    n = ip[ROWS]
    if ip[ARGUMENT] == TIME:
        s = t
    else:
        s = body_state(q, qd, ip[ARGUMENT])[2]
    if r[PERIOD] > 0.0:
        s = s - r[PERIOD] * math.floor(s / r[PERIOD])
    if s <= tab[0, 0]:
        return s, tab[0, 1], 0.0
    if s >= tab[n - 1, 0]:
        return s, tab[n - 1, 1], 0.0
    lo = 0
    hi = n - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if tab[mid, 0] <= s:
            lo = mid
        else:
            hi = mid
    w = (s - tab[lo, 0]) / (tab[hi, 0] - tab[lo, 0])
    return s, (1.0 - w) * tab[lo, 1] + w * tab[hi, 1], (tab[hi, 1] - tab[lo, 1]) / (tab[hi, 0] - tab[lo, 0])


@njit(cache=True)
def tabulated_force(t, q, qd, bj, ip, r, tab, Q, out):
    """Apply the tabulated force [T17] (slots: ``INT``, ``REAL``); tab rows (x, y)."""
    s, f, _ = table_value(t, q, qd, ip, r, tab)
    fx = f * r[DIR_X]
    fy = f * r[DIR_Y]
    px, py, sx, sy, vx, vy = point_kinematics(q, qd, bj, r[XI_J], r[ETA_J])
    if bj >= 0:
        k = 3 * bj
        Q[k] += fx
        Q[k + 1] += fy
        Q[k + 2] += sx * fy - sy * fx
    out[O_PX] = px
    out[O_PY] = py
    out[O_ARG] = s
    out[O_FX] = fx
    out[O_FY] = fy
    out[O_POWER] = fx * vx + fy * vy
