"""Steady long-bearing (L/D → ∞) and short-bearing (Ocvirk) films in the nondimensional units
of :mod:`.film` [T78, T79], used by the design table and as the limits of the finite solver.

Units: P = p c²/(6μωR²), forces in μωR⁴/c² for a bearing of L/D = λ, the flow q such that
Q = (ωR²c/2)·q, the Couette integral ∫∫dθ dζ/H (ζ = z/R over the full length).
"""

from __future__ import annotations

import math
import warnings

from scipy.integrate import IntegrationWarning, quad
from scipy.optimize import brentq

from jointdyn.film.cavitation import check_cavitation
from jointdyn.film.fv import check_ld, check_xi

_Q = {"epsabs": 1e-14, "epsrel": 1e-12, "limit": 200}


def _couette(eps: float, lam: float) -> float:
    """∫∫ dθ dζ / H over the full film = 2λ·2π/√(1−ξ²) [T75] [-]."""
    return 4.0 * math.pi * lam / math.sqrt((1.0 - eps) * (1.0 + eps))


def long_reynolds_end(eps: float) -> float:
    """Film end θ_e ∈ (π, 2π) [rad] of the long bearing with the Reynolds condition and supply at
    θ = 0 [T78]: H³P′ = H − H*, H* = H(θ_e), P(0) = P(θ_e) = 0."""

    def P_end(te):
        hs = 1.0 + eps * math.cos(te)
        with warnings.catch_warnings():  # near the root the integral cancels to ~1e-16 of ∫|·|
            warnings.simplefilter("ignore", IntegrationWarning)
            return quad(
                lambda t: (eps * math.cos(t) + 1.0 - hs) / (1.0 + eps * math.cos(t)) ** 3, 0.0, te, **_Q
            )[0]

    return brentq(P_end, math.pi * (1.0 + 1e-9), 2.0 * math.pi * (1.0 - 1e-12), xtol=1e-14, rtol=1e-14)


def long_steady(eps: float, lam: float, cavitation: str = "reynolds") -> dict:
    """Steady long bearing [T78]. ``reynolds``: H³P′ = H − H* from the supply θ = 0 to the
    rupture θ_e (P = P′ = 0 there), forces by parts F̄_r = −12λ∫P′ sin θ, F̄_t = 12λ∫P′ cos θ.
    ``gumbel``: the Sommerfeld film P = ξ sin θ(2 + ξ cos θ)/((2+ξ²)H²) kept on (0, π)."""
    check_xi(eps)
    check_ld(lam)
    check_cavitation(cavitation)
    if cavitation not in ("gumbel", "reynolds"):
        raise ValueError(
            f"cavitation = {cavitation!r}: the long bearing has closed forms for gumbel and reynolds only"
        )
    if cavitation == "reynolds":
        te = long_reynolds_end(eps)
        hs = 1.0 + eps * math.cos(te)
    else:
        te = math.pi
        hs = 2.0 * (1.0 - eps * eps) / (2.0 + eps * eps)  # periodic Sommerfeld film [T78]

    def dP(t):
        h = 1.0 + eps * math.cos(t)
        return (h - hs) / h**3

    fr = -12.0 * lam * quad(lambda t: dP(t) * math.sin(t), 0.0, te, **_Q)[0]
    # P(π) = 0 for the Sommerfeld film, so the by-parts form holds on (0, π) too
    ft = 12.0 * lam * quad(lambda t: dP(t) * math.cos(t), 0.0, te, **_Q)[0]
    tp = math.acos((hs - 1.0) / eps)  # P′ = 0 where H = H*, before the minimum film
    pmax = quad(dP, 0.0, tp, **_Q)[0]
    return {
        "W": math.hypot(fr, ft),
        "Fr": fr,
        "Ft": ft,
        "couette": _couette(eps, lam),
        "flow": 2.0 * lam * hs,  # ∫(H − H³P′)dζ at θ = 0
        "side": 0.0,
        "pmax": pmax,
        "theta_peak": tp,
        "theta_rupture": te,
        "residual": 0.0,
        "iterations": 0,
        "cavitated": None,
    }


def short_steady(eps: float, lam: float) -> dict:
    """Steady short bearing (Ocvirk, half film 0 < θ < π) [T79]: P = ξ sin θ (λ² − ζ²)/(2H³),
    F̄_r = −8λ³ξ²/(1−ξ²)², F̄_t = 2πλ³ξ/(1−ξ²)^{3/2}; no circumferential pressure flow, so the
    inlet flow is the Couette flow 2λ(1+ξ) and the side flow 4λξ."""
    check_xi(eps)
    check_ld(lam)
    e2 = (1.0 - eps) * (1.0 + eps)
    fr = -8.0 * lam**3 * eps * eps / e2**2
    ft = 2.0 * math.pi * lam**3 * eps / e2**1.5
    cm = (1.0 - math.sqrt(1.0 + 24.0 * eps * eps)) / (4.0 * eps)
    tp = math.acos(cm)
    pmax = eps * lam * lam * math.sin(tp) / (2.0 * (1.0 + eps * cm) ** 3)
    return {
        "W": math.hypot(fr, ft),
        "Fr": fr,
        "Ft": ft,
        "couette": _couette(eps, lam),
        "flow": 2.0 * lam * (1.0 + eps),
        "side": 4.0 * lam * eps,
        "pmax": pmax,
        "theta_peak": tp,
        "theta_rupture": math.pi,
        "residual": 0.0,
        "iterations": 0,
        "cavitated": None,
    }
