"""Exact derivatives of the friction laws, μ_eff(v_t) and dμ_eff/dv_t (compiled) [T97]."""

from __future__ import annotations

import math

from numba import njit

from .friction_laws import A_MU, A_V0, A_V1, AMBROSIO, C_MU, C_VREG, COULOMB


@njit(cache=True)
def coulomb_jac(vt, p):
    """μ tanh(v_t/v_reg) [T61] and (μ/v_reg) sech²(v_t/v_reg), without 1 − tanh² cancellation [T97]."""
    x = vt / p[C_VREG]
    ch = math.cosh(min(abs(x), 700.0))
    return p[C_MU] * math.tanh(x), p[C_MU] / (ch * ch) / p[C_VREG]


@njit(cache=True)
def ambrosio_jac(vt, p):
    """Ambrósio's ramp [T62] and its derivative 6μx(1 − x)/(v₁ − v₀) on the ramp [T97]."""
    a = abs(vt)
    v0 = p[A_V0]
    v1 = p[A_V1]
    sg = 1.0 if vt > 0 else -1.0
    if a <= v0:
        return 0.0, 0.0
    if a >= v1:
        return p[A_MU] * 1.0 * sg, 0.0
    x = (a - v0) / (v1 - v0)
    cd = x * x * (3.0 - 2.0 * x)
    return p[A_MU] * cd * sg, p[A_MU] * 6.0 * x * (1.0 - x) / (v1 - v0)


@njit(cache=True)
def friction_jac(code, vt, p):
    """μ_eff(v_t) and dμ_eff/dv_t of the law ``code``; (0, 0) for ``NONE`` and unknown codes [T97]."""
    if code == COULOMB:
        return coulomb_jac(vt, p)
    if code == AMBROSIO:
        return ambrosio_jac(vt, p)
    return 0.0, 0.0
