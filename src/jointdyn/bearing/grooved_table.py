"""Design table of the grooved bearing and the numerical dynamic coefficients of any ``finite``
film end [T244–T247] (columns of ``bearing-table``)."""

from __future__ import annotations

import math

import numpy as np

from jointdyn.core import interrupts
from jointdyn.film import grooved
from jointdyn.film.coefficients import stability_threshold
from jointdyn.film.field import peak_of, rupture_of
from jointdyn.film.grooved import GROOVED_MESH, Grooves, equilibrium
from jointdyn.film.jfo import flows

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


def grooved_table(
    cavitation: str, ld: float, eps, grooves: Grooves, mesh=GROOVED_MESH, coefficients: bool = True
) -> dict:
    """Steady table of the grooved bearing with the load direction fixed (grooves fixed relative
    to the load) per ε [T244–T247]: ``sommerfeld``, ``attitude_deg``, ``friction_variable``
    (Couette shear of the full clearance, as Raimondi–Boyd), ``flow_variable`` Q/(RcNL) of the
    total supply, ``side_flow_ratio``, ``pressure_ratio``, ``theta_pmax_deg``, ``theta_end_deg``,
    ``groove_flow_<k>`` the flow variable of groove k (k = 1 at +90° from the load), ``fill_min``
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
        th = prob.film_theta
        P2 = sol.P.reshape(nt, nz)
        Ft = -W * math.sin(phi)  # the film force −W·(load direction) on t = (−sin φ, cos φ)
        pmax, thp = peak_of(th, P2[:, 0])
        the = rupture_of(th, P2[:, 0], cavitation)
        r = {
            "eps": x,
            "ld": ld,
            "sommerfeld": 2.0 * ld / (math.pi * W),
            "attitude_deg": math.degrees(phi),
            "friction_variable": (4.0 * math.pi * ld / math.sqrt(1.0 - x * x) + 0.5 * x * Ft) / W,
            "flow_variable": math.pi * fl["supply"] / (2.0 * ld),
            "side_flow_ratio": fl["side"] / fl["supply"],
            "pressure_ratio": W / (24.0 * ld * pmax),
            "theta_pmax_deg": math.degrees(math.pi - thp),
            "theta_end_deg": math.degrees(the - math.pi),
            "fill_min": float(np.min(fill)),
            "residual": sol.residual,
        }
        for k, q in enumerate(fl["per_groove"]):
            r[f"groove_flow_{k + 1}"] = math.pi * q / (2.0 * ld)
        rows.append(r)
    out = {c: np.array([r[c] for r in rows]) for c in rows[0]}
    if coefficients:
        out.update(numeric_coefficients(cavitation, ld, eps, grooves, mesh))
    return out
