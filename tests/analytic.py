"""Independent closed-form references used by the tests (written apart from the library)."""

from __future__ import annotations

import numpy as np


def slider_crank_inverse_dynamics(
    t, omega, r=0.05, l=0.12, m=(0.30, 0.21, 0.14), I=(1.0e-4, 2.5e-4, 1.0e-4), g=9.81
):
    """Crank driving moment [N·m] of the ideal slider-crank at constant crank speed, from the
    power balance T·ω = dT_kin/dt + dV/dt with hand-derived kinematics (no multipliers)."""
    th = omega * t
    s, c = np.sin(th), np.cos(th)
    sb = -r * s / l
    cb = np.sqrt(1 - sb**2)
    bd = -r * omega * c / (l * cb)
    bdd = (r * omega**2 * s + l * sb * bd**2) / (l * cb)
    A = np.stack([r * c, r * s])
    Ad = np.stack([-r * omega * s, r * omega * c])
    Add = np.stack([-r * omega**2 * c, -r * omega**2 * s])
    xb = r * c + l * cb
    xbd = -r * omega * s - l * sb * bd
    xbdd = -r * omega**2 * c - l * cb * bd**2 - l * sb * bdd
    z = np.zeros_like(t)
    B = np.stack([xb, z])
    Bd = np.stack([xbd, z])
    Bdd = np.stack([xbdd, z])
    v1, a1 = Ad / 2, Add / 2
    v2, a2 = (Ad + Bd) / 2, (Add + Bdd) / 2
    v3, a3 = Bd, Bdd
    power = (
        m[0] * (v1 * a1).sum(0)
        + m[1] * (v2 * a2).sum(0)
        + I[1] * bd * bdd
        + m[2] * (v3 * a3).sum(0)
        + g * (m[0] * v1[1] + m[1] * v2[1] + m[2] * v3[1])
    )
    _ = (A, B)
    return power / omega
