"""Exact derivatives of the contact and friction kernels (compiled) [T96, T97].

One function per registered law, with its kernel's arguments:
``<law>_jac(delta, delta_dot, delta_dot0, p) -> (F_n, ∂F_n/∂δ, ∂F_n/∂δ̇)`` [N, N/m, N·s/m] (δ̇⁻
is element memory, a constant within a step) and ``<law>_jac(vt, p) -> (μ_eff, dμ_eff/dv_t)``
[-, s/m]; ``contact_jac(code, …)`` and ``friction_jac(code, …)`` dispatch like
``contact_force`` and ``friction_coefficient``. Where a law is clamped (F_n = 0 while separating)
or not differentiable (δ = 0, the ramp ends of Ambrósio's law) the derivative of the branch the
kernel takes is returned.
"""

from __future__ import annotations

import math

from numba import njit

from .contact_laws import (
    EXPONENT,
    FLORES,
    HERTZ,
    HUNT_CROSSLEY,
    KELVIN_VOIGT,
    KV_DAMPING,
    KV_STIFFNESS,
    LANKARANI_NIKRAVESH,
    RESTITUTION,
    STIFFNESS,
)


@njit(cache=True)
def _damped_jac(p, chi, delta, delta_dot, delta_dot0):
    """Kδⁿ(1 + χδ̇/δ̇⁻) clamped ≥ 0 and its derivatives [T96]."""
    K = p[STIFFNESS]
    n = p[EXPONENT]
    fe = K * delta**n
    fac = 1.0 + chi * delta_dot / delta_dot0
    f = fe * fac
    if f > 0.0:
        return f, n * K * delta ** (n - 1.0) * fac, fe * chi / delta_dot0
    return 0.0, 0.0, 0.0


@njit(cache=True)
def hertz_jac(delta, delta_dot, delta_dot0, p):
    """Hertz [T51]: (Kδⁿ, nKδ^{n−1}, 0) [T96]."""
    K = p[STIFFNESS]
    n = p[EXPONENT]
    return K * delta**n, n * K * delta ** (n - 1.0), 0.0


@njit(cache=True)
def lankarani_nikravesh_jac(delta, delta_dot, delta_dot0, p):
    """Lankarani–Nikravesh [T52], χ = 3(1 − c_r²)/4 [T96]."""
    cr = p[RESTITUTION]
    return _damped_jac(p, 0.75 * (1.0 - cr * cr), delta, delta_dot, delta_dot0)


@njit(cache=True)
def hunt_crossley_jac(delta, delta_dot, delta_dot0, p):
    """Hunt–Crossley [T53], χ = 3(1 − c_r)/2 [T96]."""
    return _damped_jac(p, 1.5 * (1.0 - p[RESTITUTION]), delta, delta_dot, delta_dot0)


@njit(cache=True)
def flores_jac(delta, delta_dot, delta_dot0, p):
    """Flores et al. [T54], χ = 8(1 − c_r)/(5c_r) [T96]."""
    cr = p[RESTITUTION]
    return _damped_jac(p, 8.0 * (1.0 - cr) / (5.0 * cr), delta, delta_dot, delta_dot0)


@njit(cache=True)
def kelvin_voigt_jac(delta, delta_dot, delta_dot0, p):
    """Kelvin–Voigt [T55]: (Kδ + Dδ̇, K, D), 0 where clamped [T96]."""
    f = p[KV_STIFFNESS] * delta + p[KV_DAMPING] * delta_dot
    if f > 0.0:
        return f, p[KV_STIFFNESS], p[KV_DAMPING]
    return 0.0, 0.0, 0.0


@njit(cache=True)
def contact_jac(code, delta, delta_dot, delta_dot0, p):
    """F_n and ∂F_n/∂(δ, δ̇) of the law with registry code ``code``; zeros for δ ≤ 0, NaNs for an
    unknown code (callers fall back to finite differences) [T96]."""
    if delta <= 0.0:
        return 0.0, 0.0, 0.0
    if code == HERTZ:
        return hertz_jac(delta, delta_dot, delta_dot0, p)
    if code == LANKARANI_NIKRAVESH:
        return lankarani_nikravesh_jac(delta, delta_dot, delta_dot0, p)
    if code == HUNT_CROSSLEY:
        return hunt_crossley_jac(delta, delta_dot, delta_dot0, p)
    if code == FLORES:
        return flores_jac(delta, delta_dot, delta_dot0, p)
    if code == KELVIN_VOIGT:
        return kelvin_voigt_jac(delta, delta_dot, delta_dot0, p)
    return math.nan, math.nan, math.nan
