"""Regenerate the figures and numbers of docs/user-guide/chaos.md (≈ 5 min on 2 cores).

    python docs/_gen_chaos.py [--only poincare,lyapunov,lyapunov_tau,spectrum,ensemble]

Writes docs/figures/chaos_*.png and the page's generated block ``chaos-ensemble``, and prints the
other numbers quoted on the page (the Lyapunov table, the Poincaré spreads and the ensemble block
are checked by tests/test_docs_chaos_current.py, the last two in the slow tier). The bifurcation
diagram comes from `jointdyn bifurcation examples/bifurcation_dry_clearance.toml --out DIR`
(copy DIR/bifurcation.png to docs/figures/chaos_bifurcation_clearance.png); the Ueda model file's
exponent from the command in examples/ueda.toml.
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

FIG = Path(__file__).resolve().parent / "figures"


POINCARE_CASES = (
    ("alshaer2005", "lubricated (π-film, μ = 0.4 Pa·s)", {"rtol": 1e-8, "atol": 1e-12}),
    ("dry", "dry (c_r = 0.9)", {"rtol": 1e-8, "atol": 1e-11}),
)


def poincare_section(joint: str, kw: dict, revs: int = 220, transient: int = 20):
    """The page's stroboscopic section of one joint (also run by
    tests/test_docs_chaos_current.py, which checks the spreads quoted on the page)."""
    from jointdyn.models.slider_crank import SPEED
    from jointdyn.studies.poincare import journal_section
    from jointdyn.studies.runs import run_shipped

    res, _, _ = run_shipped("slider-crank", joint, revs, samples_per_rev=72, **kw)
    return journal_section(res, transient=transient * 2 * math.pi / SPEED)


def poincare(revs: int = 220, transient: int = 20):
    from jointdyn.studies.poincare import plot_sections

    secs = {}
    for joint, label, kw in POINCARE_CASES:
        sec = poincare_section(joint, kw, revs, transient)
        secs[label] = sec
        x, y = sec.values["ex_bushing_over_c"], sec.values["ey_bushing_over_c"]
        print(
            f"poincare {joint}: {x.size} points, spread of ex/c {x.max() - x.min():.3g},"
            f" ey/c {y.max() - y.min():.3g} (bushing frame)"
        )
    plot_sections(
        secs, FIG / "chaos_poincare.png", "stroboscopic sections at crank angle 0, c = 0.5 mm, 5000 rpm"
    )


def lyapunov_row(joint: str, rtol: float, d0: float):
    """One entry of the page's Lyapunov table: 40 averaging revolutions after 10, τ = T/16,
    norm time scale 1/ω, atol = 1e-3·rtol (also run by tests/test_docs_chaos_current.py)."""
    from jointdyn.models import slider_crank as sc
    from jointdyn.studies.lyapunov import system_lyapunov

    T = 2 * math.pi / sc.SPEED
    return system_lyapunov(
        sc.slider_crank(joint).compile(),
        tau=T / 16,
        n_segments=16 * 40,
        transient=10 * T,
        time_scale=1 / sc.SPEED,
        d0=d0,
        rtol=rtol,
        atol=rtol * 1e-3,
    )


def lyapunov():
    from jointdyn.studies.lyapunov import plot_running

    rows = []
    for joint, rtol, d0 in (
        ("dry", 1e-9, 1e-8),
        ("dry", 1e-8, 1e-8),
        ("dry", 1e-9, 1e-7),
        ("dry", 1e-9, 1e-9),
        ("dry", 1e-10, 1e-7),
        ("dry", 1e-10, 1e-8),
        ("dry", 1e-10, 1e-9),
        ("dry", 1e-11, 1e-8),
        ("dry", 1e-11, 1e-9),
        ("dry", 1e-11, 1e-10),
        ("dry", 1e-12, 1e-10),
        ("dry", 1e-12, 1e-11),
        ("alshaer2005", 1e-8, 1e-8),
        ("alshaer2005", 1e-9, 1e-8),
    ):
        r = lyapunov_row(joint, rtol, d0)
        rows.append({"joint": joint, "rtol": rtol, "d0": d0, "lambda": r.exponent, "stderr": r.stderr})
        print(f"lyapunov {joint} rtol {rtol:g} d0 {d0:g}: {r.exponent:.1f} ± {r.stderr:.1f} 1/s")
        if rtol == 1e-9 and d0 == 1e-8 and joint == "dry":
            plot_running(r, FIG / "chaos_lyapunov_dry.png", "dry slider-crank: running estimate of λ₁")
        if rtol == 1e-8 and joint == "alshaer2005":
            plot_running(
                r, FIG / "chaos_lyapunov_lubricated.png", "lubricated slider-crank: running estimate of λ₁"
            )
    print(json.dumps(rows))


def lyapunov_tau():
    """Dry joint, rtol 1e-9, δ₀ = 1e-8: the renormalisation interval τ = T/8 and T/32 (T/16 is in
    :func:`lyapunov`), the same 40 averaging revolutions after 10 [T137]."""
    from jointdyn.models import slider_crank as sc
    from jointdyn.studies.lyapunov import system_lyapunov

    T = 2 * math.pi / sc.SPEED
    for per_rev in (8, 32):
        r = system_lyapunov(
            sc.slider_crank("dry").compile(),
            tau=T / per_rev,
            n_segments=per_rev * 40,
            transient=10 * T,
            time_scale=1 / sc.SPEED,
            d0=1e-8,
            rtol=1e-9,
            atol=1e-12,
        )
        print(f"lyapunov dry rtol 1e-9 d0 1e-8 tau T/{per_rev}: {r.exponent:.1f} ± {r.stderr:.1f} 1/s")


def spectrum():
    from jointdyn.studies.runs import run_shipped
    from jointdyn.studies.spectra import plot_spectra, run_spectra

    res, _, _ = run_shipped("slider-crank", "dry", 60, samples_per_rev=720, rtol=1e-8, atol=1e-11)
    sp = run_spectra(res, transient_revs=10, body="slider")
    plot_spectra(sp, FIG / "chaos_spectrum_dry.png", 40, "dry slider-crank, revolutions 10–60")
    print(
        "spectrum: harmonic 1 of the slider acceleration", sp["body_x_acceleration"][sp["harmonic"] == 1][0]
    )


#: the page's ensemble (its command and Python block say the same; tests/test_docs_chaos_current.py)
ENSEMBLE_KW = {"rtols": (1e-7, 1e-8, 1e-9), "replicas": 2, "revs": 110, "transient_revs": 10}
PAGE = Path(__file__).resolve().parent / "user-guide" / "chaos.md"


def ensemble_block(workers: int | None = 2) -> str:
    """The page's generated block ``chaos-ensemble``: the dry slider-crank's ensemble table
    (``ensemble_markdown``) and how far the tolerance medians lie from the pooled one, as a
    fraction of the 5–95 % width (≈ 6 min CPU)."""
    from jointdyn.studies.ensemble import ensemble as run_ensemble
    from jointdyn.studies.ensemble import ensemble_markdown, ensemble_table

    r = run_ensemble("slider-crank", {"joint": "dry"}, workers=workers, **ENSEMBLE_KW)
    rows = ensemble_table(r)
    shift = max(
        abs(row[f"median_rtol_{g}"] - row["median"]) / (row["p95"] - row["p5"])
        for row in rows
        for g in r["per_rtol"]
        if row["p95"] > row["p5"]
    )
    peak = next(row for row in rows if row["quantity"] == "peak_moment")
    return (
        ensemble_markdown(r)
        + f"\n\nThe tolerance medians lie at most {100 * shift:.0f} % of the 5–95 % width from the pooled"
        " median — the distribution is a property of the mechanism, single revolutions are not: one"
        f" revolution's peak moment lies anywhere between {peak['p5']:.0f} and {peak['p95']:.0f} N·m."
    )


def ensemble():
    """Rewrite the page's ``chaos-ensemble`` block."""
    from jointdyn.cli.docs_gen import replace_blocks
    from jointdyn.core import atomic

    block = ensemble_block()
    atomic.write_text(PAGE, replace_blocks(PAGE.read_text(encoding="utf-8"), {"chaos-ensemble": block}))
    print(block)


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--only", default="poincare,lyapunov,lyapunov_tau,spectrum,ensemble")
    for name in ap.parse_args().only.split(","):
        globals()[name]()
