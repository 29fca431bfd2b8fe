"""The dry case of the reproduction as a distribution: a small ensemble of the dry slider-crank.

The dry joint is chaotic ([T162], [T125]): the 4-revolution trajectory of the paper's comparison
is one sample of a chaotic attractor, and its last-revolution numbers change with the tolerance.
``jointdyn reproduce`` therefore also runs :data:`ENSEMBLE` — replicas with perturbed initial
velocities at two tolerances, in parallel on local processes
(:func:`jointdyn.studies.ensemble.ensemble`), a transient discarded — and reports the
median and 5–95 % band of the per-revolution quantities, the median at each tolerance and the
bootstrap standard error of the pooled median (what the sample resolves) [T120, T121, T135].
"""

from __future__ import annotations

import json
import math

#: the reproduce ensemble: 2 tolerances × 2 replicas × (3 transient + 37 recorded) revolutions
#: = 148 recorded revolutions, ≈ 1.3 s CPU on an idle machine. Measured on 48 runs × 105
#: revolutions [T361]: the replicas part within one revolution and the distribution is
#: stationary from the third; rtol 1e-6 gives the distribution of 1e-7 and 1e-8 within 1 % of
#: the 5–95 % width; the bootstrap standard error this size reports matches the spread of the
#: median over disjoint ensembles of the same size (peak moment ≈ ±3.5 %, RMS ≈ ±1.5 %).
ENSEMBLE = {
    "rtols": (1e-6, 1e-7),
    "replicas": 2,
    "revs": 40,
    "transient_revs": 3,
    "samples_per_rev": 720,
}
#: quantities reported (``revolution_stats`` names) with their label and display scale
QUANTITIES = {
    "peak_moment": ("peak crank moment", "N·m", 1.0),
    "rms_moment": ("RMS crank moment", "N·m", 1.0),
    "impacts": ("impacts per revolution", "1/rev", 1.0),
    "max_contact_force": ("max contact force", "kN", 1e-3),
    "max_penetration": ("max penetration", "µm", 1e6),
}


def dry_ensemble(workers: int | None = None, **overrides) -> dict:
    """Run the reproduce ensemble of the dry case (settings :data:`ENSEMBLE`, ``overrides``
    replace them); the result of :func:`~jointdyn.studies.ensemble.ensemble`."""
    from jointdyn.studies.ensemble import ensemble

    kw = {**ENSEMBLE, **overrides}
    model_kw = {"joint": "dry", **kw.pop("model_kw", {})}
    return ensemble("slider-crank", model_kw, workers=workers, **kw)


def _g(v: float, digits: int = 4) -> str:
    if isinstance(v, float) and math.isnan(v):
        return "–"
    return f"{v:.{digits}g}"


def ensemble_rows(result: dict) -> list[dict]:
    """One row per quantity: label, unit, median, p5, p95, bootstrap s.e. of the median, the
    median at each tolerance and the largest tolerance shift as a fraction of the 5–95 % width
    (all in the display unit)."""
    rows = []
    for k, (label, unit, f) in QUANTITIES.items():
        b = result["bands"].get(k)
        if b is None:
            continue
        rows.append(
            {
                "quantity": k,
                "label": label,
                "unit": unit,
                "median": f * b["median"],
                "p5": f * b["p5"],
                "p95": f * b["p95"],
                "se": f * b["median_se"],
                "per_rtol": {g: f * m for g, m in b["group_medians"].items()},
                "shift": b["shift"],
                "n": b["n"],
            }
        )
    return rows


def ensemble_markdown(result: dict) -> str:
    """Markdown table: quantity, median [5 %, 95 %], ± s.e. of the median, median per tolerance,
    tolerance shift (largest distance of a tolerance median from the pooled one / band width)."""
    rows = ensemble_rows(result)
    rt = list(result["per_rtol"])
    head = ["dry joint, per revolution", "median [5 %, 95 %]", "± s.e.", *(f"rtol {g}" for g in rt), "shift"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in rows:
        cells = [
            f"{r['label']} [{r['unit']}]",
            f"{_g(r['median'])} [{_g(r['p5'])}, {_g(r['p95'])}]",
            _g(r["se"], 2),
            *(_g(r["per_rtol"][g]) for g in rt),
            f"{100 * r['shift']:.0f} %",
        ]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def ensemble_sentence(result: dict) -> str:
    """How big the ensemble is and what it resolves (for the README and the report)."""
    s = result["settings"]
    n = result["bands"]["peak_moment"]["n"]
    runs = len(s["rtols"]) * s["replicas"]
    rec = s["revs"] - s["transient_revs"]
    pk = result["bands"]["peak_moment"]
    rms = result["bands"]["rms_moment"]
    return (
        f"{runs} runs of the dry case ({s['replicas']} replicas with initial velocities perturbed by "
        f"1e-9 relative, at rtol {' and '.join(f'{r:g}' for r in s['rtols'])}), "
        f"{s['transient_revs']} transient revolutions discarded, {rec} recorded each: {n} revolutions. "
        f"That resolves medians to about ±{100 * pk['median_se'] / abs(pk['median']):.0f} % (peak moment) "
        f"and ±{100 * rms['median_se'] / abs(rms['median']):.1f} % (RMS) — one bootstrap standard error — "
        f"and the band edges more coarsely (about {n // 20} revolutions lie beyond each edge); "
        "'shift' is the largest distance of a tolerance median from the pooled median as a "
        "fraction of the 5–95 % width."
    )


def ensemble_json(result: dict) -> bytes:
    """The bands, per-tolerance bands and settings as JSON (``ensemble_dry.json``)."""
    return json.dumps(result, indent=2, default=float).encode("utf-8")
