"""Reproduce Alshaer et al. (2005): the slider-crank with perfect, dry, Ott and π-film joints.

``jointdyn reproduce alshaer2005 --out DIR`` runs the paper's four cases (benchmark [T160])
plus a beyond-the-paper section (c = 0.05 mm, a viscosity series) and writes
``summary.csv``, ``<case>.csv``, the figures and a self-contained ``report.html``.
"""

from __future__ import annotations

import base64
import csv
import html
import importlib.util
import io
import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from jointdyn import post
from jointdyn.models import slider_crank as sc
from jointdyn.studies.outputs import header
from jointdyn.studies.runs import run_shipped
from jointdyn.viz.reproduce_data import figure_data
from jointdyn.viz.reproduce_figures import caption, drawing


@dataclass(frozen=True)
class Case:
    """One run of the comparison."""

    name: str
    joint: str
    label: str
    model_kw: dict = field(default_factory=dict)
    solver: str | None = None
    rtol: float = 1e-7
    atol: float = 1e-11


PAPER_CASES = (
    Case("perfect", "perfect", "perfect joint", rtol=1e-8, atol=1e-10),
    Case(
        "dry",
        "dry",
        "dry clearance joint (c = 0.5 mm, c_r = 0.9), one chaotic trajectory",
        rtol=1e-7,
        atol=1e-11,
    ),
    Case("ott", "ott", "lubricated, Ott's model (c = 0.5 mm, μ = 0.4 Pa·s)"),
    Case("alshaer2005", "alshaer2005", "lubricated, π-film model (c = 0.5 mm, μ = 0.4 Pa·s)"),
)
BEYOND_CASES = (
    Case("ott_c0.05mm", "ott", "Ott, c = 0.05 mm", {"clearance": 5e-5}),
    Case("alshaer2005_c0.05mm", "alshaer2005", "π-film, c = 0.05 mm", {"clearance": 5e-5}),
    Case("alshaer2005_mu0.1", "alshaer2005", "π-film, μ = 0.1 Pa·s", {"viscosity": 0.1}),
    Case("alshaer2005_mu1.0", "alshaer2005", "π-film, μ = 1.0 Pa·s", {"viscosity": 1.0}),
    Case("finite", "finite", "finite-length (2-D Reynolds, Gümbel), L/D = 2, c = 0.5 mm"),
    Case("alshaer2005_shear", "alshaer2005", "π-film with the film's shear torques [T75]", {"shear": True}),
)

SUMMARY_COLUMNS = (
    "case",
    "peak_moment",
    "min_moment",
    "rms_moment",
    "max_xi",
    "impacts",
    "wall_time_s",
    "peak_moment_all",
    "min_moment_all",
    "rms_moment_all",
    "rhs_evaluations",
    "accepted_steps",
    "rejected_steps",
    "solver",
    "rtol",
    "error_scale",
)


def run_case(case: Case, revs: float, progress=None):
    """Simulate one case; returns (results, columns, summary row)."""
    t0 = time.perf_counter()
    res, cols, summ = run_shipped(
        "slider-crank",
        case.joint,
        revs,
        progress=progress,
        model_kw=case.model_kw,
        solver=case.solver,
        rtol=case.rtol,
        atol=case.atol,
    )
    summ = {
        "case": case.name,
        **summ,
        "wall_time_s": time.perf_counter() - t0,
        "max_xi": summ.get("max_xi", float("nan")),
    }
    pin = "piston_pin" in res.system.element_names
    summ["impacts"] = post.impacts(res, "piston_pin") if pin else 0
    return res, cols, summ


#: columns of ``<case>.csv`` and their units (the orbit in the bushing frame, [T290])
CASE_COLUMNS = (
    "t",
    "crank_angle",
    "crank_moment",
    "ex_bushing_over_c",
    "ey_bushing_over_c",
    "h_min",
    "joint_force",
)
CASE_UNITS = {**sc.HEADLINE_UNITS, "h_min": "m", "joint_force": "N"}


def _csv(header, rows) -> bytes:
    buf = io.StringIO()
    w = csv.writer(buf)
    w.writerow(header)
    w.writerows(rows)
    return buf.getvalue().encode("utf-8")


def csv_files(runs: dict) -> dict[str, bytes]:
    """``summary.csv`` and one ``<case>.csv`` per case (name -> content)."""
    out = {
        "summary.csv": _csv(
            SUMMARY_COLUMNS, ([_fmt(s.get(c, "")) for c in SUMMARY_COLUMNS] for _, _, s, _ in runs.values())
        )
    }
    for n, (_, cols, _, _) in runs.items():
        empty = [""] * len(cols["t"])
        out[f"{n}.csv"] = _csv(
            [header(c, CASE_UNITS[c]) for c in CASE_COLUMNS],
            zip(*[_texts(cols[c]) if c in cols else empty for c in CASE_COLUMNS]),
        )
    return out


def _texts(values) -> list[str]:
    """:func:`_fmt` of each value of a float column, converted to Python floats at once (5× faster
    than one numpy scalar at a time; the same text)."""
    return ["" if math.isnan(v) else f"{v:.10g}" for v in np.asarray(values, float).tolist()]


def _short(v):
    """5 significant digits for the report table (the CSV keeps 10)."""
    if isinstance(v, (float, np.floating)):
        return "" if math.isnan(v) else f"{v:.5g}"
    return str(v)


def _fmt(v):
    if isinstance(v, (float, np.floating)):
        return "" if math.isnan(v) else f"{v:.10g}"
    return str(v)


def summary_markdown(runs: dict) -> str:
    """The summary as a markdown table (for the README and the report)."""
    cols = ("case", "peak_moment", "min_moment", "rms_moment", "max_xi", "impacts", "wall_time_s")
    lines = ["| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    for _, (_, _, s, _) in runs.items():
        lines.append(
            "| "
            + " | ".join(
                (
                    f"{s[c]:.4g}"
                    if isinstance(s.get(c), float) and not math.isnan(s[c])
                    else ("–" if isinstance(s.get(c), float) else str(s.get(c, "")))
                )
                for c in cols
            )
            + " |"
        )
    return "\n".join(lines)


def discussion(runs: dict) -> list[str]:
    """Short, number-backed comparison with the paper's statements."""
    s = {n: runs[n][2] for n in runs}
    out = []
    if "perfect" in s:
        p = s["perfect"]
        out.append(
            f"Perfect joint: peak crank moment {p['peak_moment']:.2f} N·m, minimum "
            f"{p['min_moment']:.2f} N·m — the paper's \"order of 150 N·m\"; the benchmark's "
            f"independent power-balance inverse dynamics (tests/analytic.py) agrees to 1e-6 of the peak."
        )
    if "dry" in s and "perfect" in s:
        r = s["dry"]["peak_moment_all"] / s["perfect"]["peak_moment"]
        out.append(
            f"Dry clearance joint: {s['dry']['impacts']} impacts in the run; peak moment "
            f"{s['dry']['peak_moment_all']:.0f} N·m = {r:.1f}× the perfect peak. The paper says "
            f'"two orders of magnitude"; peaks of impacts do not converge with tolerance '
            f"(the dry case is chaotic, [T162]): this row is one trajectory; the distribution over "
            f"revolutions and replicas is in the section 'Dry joint as a distribution' (full runs). "
            f"RMS of this trajectory: {s['dry']['rms_moment']:.1f} vs {s['perfect']['rms_moment']:.1f} N·m."
        )
    for n in ("ott", "alshaer2005"):
        if n in s and "perfect" in s:
            out.append(
                f"{n}: peak {s[n]['peak_moment']:.1f} N·m over the last revolution "
                f"({s[n]['peak_moment'] / s['perfect']['peak_moment']:.2f}× perfect), max ξ = "
                f"{s[n]['max_xi']:.3f}."
            )
    if "ott" in s and "alshaer2005" in s:
        a, b = runs["ott"][1], runs["alshaer2005"][1]
        d = np.hypot(
            a["ex_bushing_over_c"] - b["ex_bushing_over_c"], a["ey_bushing_over_c"] - b["ey_bushing_over_c"]
        ).max()
        out.append(
            f"Journal paths of Ott and the π-film differ by up to {d:.3f}·c: Ott's model is a "
            f"rational approximation of the same π-film [T165], 5–25 % off at moderate ξ and "
            f"far off for separating motion near the wall, which is where the path differs."
        )
    out.append(
        "Both lubricated models here use the corrected film speed Ω = ω_J + ω_B − 2γ̇ (the "
        "paper prints ω − γ̇, typo T1 of [T163]) and the corrected eqs 6–9/1–5; with the "
        "bushing in the rod eye, ω_B = φ̇_rod enters Ω [T161], which the paper may not "
        "have done — its published curves need not match a correct implementation exactly."
    )
    return out


def _ensemble_html(ens: dict | None) -> str:
    """The report's section on the dry ensemble (empty without one)."""
    if ens is None:
        return ""
    from jointdyn.studies.reproduce_ensemble import ensemble_rows, ensemble_sentence

    rt = list(ens["per_rtol"])
    head = "".join(
        f"<th>{html.escape(h)}</th>"
        for h in ["quantity", "median", "5 %", "95 %", "± s.e.", *(f"median, rtol {g}" for g in rt), "shift"]
    )
    body = "".join(
        "<tr>"
        + "".join(
            f"<td>{html.escape(v)}</td>"
            for v in [
                f"{r['label']} [{r['unit']}]",
                *(_short(r[k]) for k in ("median", "p5", "p95", "se")),
                *(_short(r["per_rtol"][g]) for g in rt),
                f"{100 * r['shift']:.0f} %",
            ]
        )
        + "</tr>"
        for r in ensemble_rows(ens)
    )
    return (
        "<h2>Dry joint as a distribution (chaotic: one trajectory is one sample)</h2>"
        f"<table><tr>{head}</tr>{body}</table><p>{html.escape(ensemble_sentence(ens))} "
        f"Wall time {ens.get('wall_time_s', math.nan):.0f} s. Data: ensemble_dry.json.</p>"
    )


def report_html(runs: dict, figs: dict, revs: float, params: dict, ens: dict | None = None) -> str:
    def img(name, width=640):
        if name not in figs:
            return ""
        b64 = base64.b64encode(figs[name]).decode()
        text = html.escape(caption(name.removesuffix(".png"), runs))
        img_tag = f'<img alt="{text}" src="data:image/png;base64,{b64}" width="{width}">'
        return f'<figure style="max-width:{width}px">{img_tag}<figcaption>{text}</figcaption></figure>'

    rows = "".join(
        "<tr>" + "".join(f"<td>{html.escape(_short(s.get(c, '')))}</td>" for c in SUMMARY_COLUMNS) + "</tr>"
        for _, (_, _, s, _) in runs.items()
    )
    head = "".join(f"<th>{c.replace('_', '_<wbr>')}</th>" for c in SUMMARY_COLUMNS)
    par = "".join(
        f"<tr><td>{html.escape(k)}</td><td>{html.escape(str(v))}</td></tr>" for k, v in params.items()
    )
    disc = "".join(f"<li>{html.escape(x)}</li>" for x in discussion(runs))
    paper = [n for n in ("perfect", "dry", "ott", "alshaer2005") if n in runs]
    beyond = [n for n in runs if n not in paper]
    title = "jointdyn — Alshaer et al. (2005) reproduction"
    interactive = (
        '<p>Zoomable curves (e.g. into the dry spikes): <a href="interactive.html">interactive.html</a>.</p>'
        if importlib.util.find_spec("plotly")
        else ""
    )
    body = f"""<!DOCTYPE html><html><head><meta charset="utf-8"><title>{title}</title>
<style>body{{font-family:sans-serif;max-width:1100px;margin:auto}}
table{{border-collapse:collapse;font-size:12px}}
td,th{{border:1px solid #bbb;padding:2px 6px}} figure{{display:inline-block;margin:6px;vertical-align:top}}
figcaption{{font-size:12px}} .wide{{overflow-x:auto;max-width:100%}} img{{max-width:100%;height:auto}}</style>
</head><body>
<h1>Slider-crank with a lubricated piston pin — reproduction of Alshaer et al., J. Mech. Des. 127 (2005)</h1>
<p>{revs:g} crank revolutions at 5000 rpm; moments over the last revolution (columns *_all: whole run).
Film models: Ott (corrected, docs/theory.md T20–T39) and the paper's π-film in the branch-free form
of T21/T163; dry contact Lankarani–Nikravesh (T50–T56).</p>
{interactive}<h2>Summary</h2><div class="wide"><table><tr>{head}</tr>{rows}</table></div>
<h2>Paper figures</h2>
{"".join(img(f"moment_{n}.png") for n in paper)}
{img("moment_overlay.png", 800)}
{"".join(img(f"orbit_{n}.png", 360) for n in paper if f"orbit_{n}.png" in figs)}
{img("film_thickness.png", 800)}{img("joint_force.png", 800)}
<h2>Comparison with the paper's statements</h2><ul>{disc}</ul>
{_ensemble_html(ens)}
<h2>Beyond the paper</h2>
<p>Cases: {html.escape(", ".join(beyond) or "none in this run")}.</p>
{img("moment_beyond.png", 800)}
{"".join(img(f"orbit_{n}.png", 360) for n in beyond if f"orbit_{n}.png" in figs)}
<h2>Parameters</h2><table>{par}</table>
</body></html>"""
    return body


def expected_names(cases) -> tuple[str, ...]:
    """The names (patterns) a reproduction of ``cases`` writes besides the fixed ones."""
    names = [f"{c.name}.csv" for c in cases]
    names += [f"{f}_{c.name}.png" for c in cases for f in ("moment", "orbit")]
    return (*names, "moment_overlay.png", "moment_beyond.png", "film_thickness.png", "joint_force.png")


def reproduce_alshaer2005(
    out: Path,
    quick: bool = False,
    beyond: bool = True,
    progress=None,
    revs: float | None = None,
    ensemble: bool | None = None,
    overwrite: bool = True,
) -> dict:
    """Run all cases, write the files; returns {case: (results, columns, summary, Case)}.

    ``ensemble`` (default: on for runs of ≥ 4 revolutions, i.e. the full job) also runs the dry
    ensemble of :mod:`jointdyn.studies.reproduce_ensemble`: ``ensemble_dry.md``/``.json`` and a report
    section (``progress`` is called with the name ``"dry ensemble"`` when it is done).

    ``out`` is claimed as an output directory of kind ``reproduce`` (:mod:`jointdyn.io.rundir`):
    with ``overwrite`` (the library default; the CLI asks for ``--overwrite``) the files its
    manifest lists (or a killed reproduction recorded) are replaced, any other file is kept;
    every file is written atomically and ``manifest.json`` last (status
    ``interrupted``/``failed`` if a case stops)."""
    from jointdyn.io.rundir import OutputDir

    revs = revs if revs is not None else (1.0 if quick else 4.0)
    ensemble = revs >= 4.0 if ensemble is None else ensemble
    cases = PAPER_CASES + (BEYOND_CASES if beyond else ())
    meta = {"paper": "alshaer2005", "revs": revs, "cases": [c.name for c in cases], "ensemble": ensemble}
    od = OutputDir(out, "reproduce", meta)
    od.claim(overwrite=overwrite, expect=expected_names(cases))
    try:
        runs = _reproduce_into(od, cases, revs, progress, ensemble)
    except BaseException as err:
        from jointdyn.errors import Interrupted

        od.finish("interrupted" if isinstance(err, (Interrupted, KeyboardInterrupt)) else "failed", str(err))
        raise
    od.finish("complete")
    return runs


def _reproduce_into(od, cases, revs, progress, ensemble: bool = False) -> dict:
    from jointdyn.multibody.system import shared_kinds
    from jointdyn.studies.runs import model_system

    runs = {}
    # every case, and the dry ensemble's workers, run with one kernel set: the union of the
    # cases' joints and laws [T322, T341] (the kinds-dependent kernels shared by dopri5 and radau5)
    joints = sorted({c.joint for c in cases})
    with shared_kinds(*(model_system("slider-crank", {"joint": j})[0] for j in joints)):
        for case in cases:
            cb = (lambda f, c=case: progress(c.name, f)) if progress else None
            res, cols, summ = run_case(case, revs, progress=cb)
            runs[case.name] = (res, cols, summ, case)
        _report(od, runs, revs, progress, ensemble)
    return runs


def _report(od, runs: dict, revs: float, progress, ensemble: bool) -> None:
    from jointdyn.core import interrupts

    def put(name: str, data: bytes) -> None:
        interrupts.check()  # Ctrl-C while the report is written stops it (status interrupted)
        with od.write(name) as tmp:
            tmp.write_bytes(data)

    with drawing(figure_data(runs, revs), revs) as drawn:  # in another process meanwhile [T220, T360]
        ens = None
        if ensemble:  # after the paper's dry case: the worker processes reuse its compiled code
            from jointdyn.studies.reproduce_ensemble import (
                dry_ensemble,
                ensemble_json,
                ensemble_markdown,
                ensemble_sentence,
            )

            t0 = time.perf_counter()
            ens = dry_ensemble()
            ens["wall_time_s"] = time.perf_counter() - t0
            put("ensemble_dry.json", ensemble_json(ens))
            put("ensemble_dry.md", (ensemble_markdown(ens) + "\n\n" + ensemble_sentence(ens) + "\n").encode())
            if progress:
                progress("dry ensemble", 1.0)

        for name, data in csv_files(runs).items():
            put(name, data)
        figs = drawn()
    for name, png in figs.items():
        put(name, png)
    params = {
        "crank": f"{sc.CRANK_LENGTH} m, {sc.CRANK_MASS} kg, {sc.CRANK_INERTIA} kg·m²",
        "rod": f"{sc.ROD_LENGTH} m, {sc.ROD_MASS} kg, {sc.ROD_INERTIA} kg·m²",
        "slider": f"{sc.SLIDER_MASS} kg",
        "crank speed": "5000 rpm (CCW)",
        "gravity": "9.81 m/s² (−y)",
        "journal radius": f"{sc.JOURNAL_RADIUS} m",
        "clearance": "0.5 mm (0.05 mm beyond the paper)",
        "bearing length": f"{sc.BEARING_LENGTH} m",
        "viscosity": f"{sc.VISCOSITY} Pa·s",
        "dry contact": "Lankarani–Nikravesh, n = 1.5, c_r = 0.9, K from E = 207 GPa, ν = 0.3",
        "bearing side": "bushing in the rod eye (body i), journal on the slider (body j)",
        "initial state": "ideal mechanism at crank angle 0, journal centred (e = 0, ė = 0)",
    }
    put("report.html", report_html(runs, figs, revs, params, ens).encode("utf-8"))
    try:  # the [interactive] extra: zoomable moment curves and orbits in interactive.html
        from jointdyn.viz.iplots import reproduction_html

        interrupts.check()
        with od.write("interactive.html") as tmp:
            reproduction_html(runs, tmp, revs)
    except ImportError:
        pass
    put("summary.md", (summary_markdown(runs) + "\n").encode("utf-8"))
