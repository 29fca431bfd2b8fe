"""Steady journal-bearing design quantities: the Raimondi–Boyd table and the equilibrium for a
given load [T73–T79].

Steady operation: bearing fixed, journal speed ω = 2πN > 0, no squeeze (A = 0, B = ξω/(2+ξ²)).
Raimondi–Boyd definitions (Trans. ASLE 1 (1958) 159–209): S = (R/c)²μN/P with P = W/(2RL) and N
in rev/s; attitude φ between the load line and the line of centres; friction variable (R/c)·f,
f = T_J/(W R) with T_J the friction torque on the journal; flow variable Q/(R c N L), Q the flow
into the film at the supply (maximum film); side-flow ratio Q_s/Q; pressure ratio P/p_max;
θ_pmax the angle from the peak pressure forward to the minimum film; θ_end the angle from the
minimum film forward to the film end (rupture) [T77].
"""

from __future__ import annotations

import math

import numpy as np

from jointdyn.bearing.operating import dimensional_point
from jointdyn.core import interrupts
from jointdyn.film import field as fm
from jointdyn.film.cavitation import check_cavitation
from jointdyn.film.fv import DEFAULT_MESH, check_ld, check_xi
from jointdyn.film.long_short import long_steady, short_steady

#: the columns of :func:`bearing_table`, in order
COLUMNS = (
    "eps",
    "ld",
    "sommerfeld",
    "attitude_deg",
    "friction_variable",
    "flow_variable",
    "side_flow_ratio",
    "pressure_ratio",
    "theta_pmax_deg",
    "theta_end_deg",
)
MODELS = ("finite", "long", "short")
#: dynamic-coefficient columns [T107–T108], added to the table where the film has a kernel twin
COEFFICIENT_COLUMNS = ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy", "critical_mass", "whirl_ratio")
#: (table model, cavitation) -> the film model whose kernel is the same film (coefficients from
#: its exact Jacobian); the other ``finite`` films get them by central differences [T247]
COEFFICIENT_MODEL = {
    ("short", "gumbel"): "short",
    ("long", "gumbel"): "alshaer2005",
    ("finite", "gumbel"): "finite",
}
#: largest eccentricity ratio the equilibrium search may use [-]
EPS_MAX = 0.999


#: film-model names (``FILM_MODELS``) accepted as table models: name -> (table model, the film's
#: own cavitation); ``finite`` is the same name in both lists (its cavitation is an option of both)
FILM_ALIASES = {"alshaer2005": ("long", "gumbel")}  # the π-film: long bearing, half-Sommerfeld [T21]


def _check_model(model, cavitation):
    """(table model, cavitation) after the film-name aliases; ``cavitation`` None: the aliased
    film's own, ``gumbel`` for ``short``, else Swift–Stieber (``reynolds``)."""
    if model in FILM_ALIASES:
        film = model
        model, own = FILM_ALIASES[film]
        if cavitation not in (None, own):
            raise ValueError(
                f"cavitation = {cavitation!r} with model {film!r}: that film is the {model!r} bearing with "
                f"{own!r} cavitation" + (f"; use model 'long' for {cavitation!r}" if model == "long" else "")
            )
        cavitation = own
    if cavitation is None:  # Ocvirk's film exists with Gümbel's condition only [T35]
        cavitation = "gumbel" if model == "short" else "reynolds"
    if model not in MODELS:
        hint = " ('ott' approximates 'alshaer2005', it is not a table model)" if model == "ott" else ""
        raise ValueError(
            f"model = {model!r}: must be one of {', '.join(MODELS)} or a film name {list(FILM_ALIASES)}{hint}"
        )
    check_cavitation(cavitation)
    if model == "short" and cavitation != "gumbel":
        raise ValueError(f"cavitation = {cavitation!r} with model 'short': Ocvirk's film allows only gumbel")
    if model == "long" and cavitation not in ("gumbel", "reynolds"):
        raise ValueError(
            f"cavitation = {cavitation!r} with model 'long': closed forms exist for gumbel and reynolds only"
        )
    return model, cavitation


def finite_steady(eps: float, ld: float, cavitation: str = "reynolds", mesh=DEFAULT_MESH, cavitated=None):
    """Nondimensional steady quantities of the finite bearing [T73–T77]: dict with W̄ = W c²/(μωR⁴),
    F̄_r, F̄_t, the Raimondi–Boyd variables, the solver's residual and iteration count, and the
    cavitated set (warm start for the next ε). Lubricant supplied at the maximum film (θ = 0)."""
    B = eps / (2.0 + eps * eps)  # ξΩ/(2+ξ²) with Ω = ω = 1
    f = fm.solve(eps, ld, 0.0, B, cavitation, feed=True, mesh=mesh, cavitated=cavitated)
    fr, ft = fm.forces(f)
    Fr, Ft = 6.0 * fr, 6.0 * ft  # F = R²·(6μωR²/c²)∫∫P → units μωR⁴/c² [T74]
    W = math.hypot(Fr, Ft)
    q = fm.inlet_flow(f)
    pmax, thp = fm.peak(f)
    the = fm.rupture_angle(f, cavitation)
    out = {
        "W": W,
        "Fr": Fr,
        "Ft": Ft,
        "couette": fm.couette_integral(f),
        "flow": q,
        "side": fm.side_flow(f),
        "pmax": pmax,
        "theta_peak": thp,
        "theta_rupture": the,
        "residual": f.residual,
        "iterations": f.iterations,
        "cavitated": f.state,  # warm start of the next ε (the condition's own state)
    }
    return out


def _row(eps, ld, d):
    """Raimondi–Boyd variables from the nondimensional results d (units μωR⁴/c², λ = ld) [T77]."""
    W = d["W"]
    return {
        "eps": eps,
        "ld": ld,
        "sommerfeld": 2.0 * ld / (math.pi * W),  # S = (R/c)²μN/P = 4λ/(2πW̄)
        "attitude_deg": math.degrees(math.atan2(d["Ft"], -d["Fr"])),
        # T_J = (μωR⁴/c)(C + ξF̄_t/2) [T75]; (R/c)f = T_J/(W c)
        "friction_variable": (d["couette"] + 0.5 * eps * d["Ft"]) / W,
        "flow_variable": math.pi * d["flow"] / (2.0 * ld),  # Q = (ωR²c/2)·q
        "side_flow_ratio": d["side"] / d["flow"],
        "pressure_ratio": W / (24.0 * ld * d["pmax"]),  # P = W/(4λR²), p_max = (6μωR²/c²)P_max
        "theta_pmax_deg": math.degrees(math.pi - d["theta_peak"]),
        "theta_end_deg": math.degrees(d["theta_rupture"] - math.pi),
    }


def _check_eps_list(eps_list):
    e = np.atleast_1d(np.asarray(eps_list, dtype=float))
    if e.size == 0:
        raise ValueError("eps list is empty: give at least one eccentricity ratio in [0, 1)")
    for x in e:
        if not (math.isfinite(x) and 0.0 < x < 1.0):
            raise ValueError(f"eps = {float(x)!r} [-]: must be in (0, 1) (ε = 0 carries no load)")
    return e


def steady_quantities(model: str, cavitation: str, ld: float, eps: float, mesh=DEFAULT_MESH, cavitated=None):
    """Nondimensional steady results (see :func:`finite_steady`) of ``model`` at one ε."""
    if model == "finite":
        return finite_steady(eps, ld, cavitation, mesh, cavitated)
    if model == "long":
        return long_steady(eps, ld, cavitation)
    return short_steady(eps, ld)


def bearing_table(
    model: str,
    cavitation: str | None,
    ld: float,
    eps_list,
    mesh=DEFAULT_MESH,
    grooves=None,
    coefficients: bool = True,
) -> dict:
    """Steady design table [T77]: dict column → array (``COLUMNS``), one entry per ε; also the
    dynamic coefficients and Lund's stability threshold (``COEFFICIENT_COLUMNS``, dimensionless
    k = Kc/W, c = Ccω/W, M̄ = mcω²/W; [T107–T108]): from the exact Jacobian of the kernel twin
    for the films in ``COEFFICIENT_MODEL``, by central differences for the other ``finite``
    films [T247] and for ``long`` with ``reynolds`` [T344].

    model       "finite" (2-D Reynolds [T70–T72]), "long" (L/D → ∞ [T78]) or "short" (Ocvirk [T79]);
                a film name of ``FILM_ALIASES`` (``alshaer2005`` = long with gumbel) is accepted
    cavitation  "reynolds" (Swift–Stieber, as Raimondi–Boyd), "gumbel" (half-Sommerfeld) or
                "jfo" (mass-conserving, ``finite`` only [T240–T243]); None: the aliased film's
                own, gumbel for short, else reynolds
    ld          L/D > 0 [-] (``long`` uses it only in the ``ld`` column)
    eps_list    eccentricity ratios, each in (0, 1) [-]
    mesh        finite-volume mesh of ``finite`` (cells around, cells on the half length) [-]
    grooves     None (supply line at the maximum film) or a :class:`~jointdyn.film.grooved.Grooves`
                (``finite`` only; table from :mod:`.grooved_table` [T244–T247])
    coefficients  False: the steady columns only (the numerical k/c of [T247] cost ≈ 10 film
                solves per ε)
    """
    model, cavitation = _check_model(model, cavitation)
    check_ld(float(ld))
    e = _check_eps_list(eps_list)
    if grooves is not None:
        if model != "finite":
            raise ValueError(f"grooves with model = {model!r}: supply grooves need the 'finite' film")
        from jointdyn.bearing.grooved_table import grooved_table

        return grooved_table(cavitation, float(ld), e, grooves, coefficients=coefficients)
    cav = None
    rows: list = [None] * e.size
    for k in np.argsort(e):  # ascending ε: the cavitated set of the previous ε is the warm start
        interrupts.check()  # a signal recorded by a caller's catching() stops here [T332]
        d = steady_quantities(model, cavitation, float(ld), float(e[k]), mesh, cav)
        cav = d.get("cavitated")
        rows[k] = _row(float(e[k]), float(ld), d)
    out = {c: np.array([r[c] for r in rows]) for c in COLUMNS}
    twin = COEFFICIENT_MODEL.get((model, cavitation))
    if not coefficients:
        pass
    elif twin is not None:
        from jointdyn.film.coefficients import dynamic_coefficients

        coef = [dynamic_coefficients(twin, float(ld), float(x)) for x in e]
        out.update({c: np.array([d[c] for d in coef]) for c in COEFFICIENT_COLUMNS})
    elif model == "long":  # Reynolds' film end: the 1-D free-boundary film differenced [T344]
        from jointdyn.film.coefficients import stability_threshold
        from jointdyn.film.long_dynamic import long_reynolds_coefficients

        rows_c = []
        for x in e:
            interrupts.check()  # [T332]
            c = long_reynolds_coefficients(float(ld), float(x))
            c.update(stability_threshold(c["K"], c["C"]))
            rows_c.append(c)
        out.update({c: np.array([r[c] for r in rows_c]) for c in COEFFICIENT_COLUMNS})
    elif model == "finite":  # the supply line stays where the equilibrium's maximum film is [T247]
        from jointdyn.bearing.grooved_table import numeric_coefficients

        out.update(numeric_coefficients(cavitation, float(ld), e, "line", (max(180, mesh[0]), mesh[1])))
    return out


def check_positive(*items) -> None:
    """ValueError naming the first ``(name, value, unit)`` that is not finite and > 0."""
    for name, v, unit in items:
        if not (math.isfinite(v) and v > 0.0):
            raise ValueError(f"{name} = {v!r} [{unit}]: must be finite and > 0")


def equilibrium(
    load: float,
    speed: float,
    radius: float,
    length: float,
    clearance: float,
    viscosity: float,
    model: str = "finite",
    cavitation: str | None = None,
    mesh=DEFAULT_MESH,
) -> dict:
    """Steady operating point for a load W and journal speed N [T77]: solves S(ε) = S_given.

    load       W > 0 [N]
    speed      N > 0 [rev/s] (bearing fixed)
    radius     journal radius R > 0 [m]
    length     bearing length L > 0 [m]
    clearance  radial clearance c > 0 [m]
    viscosity  μ > 0 [Pa·s]
    model, cavitation as :func:`bearing_table`
    Returns dict: eps [-], attitude_deg [deg], h_min [m], friction_torque [N·m] (on the journal,
    resisting), power_loss [W], peak_pressure [Pa], theta_pmax_deg, theta_end_deg [deg],
    flow [m³/s], side_flow [m³/s], sommerfeld [-].
    """
    check_positive(
        ("load", load, "N"),
        ("speed", speed, "rev/s"),
        ("radius", radius, "m"),
        ("length", length, "m"),
        ("clearance", clearance, "m"),
        ("viscosity", viscosity, "Pa·s"),
    )
    model, cavitation = _check_model(model, cavitation)
    ld = length / (2.0 * radius)
    if clearance >= radius:  # before the load is judged: c ≥ R is no journal bearing [T284]
        raise ValueError(f"clearance = {clearance!r} [m]: must be < radius = {radius!r} (c < R)")
    S_given = (radius / clearance) ** 2 * viscosity * speed / (load / (2.0 * radius * length))

    def S_of(eps):
        return _row(eps, ld, steady_quantities(model, cavitation, ld, eps, mesh))["sommerfeld"]

    S_max_load = S_of(EPS_MAX)
    if S_given < S_max_load:
        raise ValueError(
            f"load = {load!r} [N]: the bearing cannot carry it below eps = {EPS_MAX} "
            f"(S = {S_given:.4g} < S(eps = {EPS_MAX}) = {S_max_load:.4g}); the largest load is "
            f"{load * S_given / S_max_load:.4g} N"
        )
    from scipy.optimize import brentq

    # S falls monotonically with ε; solve in u = −ln(1−ε) where log S is nearly linear
    def g(u):
        return math.log(S_of(1.0 - math.exp(-u))) - math.log(S_given)

    lo, hi = 1e-4, -math.log(1.0 - EPS_MAX)
    if g(lo) < 0.0:
        raise ValueError(
            f"load = {load!r} [N]: too light, eps < 1e-4 (S = {S_given:.4g}); the film is Petroff's"
        )
    u = brentq(g, lo, hi, xtol=1e-12, rtol=1e-10)
    eps = 1.0 - math.exp(-u)
    check_xi(eps)
    d = steady_quantities(model, cavitation, ld, eps, mesh)
    r = _row(eps, ld, d)
    return dimensional_point(
        r, eps, load, speed, radius, clearance=clearance, length=length, sommerfeld=S_given
    )
