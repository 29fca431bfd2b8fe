"""Design table of the grooved bearing and the numerical dynamic coefficients of any ``finite``
film end [T244–T247] (columns of ``bearing-table``)."""

from __future__ import annotations

import math

import numpy as np

from jointdyn.bearing.operating import dimensional_point
from jointdyn.core import interrupts
from jointdyn.core.checks import check
from jointdyn.film import grooved
from jointdyn.film.coefficients import stability_threshold
from jointdyn.film.field import peak_of, rupture_of
from jointdyn.film.grooved import GROOVED_MESH, equilibrium
from jointdyn.film.jfo import flows
from jointdyn.film.jfo_step import couette_gas

EPS_MAX = 0.99  # the largest ε of the grooved operating point [T342]
_K = ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy")


def numeric_coefficients(cavitation: str, ld: float, eps, supply, mesh=GROOVED_MESH) -> dict:
    """Columns kxx … cyy, critical_mass, whirl_ratio (arrays over ε) by central differences of
    the converged film [T247]; ``supply`` a :class:`Grooves` or "line"."""
    rows = []
    for x in eps:
        interrupts.check()  # [T332]
        c = grooved.coefficients(ld, float(x), cavitation, supply, mesh)
        c.update(stability_threshold(c["K"], c["C"]))
        rows.append(c)
    cols = (*_K, "critical_mass", "whirl_ratio")
    return {k: np.array([r[k] for r in rows]) for k in cols}


def _couette(x: float, supply, fixed, prob, fill) -> float:
    """∫∫θ_f dθ dζ/H of the Couette shear over the length 2λ [T77]: around the whole clearance,
    2λ·2π/√(1 − ε²), except for a partial arc, whose open part has no bearing surface: the arc's
    nodes (uniform mesh) [T366]; a mass-conserving film's partly filled cells carry θ_f of it
    (``fill`` None: a film that is full) [T375]."""
    nt, nz = prob.shape
    if not isinstance(supply, grooved.PartialArc):
        full = 2.0 * prob.lam * (2.0 * math.pi / math.sqrt(1.0 - x * x))
    else:
        on = ~fixed.reshape(nt, nz)[:, 0]
        full = 2.0 * prob.lam * float(np.sum(2.0 * math.pi / nt / (1.0 + x * np.cos(prob.film_theta[on]))))
    if fill is None:
        return full
    H = np.repeat(1.0 + x * np.cos(prob.film_theta), nz)
    return full - couette_gas(fill, H, prob.area, prob.cv, np.diff(prob.zeta))


def grooved_table(
    cavitation: str, ld: float, eps, grooves, mesh=GROOVED_MESH, coefficients: bool = True
) -> dict:
    """Steady table of the grooved bearing with the load direction fixed (grooves fixed relative
    to the load) per ε [T244–T247]: ``sommerfeld``, ``attitude_deg``, ``friction_variable``
    (Couette shear of the full clearance, as Raimondi–Boyd; of the lubricant only, θ_f, for
    ``jfo`` [T375]), ``flow_variable`` Q/(RcNL) of the
    total supply, ``side_flow_ratio``, ``pressure_ratio``, ``theta_pmax_deg``, ``theta_end_deg``,
    ``groove_flow_<k>`` the flow variable of groove k (k = 1 at +90° from the load; ``hole_flow_<k>``,
    ``circumferential_flow_1`` for the other supply features of [T366]; NaN for a film that is not
    mass conserving and has a cavitated zone, whose ``flow_variable`` is then its side leakage,
    [T370]), ``fill_min``
    (smallest fill fraction: 1 for films that are not mass conserving), ``residual`` and the
    dynamic coefficients (central differences)."""
    rows = []
    for x in eps:
        interrupts.check()  # [T332]
        x = float(x)
        phi, W, sol, prob, fixed, lab = equilibrium(ld, x, cavitation, grooves, mesh)
        nt, nz = prob.shape
        B = x / (2.0 + x * x)
        fill = np.ones(nt * nz) if sol.fill is None else sol.fill
        fl = flows(prob, 0.0, B, sol.P, fill, fixed, lab)
        if sol.fill is None and np.any((sol.P <= 0.0) & ~fixed):
            # a film that does not conserve mass and has a cavitated zone does not know where its
            # oil goes: the supply is the side leakage (steady state), the split per feature is
            # unknown [T370]
            fl["supply"] = fl["side"]
            fl["per_groove"] = [math.nan] * len(fl["per_groove"])
        th = prob.film_theta
        P2 = sol.P.reshape(nt, nz)
        Ft = -W * math.sin(phi)  # the film force −W·(load direction) on t = (−sin φ, cos φ)
        j = int(np.argmax(P2.max(axis=0)))  # the row of the peak: mid-plane, or a land's [T366]
        pmax, thp = peak_of(th, P2[:, j])
        the = rupture_of(th, P2[:, j], cavitation)
        r = {
            "eps": x,
            "ld": ld,
            "sommerfeld": 2.0 * ld / (math.pi * W),
            "attitude_deg": math.degrees(phi),
            "friction_variable": (_couette(x, grooves, fixed, prob, sol.fill) + 0.5 * x * Ft) / W,
            "flow_variable": math.pi * fl["supply"] / (2.0 * ld),
            "side_flow_ratio": fl["side"] / fl["supply"],
            "pressure_ratio": W / (24.0 * ld * pmax),
            "theta_pmax_deg": math.degrees(math.pi - thp),
            "theta_end_deg": math.degrees(the - math.pi),
            "fill_min": float(np.min(fill)),
            "residual": sol.residual,
        }
        for k, q in enumerate(fl["per_groove"]):
            r[f"{grooves.flow_name}_{k + 1}"] = math.pi * q / (2.0 * ld)
        rows.append(r)
    out = {c: np.array([r[c] for r in rows]) for c in rows[0]}
    if coefficients:
        out.update(numeric_coefficients(cavitation, ld, eps, grooves, mesh))
    return out


def grooved_equilibrium(
    load: float,
    speed: float,
    radius: float,
    length: float,
    clearance: float,
    viscosity: float,
    cavitation: str,
    supply,
    feed_pressure: float = 0.0,
    mesh=GROOVED_MESH,
) -> dict:
    """Steady operating point of the axially grooved bearing for a load W and journal speed N,
    the load direction fixed relative to the grooves [T246, T342]: solves S(ε) = S_given with S of
    the grooved equilibrium, the supply pressure made dimensionless at this speed and viscosity
    [T245].

    load, speed, radius, length, clearance, viscosity  W [N], N [rev/s], R, L, c [m], μ [Pa·s], > 0
    supply        the supply feature (:class:`~jointdyn.film.grooved.Grooves`, ``FeedHoles`` or
                  ``CircumferentialGroove``); its ``feed`` is replaced by feed_pressure's [T366]
    feed_pressure p_f [Pa], gauge, ≥ 0
    Returns the keys of :func:`jointdyn.bearing.design.equilibrium` (``flow`` the total supply
    [m³/s]) plus the flow per feature ``<kind>_flow_<k>`` [m³/s] (k = 1 at +90° from the load)
    and ``fill_min`` [-]."""
    import dataclasses

    from scipy.optimize import brentq

    for name, v, unit in (
        ("load", load, "N"),
        ("speed", speed, "rev/s"),
        ("radius", radius, "m"),
        ("length", length, "m"),
        ("clearance", clearance, "m"),
        ("viscosity", viscosity, "Pa·s"),
    ):
        check(name, v, unit, "> 0")
    if clearance >= radius:  # [T284]
        raise ValueError(f"clearance = {clearance!r} [m]: must be < radius = {radius!r} (c < R)")
    if not (math.isfinite(feed_pressure) and feed_pressure >= 0.0):
        raise ValueError(f"feed_pressure = {feed_pressure!r} [Pa]: must be finite and >= 0 (gauge)")
    omega = 2.0 * math.pi * speed
    feed = feed_pressure * clearance**2 / (6.0 * viscosity * omega * radius**2)  # P_f [T245]
    supply = dataclasses.replace(supply, feed=feed)
    ld = length / (2.0 * radius)
    S_given = (radius / clearance) ** 2 * viscosity * speed / (load / (2.0 * radius * length))

    def row(eps):
        try:
            tab = grooved_table(cavitation, ld, [eps], supply, mesh, False)
        except RuntimeError as err:  # the attitude iteration [T246]
            raise ValueError(f"load = {load!r} [N]: no grooved equilibrium found ({err})") from None
        return {k: float(v[0]) for k, v in tab.items()}

    def g(u):  # S falls with ε; log S is nearly linear in u = −ln(1 − ε)
        return math.log(row(1.0 - math.exp(-u))["sommerfeld"]) - math.log(S_given)

    lo, hi = 1e-3, -math.log(1.0 - EPS_MAX)  # the 2° mesh resolves h_min = 0.01c
    if g(hi) > 0.0:
        raise ValueError(
            f"load = {load!r} [N]: the grooved bearing cannot carry it below eps = {EPS_MAX} "
            f"(S = {S_given:.4g} < S(eps = {EPS_MAX}) = {math.exp(g(hi)) * S_given:.4g})"
        )
    if g(lo) < 0.0:
        raise ValueError(
            f"load = {load!r} [N]: too light, eps < 1e-3 (S = {S_given:.4g}); the film is Petroff's"
        )
    eps = 1.0 - math.exp(-brentq(g, lo, hi, xtol=1e-12, rtol=1e-10))
    r = row(eps)
    out = dimensional_point(r, eps, load, speed, radius, length, clearance, S_given)
    out["fill_min"] = r["fill_min"]
    q = radius * clearance * speed * length  # flow variable Q/(R c N L) [T77]
    out.update({k: v * q for k, v in r.items() if k.startswith(supply.flow_name + "_")})
    return out
