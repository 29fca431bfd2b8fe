"""Linear spring–damper between two body points."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from numba import njit

from jointdyn.core.kinematics import point_kinematics
from jointdyn.core.layout import ETA_I, ETA_J, HEADER, POINTS, XI_I, XI_J, Layout
from jointdyn.forces.transfer import apply_pair, pair_power

SPRING_DAMPER = 0
REAL = Layout(POINTS + ("stiffness", "damping", "free_length"))
INT = Layout(HEADER)
OUTPUTS = {"dx": "m", "dy": "m", "length": "m", "length_rate": "m/s", "Fx": "N", "Fy": "N", "power": "W"}
K, D, L0 = REAL.slots("stiffness", "damping", "free_length")
O_DX, O_DY, O_LEN, O_LEND, O_FX, O_FY, O_POWER = Layout(OUTPUTS).slots(*OUTPUTS)


@dataclass(frozen=True)
class SpringDamper:
    """Point-to-point spring–damper [T9]: F_j = −[k (ℓ − ℓ₀) + d ℓ̇] u, u = (P_j − P_i)/ℓ."""

    body_i: str
    """body carrying point_i (the bearing/hole side; ``"ground"`` allowed)"""
    point_i: str
    """name of a point of body_i (coordinates in the body frame)"""
    body_j: str
    """body carrying point_j (the journal/pin side; ``"ground"`` allowed)"""
    point_j: str
    """name of a point of body_j (coordinates in the body frame)"""
    stiffness: float
    """k [N/m]"""
    damping: float = 0.0
    """d [N·s/m]"""
    free_length: float = 0.0
    """ℓ₀ [m]"""
    code: ClassVar[int] = SPRING_DAMPER
    REAL: ClassVar[Layout] = REAL
    INT: ClassVar[Layout] = INT
    OUTPUTS: ClassVar[dict[str, str]] = OUTPUTS
    """output columns written by the kernel (name -> unit), force on body j, world frame"""
    MEMORY: ClassVar[dict[str, str]] = {}

    @classmethod
    def example(cls):
        """A spring–damper between points "A" of body "a" and "B" of body "b" (contract tests)."""
        return cls("a", "A", "b", "B", stiffness=1e4, damping=20.0, free_length=0.01)

    def pack(self, tables: list, body_index) -> tuple[dict, dict, dict]:
        """Element-specific slots (ints, reals, blocks) of the declared layouts."""
        return {}, {"stiffness": self.stiffness, "damping": self.damping, "free_length": self.free_length}, {}

    def validate(self):
        for name, v, unit in (
            ("stiffness", self.stiffness, "N/m"),
            ("damping", self.damping, "N·s/m"),
            ("free_length", self.free_length, "m"),
        ):
            if not math.isfinite(v) or v < 0:
                raise ValueError(f"SpringDamper.{name} = {v!r} [{unit}]: must be finite and ≥ 0")


@njit(cache=True)
def spring_damper(q, qd, bi, bj, r, Q, out):
    """Apply the spring–damper of real-parameter row r [T9]; fill ``out`` (``OUTPUTS``)."""
    pix, piy, six, siy, vix, viy = point_kinematics(q, qd, bi, r[XI_I], r[ETA_I])
    pjx, pjy, sjx, sjy, vjx, vjy = point_kinematics(q, qd, bj, r[XI_J], r[ETA_J])
    dx = pjx - pix
    dy = pjy - piy
    ell = math.sqrt(dx * dx + dy * dy)
    if ell > 0.0:
        ux = dx / ell
        uy = dy / ell
    else:
        ux = 1.0
        uy = 0.0
    elld = ux * (vjx - vix) + uy * (vjy - viy)
    f = -(r[K] * (ell - r[L0]) + r[D] * elld)
    fx = f * ux
    fy = f * uy
    apply_pair(Q, bi, bj, fx, fy, sjx, sjy, six + dx, siy + dy)
    out[O_DX] = dx
    out[O_DY] = dy
    out[O_LEN] = ell
    out[O_LEND] = elld
    out[O_FX] = fx
    out[O_FY] = fy
    out[O_POWER] = pair_power(qd, bi, bj, fx, fy, sjx, sjy, six + dx, siy + dy)
