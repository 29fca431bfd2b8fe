"""Long-bearing film models (compiled scalar kernels) and their registry.

All kernels share one signature ``kernel(xi, xi_dot, xi_Omega, mu, R, L, c, table) -> (Fr, Ft)``:
eccentricity ratio ξ [-] in [0, 1), ξ̇ [1/s], the product ξΩ [rad/s] with
Ω = ω_J + ω_B − 2γ̇ (spec §2.1), viscosity μ [Pa·s], journal radius R [m], length L [m],
radial clearance c [m], and a 3-D float table used only by tabulated models. F_r is the film
force on the journal along u = e/|e|, F_t along t = ẑ × u [N] (spec §1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from numba import njit

OTT = 0
ALSHAER2005 = 1


@njit(cache=True)
def pi_film_force(xi, xi_dot, xi_Omega, mu, R, L, c, table):
    """Paper's π-film long bearing, branch-free form [T21] (spec §3.3):

    A = ξ̇, B = ξΩ/(2+ξ²), ρ = √(A²+B²), Δδ = 2 atan2(ρ√(1−ξ²), −ξA),
    F_t = 6k B Δδ/√(1−ξ²), F_r = −6k[A Δδ/(1−ξ²)^{3/2} + 2ξρ/(1−ξ²)], k = μLR³/c².
    For A < 0 the equivalent F_r = 12k(ρ/ξ)[1 + (atan(y)/y − 1)/(1−ξ²)], y = ρ√(1−ξ²)/(ξ|A|),
    avoids cancellation near the wall [T22]. F = 0 at A = B = 0 (continuous limit)."""
    k = mu * L * R * R * R / (c * c)
    A = xi_dot
    B = xi_Omega / (2.0 + xi * xi)
    rho = math.sqrt(A * A + B * B)
    if rho == 0.0:
        return 0.0, 0.0
    w = (1.0 - xi) * (1.0 + xi)
    sw = math.sqrt(w)
    dd = 2.0 * math.atan2(rho * sw, -xi * A)
    ft = 6.0 * k * B * dd / sw
    if A < 0.0 and xi > 0.0:
        y = rho * sw / (xi * (-A))
        if y < 0.1:
            y2 = y * y
            g = -y2 / 3.0 + y2 * y2 / 5.0 - y2 * y2 * y2 / 7.0 + y2 * y2 * y2 * y2 / 9.0
        else:
            g = math.atan(y) / y - 1.0
        fr = 12.0 * k * (rho / xi) * (1.0 + g / w)
    else:
        fr = -6.0 * k * (A * dd / (w * sw) + 2.0 * xi * rho / w)
    return fr, ft


@njit(cache=True)
def ott_force(xi, xi_dot, xi_Omega, mu, R, L, c, table):
    """Ott's long-bearing model, corrected (1−ξ²) denominators, ω-free form [T23] (spec §4.1):

    G = √((1−ξ²)(ξ²Ω² + 4ξ̇²))/ξ = κ|ωE|, Φ = (κ+3)/(κ+3/2) (ξ̇>0), κ/(κ+3/2) (ξ̇<0), 1 (ξ̇=0),
    F_t = 6πk ξΩ Φ/[(2+ξ²)√(1−ξ²)], F_r = −3k[4ξ²G + 2π(2+ξ²)ξ̇Φ]/[(2+ξ²)(1−ξ²)^{3/2}]."""
    k = mu * L * R * R * R / (c * c)
    w = (1.0 - xi) * (1.0 + xi)
    sw = math.sqrt(w)
    s = 2.0 + xi * xi
    # ξ²G = ξ √((1−ξ²)(ξ²Ω² + 4ξ̇²)) stays finite at ξ = 0
    x2g = xi * math.sqrt(w * (xi_Omega * xi_Omega + 4.0 * xi_dot * xi_dot))
    if xi_dot == 0.0:
        phi = 1.0
    else:
        # κ = G/(2|ξ̇|) = √((1−ξ²)((ξΩ)²/(4ξ̇²) + 1))/ξ
        if xi == 0.0:
            phi = 1.0
        else:
            kap = sw * math.sqrt(xi_Omega * xi_Omega / (4.0 * xi_dot * xi_dot) + 1.0) / xi
            phi = (kap + 3.0) / (kap + 1.5) if xi_dot > 0.0 else kap / (kap + 1.5)
    ft = 6.0 * math.pi * k * xi_Omega * phi / (s * sw)
    fr = -3.0 * k * (4.0 * x2g + 2.0 * math.pi * s * xi_dot * phi) / (s * w * sw)
    return fr, ft


@njit(cache=True)
def film_force(code, xi, xi_dot, xi_Omega, mu, R, L, c, table):
    """Dispatch to the film kernel ``code`` (see ``FILM_MODELS``)."""
    if code == ALSHAER2005:
        return pi_film_force(xi, xi_dot, xi_Omega, mu, R, L, c, table)
    elif code == OTT:
        return ott_force(xi, xi_dot, xi_Omega, mu, R, L, c, table)
    return math.nan, math.nan


@dataclass(frozen=True)
class Ott:
    """Ott's long-bearing solution (paper eqs 1–5, corrected; spec §4) [T23]."""

    code: ClassVar[int] = OTT
    tag: ClassVar[str] = "T23"


@dataclass(frozen=True)
class Alshaer2005:
    """The paper's π-film long-bearing solution (eqs 6–9, corrected; spec §3.3) [T21]."""

    code: ClassVar[int] = ALSHAER2005
    tag: ClassVar[str] = "T21"


FILM_MODELS = {"ott": Ott, "alshaer2005": Alshaer2005}

_UNITS = {"xi": "-", "xi_dot": "1/s", "gamma": "rad", "gamma_dot": "rad/s", "omega_journal": "rad/s",
          "omega_bearing": "rad/s", "viscosity": "Pa·s", "length": "m", "radius": "m", "clearance": "m"}


def film_forces(model, xi, xi_dot, gamma, gamma_dot, omega_journal, omega_bearing, viscosity,
                length, radius, clearance):
    """Vectorised film force on the journal for arrays of states (SI, global rates).

    Returns ``dict(Fr, Ft, Fx, Fy)`` [N] with Ω = ω_J + ω_B − 2γ̇, F_x = F_r cosγ − F_t sinγ,
    F_y = F_r sinγ + F_t cosγ (spec §1)."""
    if model not in FILM_MODELS:
        raise ValueError(f"film model {model!r} is unknown; valid: {sorted(FILM_MODELS)}")
    args = dict(xi=xi, xi_dot=xi_dot, gamma=gamma, gamma_dot=gamma_dot, omega_journal=omega_journal,
                omega_bearing=omega_bearing, viscosity=viscosity, length=length, radius=radius,
                clearance=clearance)
    arr = dict(zip(args, np.broadcast_arrays(*[np.asarray(v, dtype=float) for v in args.values()])))
    for name, v in arr.items():
        bad = np.flatnonzero(~np.isfinite(v.ravel()))
        if bad.size:
            raise ValueError(f"{name} [{_UNITS[name]}] is not finite at index {bad[0]}")
    for name in ("viscosity", "length", "radius", "clearance"):
        bad = np.flatnonzero(arr[name].ravel() <= 0)
        if bad.size:
            raise ValueError(f"{name} = {arr[name].ravel()[bad[0]]!r} [{_UNITS[name]}] at index {bad[0]}: must be > 0")
    bad = np.flatnonzero((arr["xi"].ravel() < 0) | (arr["xi"].ravel() >= 1))
    if bad.size:
        raise ValueError(f"xi = {arr['xi'].ravel()[bad[0]]!r} [-] at index {bad[0]}: must be in [0, 1)")
    code = FILM_MODELS[model].code
    shape = arr["xi"].shape
    fr = np.empty(shape)
    ft = np.empty(shape)
    table = np.zeros((1, 1, 1))
    xi_om = arr["xi"] * (arr["omega_journal"] + arr["omega_bearing"] - 2.0 * arr["gamma_dot"])
    for idx in np.ndindex(shape):
        fr[idx], ft[idx] = film_force(code, arr["xi"][idx], arr["xi_dot"][idx], xi_om[idx],
                                      arr["viscosity"][idx], arr["radius"][idx], arr["length"][idx],
                                      arr["clearance"][idx], table)
    g = arr["gamma"]
    return {"Fr": fr, "Ft": ft, "Fx": fr * np.cos(g) - ft * np.sin(g), "Fy": fr * np.sin(g) + ft * np.cos(g)}
