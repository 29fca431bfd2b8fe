"""Rotational force elements: a cubic torsional spring–damper between two bodies (or a body and
the ground) and a harmonic driving torque on a body.

Both act on the body angles only (pure couples, no forces), so they need no points. Together
they turn a body on a revolute joint into a forced Duffing oscillator, e.g. the Ueda oscillator
(``examples/ueda.toml``) [T132–T134].
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from numba import njit

from jointdyn.core.layout import HEADER, POINTS, Layout, check_finite

TORSION_SPRING = 4
HARMONIC_TORQUE = 5

# -- torsional spring -------------------------------------------------------------------------
REAL = Layout(POINTS + ("stiffness", "cubic_stiffness", "damping", "free_angle"))
INT = Layout(HEADER)
OUTPUTS = {"angle": "rad", "angle_rate": "rad/s", "moment": "N·m", "energy": "J", "power": "W"}
K1, K3, C, THETA0 = REAL.slots("stiffness", "cubic_stiffness", "damping", "free_angle")
O_TH, O_THD, O_M, O_E, O_P = Layout(OUTPUTS).slots(*OUTPUTS)

# -- harmonic torque --------------------------------------------------------------------------
TREAL = Layout(POINTS + ("amplitude", "frequency", "phase"))
TOUTPUTS = {"moment": "N·m", "power": "W"}
AMP, OMEGA, PHASE = TREAL.slots("amplitude", "frequency", "phase")
TO_M, TO_P = Layout(TOUTPUTS).slots(*TOUTPUTS)


def _check(owner: str, name: str, v: float, unit: str, nonneg: bool) -> None:
    """One-line ValueError (a ``FieldError``) unless v is finite (and ≥ 0 if ``nonneg``)."""
    if nonneg:
        check_finite(owner, name, v, unit, "finite and ≥ 0", lambda x: x >= 0)
    else:
        check_finite(owner, name, v, unit, "finite", lambda x: True)


@dataclass(frozen=True)
class TorsionSpring:
    """Torsional spring–damper on the relative rotation θ = φ_j − φ_i − θ₀ [T132]: moment on
    body j M = −(k θ + k₃ θ³) − c θ̇, −M on body i (``"ground"`` allowed for either). Stored
    energy V = ½ k θ² + ¼ k₃ θ⁴ (output ``energy``). θ is the unwrapped angle difference, so
    several turns of wind-up are counted."""

    body_i: str
    """first body (``"ground"`` allowed)"""
    body_j: str
    """second body; θ = φ_j − φ_i − free_angle"""
    stiffness: float = 0.0
    """k, linear stiffness [N·m/rad]"""
    cubic_stiffness: float = 0.0
    """k₃, cubic stiffness (negative = softening) [N·m/rad³]"""
    damping: float = 0.0
    """c, viscous damping on θ̇ [N·m·s/rad]"""
    free_angle: float = 0.0
    """θ₀, relative angle at which the spring is relaxed [rad]"""
    code: ClassVar[int] = TORSION_SPRING
    REAL: ClassVar[Layout] = REAL
    INT: ClassVar[Layout] = INT
    OUTPUTS: ClassVar[dict[str, str]] = OUTPUTS
    """output columns (name -> unit): θ, θ̇, moment on body j, stored energy, power into the bodies"""
    MEMORY: ClassVar[dict[str, str]] = {}
    point_i: ClassVar[None] = None
    point_j: ClassVar[None] = None

    @classmethod
    def example(cls):
        """A stiffening spring–damper between bodies "a" and "b" (contract tests)."""
        return cls("a", "b", stiffness=50.0, cubic_stiffness=20.0, damping=0.3, free_angle=0.1)

    def validate(self):
        o = "TorsionSpring"
        _check(o, "stiffness", self.stiffness, "N·m/rad", True)
        _check(o, "cubic_stiffness", self.cubic_stiffness, "N·m/rad³", False)
        _check(o, "damping", self.damping, "N·m·s/rad", True)
        _check(o, "free_angle", self.free_angle, "rad", False)

    def pack(self, tables: list, body_index) -> tuple[dict, dict, dict]:
        """Element-specific slots (ints, reals, blocks) of the declared layouts."""
        reals = {
            "stiffness": self.stiffness,
            "cubic_stiffness": self.cubic_stiffness,
            "damping": self.damping,
            "free_angle": self.free_angle,
        }
        return {}, reals, {}


@dataclass(frozen=True)
class HarmonicTorque:
    """Prescribed moment M(t) = A cos(ω t + φ) on ``body_j`` [T133], reacted by the ground."""

    body_j: str
    """body the moment acts on"""
    amplitude: float
    """A [N·m]"""
    frequency: float
    """ω, angular frequency [rad/s]"""
    phase: float = 0.0
    """φ [rad]"""
    code: ClassVar[int] = HARMONIC_TORQUE
    REAL: ClassVar[Layout] = TREAL
    INT: ClassVar[Layout] = INT
    OUTPUTS: ClassVar[dict[str, str]] = TOUTPUTS
    """output columns (name -> unit): moment on body j, power into body j"""
    MEMORY: ClassVar[dict[str, str]] = {}
    body_i: ClassVar[str] = "ground"
    point_i: ClassVar[None] = None
    point_j: ClassVar[None] = None

    @classmethod
    def example(cls):
        """A 7.5 N·m moment at 1 rad/s on body "b" (contract tests)."""
        return cls("b", amplitude=7.5, frequency=1.0, phase=0.2)

    def validate(self):
        o = "HarmonicTorque"
        _check(o, "amplitude", self.amplitude, "N·m", False)
        _check(o, "frequency", self.frequency, "rad/s", True)
        _check(o, "phase", self.phase, "rad", False)

    def pack(self, tables: list, body_index) -> tuple[dict, dict, dict]:
        """Element-specific slots (ints, reals, blocks) of the declared layouts."""
        return {}, {"amplitude": self.amplitude, "frequency": self.frequency, "phase": self.phase}, {}


@njit(cache=True)
def torsion_spring(q, qd, bi, bj, r, Q, out):
    """Apply the torsional spring–damper of real-parameter row r [T132]; fill ``out``."""
    phi_i = q[3 * bi + 2] if bi >= 0 else 0.0
    phi_j = q[3 * bj + 2] if bj >= 0 else 0.0
    w_i = qd[3 * bi + 2] if bi >= 0 else 0.0
    w_j = qd[3 * bj + 2] if bj >= 0 else 0.0
    th = phi_j - phi_i - r[THETA0]
    thd = w_j - w_i
    th2 = th * th
    m = -(r[K1] + r[K3] * th2) * th - r[C] * thd
    if bj >= 0:
        Q[3 * bj + 2] += m
    if bi >= 0:
        Q[3 * bi + 2] -= m
    out[O_TH] = th
    out[O_THD] = thd
    out[O_M] = m
    out[O_E] = 0.5 * r[K1] * th2 + 0.25 * r[K3] * th2 * th2
    out[O_P] = m * thd


@njit(cache=True)
def harmonic_torque(t, qd, bj, r, Q, out):
    """Apply M(t) = A cos(ω t + φ) to body j [T133]; fill ``out``."""
    m = r[AMP] * math.cos(r[OMEGA] * t + r[PHASE])
    w = 0.0
    if bj >= 0:
        Q[3 * bj + 2] += m
        w = qd[3 * bj + 2]
    out[TO_M] = m
    out[TO_P] = m * w
