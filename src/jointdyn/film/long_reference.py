"""Numerical long-bearing Reynolds solver: the independent reference for the film models.

Solves the infinitely-long-bearing Reynolds equation in the **bearing-fixed (global) frame**
[T30] (derived in [T20])

    ∂/∂α( h³ ∂p/∂α ) = 6μR² [ (ω_J + ω_B) ∂h/∂α + 2 ∂h/∂t|_α ],   h(α, t) = c − e·(cos α, sin α),

with e = cξ(cos γ, sin γ), so ∂h/∂t|_α = −cξ̇ cos(α−γ) − cξγ̇ sin(α−γ) is built from ξ̇ and γ̇
directly: the combination Ω = ω_J + ω_B − 2γ̇ of the closed forms is **not** assumed here.

Method (no closed-form film result is used):

1. One exact integration in α: h³p′ = 6μR²[(ω_J+ω_B)h + 2∫∂h/∂t dα] + C₁  [T31].
2. C₁ from periodicity, ∮p′ dα = 0, both integrals by adaptive quadrature (full 2π film) [T31].
3. π-film [T32]: its start α₁ is the root of d(α) = p_S(α) − p_S(α+π) = −∫_α^{α+π} p′ found by
   Brent's method (d(a+π) = −d(a), so any interval of length π brackets a root); of the two
   half films [α₁, α₁+π] and [α₁+π, α₁+2π] the one with the larger mean pressure is kept and
   p = p_S − p_S(α₁) there, p = 0 on the other half.
4. Forces on the journal [T33]: F = −RL∫p (cos α, sin α) dα; p vanishes at the film ends (or is
   periodic), so F_x = RL∫p′ sin α dα, F_y = −RL∫p′ cos α dα; then F_r = F·u, F_t = F·t with
   u = (cos γ, sin γ), t = ẑ × u (conventions of docs/theory.md).

Quadrature: scipy.integrate.quad with epsrel = 1e-13, split at the minimum film α = γ (mod 2π)
where 1/h³ peaks near the wall. Accuracy: ≤ 5e-11 of |F| over 1,000 random states with
ξ ≤ 0.999 (median 6e-15), ≤ 4e-9 against the 9-digit tables of [T164] (their rounding), both
measured by ``python tests/test_film_models.py``. Speed: ~6 ms per π-film state.
"""

from __future__ import annotations

import math
import warnings

from scipy.integrate import IntegrationWarning, quad
from scipy.optimize import brentq

TWO_PI = 2.0 * math.pi
_EPSREL = 1e-13


class _Film:
    """p′(α) of the full (Sommerfeld) film in units of 6μR²/c² (so p′ = (6μR²/c²)·dp(α))."""

    def __init__(self, xi, xi_dot, gamma_dot, omega_journal, omega_bearing, gamma):
        self.xi, self.xd, self.gd, self.ws, self.g = (
            xi,
            xi_dot,
            gamma_dot,
            omega_journal + omega_bearing,
            gamma,
        )
        # periodicity constant C̃ = −∮N/H³ / ∮1/H³ (step 2) [T31]
        a, b = gamma - math.pi, gamma + math.pi
        self.C = 0.0
        num = self.integral(self.dp, a, b)
        den = self.integral(lambda x: 1.0 / self.H(x) ** 3, a, b)
        self.C = -num / den

    def H(self, a):
        """h/c = 1 − ξ cos(α − γ) [-]"""
        return 1.0 - self.xi * math.cos(a - self.g)

    def dp(self, a):
        """c²p′/(6μR²) = [(ω_J+ω_B)H + 2s + C̃]/H³, s = (1/c)∫∂h/∂t dα = −ξ̇ sin(α−γ) + ξγ̇ cos(α−γ) [T31]"""
        s = -self.xd * math.sin(a - self.g) + self.xi * self.gd * math.cos(a - self.g)
        H = self.H(a)
        return (self.ws * H + 2.0 * s + self.C) / (H * H * H)

    def integral(self, f, a, b):
        """∫_a^b f dα by adaptive quadrature, split where the film is thinnest (α ≡ γ)."""
        cuts = [a]
        n = math.ceil((a - self.g) / TWO_PI)
        while self.g + n * TWO_PI < b:
            if self.g + n * TWO_PI > a:
                cuts.append(self.g + n * TWO_PI)
            n += 1
        cuts.append(b)
        total = 0.0
        with warnings.catch_warnings():
            # roundoff warnings occur when the integral cancels to far below ∫|f| (ξ̇ < 0 near
            # the wall); the result is then still good to ~1e-16·∫|f|
            warnings.simplefilter("ignore", IntegrationWarning)
            for lo, hi in zip(cuts[:-1], cuts[1:]):
                total += quad(f, lo, hi, epsabs=0.0, epsrel=_EPSREL, limit=400)[0]
        return total

    def forces(self, a, b, k6RL):
        """(F_r, F_t) [N] of the film p′ on [a, b] (p = 0 at a and b, or a full period) [T33]."""
        fx = k6RL * self.integral(lambda x: self.dp(x) * math.sin(x), a, b)
        fy = -k6RL * self.integral(lambda x: self.dp(x) * math.cos(x), a, b)
        cg, sg = math.cos(self.g), math.sin(self.g)
        return fx * cg + fy * sg, -fx * sg + fy * cg

    def pi_film_start(self):
        """Start α₁ [rad] of the positive π-film (step 3) [T32]."""

        def d(x):  # ∝ p_S(x+π) − p_S(x); same roots as p_S(x) − p_S(x+π)
            return self.integral(self.dp, x, x + math.pi)

        # d(a+π) = −d(a): [a, a+π] brackets a root; start where |d| is the larger of two
        # points a quarter turn apart, so the bracket ends are far from the root
        a = self.g if abs(d(self.g)) >= abs(d(self.g + 0.5 * math.pi)) else self.g + 0.5 * math.pi
        if d(a) == 0.0:  # A = B = 0: no film pressure at all
            r = a
        else:
            r = brentq(d, a, a + math.pi, xtol=1e-15, rtol=1e-15, maxiter=200)

        def mean_p(lo):  # ∫_lo^{lo+π} (p_S(α) − p_S(lo)) dα = ∫ (lo + π − α) p′ dα
            return self.integral(lambda x: (lo + math.pi - x) * self.dp(x), lo, lo + math.pi)

        return r if mean_p(r) >= mean_p(r + math.pi) else r + math.pi


def _scale(mu, R, L, c):
    """RL·6μR²/c² = 6k, k = μLR³/c² [N·s]"""
    return 6.0 * mu * L * R**3 / (c * c)


def full_film_force(xi, xi_dot, gamma_dot, omega_journal, omega_bearing, mu, R, L, c, gamma=0.0):
    """(F_r, F_t) [N] on the journal of the full 2π (Sommerfeld) film, by quadrature [T31, T33].

    xi             eccentricity ratio, 0 ≤ ξ < 1 [-]
    xi_dot         dξ/dt [1/s]
    gamma_dot      dγ/dt, global [rad/s]
    omega_journal  journal angular velocity ω_J [rad/s]
    omega_bearing  bearing angular velocity ω_B [rad/s]
    mu             viscosity [Pa·s]
    R, L, c        journal radius, length, radial clearance [m]
    gamma          line-of-centres angle (the result must not depend on it) [rad]
    """
    f = _Film(xi, xi_dot, gamma_dot, omega_journal, omega_bearing, gamma)
    return f.forces(gamma - math.pi, gamma + math.pi, _scale(mu, R, L, c))


def pi_film_force(xi, xi_dot, gamma_dot, omega_journal, omega_bearing, mu, R, L, c, gamma=0.0):
    """(F_r, F_t) [N] on the journal of the π-film (film start found numerically) [T32, T33].
    Arguments as in :func:`full_film_force`."""
    f = _Film(xi, xi_dot, gamma_dot, omega_journal, omega_bearing, gamma)
    a1 = f.pi_film_start()
    return f.forces(a1, a1 + math.pi, _scale(mu, R, L, c))


def pi_film_theta1(xi, xi_dot, gamma_dot, omega_journal, omega_bearing, gamma=0.0):
    """Film start θ₁ = α₁ − γ − π [rad], wrapped to (−π, π] (angle from the maximum film, [T20])."""
    f = _Film(xi, xi_dot, gamma_dot, omega_journal, omega_bearing, gamma)
    th = math.remainder(f.pi_film_start() - gamma - math.pi, TWO_PI)
    return math.pi if th == -math.pi else th
