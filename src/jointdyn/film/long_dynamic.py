"""The long bearing (L/D → ∞) with Reynolds' film end under dynamic load, and its dynamic
coefficients [T344].

Bearing-fixed angle α from the load line in the direction of rotation (the frame of
:mod:`.grooved`), journal at e = (e_L, e_P) [c] moving at ė [cω], film H = 1 − e_L cos α − e_P sin α,
bearing at rest, journal at ω = 1. Integrating the 1-D Reynolds equation ∂(H³P′)/∂α = ∂H/∂α +
2∂H/∂τ [T70] once: H³P′ = H + 2(ė_P cos α − ė_L sin α) + K. The film starts at the supply line
α_s (P = 0; the equilibrium's maximum film, fixed in the bearing, as [T247]) and ends at α_e with
P = P′ = 0 (Swift–Stieber): P′(α_e) = 0 fixes K, ∫_{α_s}^{α_e} P′ dα = 0 fixes α_e (Brent near
the steady end). Force on the journal F = −12λ∫P(cos α, sin α)dα = 12λ∫P′(sin α, −cos α)dα
[μωR⁴/c²] (by parts, P = 0 at both ends).
"""

from __future__ import annotations

import math
import warnings

from scipy.integrate import IntegrationWarning, quad
from scipy.optimize import brentq

from jointdyn.film.long_short import _Q, long_reynolds_end, long_steady


def long_reynolds_force(lam: float, e, edot, alpha_s: float, alpha_e0: float) -> tuple:
    """(F (2,) in the load frame [μωR⁴/c²], α_e [rad]) of the long Reynolds film with the supply
    at α_s [rad]; ``alpha_e0`` [rad] the steady film end, the root is searched within ±0.5 rad."""
    ex, ey = float(e[0]), float(e[1])
    vx, vy = float(edot[0]), float(edot[1])

    def H(a):
        return 1.0 - ex * math.cos(a) - ey * math.sin(a)

    def source(a):  # H + 2(ė_P cos α − ė_L sin α), the right-hand side before K
        return H(a) + 2.0 * (vy * math.cos(a) - vx * math.sin(a))

    def dP(a, k):
        return (source(a) + k) / H(a) ** 3

    def P_end(ae):
        k = -source(ae)
        with warnings.catch_warnings():  # near the root the integral cancels to ~1e-16 of ∫|·|
            warnings.simplefilter("ignore", IntegrationWarning)
            return quad(dP, alpha_s, ae, args=(k,), **_Q)[0]

    ae = brentq(P_end, alpha_e0 - 0.5, min(alpha_e0 + 0.5, alpha_s + 2.0 * math.pi), xtol=1e-14, rtol=1e-14)
    k = -source(ae)
    with warnings.catch_warnings():  # a component near zero cancels to round-off of ∫|·|
        warnings.simplefilter("ignore", IntegrationWarning)
        fx = 12.0 * lam * quad(lambda a: dP(a, k) * math.sin(a), alpha_s, ae, **_Q)[0]
        fy = -12.0 * lam * quad(lambda a: dP(a, k) * math.cos(a), alpha_s, ae, **_Q)[0]
    return (fx, fy), ae


def long_reynolds_coefficients(lam: float, eps: float, h: float | None = None) -> dict:
    """Dynamic coefficients k = Kc/W, c = Ccω/W of the long bearing with Reynolds' film end at ε,
    by central differences of :func:`long_reynolds_force` at the steady equilibrium [T344, T247]
    (``h``: the steps, default ``grooved.STEP``); also ``attitude`` [rad] and ``load`` W̄."""
    import numpy as np

    from jointdyn.film.grooved import STEP, differenced_coefficients

    st = long_steady(eps, lam, "reynolds")
    phi = math.atan2(st["Ft"], -st["Fr"])  # attitude from the load line [T77]
    alpha_s = phi + math.pi  # the maximum film of the equilibrium
    alpha_e0 = alpha_s + long_reynolds_end(eps)

    def film(e, edot):
        return np.array(long_reynolds_force(lam, e, edot, alpha_s, alpha_e0)[0])

    return differenced_coefficients(film, eps, phi, st["W"], STEP if h is None else h)
