"""Comparison of the design table with the published Raimondi–Boyd (1958) tables [T77]:
used by the validation tests and the docs page's figure."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from .design import bearing_table

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
            tab = bearing_table("long", cavitation, 1.0, pub["eps"])
        else:
            tab = bearing_table("finite", cavitation, ld, pub["eps"])
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


def plot_validation(published_path: str | Path, out_png: str | Path) -> None:
    """Figure S(ε) and attitude(ε): computed curves (``finite`` Reynolds, long Reynolds) over
    the published Raimondi–Boyd points, one colour per L/D; saved as PNG."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    pub = load_published(published_path)
    eps = np.linspace(0.05, 0.97, 40)
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4.2))
    for k, ld in enumerate(sorted(pub, key=lambda x: -x if math.isfinite(x) else -1e9)):
        col = f"C{k}"
        lab = "L/D = ∞" if math.isinf(ld) else f"L/D = {ld:g}"
        tab = (
            bearing_table("long", "reynolds", 1.0, eps)
            if math.isinf(ld)
            else bearing_table("finite", "reynolds", ld, eps)
        )
        a1.semilogy(tab["eps"], tab["sommerfeld"], color=col, label=lab + " (computed)")
        a1.semilogy(pub[ld]["eps"], pub[ld]["sommerfeld"], "o", mfc="none", color=col)
        a2.plot(tab["eps"], tab["attitude_deg"], color=col, label=lab)
        a2.plot(pub[ld]["eps"], pub[ld]["attitude_deg"], "o", mfc="none", color=col)
    a1.set(
        xlabel="eccentricity ratio ε [-]",
        ylabel="Sommerfeld number S [-]",
        title="S(ε): lines computed, o Raimondi–Boyd 1958",
    )
    a2.set(xlabel="eccentricity ratio ε [-]", ylabel="attitude angle φ [deg]", title="attitude φ(ε)")
    a1.legend(fontsize=8)
    a1.grid(True, which="both", alpha=0.3)
    a2.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(out_png, dpi=110)
    plt.close(fig)
