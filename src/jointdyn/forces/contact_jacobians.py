"""Exact derivatives of the contact and friction kernels (compiled) [T96, T97].

``contact_jac(code, delta, delta_dot, delta_dot0, p) -> (F_n, ∂F_n/∂δ, ∂F_n/∂δ̇)`` [N, N/m, N·s/m]
mirrors :func:`jointdyn.forces.contact_laws.contact_force` (δ̇⁻ is element memory, a constant
within a step). ``friction_jac(code, vt, p) -> (μ_eff, dμ_eff/dv_t)`` [-, s/m] mirrors
:func:`jointdyn.forces.friction_laws.friction_coefficient`. Where a law is clamped (F_n = 0 while
separating) or not differentiable (δ = 0, the ramp ends of Ambrósio's law), the one-sided
derivative of the branch the kernel takes is returned.
"""

from __future__ import annotations

import math

from numba import njit

from .contact_laws import FLORES, HERTZ, HUNT_CROSSLEY, KELVIN_VOIGT, LANKARANI_NIKRAVESH
from .friction_laws import AMBROSIO, COULOMB


@njit(cache=True)
def contact_jac(code, delta, delta_dot, delta_dot0, p):
    """F_n and its partial derivatives w.r.t. δ and δ̇ [T96]."""
    if delta <= 0.0:
        return 0.0, 0.0, 0.0
    K = p[0]
    if code == KELVIN_VOIGT:
        f = K * delta + p[2] * delta_dot  # [T55]
        if f > 0.0:
            return f, K, p[2]
        return 0.0, 0.0, 0.0
    n = p[1]
    fe = K * delta**n
    fe_d = n * K * delta ** (n - 1.0)
    cr = p[2]
    if code == HERTZ:
        return fe, fe_d, 0.0
    if code == LANKARANI_NIKRAVESH:
        chi = 0.75 * (1.0 - cr * cr)
    elif code == HUNT_CROSSLEY:
        chi = 1.5 * (1.0 - cr)
    elif code == FLORES:
        chi = 8.0 * (1.0 - cr) / (5.0 * cr)
    else:
        return math.nan, math.nan, math.nan
    fac = 1.0 + chi * delta_dot / delta_dot0
    f = fe * fac
    if f > 0.0:
        return f, fe_d * fac, fe * chi / delta_dot0
    return 0.0, 0.0, 0.0


@njit(cache=True)
def friction_jac(code, vt, p):
    """μ_eff(v_t) and dμ_eff/dv_t [T97]."""
    if code == COULOMB:
        x = vt / p[1]
        ch = math.cosh(min(abs(x), 700.0))
        return p[0] * math.tanh(x), p[0] / (ch * ch) / p[1]  # sech² without 1 − tanh² cancellation
    if code == AMBROSIO:
        a = abs(vt)
        v0 = p[1]
        v1 = p[2]
        sg = 1.0 if vt > 0 else -1.0
        if a <= v0:
            return 0.0, 0.0
        if a >= v1:
            return p[0] * sg, 0.0
        x = (a - v0) / (v1 - v0)
        cd = x * x * (3.0 - 2.0 * x)
        return p[0] * cd * sg, p[0] * 6.0 * x * (1.0 - x) / (v1 - v0)
    return 0.0, 0.0
