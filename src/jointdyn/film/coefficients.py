"""Bearing dynamic coefficients, equilibrium locus and Lund's stability threshold [T105–T109].

Convention (issue 14): bearing fixed, journal spinning counter-clockwise at ω > 0, static load W
on the journal along −y, so the film force on the journal at equilibrium is +W ŷ; x, y are the
journal-centre displacements from the bearing centre. K_ij = −∂F_i/∂x_j, C_ij = −∂F_i/∂ẋ_j at
the equilibrium, dimensionless k_ij = K_ij c/W, c_ij = C_ij cω/W. All results are
dimensionless and depend on the film model, ε and (``short``, ``finite``) L/D only.
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from jointdyn.core import interrupts
from jointdyn.core.layout import params_of
from jointdyn.film.models import FILM_MODELS, FILM_WIDTH, film_jac, film_model

_NAMES = ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy")
COLUMNS = {
    **{k: "-" for k in _NAMES},
    "eps": "-",
    "attitude": "rad",
    "sommerfeld": "-",
    "critical_mass": "-",
    "whirl_ratio": "-",
}
"""keys of :func:`dynamic_coefficients` -> unit (all dimensionless but the attitude angle): the
columns for ``bearing-table``"""


def _check(model, ld, eps):
    if not isinstance(model, str) or model not in FILM_MODELS:
        raise ValueError(f"model = {model!r}: unknown film model; valid: {sorted(FILM_MODELS)}")
    if not (isinstance(ld, numbers.Real) and math.isfinite(ld) and ld > 0):
        raise ValueError(f"ld = {ld!r} [-]: L/D must be finite and > 0")
    if not (isinstance(eps, numbers.Real) and math.isfinite(eps) and 0.0 < eps < 1.0):
        raise ValueError(f"eps = {eps!r} [-]: eccentricity ratio must be in (0, 1) (W = 0 at ε = 0)")


_TABLES: dict[float, np.ndarray] = {}


def _table(fm, ld):
    if not hasattr(fm, "table"):
        return np.zeros((1, 2))
    if ld not in _TABLES:
        _TABLES[ld] = fm.table(2.0 * ld, 1.0)  # L = 2·ld for R = 1
    return _TABLES[ld]


def _film_cartesian(model, ld, eps, omega=1.0):
    """Static film force F (2,), ∂F/∂e, ∂F/∂ė (2×2) at e = ε(cosγ, sinγ) with γ = 0, ė = 0, for
    R = c = μ = 1, L = 2·ld [T105]. Rotating to the equilibrium angle is done by the caller."""
    fm = film_model(model)
    tab = _table(fm, ld)
    p = np.zeros(FILM_WIDTH)
    p[: len(type(fm).PARAMS)] = params_of(fm)
    fr, ft, frx, fra, fro, ftx, fta, fto = film_jac(
        fm.code, eps, 0.0, eps * omega, 1.0, 1.0, 2.0 * ld, 1.0, p, tab
    )
    u = np.array([1.0, 0.0])
    t = np.array([0.0, 1.0])
    # ξ = |e|/c, ξ̇ = u·ė/c, X = ξω − 2 t·ė/c; du = t (t·de)/|e|, dt = −u (t·de)/|e| (c = 1)  [T105]
    dfr_de = (frx + omega * fro) * u
    dft_de = (ftx + omega * fto) * u
    dF_de = np.outer(u, dfr_de) + np.outer(t, dft_de) + (fr * np.outer(t, t) - ft * np.outer(u, t)) / eps
    dF_ded = np.outer(u, fra * u - 2.0 * fro * t) + np.outer(t, fta * u - 2.0 * fto * t)
    return np.array([fr, ft]), dF_de, dF_ded


def equilibrium(model: str, ld: float, eps: float) -> dict:
    """Static equilibrium at eccentricity ratio ε [T106]: ``attitude`` φ [rad] (angle from the load
    line −ŷ to the line of centres, in the direction of rotation), ``gamma`` = φ − π/2 [rad]
    (direction of e), ``sommerfeld`` S = μ N L D (R/c)²/W with N = ω/2π [-]."""
    _check(model, ld, eps)
    ld, eps = float(ld), float(eps)  # numpy scalars compute in float64 [T288]
    F, _, _ = _film_cartesian(model, ld, eps)
    W = math.hypot(F[0], F[1])
    phi = math.atan2(F[1], -F[0])
    # R = c = μ = ω = 1, L = 2·ld, D = 2: S = (1/2π)·L·D/W
    return {"attitude": phi, "gamma": phi - 0.5 * math.pi, "sommerfeld": 2.0 * ld / (math.pi * W), "load": W}


def dynamic_coefficients(model: str, ld: float, eps: float) -> dict:
    """Dimensionless stiffness and damping coefficients at the static equilibrium with eccentricity
    ratio ε ∈ (0, 1) of film model ``model`` (``FILM_MODELS``) and length ratio ld = L/D [-]
    [T105–T108]. Returns a dict with ``kxx, kxy, kyx, kyy, cxx, cxy, cyx, cyy`` (k = Kc/W,
    c = Ccω/W), ``eps``, ``attitude`` [rad] (``bearing-table``'s ``attitude_deg`` is the same angle
    in degrees), ``sommerfeld`` [-], ``critical_mass`` (Lund's
    M̄ = m c ω²/W at the threshold, inf if stable for any mass) and ``whirl_ratio`` ν/ω [-]."""
    _check(model, ld, eps)
    ld, eps = float(ld), float(eps)  # numpy scalars compute in float64 [T288]
    F, dF_de, dF_ded = _film_cartesian(model, ld, eps)
    eq = equilibrium(model, ld, eps)
    W = eq["load"]
    g = eq["gamma"]
    Rm = np.array([[math.cos(g), -math.sin(g)], [math.sin(g), math.cos(g)]])  # frame at γ = 0 → γ
    K = -Rm @ dF_de @ Rm.T / W  # c = 1  [T107]
    C = -Rm @ dF_ded @ Rm.T / W  # cω/W with c = ω = 1  [T107]
    out = dict(zip(_NAMES, [*K.ravel(), *C.ravel()], strict=True))
    out.update(eps=eps, attitude=eq["attitude"], sommerfeld=eq["sommerfeld"])
    out.update(stability_threshold(K, C))
    return out


def stability_threshold(k, c) -> dict:
    """Lund's threshold of a rigid symmetric rotor (mass m per bearing) on bearings with
    dimensionless coefficients k, c (2×2) [T108]:
    K_eq = (k_xx c_yy + k_yy c_xx − k_xy c_yx − k_yx c_xy)/(c_xx + c_yy),
    (ν/ω)² = [(k_xx − K_eq)(k_yy − K_eq) − k_xy k_yx]/(c_xx c_yy − c_xy c_yx), M̄_crit = K_eq/(ν/ω)².
    Returns ``critical_mass`` (inf if (ν/ω)² ≤ 0 or K_eq ≤ 0: no threshold) and ``whirl_ratio``."""
    k = np.asarray(k, float)
    c = np.asarray(c, float)
    keq = (k[0, 0] * c[1, 1] + k[1, 1] * c[0, 0] - k[0, 1] * c[1, 0] - k[1, 0] * c[0, 1]) / (
        c[0, 0] + c[1, 1]
    )
    g2 = ((k[0, 0] - keq) * (k[1, 1] - keq) - k[0, 1] * k[1, 0]) / (c[0, 0] * c[1, 1] - c[0, 1] * c[1, 0])
    if not (g2 > 0 and keq > 0):
        return {"critical_mass": math.inf, "whirl_ratio": math.nan}
    return {"critical_mass": keq / g2, "whirl_ratio": math.sqrt(g2)}


def equilibrium_locus(model: str, ld: float, eps_values) -> dict:
    """(ε, attitude [rad], S [-]) over a sequence of ε ∈ (0, 1) [T106]: the locus as arrays."""
    rows = []
    for e in eps_values:
        interrupts.check()  # [T336]
        rows.append(equilibrium(model, ld, float(e)))
    return {
        "eps": np.array([float(e) for e in eps_values]),
        "attitude": np.array([r["attitude"] for r in rows]),
        "sommerfeld": np.array([r["sommerfeld"] for r in rows]),
    }
