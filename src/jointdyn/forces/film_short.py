"""Short-bearing (Ocvirk) π-film: closed-form, branch-free film force [T40–T43].

Theory (docs/_fragments/film_short_finite.md). Dropping the circumferential flow term of the
Reynolds equation (spec §1 conventions, z ∈ [−L/2, L/2], p = 0 at z = ±L/2)

    ∂/∂z(h³ ∂p/∂z) = 6μ[Ω ∂h/∂θ + 2cξ̇ cos θ] = 6μc·g(θ),   g = 2ξ̇ cos θ − ξΩ sin θ,

gives p(θ, z) = (3μ/h³)(z² − L²/4)·c·g(θ) [T40]. p > 0 exactly where g < 0: the half film
θ ∈ (θ₁, θ₁ + π) with θ₁ = atan2(2ξ̇, ξΩ), i.e. tan θ₁ = 2ξ̇/(ξΩ) [T41]. Integrating over z
(∫(z² − L²/4)dz = −L³/6) and over that arc, with a = 2ξ̇, b = ξΩ, r = √(a²+b²), w = 1 − ξ²,
q = a² + w·b², k_s = μRL³/(2c²) and Δδ = 2·atan2(r√w, −ξa) ∈ (0, 2π) [T42]:

    F_t = k_s [ b·Δδ/(2w^{3/2}) + ξabr/(w q) ]
    F_r = −k_s [ (1+2ξ²)·a·Δδ/(2w^{5/2}) + ξr(3a² + 2w·b²)/(w² q) ]

For a < 0 near the wall (y = r√w/(ξ|a|) < 1) the two F_r terms (and the two F_t terms) cancel
to O(1); the identical guarded form with φ(y) = (atan(y)/y − 1 + y²/3)/y⁴ is used [T43].
Steady limit (ξ̇ = 0): F_r = −μΩRL³ξ²/(c²(1−ξ²)²), F_t = πμΩRL³ξ/(4c²(1−ξ²)^{3/2})
(Ocvirk 1952, NACA TN 2808; Hamrock, Schmid & Jacobson, *Fundamentals of Machine Elements* /
Hamrock, *Fundamentals of Fluid Film Lubrication*, short-bearing chapter).
"""

from __future__ import annotations

import math
import warnings

from numba import njit

from ..errors import PhysicsWarning

#: L/D above which the short-bearing theory is outside its usual validity domain [-]
SHORT_MAX_L_OVER_D = 0.5


@njit(cache=True)
def _phi(y):
    """φ(y) = (atan(y)/y − 1 + y²/3)/y⁴ = Σ_{m≥0} (−1)^m y^{2m}/(2m+5) for 0 ≤ y ≤ 1 [T43].

    Series for y < 0.5 (30 terms: remainder < 0.25^30/65 ≈ 1e-20), closed form above (the
    cancellation in the numerator then costs at most a factor 1/(0.5⁴·0.2) = 80 of ε)."""
    if y < 0.5:
        z = y * y
        s = 0.0
        for m in range(29, -1, -1):
            s = (-1.0) ** m / (2.0 * m + 5.0) + z * s
        return s
    y2 = y * y
    return (math.atan(y) / y - 1.0 + y2 / 3.0) / (y2 * y2)


@njit(cache=True)
def short_force(xi, xi_dot, xi_Omega, mu, R, L, c, table):
    """Short-bearing (Ocvirk) π-film force on the journal [T40–T43].

    xi        eccentricity ratio ξ, 0 ≤ ξ < 1 [-]
    xi_dot    ξ̇ [1/s]
    xi_Omega  ξΩ, Ω = ω_J + ω_B − 2γ̇ [rad/s]
    mu        dynamic viscosity [Pa·s]
    R         journal radius [m]
    L         bearing length [m]
    c         radial clearance [m]
    table     float64 array, ignored (uniform kernel signature) [-]

    a = 2ξ̇, b = ξΩ, r = √(a²+b²), w = (1−ξ)(1+ξ), q = a² + w b², k_s = μRL³/(2c²),
    Δδ = 2·atan2(r√w, −ξa)                                                       [T42]
    F_t = k_s[bΔδ/(2w^{3/2}) + ξabr/(wq)],
    F_r = −k_s[(1+2ξ²)aΔδ/(2w^{5/2}) + ξr(3a² + 2wb²)/(w²q)]                      [T42]
    a < 0 and y = r√w/(ξ|a|) < 1 (same value, no cancellation), φ(y) of [T43]:
    F_r = k_s(r/ξ)[−r²(a² + (1+2ξ²)b²)/(3ξ²a²q) + (1+2ξ²)r⁴φ(y)/(ξ⁴a⁴)],
    F_t = k_s(br/(ξ|a|))[r²/q − r²/(3ξ²a²) + r⁴wφ(y)/(ξ⁴a⁴)]                     [T43]
    Returns (F_r, F_t) [N]; (0, 0) at ξ̇ = ξΩ = 0 (continuous limit: F is homogeneous of
    degree 1 in (ξ̇, ξΩ)).
    """
    a = 2.0 * xi_dot
    b = xi_Omega
    r = math.hypot(a, b)
    if r == 0.0:
        return 0.0, 0.0
    ks = mu * R * L * L * L / (2.0 * c * c)
    w = (1.0 - xi) * (1.0 + xi)
    sw = math.sqrt(w)
    q = a * a + w * b * b
    e2 = 1.0 + 2.0 * xi * xi
    if a < 0.0 and r * sw < xi * -a:
        y = r * sw / (xi * -a)
        ph = _phi(y)
        a2 = a * a
        r2 = r * r
        r4a4 = (r2 / a2) * (r2 / a2)
        x2 = xi * xi
        fr = ks * (r / xi) * (-r2 * (a2 + e2 * b * b) / (3.0 * x2 * a2 * q) + e2 * r4a4 * ph / (x2 * x2))
        ft = ks * (b * r / (xi * -a)) * (r2 / q - r2 / (3.0 * x2 * a2) + r4a4 * w * ph / (x2 * x2))
        return fr, ft
    dd = 2.0 * math.atan2(r * sw, -xi * a)
    ft = ks * (b * dd / (2.0 * w * sw) + xi * a * b * r / (w * q))
    # 3r² − (1+2ξ²)b² = 3a² + 2wb² (no cancellation as ξ → 1)
    fr = -ks * (e2 * a * dd / (2.0 * w * w * sw) + xi * r * (3.0 * a * a + 2.0 * w * b * b) / (w * w * q))
    return fr, ft


def short_film_start(xi_dot: float, xi_Omega: float) -> float:
    """Start θ₁ of the positive-pressure half film (θ₁, θ₁+π) of the short π-film [T41] [rad].

    xi_dot    ξ̇ [1/s]
    xi_Omega  ξΩ [rad/s]
    θ₁ = atan2(2ξ̇, ξΩ): the bracket g = 2ξ̇cosθ − ξΩ sinθ vanishes at θ₁ and θ₁ + π
    (tan θ₁ = 2ξ̇/(ξΩ)) and is negative (p > 0) in between.
    """
    return math.atan2(2.0 * xi_dot, xi_Omega)


def short_validity_warning(L: float, D: float) -> bool:
    """Issue a :class:`~jointdyn.errors.PhysicsWarning` if L/D > 0.5 (short-bearing theory
    outside its validity domain) [T44]; returns True if it warned.

    L  bearing length [m]
    D  journal diameter [m]
    """
    if not (math.isfinite(L) and L > 0.0):
        raise ValueError(f"L [m] must be finite and > 0; got {L!r}")
    if not (math.isfinite(D) and D > 0.0):
        raise ValueError(f"D [m] must be finite and > 0; got {D!r}")
    ratio = L / D
    if ratio > SHORT_MAX_L_OVER_D:
        warnings.warn(
            f"short-bearing (Ocvirk) film model used at L/D = {ratio:.3g} > {SHORT_MAX_L_OVER_D}: "
            "outside its validity domain; it overestimates the film force (about 1.9x the finite-length "
            "Reynolds solution at L/D = 1, see [T44]); consider the 'finite' film model",
            PhysicsWarning,
            stacklevel=2,
        )
        return True
    return False
