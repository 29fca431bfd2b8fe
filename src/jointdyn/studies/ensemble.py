"""Ensemble statistics of a chaotic run: distributions over revolutions (after a transient)
and over replicas (perturbed initial state, several tolerances), with a convergence check.

A chaotic trajectory is not reproducible sample by sample: any change of tolerance or initial
state gives a different one after a few revolutions. What is reproducible is the distribution
of per-revolution quantities on the attractor [T120]; we report its median and 5–95 % band and
check that these do not move with the tolerance or with the number of revolutions [T121].
"""

from __future__ import annotations

import math
import os

import numpy as np

from jointdyn import post
from jointdyn.models.catalog import DEFAULT
from jointdyn.studies.poincare import stroboscopic_indices

PER_REV = (
    "peak_moment",
    "min_moment",
    "rms_moment",
    "impacts",
    "max_contact_force",
    "max_penetration",
)
UNITS = {
    "peak_moment": "N·m",
    "min_moment": "N·m",
    "rms_moment": "N·m",
    "impacts": "1/rev",
    "max_contact_force": "N",
    "max_penetration": "m",
}


def revolution_stats(
    res,
    transient_revs: int = 0,
    element: str | None = "",
    driver: str | None = None,
) -> dict[str, np.ndarray]:
    """Per-revolution quantities of a run whose output grid has samples at every angle 2πk of
    its angle driver ``driver`` (default: the model's first; the shipped runs and
    :func:`jointdyn.studies.period.per_revolution_config`): peak, min and RMS driving moment
    [N·m] (RMS by the trapezoidal rule over the revolution); for a journal ``element`` (``""``:
    the model's first, if it has one; None: none) also impacts per revolution (from the
    element's onset counter over accepted steps, exact) and the largest contact force [N] and
    penetration max(−h_min, 0) [m] over the output samples of the revolution (sample-limited).
    The first ``transient_revs`` revolutions are discarded."""
    from jointdyn.studies import period as per

    if transient_revs < 0:
        raise ValueError(f"transient_revs = {transient_revs!r} [rev]: must be ≥ 0")
    driver = per.driver_name(res.system, driver)
    angle = per.driver_angle(res, driver)
    b = stroboscopic_indices(angle, float(angle[0]))
    if b.size < transient_revs + 2:
        raise ValueError(
            f"transient_revs = {transient_revs} [rev]: the run has only {max(b.size - 1, 0)} complete "
            f"revolutions on its output grid (need > transient_revs)"
        )
    b = b[transient_revs:]
    m = post.driving_moment(res, driver)
    out = {k: [] for k in PER_REV}
    if element == "":
        journals = per.journal_elements(res.system)
        element = journals[0] if journals else None
    elif element is not None:
        element = per.journal(res.system, element)
    has_el = (
        element is not None
        and "impacts" in type(res.system.elements[res.system.element_names.index(element)]).MEMORY
    )
    if has_el:
        cnt = res.memory(element, "impacts")
        fc = res.element(element, "contact_force")
        pen = np.maximum(-res.element(element, "h_min"), 0.0)
    for a, z in zip(b[:-1], b[1:]):
        w = slice(a, z + 1)
        x = m[w]
        t = res.t[w]
        out["peak_moment"].append(x.max())
        out["min_moment"].append(x.min())
        out["rms_moment"].append(math.sqrt(np.trapezoid(x * x, t) / (t[-1] - t[0])))
        if has_el:
            out["impacts"].append(cnt[z] - cnt[a])
            out["max_contact_force"].append(fc[w].max())
            out["max_penetration"].append(pen[w].max())
    return {k: np.asarray(v, float) for k, v in out.items() if v}


def band(x: np.ndarray) -> dict:
    """median and 5 % / 95 % quantiles (linear interpolation) of a sample [T120]."""
    x = np.asarray(x, float)
    p5, med, p95 = np.quantile(x, [0.05, 0.5, 0.95])
    return {"median": float(med), "p5": float(p5), "p95": float(p95), "n": int(x.size)}


def median_se(x: np.ndarray, n_boot: int = 400, seed: int = 0) -> float:
    """Bootstrap standard error of the median of a sample (seeded) [T121]."""
    x = np.asarray(x, float)
    if x.size < 2:
        return math.inf
    rng = np.random.default_rng(seed)
    meds = np.median(x[rng.integers(0, x.size, size=(n_boot, x.size))], axis=1)
    return float(np.std(meds, ddof=1))


def convergence(groups: dict[str, dict[str, np.ndarray]], z_max: float = 3.0) -> dict:
    """Does the distribution move between groups (e.g. tolerances) or with the sample size?

    For each quantity: the pooled band; each group's median; ``shift`` = the largest distance
    of a group median from the pooled median and ``half_shift`` = the distance between the
    medians of the first and second half of the revolutions (the N check), both divided by the
    pooled 5–95 % width; ``z`` and ``half_z`` = the same distances divided by the bootstrap
    standard error of the difference [T121]. ``converged`` when both z are below ``z_max``
    (the medians agree within their sampling noise)."""
    names = sorted({k for g in groups.values() for k in g})
    out = {}
    for k in names:
        parts = {name: np.asarray(g[k], float) for name, g in groups.items() if k in g and len(g[k])}
        pooled = np.concatenate(list(parts.values()))
        pb = band(pooled)
        width = pb["p95"] - pb["p5"]
        width = width if width > 0 else max(abs(pb["median"]), 1e-300)
        se_pooled = median_se(pooled)
        meds = {name: float(np.median(p)) for name, p in parts.items()}
        dev = {name: abs(v - pb["median"]) for name, v in meds.items()}
        z = max(
            (d / math.hypot(median_se(parts[name]), se_pooled) if d > 0 else 0.0) for name, d in dev.items()
        )
        first = np.concatenate([p[: len(p) // 2] for p in parts.values()])
        second = np.concatenate([p[len(p) // 2 :] for p in parts.values()])
        dh = abs(float(np.median(first)) - float(np.median(second)))
        half_z = dh / math.hypot(median_se(first), median_se(second)) if dh > 0 else 0.0
        out[k] = {
            **pb,
            "unit": UNITS.get(k, ""),
            "group_medians": meds,
            "median_se": se_pooled,
            "shift": float(max(dev.values()) / width),
            "half_shift": float(dh / width),
            "z": float(z),
            "half_z": float(half_z),
            "converged": bool(z < z_max and half_z < z_max),
        }
    return out


def perturbed_system(system, seed: int, scale: float = 1e-9):
    """The system with its initial velocities perturbed by ``scale``·|q̇|max·N(0, 1) (seeded)
    and projected back onto the constraints [T11]; seed 0 = unperturbed."""
    import dataclasses

    from jointdyn.multibody.dynamics import project

    if seed == 0:
        return system
    y = system.y0.copy()
    n = system.n
    rng = np.random.default_rng(seed)
    y[n:] += scale * np.abs(y[n:]).max() * rng.standard_normal(n)
    project(0.0, y, system.packed(0.0), 1e-13)
    return dataclasses.replace(system, y0=y)


def _system(model, model_kw: dict):
    """(System, SimConfig) of an ensemble's model: a model file (``model_kw``: its overrides
    ``{key: value}``) or a shipped model (``model_kw``: its variant, builder arguments and keys)."""
    from jointdyn.studies.runs import model_system

    return model_system(model, model_kw)


def _run_case(model, model_kw: dict, revs: int, transient_revs: int, rtol: float, seed: int, spr: int):
    import dataclasses

    from jointdyn.simulation.simulate import simulate
    from jointdyn.studies.period import per_revolution_config

    system, cfg = _system(model, model_kw)
    system = perturbed_system(system, seed)
    cfg = per_revolution_config(system, dataclasses.replace(cfg, rtol=rtol, atol=rtol * 1e-3), revs, spr)
    res = simulate(system, cfg)
    return {k: v.tolist() for k, v in revolution_stats(res, transient_revs).items()}


def ensemble(
    model=DEFAULT,
    model_kw: dict | None = None,
    rtols=(1e-7, 1e-8, 1e-9),
    replicas: int = 1,
    revs: int = 60,
    transient_revs: int = 10,
    samples_per_rev: int = 720,
    workers: int | None = None,
) -> dict:
    """Distributions of the per-revolution quantities (:func:`revolution_stats`; revolutions of
    the model's first angle driver) of a model file (``model_kw``: its overrides) or the shipped
    shipped model (``model_kw``: its variant, builder arguments and dotted keys) over revolutions
    ``transient_revs`` … ``revs`` of ``replicas`` runs per tolerance (replica r > 0 starts from a
    seeded 1e-9 velocity perturbation; atol = 1e-3·rtol), run in parallel on local processes,
    with the convergence check across tolerances (:func:`convergence`). Returns
    ``{"bands": {quantity: band + convergence}, "per_rtol": {rtol: {quantity: band}}, "settings"}``.
    """
    from jointdyn.io.pool import run_local
    from jointdyn.studies.period import driver_period

    if replicas < 1:
        raise ValueError(f"replicas = {replicas!r} [-]: must be ≥ 1")
    rt = [float(r) for r in rtols]
    if not rt or len(set(rt)) != len(rt) or not all(0 < r < 1 for r in rt):  # [T287]
        raise ValueError(
            f"--rtols {','.join(f'{r:g}' for r in rt)} [-]: give distinct tolerances in (0, 1); a "
            "repeated one would pass the convergence check across tolerances with shift 0"
        )
    if revs <= transient_revs:
        raise ValueError(f"revs = {revs!r} [rev]: must exceed transient_revs = {transient_revs}")
    model_kw = dict(model_kw or {})
    driver_period(_system(model, model_kw)[0])  # one line before any work: the model has a revolution
    cases = [(float(r), s) for r in rtols for s in range(replicas)]
    args = [(model, model_kw, int(revs), int(transient_revs), r, s, int(samples_per_rev)) for r, s in cases]
    if (workers or os.cpu_count() or 1) > 1 and len(cases) > 1:
        out: dict[int, dict] = {}
        run_local(_run_case, enumerate(args), workers, out.__setitem__)
        results = [out[i] for i in range(len(args))]
    else:
        results = [_run_case(*a) for a in args]
    groups: dict[str, dict[str, np.ndarray]] = {}
    for (r, _), stats in zip(cases, results):
        g = groups.setdefault(f"{r:g}", {})
        for k, v in stats.items():
            g[k] = np.concatenate([g.get(k, np.empty(0)), np.asarray(v, float)])
    settings = {"model": str(model)} | {
        k: v for k, v in model_kw.items() if isinstance(v, str) and "." not in k
    }
    return {
        "bands": convergence(groups),
        "per_rtol": {name: {k: band(v) for k, v in g.items()} for name, g in groups.items()},
        "settings": settings
        | {
            "rtols": [float(r) for r in rtols],
            "replicas": int(replicas),
            "revs": int(revs),
            "transient_revs": int(transient_revs),
            "samples_per_rev": int(samples_per_rev),
            "model_kw": {
                k: v for k, v in model_kw.items() if isinstance(v, (int, float)) and not isinstance(v, bool)
            },
        },
    }


def ensemble_table(result: dict) -> list[dict]:
    """Rows (quantity, unit, median, p5, p95, n, shift, converged, medians per rtol) for a
    report table."""
    rows = []
    for k in PER_REV:
        if k in result["bands"]:
            b = result["bands"][k]
            rows.append(
                {
                    "quantity": k,
                    "unit": b["unit"],
                    "median": b["median"],
                    "p5": b["p5"],
                    "p95": b["p95"],
                    "n": b["n"],
                    "shift": b["shift"],
                    "half_shift": b["half_shift"],
                    "z": b["z"],
                    "half_z": b["half_z"],
                    "converged": b["converged"],
                    **{f"median_rtol_{g}": v for g, v in b["group_medians"].items()},
                }
            )
    return rows


def ensemble_markdown(result: dict) -> str:
    """A Markdown table of :func:`ensemble_table` (median [5 %, 95 %] per quantity, the median
    at each tolerance, and the convergence verdict) for reports and the README."""
    rows = ensemble_table(result)
    groups = list(result["per_rtol"])
    head = ["quantity", "unit", "median [5 %, 95 %]", *(f"median, rtol {g}" for g in groups), "converged (z)"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in rows:
        meds = [f"{r[f'median_rtol_{g}']:.4g}" for g in groups]
        z = max(r["z"], r["half_z"])
        cells = [r["quantity"], r["unit"], f"{r['median']:.4g} [{r['p5']:.4g}, {r['p95']:.4g}]", *meds]
        lines.append("| " + " | ".join([*cells, f"{'yes' if r['converged'] else 'no'} ({z:.1f})"]) + " |")
    return "\n".join(lines)
