"""Ready-made runs of the shipped slider-crank: simulate, derive, write files.

Used by the CLI (``jointdyn run``/``reproduce``), the benchmarks and the tests.
"""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import numpy as np

from . import post
from .models import slider_crank as sc
from .simulate import SimConfig, simulate


def slider_crank_config(
    joint: str,
    revs: float = 4.0,
    samples_per_rev: int = 720,
    solver: str | None = None,
    rtol: float = 1e-8,
    atol: float = 1e-10,
    speed: float = sc.SPEED,
) -> SimConfig:
    """Integration settings for ``revs`` crank revolutions at ``speed`` [rad/s]."""
    if not (math.isfinite(revs) and revs > 0):
        raise ValueError(f"revs = {revs!r} [revolutions]: must be > 0")
    t_end = revs * 2 * math.pi / speed
    return SimConfig(
        t_end=t_end,
        n_out=int(round(revs * samples_per_rev)) + 1,
        solver=solver or "auto",
        rtol=rtol,
        atol=atol,
    )


def slider_crank_table(res, joint_element: str | None = None) -> dict[str, np.ndarray]:
    """Time series of a slider-crank run: t [s], crank_angle [rad, unwrapped], crank_moment
    [N·m] (the drive's moment on the crank, CCW positive), and for an imperfect piston pin
    ex_over_c, ey_over_c [-], h_min [m], joint_force [N] (magnitude on the journal)."""
    cols = {
        "t": res.t,
        "crank_angle": post.body_angle(res, "crank"),
        "crank_moment": post.driving_moment(res, "drive"),
    }
    if joint_element is not None:
        c = res.system.elements[res.system.element_names.index(joint_element)].clearance
        cols["ex_over_c"] = res.element(joint_element, "ex") / c
        cols["ey_over_c"] = res.element(joint_element, "ey") / c
        cols["h_min"] = res.element(joint_element, "h_min")
        cols["joint_force"] = np.hypot(res.element(joint_element, "Fx"), res.element(joint_element, "Fy"))
        cols["contact_force"] = res.element(joint_element, "contact_force")
    return cols


def summarize(res, cols: dict, revs: float) -> dict:
    """Summary metrics: moment statistics over the last revolution and the whole run."""
    t_last = res.t[-1] - (res.t[-1] / revs if revs >= 1 else res.t[-1])
    last = post.window(res, t_last)
    m = cols["crank_moment"]
    out = {
        "joint": res.system.name,
        "revolutions": revs,
        "solver": res.config["solver"],
        "rtol": res.config["rtol"],
        "wall_time_s": res.wall_time,
        **res.stats,
        "max_drift_position": float(res.drift[:, 0].max()),
        "max_drift_velocity": float(res.drift[:, 1].max()),
    }
    out.update({f"{k}_moment": v for k, v in post.stats(m[last]).items()})
    out.update({f"{k}_moment_all": v for k, v in post.stats(m).items()})
    if "ex_over_c" in cols:
        xi = np.hypot(cols["ex_over_c"], cols["ey_over_c"])
        out["max_xi"] = float(xi.max())
        out["min_h_min"] = float(cols["h_min"].min())
        in_contact = cols["contact_force"] > 0
        dt = np.diff(res.t)
        out["contact_time_s"] = float(np.sum(dt * 0.5 * (in_contact[1:] + in_contact[:-1])))
        out["contact_fraction"] = out["contact_time_s"] / float(res.t[-1] - res.t[0])
        out["max_contact_force"] = float(cols["contact_force"].max())
        out["max_penetration"] = post.max_penetration(res, "piston_pin")  # over accepted steps
        out["impacts"] = post.impacts(res, "piston_pin")
    return out


def write_run(out: Path, res, cols: dict, summary: dict, title: str) -> None:
    """results.nc, timeseries.csv, summary.json and moment.png into ``out``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from . import plots

    out.mkdir(parents=True, exist_ok=True)
    res.save(out / "results.nc")
    with open(out / "timeseries.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(list(cols))
        for row in zip(*cols.values()):
            w.writerow([f"{v:.10g}" for v in row])
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    fig, ax = plt.subplots(figsize=(7, 4))
    plots.moment_vs_angle(cols["crank_angle"], cols["crank_moment"], ax=ax)
    ax.set_title(title)
    fig.tight_layout()
    fig.savefig(out / "moment.png", dpi=120)
    plt.close(fig)
    if "ex_over_c" in cols:
        fig, ax = plt.subplots(figsize=(5, 5))
        plots.journal_orbit(cols["ex_over_c"], cols["ey_over_c"], ax=ax)
        ax.set_title(title)
        fig.tight_layout()
        fig.savefig(out / "orbit.png", dpi=120)
        plt.close(fig)


def run_slider_crank(
    joint: str = "perfect",
    revs: float = 4.0,
    out: Path | None = None,
    progress=None,
    model_kw: dict | None = None,
    **cfg_kw,
):
    """Simulate the benchmark slider-crank; optionally write the run files. Returns
    (results, columns, summary)."""
    model = sc.slider_crank(joint, **(model_kw or {}))
    system = model.compile()
    cfg = slider_crank_config(joint, revs, **cfg_kw)
    res = simulate(system, cfg, progress=progress, chunks=max(1, int(math.ceil(revs * 8))))
    el = "piston_pin" if "piston_pin" in system.element_names else None
    cols = slider_crank_table(res, el)
    summary = summarize(res, cols, revs)
    if out is not None:
        write_run(Path(out), res, cols, summary, f"slider-crank, {joint} piston pin")
    return res, cols, summary
