"""Compiled film-force kernels of the closed-form film models and their dispatch by code.

All kernels share one signature ``kernel(xi, xi_dot, xi_Omega, mu, R, L, c, p, table) -> (Fr, Ft)``
(arguments and conventions in :mod:`jointdyn.film.models`, theory docs/theory.md [T20–T39]); the
registry with the dataclasses and the dispatch by code (generated from it [T229]) is
:mod:`jointdyn.film.models`, the exact Jacobians are :mod:`jointdyn.film.jacobians`.
"""

from __future__ import annotations

import math

from numba import njit

OTT = 0
ALSHAER2005 = 1
SHORT = 2
FINITE = 3


@njit(cache=True)
def _atan_y_over_y_minus_1(y):
    """atan(y)/y − 1 for y ≥ 0 without cancellation at small y [T23]."""
    if y < 0.1:
        # Σ_{n=1..9} (−1)^n y^{2n}/(2n+1); the first omitted term is < 1e-19 of the sum at y = 0.1
        z = y * y
        s = -1.0 / 19.0
        for n in range(8, 0, -1):
            s = (-1.0) ** n / (2.0 * n + 1.0) + z * s
        return z * s
    return math.atan(y) / y - 1.0


@njit(cache=True)
def pi_film_force(xi, xi_dot, xi_Omega, mu, R, L, c, p, table):
    """The paper's π-film long bearing (alshaer2005), branch-free compact form [T21] ([T163]).

    k = μLR³/c², A = ξ̇, B = ξΩ/(2+ξ²), ρ = √(A²+B²), w = 1−ξ² = (1−ξ)(1+ξ),
    Δδ = δ₂ − δ₁ = 2·atan2(ρ√w, −ξA) ∈ (0, 2π), film start θ₁ = atan2(A, B)  [T22]
    F_t = 6k·B·Δδ/√w,  F_r = −6k·[A·Δδ/w^{3/2} + 2ξρ/w]                   [T21]
    For A < 0 and y = ρ√w/(ξ|A|) < 1 (near the wall, ξ > 1/√2) the identical form
    F_r = 12k(ρ/ξ)·[1 + (atan(y)/y − 1)/w] avoids cancelling two O(1/w) terms; it is not used
    for y ≥ 1, where it would lose digits as ξ → 0 (error ~ ε_mach/ξ)               [T23]
    F = 0 at A = B = 0, its continuous limit (F is homogeneous of degree 1 in (A, B))  [T24]
    """
    A = xi_dot
    B = xi_Omega / (2.0 + xi * xi)
    rho = math.hypot(A, B)
    if rho == 0.0:
        return 0.0, 0.0
    k = mu * L * R * R * R / (c * c)
    w = (1.0 - xi) * (1.0 + xi)
    sw = math.sqrt(w)
    dd = 2.0 * math.atan2(rho * sw, -xi * A)
    ft = 6.0 * k * B * dd / sw
    if A < 0.0 and rho * sw < xi * -A:
        y = rho * sw / (xi * -A)
        fr = 12.0 * k * (rho / xi) * (1.0 + _atan_y_over_y_minus_1(y) / w)
    else:
        fr = -6.0 * k * (A * dd / (w * sw) + 2.0 * xi * rho / w)
    return fr, ft


@njit(cache=True)
def ott_force(xi, xi_dot, xi_Omega, mu, R, L, c, p, table):
    """Ott's long-bearing model (paper eqs 1–5) with (1−ξ²) denominators, ω-free form [T25]
    ([T163]):

    k = μLR³/c², w = 1−ξ², G = √(w(Ω² + 4ξ̇²/ξ²)), so ξ²G = ξ√(w((ξΩ)² + 4ξ̇²))   [T25]
    κ = G/(2|ξ̇|), Φ = (κ+3)/(κ+3/2) for ξ̇ > 0, κ/(κ+3/2) for ξ̇ < 0, 1 at ξ̇ = 0; written
    branch-free as Φ = 1 + 3ξξ̇/(√w·hypot(ξΩ, 2ξ̇) + 3ξ|ξ̇|)                       [T26]
    F_t = 6πk·ξΩ·Φ/[(2+ξ²)√w],  F_r = −3k[4ξ²G + 2π(2+ξ²)ξ̇Φ]/[(2+ξ²)w^{3/2}]        [T25]
    F = 0 at ξ̇ = ξΩ = 0.
    """
    h = math.hypot(xi_Omega, 2.0 * xi_dot)
    if h == 0.0:
        return 0.0, 0.0
    k = mu * L * R * R * R / (c * c)
    w = (1.0 - xi) * (1.0 + xi)
    sw = math.sqrt(w)
    s = 2.0 + xi * xi
    x2g = xi * sw * h  # ξ²G, finite at ξ = 0
    den = sw * h + 3.0 * xi * abs(xi_dot)  # > 0 because h > 0 and w > 0
    phi = 1.0 + 3.0 * xi * xi_dot / den
    ft = 6.0 * math.pi * k * xi_Omega * phi / (s * sw)
    fr = -3.0 * k * (4.0 * x2g + 2.0 * math.pi * s * xi_dot * phi) / (s * w * sw)
    return fr, ft


@njit(cache=True)
def _sommerfeld_angle(xi, sw, th):
    """Sommerfeld variable δ(θ): 1 + ξcosθ = (1−ξ²)/(1 − ξcosδ), principal value [T35]."""
    return math.atan2(sw * math.sin(th), math.cos(th) + xi)


@njit(cache=True)
def short_force(xi, xi_dot, xi_Omega, mu, R, L, c, p, table):
    """Short-bearing (Ocvirk) π-film [T35]: p = −(3μ/h³)(L²/4 − z²)·g(θ)/c², g = 2ξ̇cosθ − ξΩ sinθ,
    kept where g < 0 (a half film θ ∈ (π/2 − β, 3π/2 − β), β = atan2(ξΩ, 2ξ̇)); with
    k_s = μRL³/(2c²) and w = 1 + ξcosθ:

    F_r = −k_s[2ξ̇·I_cc − ξΩ·I_sc],  F_t = −k_s[2ξ̇·I_sc − ξΩ·I_ss],
    I_sc = [−cos²θ/(2w²)], I_ss = [(δ/2 − sin2δ/4)]/(1−ξ²)^{3/2},
    I_cc = [δ(1+ξ²/2) − 2ξ sinδ + ξ² sin2δ/4]/(1−ξ²)^{5/2} − I_ss over the arc (δ unwrapped).
    Steady limit (ξ̇ = 0): F_r = −μΩRL³ξ²/(c²(1−ξ²)²), F_t = πμΩRL³ξ/(4c²(1−ξ²)^{3/2})
    (Hamrock, *Fundamentals of Fluid Film Lubrication*, short-bearing theory)."""
    a = 2.0 * xi_dot
    b = xi_Omega
    if a == 0.0 and b == 0.0:
        return 0.0, 0.0
    ks = mu * R * L * L * L / (2.0 * c * c)
    beta = math.atan2(b, a)
    t0 = 0.5 * math.pi - beta
    t1 = t0 + math.pi
    w1 = (1.0 - xi) * (1.0 + xi)
    sw = math.sqrt(w1)
    d0 = _sommerfeld_angle(xi, sw, t0)
    dd = (_sommerfeld_angle(xi, sw, t1) - d0) % (2.0 * math.pi)
    d1 = d0 + dd
    c0 = math.cos(t0)
    c1 = math.cos(t1)
    isc = -c1 * c1 / (2.0 * (1.0 + xi * c1) ** 2) + c0 * c0 / (2.0 * (1.0 + xi * c0) ** 2)
    iss = ((d1 - d0) / 2.0 - (math.sin(2.0 * d1) - math.sin(2.0 * d0)) / 4.0) / (w1 * sw)
    j3 = (
        (d1 - d0) * (1.0 + 0.5 * xi * xi)
        - 2.0 * xi * (math.sin(d1) - math.sin(d0))
        + 0.25 * xi * xi * (math.sin(2.0 * d1) - math.sin(2.0 * d0))
    ) / (w1 * w1 * sw)
    icc = j3 - iss
    return -ks * (a * icc - b * isc), -ks * (a * isc - b * iss)
