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

from jointdyn.core.dispatch import all_laws, law_switch
from jointdyn.core.layout import block_width, check_codes, params_of
from jointdyn.film import jacobians as _jac
from jointdyn.film.finite import DEFAULT_CAVITATION, finite_force
from jointdyn.film.kernels import (  # noqa: F401  (the kernels are part of this module's API)
    ALSHAER2005,
    FINITE,
    OTT,
    SHORT,
    ott_force,
    pi_film_force,
    short_force,
)


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
    cavitation condition (built once, cached on disk) [T36–T38, T70–T80]; with ``cavitation =
    "jfo"`` the transient mass-conserving film, its cell contents carried by the element [T306]."""

    cavitation: str = DEFAULT_CAVITATION
    """film rupture condition, a name in :mod:`jointdyn.film.cavitation`'s registry: ``gumbel``
    (half-Sommerfeld: negative pressures clipped), ``reynolds`` (Swift–Stieber: p ≥ 0 and
    ∂p/∂θ = 0 at rupture, the classical design tables), ``jfo`` (mass-conserving, transient: no
    table, the film's history is part of the element [T306]) or a registered plugin [T88]"""
    supply: str = "axial_grooves"
    """jfo only: the supply feature [T366]: ``axial_grooves`` (over the full length),
    ``feed_holes`` (round, at mid-length) or ``circumferential_groove`` (all around, at mid-length)"""
    supply_angle: float = 90.0
    """jfo only: centre of the (first) axial groove or feed hole in the bushing frame, from the
    bushing body's x axis counter-clockwise [deg], in [0, 360)"""
    supply_count: int = 1
    """jfo only: axial grooves or feed holes, evenly spaced from ``supply_angle`` [-], 1 … 8"""
    supply_width: float = 20.0
    """jfo only: angular width of each axial groove [deg], in (0, 360/supply_count)"""
    supply_diameter: float = 0.0
    """jfo only: feed-hole diameter, or the circumferential groove's axial width [m], > 0 and
    < the bearing length (needed by those two features)"""
    supply_pressure: float = 0.0
    """jfo only: gauge pressure of the oil in the supply groove [Pa], ≥ 0"""
    cells_around: int = 30
    """jfo only: cells of the uniform mesh around the bearing [-], 8 … 720 (default 30 × 3 [T351])"""
    cells_half_length: int = 3
    """jfo only: cells of the uniform mesh on the half length [-], 2 … 64"""
    code: ClassVar[int] = FINITE
    kernel: ClassVar = finite_force
    tag: ClassVar[str] = "T36"
    PARAMS: ClassVar[tuple[str, ...]] = ()

    def __post_init__(self):
        from jointdyn.film.cavitation import names

        if self.cavitation not in names():
            raise ValueError(f"Finite.cavitation = {self.cavitation!r}: unknown; valid: {list(names())}")
        if self.supply not in SUPPLY_FEATURES:
            raise ValueError(f"Finite.supply = {self.supply!r}: unknown; valid: {list(SUPPLY_FEATURES)}")
        if self.supply != "axial_grooves" and not self.supply_diameter > 0.0:
            raise ValueError(
                f"Finite.supply_diameter = {self.supply_diameter!r} [m]: {self.supply} need(s) it > 0 "
                "(hole diameter or groove width, < the bearing length)"
            )
        checks = (
            ("supply_angle", "deg", "in [0, 360)", lambda v: 0.0 <= v < 360.0),
            ("supply_count", "-", "an integer in [1, 8]", lambda v: v == int(v) and 1 <= v <= 8),
            ("supply_diameter", "m", ">= 0", lambda v: v >= 0.0),
            ("supply_width", "deg", "in (0, 360)", lambda v: 0.0 < v < 360.0),
            ("supply_pressure", "Pa", ">= 0", lambda v: v >= 0.0),
            ("cells_around", "-", "an integer in [8, 720]", lambda v: v == int(v) and 8 <= v <= 720),
            ("cells_half_length", "-", "an integer in [2, 64]", lambda v: v == int(v) and 2 <= v <= 64),
        )
        for name, unit, allowed, ok in checks:
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and ok(v)):
                raise ValueError(f"Finite.{name} = {v!r} [{unit}]: must be {allowed}")

    @property
    def transient(self) -> bool:
        """True for the mass-conserving film: no table, the element carries its contents [T306]."""
        from jointdyn.film.cavitation import condition

        return condition(self.cavitation).mass_conserving

    def table(self, length: float, journal_radius: float) -> np.ndarray:
        """The force table of a bearing of this length and journal radius [m, m]."""
        from jointdyn.film.finite import build_table

        if self.transient:
            raise ValueError(
                f"Finite.cavitation = {self.cavitation!r}: a mass-conserving film needs its content "
                "history, which a table has not; it runs as a journal_bearing element in the "
                "multibody loop [T306] (steady: film-force/bearing-table --cavitation jfo)"
            )
        return build_table(length / (2.0 * journal_radius), cavitation=self.cavitation)


#: the supply features of the transient jfo film [T366]
SUPPLY_FEATURES = ("axial_grooves", "feed_holes", "circumferential_groove")
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
    with np.errstate(over="ignore", invalid="ignore"):  # overflow is found and refused below
        F = {"Fr": fr, "Ft": ft, "Fx": fr * np.cos(g) - ft * np.sin(g), "Fy": fr * np.sin(g) + ft * np.cos(g)}
    bad = np.flatnonzero(~np.all([np.isfinite(v) for v in F.values()], axis=0))
    if bad.size:  # overflow of huge rates or properties: refused, never written [T284]
        raise ValueError(
            f"film force not finite (overflow: the state's rates or properties are too large for a "
            f"float) at index {bad[0]}"
        )
    return F  # [T27]


# -- optional capability: exact Jacobians [T90–T97] ------------------------------------------------
# ``jacobian(xi, xi_dot, xi_Omega, mu, R, L, c, p, table) -> (Fr, Ft, ∂Fr/∂ξ, ∂Fr/∂ξ̇, ∂Fr/∂(ξΩ),
# ∂Ft/∂ξ, ∂Ft/∂ξ̇, ∂Ft/∂(ξΩ))``; a model without one is differentiated by central differences of
# its kernel in the compiled Jacobian (``jacobians.FD_JAC`` [T229]; ``simulate`` names it in a warning).

Ott.jacobian = _jac.ott_jac  # type: ignore[attr-defined]
Alshaer2005.jacobian = _jac.pi_film_jac  # type: ignore[attr-defined]
Short.jacobian = _jac.short_jac  # type: ignore[attr-defined]
Finite.jacobian = _jac.finite_jac  # type: ignore[attr-defined]


# -- the dispatch by code, generated from FILM_MODELS when a caller is compiled [T229] -------------
_ARGS = ("xi", "xi_dot", "xi_Omega", "mu", "R", "L", "c", "p", "table")
film_dispatch = law_switch("film_dispatch", 0, FILM_MODELS, _ARGS, None, "(math.nan, math.nan)")
"""compiled only: ``film_dispatch(laws, code, *args) -> (Fr, Ft)`` over the film models present in
``laws`` (the journal element's entry of the system's kinds); (nan, nan) for another code"""
film_jac_dispatch = law_switch(
    "film_jac_dispatch",
    0,
    FILM_MODELS,
    _ARGS,
    _jac.FD_JAC,
    "(" + "math.nan, " * 8 + ")",
)
"""compiled only: the 8-tuple of ``jacobian`` (exact, or central differences of the kernel)"""


@njit(cache=True)
def _film_force(laws, code, xi, xi_dot, xi_Omega, mu, R, L, c, p, table):
    return film_dispatch(laws, code, xi, xi_dot, xi_Omega, mu, R, L, c, p, table)


@njit(cache=True)
def _film_jac(laws, code, xi, xi_dot, xi_Omega, mu, R, L, c, p, table):
    return film_jac_dispatch(laws, code, xi, xi_dot, xi_Omega, mu, R, L, c, p, table)


def film_force(code, xi, xi_dot, xi_Omega, mu, R, L, c, p, table):
    """Film force (F_r, F_t) [N] of the model with registry code ``code`` through the compiled
    dispatch over every registered model [T229]; (nan, nan) for an unknown code. Arguments as
    in the module docstring."""
    return _film_force(all_laws(FILM_MODELS, 0), code, xi, xi_dot, xi_Omega, mu, R, L, c, p, table)


def film_jac(code, xi, xi_dot, xi_Omega, mu, R, L, c, p, table):
    """Film force and Jacobian (the 8-tuple of :mod:`jointdyn.film.jacobians`) of model ``code``:
    its ``jacobian``, or central differences of its kernel for a model without one [T90, T229];
    NaNs for an unknown code."""
    return _film_jac(all_laws(FILM_MODELS, 0), code, xi, xi_dot, xi_Omega, mu, R, L, c, p, table)
