"""Compiled film outputs of the π-film models (long ``alshaer2005``/``ott`` [T21] and short
``short`` [T35]) at a bearing state: peak pressure and its angle, film start and end, side flow
[T81, T82]. Same state arguments as the force kernels; angles θ from the maximum film
(bearing frame: global α = θ + γ + π), in (−π, 3π).
"""

from __future__ import annotations

import math

from numba import njit


@njit(cache=True)
def long_pi_outputs(xi, xi_dot, xi_Omega, mu, R, c):
    """(p_max [Pa], θ_pmax, θ_start, θ_end [rad]) of the long π-film [T81]. The film is
    [θ₁, θ₁+π], θ₁ = atan2(ξ̇, ξΩ/(2+ξ²)) [T22]; p′ ∝ Π(θ)/H³ with
    Π = ξΩ cos θ + 2ξ̇ sin θ + 3ξ²Ω/(2+ξ²) (Reynolds' first integral with the periodic
    constant), so the peak is where Π falls through 0: θ_m = φ + acos(d/ρ), ρ = √(ξ²Ω² + 4ξ̇²),
    φ = atan2(2ξ̇, ξΩ), d = −3ξ²Ω/(2+ξ²) (|d| < ρ for ξ < 1). p_max = p_S(θ_m) − p_S(θ₁) with the
    Sommerfeld pressure p_S = (6μR²/c²)[K sin θ (2 + ξ cos θ) + ξ̇/ξ]/H², K = ξΩ/(2+ξ²), the
    ξ̇/ξ term taken as a difference that is regular at ξ = 0. (0, nan, nan, nan) without film."""
    A = xi_dot
    B = xi_Omega / (2.0 + xi * xi)
    if A == 0.0 and B == 0.0:
        return 0.0, math.nan, math.nan, math.nan
    t1 = math.atan2(A, B)
    rho = math.sqrt(xi_Omega * xi_Omega + 4.0 * A * A)
    d = -3.0 * xi * xi_Omega / (2.0 + xi * xi)
    phi = math.atan2(2.0 * A, xi_Omega)
    tm = phi + math.acos(max(-1.0, min(1.0, d / rho)))
    # bring θ_m into the film [θ₁, θ₁ + π]
    tm = t1 + ((tm - t1) % (2.0 * math.pi))
    h1 = 1.0 + xi * math.cos(t1)
    hm = 1.0 + xi * math.cos(tm)
    c1, cm = math.cos(t1), math.cos(tm)
    rot = B * (math.sin(tm) * (2.0 + xi * cm) / (hm * hm) - math.sin(t1) * (2.0 + xi * c1) / (h1 * h1))
    sq = A * (c1 - cm) * (2.0 + xi * (c1 + cm)) / (hm * hm * h1 * h1)
    return 6.0 * mu * R * R / (c * c) * (rot + sq), tm, t1, t1 + math.pi


@njit(cache=True)
def short_pi_outputs(xi, xi_dot, xi_Omega, mu, R, L, c):
    """(p_max [Pa], θ_pmax, θ_start, θ_end [rad], Q_s [m³/s]) of the short (Ocvirk) π-film [T82].
    Mid-plane p = (3μL²/(4c²))·(−g)/H³, g = 2ξ̇ cos θ − ξΩ sin θ, positive on
    (π/2 − β, 3π/2 − β), β = atan2(ξΩ, 2ξ̇) [T35]; the peak is the root of
    −g′H − 3ξ g sin θ on that arc (bisection: the function falls from > 0 to < 0). Side flow
    through both ends Q_s = LcR·√(4ξ̇² + ξ²Ω²) (axial Poiseuille flow at z = ±L/2 over the film)."""
    a2 = 2.0 * xi_dot
    b = xi_Omega
    if a2 == 0.0 and b == 0.0:
        return 0.0, math.nan, math.nan, math.nan, 0.0
    beta = math.atan2(b, a2)
    lo = 0.5 * math.pi - beta
    hi = lo + math.pi
    for _ in range(80):
        t = 0.5 * (lo + hi)
        g = a2 * math.cos(t) - b * math.sin(t)
        gp = -a2 * math.sin(t) - b * math.cos(t)
        f = -gp * (1.0 + xi * math.cos(t)) - 3.0 * xi * g * math.sin(t)
        if f > 0.0:
            lo = t
        else:
            hi = t
    t = 0.5 * (lo + hi)
    g = a2 * math.cos(t) - b * math.sin(t)
    h = 1.0 + xi * math.cos(t)
    pm = 3.0 * mu * L * L / (4.0 * c * c) * (-g) / (h * h * h)
    qs = L * c * R * math.sqrt(a2 * a2 + b * b)
    return pm, t, 0.5 * math.pi - beta, 1.5 * math.pi - beta, qs
