"""Viscous shear torques of a journal-bearing film on journal and bushing [T75] (compiled; used
by the bearing element and by the steady design quantities of :mod:`jointdyn.bearing`)."""

from __future__ import annotations

import math

from numba import njit


@njit(cache=True)
def couette_torque(xi, mu, R, L, c, omega_rel):
    """M_C = 2πμ ω_rel R³L/(c√(1−ξ²)) [N·m] (full-film Couette shear; ω_rel = ω_J − ω_B [rad/s]) [T75]."""
    return 2.0 * math.pi * mu * omega_rel * R * R * R * L / (c * math.sqrt((1.0 - xi) * (1.0 + xi)))


@njit(cache=True)
def shear_torques(xi, F_t, mu, R, L, c, omega_journal, omega_bearing):
    """(M_J, M_B) [N·m]: film torques about +z on journal and bushing [T75].

    xi             eccentricity ratio, 0 ≤ ξ < 1 [-]
    F_t            tangential film force on the journal (along t = ẑ × e/|e|) [N]
    mu             viscosity [Pa·s]; R, L, c journal radius, length, radial clearance [m]
    omega_journal  absolute angular velocity of the journal ω_J [rad/s]
    omega_bearing  absolute angular velocity of the bushing ω_B [rad/s]
    """
    mc = couette_torque(xi, mu, R, L, c, omega_journal - omega_bearing)
    half = 0.5 * c * xi * F_t
    return -mc - half, mc - half
