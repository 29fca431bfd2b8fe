"""Comparison of the design table with the published Raimondi–Boyd (1958) tables [T77] and
Butenschön's (1976) finite-bearing table [T84]: used by the validation tests and the docs page."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from jointdyn.bearing.design import bearing_table

#: compared columns and their published counterparts
COMPARED = (
    "sommerfeld",
    "attitude_deg",
    "friction_variable",
    "flow_variable",
    "side_flow_ratio",
    "pressure_ratio",
)


def load_published(path: str | Path) -> dict:
    """{ld: {column: array}} from a CSV with '#' comment lines (ld = 'inf' → math.inf)."""
    with open(path) as fh:
        rows = list(csv.DictReader(line for line in fh if not line.startswith("#")))
    out: dict = {}
    for r in rows:
        ld = math.inf if r["ld"] == "inf" else float(r["ld"])
        d = out.setdefault(ld, {})
        for k, v in r.items():
            if k != "ld":
                d.setdefault(k, []).append(float(v))
    return {ld: {k: np.array(v) for k, v in d.items()} for ld, d in out.items()}


def compare(published: dict, cavitation: str = "reynolds") -> dict:
    """{ld: {column: (computed, published, error)}}; error relative for all columns but the
    attitude (absolute, degrees). ld = inf uses the long-bearing model [T78]."""
    res: dict = {}
    for ld, pub in published.items():
        if math.isinf(ld):
            tab = bearing_table("long", cavitation, 1.0, pub["eps"], coefficients=False)
        else:
            tab = bearing_table("finite", cavitation, ld, pub["eps"], coefficients=False)
        res[ld] = {}
        for c in COMPARED:
            got, ref = tab[c], pub[c]
            if c == "attitude_deg":
                err = got - ref
            else:
                with np.errstate(divide="ignore", invalid="ignore"):
                    err = np.where(ref != 0.0, got / np.where(ref != 0.0, ref, 1.0) - 1.0, got)
            res[ld][c] = (got, ref, err)
    return res


def load_butenschoen(path: str | Path) -> dict:
    """{L/D: {"eps", "So", "beta_deg", "Q": array}} from the Butenschön CSV ('#' comment lines;
    bd written as '1', '1/2', '1/2.5', ...) [T84]."""
    with open(path) as fh:
        rows = list(csv.DictReader(line for line in fh if not line.startswith("#")))
    out: dict = {}
    for r in rows:
        num, _, den = r["bd"].partition("/")
        d = out.setdefault(float(num) / float(den or 1.0), {})
        for k in r:
            if k != "bd":
                d.setdefault(k, []).append(float(r[k]))
    return {ld: {k: np.array(v) for k, v in d.items()} for ld, d in out.items()}


def squeeze_quantities(ld: float, eps: float, cavitation: str, mesh=None) -> dict:
    """Butenschön's pure-squeeze variables [T367] of the plain finite bearing: the journal at ε
    moving along the line of centres, towards the minimum film for ``eps`` > 0 (approach), away
    from it for ``eps`` < 0 (separation), no rotation; fed at ambient pressure through a line at
    the maximum film (approach) or the minimum film (separation), as the source's reference setup.
    So = Fψ²/(BDη|ε̇|) = |F̄|/(4λ), β = angle of the force from the line of centres [deg] (180 for
    approach: the film pushes back), Q = Q_side/(R²c|ε̇|)."""
    from jointdyn.film.grooved import GROOVED_MESH, film_at
    from jointdyn.film.jfo import flows

    xi, rate = abs(eps), (1.0 if eps > 0.0 else -1.0)
    line = ("line", math.pi if rate > 0.0 else 0.0)
    # ė = (ξ̇, ξ/2): t·ė = ξ/2 makes Ω = 0 in film_at's ξ − 2t·ė = ξΩ [T246]; rates in |ε̇| = 1
    F, sol, prob, fixed, lab = film_at(
        ld, (max(xi, 1e-12), 0.0), (rate, 0.5 * xi), cavitation, line, mesh or GROOVED_MESH
    )
    fill = np.ones(sol.P.size) if sol.fill is None else sol.fill
    q = flows(prob, rate, 0.0, sol.P, fill, fixed, lab)["side"]  # [ωR²c/2], here ω → |ε̇|
    return {
        "So": math.hypot(F[0], F[1]) / (4.0 * ld),
        "beta_deg": math.degrees(math.atan2(F[1], F[0])),
        "Q": 0.5 * q,
    }


def butenschoen_quantities(tab: dict) -> dict:
    """Butenschön's variables from a :func:`bearing_table` result [T84]: So = 1/(2πS),
    β = attitude [deg], Q = Q_s/(R²cω) = (flow variable)(side-flow ratio)(L/D)/π."""
    return {
        "So": 1.0 / (2.0 * math.pi * tab["sommerfeld"]),
        "beta_deg": tab["attitude_deg"],
        "Q": tab["flow_variable"] * tab["side_flow_ratio"] * tab["ld"] / math.pi,
    }


def compare_butenschoen(published: dict, cavitation: str = "reynolds", mesh=None) -> dict:
    """{L/D: {column: (computed, published, error, rounding)}} for So, beta_deg, Q [T84]: error
    relative (β absolute [deg]); rounding = half a unit of the last printed digit, relative to the
    published value (β: absolute)."""
    res: dict = {}
    for ld, pub in published.items():
        kw = {} if mesh is None else {"mesh": mesh}
        got = butenschoen_quantities(
            bearing_table("finite", cavitation, ld, pub["eps"], coefficients=False, **kw)
        )
        res[ld] = {}
        for c, half in (("So", 5e-5), ("beta_deg", 5e-4), ("Q", 5e-5)):
            ref = pub[c]
            if c == "beta_deg":
                res[ld][c] = (got[c], ref, got[c] - ref, np.full(ref.shape, half))
            else:
                res[ld][c] = (got[c], ref, got[c] / ref - 1.0, half / ref)
    return res


def butenschoen_table(path: str | Path) -> str:
    """Markdown table of max / mean errors against Butenschön's table per L/D [T84] (docs page)."""
    res = compare_butenschoen(load_butenschoen(path))
    names = {1.0: "1", 0.5: "1/2", 0.4: "1/2.5", 1 / 3: "1/3", 0.25: "1/4", 0.2: "1/5", 1 / 6: "1/6"}
    names[0.125] = "1/8"
    lines = [
        "| L/D | So max / mean | β max / mean [°] | Q max / mean | So max beyond rounding |",
        "|---|---|---|---|---|",
    ]
    for ld in sorted(res, reverse=True):
        r = res[ld]
        so, b, q = (np.abs(r[c][2]) for c in ("So", "beta_deg", "Q"))
        beyond = np.max(np.maximum(so - r["So"][3], 0.0))
        lines.append(
            f"| {names.get(ld, f'{ld:.4g}')} | {100 * so.max():.2g} % / {100 * so.mean():.2g} % | "
            f"{b.max():.2g} / {b.mean():.2g} | {100 * q.max():.2g} % / {100 * q.mean():.2g} % | "
            f"{100 * beyond:.2g} % |"
        )
    return "\n".join(lines)


def validation_curves(published_path: str | Path, butenschoen_path=None) -> list[dict]:
    """What :func:`plot_validation` draws, per published L/D: the computed S(ε) and attitude(ε)
    lines (``finite`` Reynolds, long Reynolds for L/D = ∞) over ``eps`` (48 points), the published
    points and the published S relative to the computed one at the published ε [%]; Butenschön's
    points as ``but_*`` where he has the L/D [T84]."""
    pub = load_published(published_path)
    but = load_butenschoen(butenschoen_path) if butenschoen_path is not None else {}
    eps = np.linspace(0.05, 0.99, 48)
    out = []
    for ld in sorted(pub, key=lambda x: -x if math.isfinite(x) else -1e9):
        model, ld_arg = ("long", 1.0) if math.isinf(ld) else ("finite", ld)
        tab = bearing_table(model, "reynolds", ld_arg, eps, coefficients=False)
        S_here = bearing_table(model, "reynolds", ld_arg, pub[ld]["eps"], coefficients=False)["sommerfeld"]
        c = {
            "ld": ld,
            "eps": tab["eps"],
            "S": tab["sommerfeld"],
            "attitude": tab["attitude_deg"],
            "pub_eps": pub[ld]["eps"],
            "pub_S": pub[ld]["sommerfeld"],
            "pub_attitude": pub[ld]["attitude_deg"],
            "pub_dev": 100 * (pub[ld]["sommerfeld"] / S_here - 1),
        }
        if ld in but:
            b = but[ld]
            S_b = 1.0 / (2.0 * math.pi * b["So"])
            S_here = bearing_table("finite", "reynolds", ld, b["eps"], coefficients=False)["sommerfeld"]
            c |= {
                "but_eps": b["eps"],
                "but_S": S_b,
                "but_beta": b["beta_deg"],
                "but_dev": 100 * (S_b / S_here - 1),
            }
        out.append(c)
    return out


def curves_digest(curves: list[dict]) -> str:
    """SHA-256 of the plotted arrays rounded to 5 significant digits (far below what a figure
    resolves, above the round-off of another CPU): the committed figure carries it."""
    import hashlib

    h = hashlib.sha256()
    for c in curves:
        for k in sorted(c):
            values = np.atleast_1d(np.asarray(c[k], dtype=float))
            h.update((k + ":" + ";".join(f"{v:.5g}" for v in values) + "\n").encode())
    return h.hexdigest()


#: PNG text key of the plotted-data digest
DIGEST_KEY = "jointdyn-plotted-data-sha256"


def plot_validation(published_path: str | Path, out_png: str | Path, butenschoen_path=None) -> str:
    """Figure S(ε) and attitude(ε): computed curves (``finite`` Reynolds, long Reynolds) over
    the published Raimondi–Boyd points (o), one colour per L/D, and Butenschön's (+) for the same
    L/D when ``butenschoen_path`` is given [T84]; a third panel shows each published S relative
    to the computed one (the ±3 % band of issue 13 shaded); saved as PNG with the digest of the
    plotted arrays (:func:`curves_digest`) as a text chunk, which is returned."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    curves = validation_curves(published_path, butenschoen_path)
    fig, (a1, a2, a3) = plt.subplots(1, 3, figsize=(15, 4.4))
    for k, c in enumerate(curves):
        col = f"C{k}"
        lab = "L/D = ∞" if math.isinf(c["ld"]) else f"L/D = {c['ld']:g}"
        a1.semilogy(c["eps"], c["S"], color=col, label=lab + " (computed)")
        a1.semilogy(c["pub_eps"], c["pub_S"], "o", mfc="none", color=col)
        a2.plot(c["eps"], c["attitude"], color=col, label=lab)
        a2.plot(c["pub_eps"], c["pub_attitude"], "o", mfc="none", color=col)
        a3.plot(c["pub_eps"], c["pub_dev"], "o-", mfc="none", color=col, lw=0.8)
        if "but_eps" in c:
            a1.semilogy(c["but_eps"], c["but_S"], "+", ms=7, color=col)
            a2.plot(c["but_eps"], c["but_beta"], "+", ms=7, color=col)
            a3.plot(c["but_eps"], c["but_dev"], "+--", ms=7, color=col, lw=0.8)
    a1.set(
        xlabel="eccentricity ratio ε [-]",
        ylabel="Sommerfeld number S [-]",
        title="S(ε): lines computed, o Raimondi–Boyd 1958, + Butenschön 1976",
    )
    a2.set(xlabel="eccentricity ratio ε [-]", ylabel="attitude angle φ [deg]", title="attitude φ(ε)")
    a3.axhspan(-3, 3, color="0.9", zorder=0)
    a3.set(
        xlabel="eccentricity ratio ε [-]",
        ylabel="published S / computed S − 1 [%]",
        title="o Raimondi–Boyd, + Butenschön (band ±3 %)",
    )
    a1.legend(fontsize=8)
    a1.grid(True, which="both", alpha=0.3)
    a2.grid(True, alpha=0.3)
    a3.grid(True, alpha=0.3)
    fig.tight_layout()
    from jointdyn.core.atomic import replacing

    digest = curves_digest(curves)
    with replacing(out_png) as tmp:
        fig.savefig(tmp, dpi=110, format="png", metadata={DIGEST_KEY: digest})
    plt.close(fig)
    return digest
