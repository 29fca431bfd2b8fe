"""Ideal joints as kinematic constraints Φ(q, t) = 0 (paper eqs 10–11).

Each constraint adds rows to Φ, to its Jacobian Φ_q, to Φ_t and to the acceleration
right-hand side γ (Φ_q q̈ = γ) [T4]. The multipliers λ enter the equations of motion as
M q̈ = Q + Φ_qᵀ λ [T3], so Φ_qᵀ λ is the generalised constraint force. What λ means for each
constraint type is stated in its docstring and tested in ``tests/test_constraints.py``.

Implementer contract for a new constraint type:
1. a frozen dataclass below with its fields (they are the model-file schema), ``rows``, its
   ``REAL`` layout (the two points, then its own slots) and ``pack() -> {slot: value}``;
2. a branch in :func:`eval_constraints` filling Φ, Φ_q, Φ_t and γ for its rows through the slot
   constants of its layout, citing its tag;
3. an entry in :data:`CONSTRAINTS` and an ``example()``; the registry contract tests (finite-
   difference Jacobians, γ) then cover it automatically.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from numba import njit

from jointdyn.core.kinematics import body_state, body_trig, point_kinematics_trig, trig_of
from jointdyn.core.layout import BODY_I, BODY_J, ETA_I, ETA_J, HEADER, POINTS, TYPE, XI_I, XI_J, Layout

REVOLUTE = 0
TRANSLATIONAL = 1
ANGLE_DRIVER = 2
INT = Layout(HEADER + ("row",))
(ROW,) = INT.slots("row")
REVOLUTE_REAL = Layout(POINTS)
TRANSLATIONAL_REAL = Layout(POINTS + ("axis_x", "axis_y", "angle"))
ANGLE_DRIVER_REAL = Layout(POINTS + ("phi0", "omega", "alpha"))
AXIS_X, AXIS_Y, THETA0 = TRANSLATIONAL_REAL.slots("axis_x", "axis_y", "angle")
PHI0, OMEGA, ALPHA = ANGLE_DRIVER_REAL.slots("phi0", "omega", "alpha")


@dataclass(frozen=True)
class Revolute:
    """Ideal pin: point ``point_i`` of ``body_i`` coincides with ``point_j`` of ``body_j`` [T5].

    Φ = (r_i + A_i s'_i) − (r_j + A_j s'_j). λ = (λ_x, λ_y) is the reaction force the joint
    applies to body i, world frame [N]; body j receives −λ.
    """

    body_i: str
    """body carrying point_i (the bearing/hole side; ``"ground"`` allowed)"""
    point_i: str
    """name of a point of body_i (coordinates in the body frame)"""
    body_j: str
    """body carrying point_j (the journal/pin side; ``"ground"`` allowed)"""
    point_j: str
    """name of a point of body_j (coordinates in the body frame)"""
    code: ClassVar[int] = REVOLUTE
    rows: ClassVar[int] = 2
    LAMBDA_UNITS: ClassVar[tuple[str, ...]] = ("N", "N")
    """unit of each λ row (generic code asks this; default: ``N`` per row)"""
    REAL: ClassVar[Layout] = REVOLUTE_REAL

    def pack(self, angle_of) -> dict:
        """Own slots of ``REAL`` beyond the two points (none)."""
        return {}

    @classmethod
    def example(cls):
        """A pin between two bodies' points "A" and "B" (for the contract tests)."""
        return cls("a", "A", "b", "B")


@dataclass(frozen=True)
class Translational:
    """Ideal slider: ``point_j`` of body j moves on the line through ``point_i`` of body i along
    the body-i direction ``axis`` (unit vector, local frame); relative rotation locked [T6].

    Rows: Φ₁ = nᵀ(P_j − P_i) with n = A_i (ẑ × axis), Φ₂ = φ_j − φ_i − θ₀ (θ₀ taken from the
    assembled configuration). λ₁ is the normal force on body j along n [N] (body i gets −λ₁ n,
    moments from the points); λ₂ is the locking moment on body j [N·m] (−λ₂ on body i).
    """

    body_i: str
    """body carrying point_i (the bearing/hole side; ``"ground"`` allowed)"""
    point_i: str
    """name of a point of body_i (coordinates in the body frame)"""
    body_j: str
    """body carrying point_j (the journal/pin side; ``"ground"`` allowed)"""
    point_j: str
    """name of a point of body_j (coordinates in the body frame)"""
    axis: tuple[float, float] = (1.0, 0.0)
    """guide direction in body i's frame (normalised on compile) [-]"""
    angle: float | None = None
    """locked relative angle θ₀ = φ_j − φ_i; None takes it from the initial guess [rad]"""
    code: ClassVar[int] = TRANSLATIONAL
    rows: ClassVar[int] = 2
    LAMBDA_UNITS: ClassVar[tuple[str, ...]] = ("N", "N·m")
    """the normal force, then the moment that keeps the angle"""
    REAL: ClassVar[Layout] = TRANSLATIONAL_REAL

    def pack(self, angle_of) -> dict:
        """Own slots of ``REAL``: unit guide axis [-] and locked angle θ₀ [rad]."""
        ax = np.asarray(self.axis, dtype=float)
        ax = ax / np.hypot(*ax)
        th0 = self.angle if self.angle is not None else angle_of(self.body_j) - angle_of(self.body_i)
        return {"axis_x": ax[0], "axis_y": ax[1], "angle": th0}

    @classmethod
    def example(cls):
        """A slider along an oblique axis (for the contract tests)."""
        return cls("a", "A", "b", "B", axis=(0.6, 0.8))


@dataclass(frozen=True)
class AngleDriver:
    """Rheonomic driver: φ_j − φ_i = φ₀ + ω t + ½ α t² [T7].

    ``body_i`` is the reference (usually ``"ground"``). λ is the driving moment the driver
    applies to body j, positive counter-clockwise [N·m] (body i receives −λ).
    """

    body_i: str
    """body carrying point_i (the bearing/hole side; ``"ground"`` allowed)"""
    body_j: str
    """body carrying point_j (the journal/pin side; ``"ground"`` allowed)"""
    phi0: float = 0.0
    """initial relative angle [rad]"""
    omega: float = 0.0
    """constant angular speed [rad/s]"""
    alpha: float = 0.0
    """constant angular acceleration [rad/s²]"""
    code: ClassVar[int] = ANGLE_DRIVER
    rows: ClassVar[int] = 1
    LAMBDA_UNITS: ClassVar[tuple[str, ...]] = ("N·m",)
    """the driving moment"""
    DRIVES_ANGLE: ClassVar[bool] = True
    """it turns ``body_j`` (``Results.driver``/``crank_angle`` look for the first such constraint)"""
    REAL: ClassVar[Layout] = ANGLE_DRIVER_REAL
    point_i: ClassVar[None] = None
    point_j: ClassVar[None] = None

    def pack(self, angle_of) -> dict:
        """Own slots of ``REAL``: φ₀ [rad], ω [rad/s], α [rad/s²]."""
        return {"phi0": self.phi0, "omega": self.omega, "alpha": self.alpha}

    @classmethod
    def example(cls):
        """An accelerating driver (for the contract tests)."""
        return cls("a", "b", phi0=0.3, omega=2.0, alpha=0.5)


CONSTRAINTS = {"revolute": Revolute, "translational": Translational, "angle_driver": AngleDriver}


@njit(cache=True)
def _add_point_jac(J, r, col_b, sign, sx, sy):
    """Add sign·[I, B s'] (B s' = (−s_y, s_x)) of a body point to rows r, r+1 [T2]."""
    if col_b < 0:
        return
    k = 3 * col_b
    J[r, k] += sign
    J[r + 1, k + 1] += sign
    J[r, k + 2] += -sign * sy
    J[r + 1, k + 2] += sign * sx


@njit(cache=True)
def translational_frame(q, qd, bi, bj, row):
    """Geometry of a translational row [T6]: arms s_i, s_j [m], rates ω_i, ω_j [rad/s], the
    world normal n = A_i(ẑ × axis) and B n = ẑ × n [-], d = P_j − P_i [m] and ḋ [m/s]."""
    phii = body_state(q, qd, bi)[2]
    phij = body_state(q, qd, bj)[2]
    return translational_frame_trig(
        q, qd, bi, bj, row, math.cos(phii), math.sin(phii), math.cos(phij), math.sin(phij)
    )


@njit(inline="always")
def translational_frame_trig(q, qd, bi, bj, row, ci, si, cj, sj):
    """:func:`translational_frame` with the bodies' cos φ, sin φ given."""
    pix, piy, six, siy, vix, viy = point_kinematics_trig(q, qd, bi, row[XI_I], row[ETA_I], ci, si)
    pjx, pjy, sjx, sjy, vjx, vjy = point_kinematics_trig(q, qd, bj, row[XI_J], row[ETA_J], cj, sj)
    wi = body_state(q, qd, bi)[5]
    wj = body_state(q, qd, bj)[5]
    nlx = -row[AXIS_Y]  # local normal n' = ẑ × axis
    nly = row[AXIS_X]
    nx = ci * nlx - si * nly
    ny = si * nlx + ci * nly
    return (six, siy, sjx, sjy, wi, wj, nx, ny, -ny, nx, pjx - pix, pjy - piy, vjx - vix, vjy - viy)


@njit(cache=True)
def eval_constraints(t, q, qd, cint, creal, Phi, J, Phit, gam):
    """Fill Φ, Φ_q (J, zeroed here), Φ_t and γ with Φ_q q̈ = γ [T4–T7]."""
    eval_constraints_into(t, q, qd, cint, creal, Phi, J, Phit, gam, np.empty(q.shape[0]))


@njit(cache=True)
def eval_constraints_into(t, q, qd, cint, creal, Phi, J, Phit, gam, cs):
    """:func:`eval_constraints` with scratch ``cs`` (length of q) for the bodies' cos φ, sin φ,
    evaluated once per body instead of once per constraint touching it [T223]."""
    J[:, :] = 0.0
    body_trig(q, cs)
    for k in range(cint.shape[0]):
        typ = cint[k, TYPE]
        bi = cint[k, BODY_I]
        bj = cint[k, BODY_J]
        r = cint[k, ROW]
        if typ == REVOLUTE:
            ci, si = trig_of(cs, bi)
            cj, sj = trig_of(cs, bj)
            row = creal[k]
            pix, piy, six, siy, vix, viy = point_kinematics_trig(q, qd, bi, row[XI_I], row[ETA_I], ci, si)
            pjx, pjy, sjx, sjy, vjx, vjy = point_kinematics_trig(q, qd, bj, row[XI_J], row[ETA_J], cj, sj)
            wi = body_state(q, qd, bi)[5]
            wj = body_state(q, qd, bj)[5]
            Phi[r] = pix - pjx
            Phi[r + 1] = piy - pjy
            Phit[r] = 0.0
            Phit[r + 1] = 0.0
            _add_point_jac(J, r, bi, 1.0, six, siy)
            _add_point_jac(J, r, bj, -1.0, sjx, sjy)
            # γ = φ̇_i² A_i s'_i − φ̇_j² A_j s'_j  [T5]
            gam[r] = wi * wi * six - wj * wj * sjx
            gam[r + 1] = wi * wi * siy - wj * wj * sjy
        elif typ == TRANSLATIONAL:
            # n = A_i(ẑ × axis), Bn = ẑ × n, d = P_j − P_i  [T6]
            ci, si = trig_of(cs, bi)
            cj, sj = trig_of(cs, bj)
            six, siy, sjx, sjy, wi, wj, nx, ny, bnx, bny, dx, dy, ddx, ddy = translational_frame_trig(
                q, qd, bi, bj, creal[k], ci, si, cj, sj
            )
            phii = body_state(q, qd, bi)[2]
            phij = body_state(q, qd, bj)[2]
            Phi[r] = nx * dx + ny * dy
            Phit[r] = 0.0
            if bj >= 0:
                kj = 3 * bj
                J[r, kj] += nx
                J[r, kj + 1] += ny
                J[r, kj + 2] += -nx * sjy + ny * sjx
            if bi >= 0:
                ki = 3 * bi
                J[r, ki] += -nx
                J[r, ki + 1] += -ny
                J[r, ki + 2] += (bnx * dx + bny * dy) - (-nx * siy + ny * six)
            # γ = φ̇_i² nᵀd − 2φ̇_i (B_i n')ᵀ ḋ + φ̇_j² nᵀ s_j − φ̇_i² nᵀ s_i  [T6]
            gam[r] = (
                wi * wi * (nx * dx + ny * dy)
                - 2.0 * wi * (bnx * ddx + bny * ddy)
                + wj * wj * (nx * sjx + ny * sjy)
                - wi * wi * (nx * six + ny * siy)
            )
            Phi[r + 1] = phij - phii - creal[k, THETA0]
            Phit[r + 1] = 0.0
            gam[r + 1] = 0.0
            if bj >= 0:
                J[r + 1, 3 * bj + 2] += 1.0
            if bi >= 0:
                J[r + 1, 3 * bi + 2] += -1.0
        elif typ == ANGLE_DRIVER:
            phii = body_state(q, qd, bi)[2]
            phij = body_state(q, qd, bj)[2]
            phi0 = creal[k, PHI0]
            om = creal[k, OMEGA]
            al = creal[k, ALPHA]
            # Φ = φ_j − φ_i − (φ₀ + ωt + ½αt²), Φ_t = −(ω + αt), γ = α  [T7]
            Phi[r] = phij - phii - (phi0 + om * t + 0.5 * al * t * t)
            Phit[r] = -(om + al * t)
            gam[r] = al
            if bj >= 0:
                J[r, 3 * bj + 2] += 1.0
            if bi >= 0:
                J[r, 3 * bi + 2] += -1.0


def constraint_table(constraints, body_index, point_of, angle_of):
    """Pack constraint dataclasses into (cint, creal, total rows) through their layouts.

    ``body_index(name) -> int`` (−1 for ground), ``point_of(body, point) -> (ξ, η)`` [m],
    ``angle_of(body) -> φ`` of the initial guess [rad].
    """
    width = max(cls.REAL.width for cls in CONSTRAINTS.values())
    cint = np.zeros((len(constraints), INT.width), dtype=np.int64)
    creal = np.zeros((len(constraints), width))
    row = 0
    for k, c in enumerate(constraints):
        INT.pack(
            cint[k],
            {"type": c.code, "body_i": body_index(c.body_i), "body_j": body_index(c.body_j), "row": row},
        )
        row += c.rows
        pi = point_of(c.body_i, c.point_i) if c.point_i is not None else (0.0, 0.0)
        pj = point_of(c.body_j, c.point_j) if c.point_j is not None else (0.0, 0.0)
        points = {"xi_i": pi[0], "eta_i": pi[1], "xi_j": pj[0], "eta_j": pj[1]}
        type(c).REAL.pack(creal[k], {**points, **c.pack(angle_of)})
    return cint, creal, row
