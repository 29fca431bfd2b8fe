"""Regenerate every number and figure the README and the docs show, from the code.

``python -m jointdyn.cli.docs_gen`` runs the Alshaer et al. (2005) comparison (4 revolutions, the
paper's cases and the beyond-the-paper cases) and the clearance × viscosity sweep of
``examples/sweep_clearance_viscosity.toml``, then rewrites

* the blocks between ``<!-- generated:NAME -->`` and ``<!-- /generated -->`` of the README and
  of ``docs/reproduction.md`` (``reproduce-table``, ``dry-ensemble``, ``reproduce-claims``,
  ``sweep-claims``), and
* the figures in ``docs/figures/`` (``moment_overlay.png``, ``orbit_*.png``,
  ``film_thickness.png``, ``joint_force.png``, ``moment_beyond.png``, ``sweep_*.png``,
  ``validation_raimondi_boyd.png``; ``--validation-figure`` redraws that one only).

``python -m jointdyn.cli.docs_gen --check`` recomputes the numbers only and exits 1 listing every
README number that is out of date (``tests/test_docs_current.py`` runs the same check).
"""

from __future__ import annotations

import argparse
import math
import re
import sys
import tempfile
from pathlib import Path

import numpy as np

from jointdyn.core import atomic

ROOT = Path(__file__).resolve().parents[3]
README = ROOT / "README.md"
#: documents with generated blocks: the README must have every block, docs pages may use some
PAGES = (ROOT / "docs" / "reproduction.md", ROOT / "docs" / "validation.md")
FIGURES = ROOT / "docs" / "figures"
SWEEP_SPEC = ROOT / "examples" / "sweep_clearance_viscosity.toml"
REVS = 4.0
TABLE_COLUMNS = ("peak_moment", "min_moment", "rms_moment", "max_xi", "impacts")
#: figures of the reproduction copied to docs/figures (README and docs pages use them)
REPRO_FIGURES = (
    "moment_overlay.png",
    "orbit_dry.png",
    "orbit_ott.png",
    "orbit_alshaer2005.png",
    "film_thickness.png",
    "joint_force.png",
    "moment_beyond.png",
)
#: generated blocks that live on a docs page only, not in the README
PAGE_ONLY = ("butenschoen-table",)
BLOCK = re.compile(r"(<!-- generated:(?P<name>[\w-]+) -->\n)(?P<body>.*?)(<!-- /generated -->)", re.S)


def _g(v: float, digits: int = 4) -> str:
    """``digits`` significant digits, no exponent for the magnitudes shown here."""
    if isinstance(v, float) and math.isnan(v):
        return "–"
    return f"{v:#.{digits}g}".rstrip(".")  # keeps trailing zeros (127.0), no bare point (-1263)


# -- computing --------------------------------------------------------------------------------
def reproduce_runs(out: Path, figures: bool = True, workers: int | None = None) -> tuple[dict, dict]:
    """The runs of ``jointdyn reproduce alshaer2005`` (4 revolutions, all cases) and its dry
    ensemble (:mod:`jointdyn.studies.reproduce_ensemble`)."""
    import json

    from jointdyn.studies.reproduce import BEYOND_CASES, PAPER_CASES, reproduce_alshaer2005, run_case
    from jointdyn.studies.reproduce_ensemble import dry_ensemble

    if figures:
        runs = reproduce_alshaer2005(out, revs=REVS, ensemble=True)
        return runs, json.loads((out / "ensemble_dry.json").read_text(encoding="utf-8"))
    runs = {c.name: (*run_case(c, REVS), c) for c in PAPER_CASES + BEYOND_CASES}
    return runs, dry_ensemble(workers=workers)


def sweep_dataset(out: Path, workers: int | None = None):
    """The clearance × viscosity sweep of ``examples/sweep_clearance_viscosity.toml``."""
    from jointdyn.studies.sweep import load_sweep, run_sweep

    return run_sweep(load_sweep(SWEEP_SPEC), out, workers=workers)


# -- text -------------------------------------------------------------------------------------
def reproduce_table(runs: dict) -> str:
    """Markdown table of the reproduction (moments over the last revolution [N·m])."""
    lines = ["| case | " + " | ".join(TABLE_COLUMNS) + " |", "|---" * (len(TABLE_COLUMNS) + 1) + "|"]
    for _, _, s, case in runs.values():
        vals = [str(int(s[c])) if c == "impacts" else _g(float(s.get(c, math.nan))) for c in TABLE_COLUMNS]
        name = f"{case.name} (one chaotic trajectory)" if case.joint == "dry" else case.name
        lines.append(f"| {name} | " + " | ".join(vals) + " |")
    return "\n".join(lines)


def _orbit_gap(r1, r2) -> float:
    """Largest distance between two journal paths of the piston pin [c]."""
    (x1, y1), (x2, y2) = r1.orbit("piston_pin"), r2.orbit("piston_pin")
    return float(np.hypot(x1 - x2, y1 - y2).max())


def reproduce_claims(runs: dict) -> str:
    """The numbers the README's discussion of the paper's claims rests on."""
    s = {n: runs[n][2] for n in runs}
    p, d, a, o = s["perfect"], s["dry"], s["alshaer2005"], s["ott"]
    ott, pi = runs["ott"][0], runs["alshaer2005"][0]
    gap_all, gap_last = _orbit_gap(ott, pi), _orbit_gap(ott.last_revolutions(1), pi.last_revolutions(1))
    rms_pct = 100 * (a["rms_moment"] / p["rms_moment"] - 1)
    spike = max(d["peak_moment_all"], -d["min_moment_all"]) / p["peak_moment"]
    perfect = (
        f"- **Perfect joint**: peak {p['peak_moment']:+.2f} / {p['min_moment']:+.2f} N·m "
        '("order of 150 N·m"); an independent power-balance inverse dynamics (`tests/analytic.py`) '
        "agrees to < 1e-6 of the peak."
    )
    dry = (
        f"- **Dry joint**: {d['impacts']} impacts in {REVS:g} revolutions and moment spikes of "
        f"{d['peak_moment_all']:+.0f} / {d['min_moment_all']:+.0f} N·m over the run ({spike:.1f}× the "
        "perfect peak); RMS over the last revolution "
        f"{d['rms_moment']:.1f} N·m against {p['rms_moment']:.1f} N·m. The paper's \"two orders of "
        'magnitude" is not reproduced with this contact stiffness. These numbers are one trajectory of a '
        "chaotic system ([T162]): they change with the tolerance after the first impacts. The "
        "distribution over revolutions and replicas above is what is reproducible."
    )
    lub = (
        "- **Lubricated joints**: the π-film crank moment is of the same order as the perfect one "
        f"(peak {a['peak_moment']:.1f} N·m, RMS {rms_pct:+.1f} %), the journal runs close to the clearance "
        f"circle (max ξ = {a['max_xi']:.3f}) on a nearly periodic orbit. Ott's path differs from the "
        f"π-film's by up to {gap_all:.3f}·c ({gap_last:.3f}·c in the last revolution; Ott is a rational "
        f"approximation of the π-film, [T165]); its moment (peak {o['peak_moment']:.1f} N·m) is equally "
        'smooth: we do not see the "peaks" the paper attributes to Ott\'s model.'
    )
    return "\n".join([perfect, dry, lub])


def sweep_claims(ds) -> str:
    """One sentence on the sweep's extremes."""

    def at_max(da):
        i = np.unravel_index(int(np.nanargmax(da.values)), da.shape)
        return float(da.values[i]), {dim: float(da[dim].values[k]) for dim, k in zip(da.dims, i)}

    pk, cp = at_max(ds["peak_moment"])
    xi, cx = at_max(ds["max_xi"])
    lo = float(np.nanmin(ds["peak_moment"].values))
    return (
        f"Over the grid the peak crank moment moves by {100 * (pk / lo - 1):.1f} % only ({lo:.1f} … "
        f"{pk:.1f} N·m, the largest at c = {cp['clearance'] * 1e6:.3g} µm, μ = {cp['viscosity']:.3g} Pa·s): "
        f"the film changes where the journal runs, not the drive's load; the largest eccentricity, "
        f"ξ = {xi:.4f}, is at c = {cx['clearance'] * 1e6:.3g} µm, μ = {cx['viscosity']:.3g} Pa·s."
    )


# -- README blocks ----------------------------------------------------------------------------
def blocks(text: str) -> dict[str, str]:
    """Generated blocks of a document: name -> body."""
    return {m["name"]: m["body"].rstrip("\n") for m in BLOCK.finditer(text)}


def replace_blocks(text: str, new: dict[str, str]) -> str:
    def sub(m):
        name = m["name"]
        return m.group(1) + (new[name] + "\n" if name in new else m["body"]) + m.group(4)

    return BLOCK.sub(sub, text)


NUMBER = re.compile(r"[-+−]?\d+(?:\.\d+)?(?:e[-+]?\d+)?")


def numbers(text: str) -> list[float]:
    """Every number in a text, in order (the Unicode minus read as '-')."""
    return [float(x.replace("−", "-")) for x in NUMBER.findall(text)]


def compare(old: str, new: str, name: str) -> list[str]:
    """Differences between two renderings of a block, number by number.

    The README shows 3–4 significant digits; a fresh computation on this machine class is bit
    for bit the same, so any difference in a printed digit means the README is out of date.
    Tolerance: one unit in the last printed digit of the shown number (a value that sits on a
    rounding boundary may print either way)."""
    a, b = NUMBER.findall(old), NUMBER.findall(new)
    if len(a) != len(b):
        return [f"{name}: {len(a)} numbers in the document, {len(b)} now"]
    out = []
    for x, y in zip(a, b):
        fx, fy = float(x.replace("−", "-")), float(y.replace("−", "-"))
        decimals = len(x.split(".")[1].split("e")[0]) if "." in x else 0
        exp = int(x.split("e")[1]) if "e" in x else 0
        if abs(fx - fy) > 1.0001 * 10.0 ** (exp - decimals):
            out.append(f"{name}: the document shows {x}, the code now gives {y}")
    return out


def validation_table() -> str:
    """Max and mean errors of the steady design table against Raimondi & Boyd (1958) per L/D
    (relative; attitude in degrees), ``finite`` with Reynolds' condition, ``long`` for L/D = ∞."""
    from jointdyn.bearing.validation import compare, load_published

    res = compare(load_published(ROOT / "tests" / "data" / "raimondi_boyd_1958.csv"))
    lines = [
        "| L/D | S max / mean | φ max / mean [°] | (R/c)f max / mean | Q/(RcNL) max / mean "
        "| Q_s/Q max | P/p_max max |",
        "|---|---|---|---|---|---|---|",
    ]

    def pct(err, mean=True):
        a = np.abs(err[np.isfinite(err)])
        return f"{100 * a.max():.2g} %" + (f" / {100 * a.mean():.2g} %" if mean else "")

    for ld in sorted(res, key=lambda x: -1 if np.isinf(x) else x, reverse=True):
        r = res[ld]
        name = "∞ (`long`)" if np.isinf(ld) else {1.0: "1", 0.5: "1/2", 0.25: "1/4"}.get(ld, f"{ld:g}")
        att = np.abs(r["attitude_deg"][2])
        side = pct(r["side_flow_ratio"][2], mean=False) if not np.isinf(ld) else "–"
        lines.append(
            f"| {name} | {pct(r['sommerfeld'][2])} | {att.max():.2g} / {att.mean():.2g} | "
            f"{pct(r['friction_variable'][2])} | {pct(r['flow_variable'][2])} | {side} | "
            f"{pct(r['pressure_ratio'][2], mean=False)} |"
        )
    return "\n".join(lines)


def _butenschoen_table() -> str:
    from jointdyn.bearing.validation import butenschoen_table

    return butenschoen_table(ROOT / "tests" / "data" / "butenschoen_1976.csv")


def dry_ensemble_block(ens: dict) -> str:
    """The dry case as a distribution: the reproduce ensemble's table and what it resolves."""
    from jointdyn.studies.reproduce_ensemble import ensemble_markdown, ensemble_sentence

    return ensemble_markdown(ens) + "\n\n" + ensemble_sentence(ens)


def _blocks_now(runs, ds, ens) -> dict[str, str]:
    return {
        "reproduce-table": reproduce_table(runs),
        "dry-ensemble": dry_ensemble_block(ens),
        "reproduce-claims": reproduce_claims(runs),
        "sweep-claims": sweep_claims(ds),
        "validation-table": validation_table(),
        "butenschoen-table": _butenschoen_table(),
    }


def generate(
    readme: Path = README, figures: Path = FIGURES, workers: int | None = None, pages=PAGES
) -> dict[str, str]:
    """Recompute everything, write the figures and the blocks of the README and the docs pages;
    returns the blocks."""

    with tempfile.TemporaryDirectory() as tmp:
        runs, ens = reproduce_runs(Path(tmp) / "repro")
        figures.mkdir(parents=True, exist_ok=True)
        for f in REPRO_FIGURES:
            atomic.write_bytes(figures / f, (Path(tmp) / "repro" / f).read_bytes())
        ds = sweep_dataset(Path(tmp) / "sweep", workers=workers)
        sweep_figures(ds, figures)
        validation_figure(figures)
    new = _blocks_now(runs, ds, ens)
    for doc in (readme, *pages):
        if doc.exists():
            atomic.write_text(doc, replace_blocks(doc.read_text(encoding="utf-8"), new))
    return new


VALIDATION_FIGURE = "validation_raimondi_boyd.png"


def validation_figure(figures: Path = FIGURES) -> str:
    """docs/validation.md's figure (committed, so the page shows it on GitHub too); returns the
    digest of its plotted arrays, which the PNG carries (tests/test_docs_current.py)."""
    from jointdyn.bearing.validation import plot_validation

    data = ROOT / "tests" / "data"
    return plot_validation(
        data / "raimondi_boyd_1958.csv", figures / VALIDATION_FIGURE, data / "butenschoen_1976.csv"
    )


def sweep_figures(ds, figures: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from jointdyn.viz import plots

    for metric in ("peak_moment", "max_xi"):
        fig, ax = plt.subplots(figsize=(6.2, 4.8))
        plots.sweep_metric(ds[metric], ax=ax)
        fig.tight_layout()
        with atomic.replacing(figures / f"sweep_{metric}.png") as tmp:
            fig.savefig(tmp, dpi=130, format="png")
        plt.close(fig)


def check(readme: Path = README, workers: int | None = None, pages=PAGES) -> list[str]:
    """Recompute the numbers (no figures) and list the numbers of the README and the docs pages
    that differ."""
    with tempfile.TemporaryDirectory() as tmp:
        runs, ens = reproduce_runs(Path(tmp), figures=False, workers=workers)
        ds = sweep_dataset(Path(tmp) / "sweep", workers=workers)
    new = _blocks_now(runs, ds, ens)
    old = blocks(readme.read_text(encoding="utf-8"))
    problems = [f"README has no generated block {k!r}" for k in new if k not in old and k not in PAGE_ONLY]
    for k in new:
        if k in old:
            problems += compare(old[k], new[k], k)
    for page in pages:
        if page.exists():
            for k, body in blocks(page.read_text(encoding="utf-8")).items():
                problems += compare(body, new[k], f"{page.name}: {k}") if k in new else [f"{page.name}: {k}?"]
    return problems


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m jointdyn.cli.docs_gen", description=__doc__.split("\n\n")[0])
    ap.add_argument("--check", action="store_true", help="only compare the README numbers; exit 1 if stale")
    ap.add_argument(
        "--validation-figure", action="store_true", help=f"only redraw docs/figures/{VALIDATION_FIGURE}"
    )
    ap.add_argument("--workers", type=int, default=None, help="processes for the sweep (default: all cores)")
    a = ap.parse_args(argv)
    if not README.exists():
        ap.error(f"no README.md at {README}: run from a source checkout (pip install -e .)")
    if a.validation_figure:
        print(f"wrote {FIGURES / VALIDATION_FIGURE} (plotted data {validation_figure()[:12]}…)")
        return 0
    if a.check:
        problems = check(workers=a.workers)
        for p in problems:
            print(p)
        print("README numbers are current" if not problems else f"{len(problems)} stale number(s)")
        return 1 if problems else 0
    new = generate(workers=a.workers)
    print(f"wrote {len(new)} README blocks and {len(REPRO_FIGURES) + 3} figures in {FIGURES}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
