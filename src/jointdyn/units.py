"""Unit helpers for the edges of the library. Everything inside is SI [m, kg, s, rad, N]."""

from __future__ import annotations

import math


def rpm(value: float) -> float:
    """Revolutions per minute -> angular speed [rad/s]."""
    return float(value) * 2.0 * math.pi / 60.0


def mm(value: float) -> float:
    """Millimetres -> metres [m]."""
    return float(value) * 1e-3


def deg(value: float) -> float:
    """Degrees -> radians [rad]."""
    return math.radians(float(value))


def to_rpm(omega: float) -> float:
    """Angular speed [rad/s] -> revolutions per minute."""
    return float(omega) * 60.0 / (2.0 * math.pi)
