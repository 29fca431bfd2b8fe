"""Greenwood–Tripp asperity contact of two rough surfaces and its load on a journal bearing
[T260–T263].

Two nominally flat rough surfaces with Gaussian heights, composite roughness σ = √(σ₁² + σ₂²),
asperity density η, asperity tip radius β, composite modulus E' (1/E' = (1−ν₁²)/E₁ + (1−ν₂²)/E₂)
carry at a mean separation h the nominal contact pressure [T260]

    p_a(h) = K·E'·F_{5/2}(h/σ),   K = (16√2π/15)·(ηβσ)²·√(σ/β),

    F_n(H) = (1/√(2π)) ∫_H^∞ (s − H)^n e^{−s²/2} ds = Γ(n+1)/√(2π) · e^{−H²/4} · D_{−n−1}(H),

D_ν the parabolic-cylinder function (scipy.special.pbdv) [T261]. The widely used power-law fit
F_{5/2} ≈ 4.4086·10⁻⁵·(4 − H)^6.804 (H < 4, 0 beyond) is kept for comparison only: it is 11 % low
at H = 0, a factor 3.9 low at H = 3 and 57 at H = 3.5 (:func:`f52_power_law`).

In the bearing the mean separation is the film h = c(1 + ξ cos θ) of the aligned journal; the
asperity pressure acts on the journal like the film pressure, so its resultant is
R·L∫p_a(θ)(cos θ, sin θ) dθ along the line of centres [T262] (p_a is symmetric about θ = π: no
tangential part), integrated with the FV θ nodes (periodic trapezoid rule on the clustered map,
spectrally accurate for the smooth p_a).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: the fitted power law of F_{5/2} (coefficient, exponent, upper end in H)
POWER_LAW = (4.4086e-5, 6.804, 4.0)


def gt_integral(n: float, H):
    """F_n(H) = (1/√(2π))∫_H^∞(s−H)^n e^{−s²/2} ds [-] in closed form through D_{−n−1}(H) [T261]
    (n > −1; H any real [-]). Underflows to 0 for H ≳ 38."""
    from scipy.special import gamma, pbdv

    H = np.asarray(H, dtype=float)
    with np.errstate(under="ignore"):
        d = pbdv(-n - 1.0, H)[0]
        out = gamma(n + 1.0) / math.sqrt(2.0 * math.pi) * np.exp(-0.25 * H * H) * d
    return np.where(np.isfinite(out), out, 0.0) if out.ndim else (float(out) if np.isfinite(out) else 0.0)


def f52(H):
    """F_{5/2}(H) [-] (exact, :func:`gt_integral`) [T261]."""
    return gt_integral(2.5, H)


def f52_power_law(H):
    """The fitted power law 4.4086e-5·(4 − H)^6.804 for H < 4, else 0 [-] (for comparison) [T261]."""
    a, b, h4 = POWER_LAW
    H = np.asarray(H, dtype=float)
    return np.where(H < h4, a * np.clip(h4 - H, 0.0, None) ** b, 0.0)


def composite_sigma(sigma1: float, sigma2: float) -> float:
    """σ = √(σ₁² + σ₂²) [m] of the journal (σ₁) and bushing (σ₂) RMS roughness [m]; each ≥ 0 and
    not both 0 (ValueError naming the parameter)."""
    for name, v in (("sigma1", sigma1), ("sigma2", sigma2)):
        if not (math.isfinite(v) and v >= 0.0):
            raise ValueError(f"roughness {name} = {v!r} [m]: must be finite and >= 0")
    s = math.hypot(sigma1, sigma2)
    if not s > 0.0:
        raise ValueError(f"roughness sigma = {s!r} [m]: the composite RMS roughness must be > 0")
    return s


@dataclass(frozen=True)
class GreenwoodTripp:
    """Greenwood–Tripp asperity contact [T260].

    sigma            composite RMS roughness σ > 0 [m]
    eta_beta_sigma   roughness parameter ηβσ > 0 [-] (typically 0.03–0.07)
    sigma_over_beta  σ/β > 0 [-] (typically 10⁻⁴–10⁻²)
    modulus          composite modulus E' > 0 [Pa], 1/E' = (1−ν₁²)/E₁ + (1−ν₂²)/E₂
    """

    sigma: float
    eta_beta_sigma: float = 0.04
    sigma_over_beta: float = 0.001
    modulus: float = 1.1e11

    def __post_init__(self):
        for name, v, unit in (
            ("sigma", self.sigma, "m"),
            ("eta_beta_sigma", self.eta_beta_sigma, "-"),
            ("sigma_over_beta", self.sigma_over_beta, "-"),
            ("modulus", self.modulus, "Pa"),
        ):
            if not (math.isfinite(v) and v > 0.0):
                raise ValueError(f"{name} = {v!r} [{unit}]: must be finite and > 0")

    @property
    def K(self) -> float:
        """K = (16√2π/15)(ηβσ)²√(σ/β) [-] [T260]."""
        return (
            16.0 * math.sqrt(2.0) * math.pi / 15.0 * self.eta_beta_sigma**2 * math.sqrt(self.sigma_over_beta)
        )

    def pressure(self, h):
        """Nominal asperity pressure p_a = K E' F_{5/2}(h/σ) [Pa] at mean separation h [m] [T260]."""
        return self.K * self.modulus * f52(np.asarray(h, dtype=float) / self.sigma)


def asperity_load(gt: GreenwoodTripp, xi: float, R: float, L: float, c: float, theta, weights) -> dict:
    """Asperity resultant on the journal of an aligned bearing at eccentricity ratio ξ [T262].

    gt       the contact (:class:`GreenwoodTripp`)
    xi       eccentricity ratio, 0 ≤ ξ < 1 [-]
    R, L, c  journal radius, bearing length, radial clearance [m]
    theta    θ nodes from the maximum film (n,) [rad]; weights their quadrature weights (n,) [rad]
    Returns dict: F_r [N] along the line of centres (same sign convention as the film's F_r:
    negative pushes the journal back toward the centre), F_t [N], normal [N] (∫p_a dA, the load on
    which boundary friction acts), p_max [Pa] (at θ = π).
    """
    p = gt.pressure(c * (1.0 + xi * np.cos(theta)))
    RL = R * L
    return {
        "F_r": float(RL * np.sum(weights * p * np.cos(theta))),
        "F_t": float(RL * np.sum(weights * p * np.sin(theta))),
        "normal": float(RL * np.sum(weights * p)),
        "p_max": float(gt.pressure(c * (1.0 - xi))),
    }
