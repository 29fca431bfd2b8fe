"""Film models (compiled scalar kernels) and their registry ``FILM_MODELS``: long-bearing Ott and
π-film (alshaer2005), short-bearing π-film, and the tabulated finite-length bearing.

Each model is a frozen dataclass registered in ``FILM_MODELS`` with its integer ``code``, its
compiled ``kernel``, its theory ``tag`` and its ``PARAMS`` (names of its own real-valued fields,
packed in order into the block ``p``; empty for the models below). A tabulated model also has a
``table(length, journal_radius)`` method. All kernels share one signature
``kernel(xi, xi_dot, xi_Omega, mu, R, L, c, p, table) -> (Fr, Ft)``:

* xi        eccentricity ratio ξ = |e|/c, 0 ≤ ξ < 1 [-]
* xi_dot    ξ̇ = dξ/dt [1/s]
* xi_Omega  the product ξΩ, Ω = ω_J + ω_B − 2γ̇ (global rates, [T20]); the product keeps
            ξ = 0 regular ([T24], Cartesian form B = ξΩ/(2+ξ²)) [rad/s]
* mu        dynamic viscosity μ [Pa·s]
* R         journal radius [m]
* L         bearing length [m]
* c         radial clearance [m]
* p         the model's own parameter block (its ``PARAMS``, SI) [-]
* table     float64 2-D array (rows, 2) used only by tabulated models (``finite``) [-]

F_r is the film force on the journal along u = e/|e| (bearing centre → journal centre), F_t along
t = ẑ × u [N] (conventions of docs/theory.md). Theory: docs/theory.md [T20–T39].
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from numba import njit

from ..layout import block_width, check_codes, params_of
from .film_finite import DEFAULT_CAVITATION, finite_force

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


@njit(cache=True)
def film_force(code, xi, xi_dot, xi_Omega, mu, R, L, c, p, table):
    """Film force (F_r, F_t) [N] of the model with registry code ``code``; (nan, nan) for an
    unknown code. Arguments as in the module docstring. One branch per registry entry (the
    contract tests check every entry of ``FILM_MODELS`` against its own kernel)."""
    if code == OTT:
        return ott_force(xi, xi_dot, xi_Omega, mu, R, L, c, p, table)
    elif code == ALSHAER2005:
        return pi_film_force(xi, xi_dot, xi_Omega, mu, R, L, c, p, table)
    elif code == SHORT:
        return short_force(xi, xi_dot, xi_Omega, mu, R, L, c, p, table)
    elif code == FINITE:
        return finite_force(xi, xi_dot, xi_Omega, mu, R, L, c, p, table)
    else:
        return math.nan, math.nan


@dataclass(frozen=True)
class Ott:
    """Ott's long-bearing solution (paper eqs 1–5, (2−ξ²) typo corrected to (1−ξ²); [T163]).
    An approximation of the π-film (exact for steady load and ξ → 0; off by 5–25 % at moderate ξ
    and diverging for ξ̇ < 0 near the wall) [T25]."""

    code: ClassVar[int] = OTT
    kernel: ClassVar = ott_force
    tag: ClassVar[str] = "T25"
    PARAMS: ClassVar[tuple[str, ...]] = ()


@dataclass(frozen=True)
class Alshaer2005:
    """The paper's π-film long-bearing solution (eqs 6–9 with typos T1–T7 corrected; [T163]):
    exact for the long-bearing Reynolds equation on a half film starting at θ₁ [T21]."""

    code: ClassVar[int] = ALSHAER2005
    kernel: ClassVar = pi_film_force
    tag: ClassVar[str] = "T21"
    PARAMS: ClassVar[tuple[str, ...]] = ()


@dataclass(frozen=True)
class Short:
    """Short-bearing (Ocvirk) π-film: valid for L/D ≲ 0.5 (a PhysicsWarning is issued beyond) [T35]."""

    code: ClassVar[int] = SHORT
    kernel: ClassVar = short_force
    tag: ClassVar[str] = "T35"
    PARAMS: ClassVar[tuple[str, ...]] = ()
    max_length_over_diameter: ClassVar[float] = 0.5


@dataclass(frozen=True)
class Finite:
    """Finite-length bearing: 2-D Reynolds equation solved numerically, tabulated per L/D and
    cavitation condition (built once, cached on disk) [T36–T38, T70–T80]."""

    cavitation: str = DEFAULT_CAVITATION
    """film rupture condition, a name in :mod:`jointdyn.bearing.cavitation`'s registry: ``gumbel``
    (half-Sommerfeld: negative pressures clipped), ``reynolds`` (Swift–Stieber: p ≥ 0 and
    ∂p/∂θ = 0 at rupture, the classical design tables) or a registered plugin [T88]"""
    code: ClassVar[int] = FINITE
    kernel: ClassVar = finite_force
    tag: ClassVar[str] = "T36"
    PARAMS: ClassVar[tuple[str, ...]] = ()

    def __post_init__(self):
        from ..bearing.cavitation import names

        if self.cavitation not in names():
            raise ValueError(f"Finite.cavitation = {self.cavitation!r}: unknown; valid: {list(names())}")

    def table(self, length: float, journal_radius: float) -> np.ndarray:
        """The force table of a bearing of this length and journal radius [m, m]."""
        from .film_finite import build_table

        return build_table(length / (2.0 * journal_radius), cavitation=self.cavitation)


FILM_MODELS = {"ott": Ott, "alshaer2005": Alshaer2005, "short": Short, "finite": Finite}
check_codes(FILM_MODELS, "film model")
FILM_WIDTH = block_width(FILM_MODELS)
NONE = -1  # no film (dry clearance joint)


def film_model(film):
    """The film-model instance for ``film``: a registry name or an instance of a registered
    model (ValueError listing the valid names otherwise)."""
    if isinstance(film, str):
        if film not in FILM_MODELS:
            raise ValueError(f"film model {film!r} is unknown; valid names: {', '.join(FILM_MODELS)}")
        return FILM_MODELS[film]()
    if type(film) not in FILM_MODELS.values():
        raise ValueError(f"film = {film!r}: not a film model; valid names: {', '.join(FILM_MODELS)}")
    return film


def film_name(film) -> str:
    """Registry name of a film model given by name or instance."""
    m = film_model(film)
    return next(k for k, v in FILM_MODELS.items() if v is type(m))


_UNITS = {
    "xi": "-",
    "xi_dot": "1/s",
    "gamma": "rad",
    "gamma_dot": "rad/s",
    "omega_journal": "rad/s",
    "omega_bearing": "rad/s",
    "viscosity": "Pa·s",
    "length": "m",
    "radius": "m",
    "clearance": "m",
}
_NO_TABLE = np.zeros((1, 2))


def film_forces(
    model, xi, xi_dot, gamma, gamma_dot, omega_journal, omega_bearing, viscosity, length, radius, clearance
):
    """Film force on the journal for arrays of states (numpy broadcasting, SI, global rates).

    model          name in ``FILM_MODELS`` or a film-model instance
    xi             eccentricity ratio, 0 ≤ ξ < 1 [-]
    xi_dot         dξ/dt [1/s]
    gamma          line-of-centres angle γ = atan2(e_y, e_x) [rad]
    gamma_dot      dγ/dt in the global frame [rad/s]
    omega_journal  absolute angular velocity of the journal ω_J [rad/s]
    omega_bearing  absolute angular velocity of the bearing ω_B [rad/s]
    viscosity      dynamic viscosity μ > 0 [Pa·s]
    length         bearing length L > 0 [m]
    radius         journal radius R > 0 [m]
    clearance      radial clearance c > 0 [m]

    Returns ``dict(Fr, Ft, Fx, Fy)`` [N] with Ω = ω_J + ω_B − 2γ̇ [T20],
    F_x = F_r cosγ − F_t sinγ, F_y = F_r sinγ + F_t cosγ [T27]. Raises ``ValueError`` naming the
    parameter, its unit, the allowed range and the flat index of the first bad row.
    """
    fm = film_model(model)
    args = dict(
        xi=xi,
        xi_dot=xi_dot,
        gamma=gamma,
        gamma_dot=gamma_dot,
        omega_journal=omega_journal,
        omega_bearing=omega_bearing,
        viscosity=viscosity,
        length=length,
        radius=radius,
        clearance=clearance,
    )
    try:
        arr = dict(zip(args, np.broadcast_arrays(*[np.asarray(v, dtype=float) for v in args.values()])))
    except ValueError as err:
        raise ValueError(f"film_forces: inputs do not broadcast to one shape ({err})") from None
    for name, v in arr.items():
        bad = np.flatnonzero(~np.isfinite(v))
        if bad.size:
            raise ValueError(
                f"{name} [{_UNITS[name]}] must be finite; got {v.flat[bad[0]]!r} at index {bad[0]}"
            )
    for name in ("viscosity", "length", "radius", "clearance"):
        bad = np.flatnonzero(arr[name] <= 0.0)
        if bad.size:
            raise ValueError(
                f"{name} [{_UNITS[name]}] must be > 0; got {arr[name].flat[bad[0]]!r} at index {bad[0]}"
            )
    x = arr["xi"]
    bad = np.flatnonzero((x < 0.0) | (x >= 1.0))
    if bad.size:
        raise ValueError(f"xi [-] must be in [0, 1); got {x.flat[bad[0]]!r} at index {bad[0]}")
    code = fm.code
    p = np.zeros(FILM_WIDTH)
    p[: len(fm.PARAMS)] = params_of(fm)
    xi_om = x * (arr["omega_journal"] + arr["omega_bearing"] - 2.0 * arr["gamma_dot"])  # [T20]
    fr = np.empty(x.shape)
    ft = np.empty(x.shape)
    tables = {}
    if hasattr(fm, "table"):  # one table per distinct (length, radius)
        for i in range(x.size):
            key = (float(arr["length"].flat[i]), float(arr["radius"].flat[i]))
            if key not in tables:
                tables[key] = fm.table(*key)
    for i in range(x.size):
        tab = tables.get((float(arr["length"].flat[i]), float(arr["radius"].flat[i])), _NO_TABLE)
        fr.flat[i], ft.flat[i] = film_force(
            code,
            x.flat[i],
            arr["xi_dot"].flat[i],
            xi_om.flat[i],
            arr["viscosity"].flat[i],
            arr["radius"].flat[i],
            arr["length"].flat[i],
            arr["clearance"].flat[i],
            p,
            tab,
        )
    g = arr["gamma"]
    return {
        "Fr": fr,
        "Ft": ft,
        "Fx": fr * np.cos(g) - ft * np.sin(g),
        "Fy": fr * np.sin(g) + ft * np.cos(g),
    }  # [T27]


# -- optional capability: exact Jacobians [T90–T97] ------------------------------------------------
# ``jacobian(xi, xi_dot, xi_Omega, mu, R, L, c, p, table) -> (Fr, Ft, ∂Fr/∂ξ, ∂Fr/∂ξ̇, ∂Fr/∂(ξΩ),
# ∂Ft/∂ξ, ∂Ft/∂ξ̇, ∂Ft/∂(ξΩ))``; a model without one is differentiated by finite differences in the
# system Jacobian (``element_jacobians.fallback_elements`` names such elements).
from . import film_jacobians as _jac  # noqa: E402  (it reads the codes above)

Ott.jacobian = _jac.ott_jac  # type: ignore[attr-defined]
Alshaer2005.jacobian = _jac.pi_film_jac  # type: ignore[attr-defined]
Short.jacobian = _jac.short_jac  # type: ignore[attr-defined]
Finite.jacobian = _jac.finite_jac  # type: ignore[attr-defined]
