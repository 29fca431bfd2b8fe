"""The one output contract of a run (shipped model, model file or sweep case).

Every run directory holds ``results.nc``, ``timeseries.csv`` (units in the headers: the
model's headline columns first, then every coordinate, velocity, multiplier and every force
element's declared outputs), ``summary.json``, the figures ``moment.png`` (first angle driver)
and ``orbit.png`` (first journal element, bushing frame [T290]), ``model.toml`` when the run came
from a model file, and ``manifest.json`` (written last, see :mod:`jointdyn.io.rundir`). Names and
units come from the system (coordinate labels, constraint types, the elements' ``OUTPUTS``),
never a side list.
"""

from __future__ import annotations

import csv
import json
import math

import numpy as np

from jointdyn import post
from jointdyn.core import atomic, interrupts
from jointdyn.core.constraints import CONSTRAINTS
from jointdyn.forces.elements import output_slots
from jointdyn.studies.metrics import metric_units, metrics
from jointdyn.studies.period import angle_drivers, journal_elements

_COORD_UNITS = {"x": "m", "y": "m", "phi": "rad"}
#: multiplier units by constraint registry name (row order as in ``joints.constraints``)
_LAMBDA_UNITS = {"revolute": ("N", "N"), "translational": ("N", "N·m"), "angle_driver": ("N·m",)}


def header(name: str, unit: str) -> str:
    """A CSV column header: ``name [unit]``."""
    return f"{name} [{unit}]"


def system_columns(res) -> dict[str, np.ndarray]:
    """time, every coordinate and velocity, every multiplier row and every element output,
    keyed ``name [unit]`` (SI)."""
    s = res.system
    cols = {header("time", "s"): res.t}
    labels = s.coordinate_labels()
    for k, lab in enumerate(labels):
        cols[header(lab, _COORD_UNITS[lab.rsplit(".", 1)[1]])] = res.q[:, k]
    for k, lab in enumerate(labels):
        cols[header(lab + "_dot", _COORD_UNITS[lab.rsplit(".", 1)[1]] + "/s")] = res.qd[:, k]
    names = {cls: n for n, cls in CONSTRAINTS.items()}
    for name, c, (a, b) in zip(s.constraint_names, s.constraints, s.constraint_rows):
        units = _LAMBDA_UNITS.get(names.get(type(c), ""), ())
        for r in range(b - a):
            lab = f"lambda.{name}[{r}]"
            cols[header(lab, units[r]) if r < len(units) else lab] = res.lam[:, a + r]
    for name, el in zip(s.element_names, s.elements):
        for out, unit in output_slots(el).items():
            cols[header(f"{name}.{out}", unit)] = res.element(name, out)
    return cols


def write_csv(path, cols: dict[str, np.ndarray], digits: int = 17) -> None:
    """Columns of equal length as CSV (``%.<digits>g``), header row first."""
    arrays = [np.asarray(v, dtype=float) for v in cols.values()]
    fmt = f"%.{digits}g"
    with atomic.replacing(path) as tmp, open(tmp, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(list(cols))
        for i in range(len(arrays[0]) if arrays else 0):
            w.writerow([fmt % a[i] for a in arrays])
            if i % 4096 == 0:
                interrupts.check()


def summary(res, status: str = "complete", aliases: dict[str, str] | None = None) -> dict:
    """Model-independent summary: solver, statistics, drift, and ``metrics`` (with their
    ``metric_units``) of :func:`jointdyn.studies.metrics.metrics` (``aliases``: a shipped model's
    short names of some metrics)."""
    out = {
        "model": res.system.name,
        "status": status,
        "t_end": float(res.t[-1]) if len(res.t) else 0.0,
        "samples": len(res.t),
        "solver": res.config["solver"],
        "rtol": res.config["rtol"],
        "error_scale": res.config.get("error_scale", "state"),
        "atol": res.config["atol"],
        "wall_time_s": res.wall_time,
        **res.stats,
        "max_drift_position": float(res.drift[:, 0].max()) if len(res.t) else math.nan,
        "max_drift_velocity": float(res.drift[:, 1].max()) if len(res.t) else math.nan,
    }
    if len(res.t):
        out["metrics"] = metrics(res, aliases)
        out["metric_units"] = metric_units(res.system, aliases)
    from jointdyn.simulation.ranges import film_range_exits

    out["film_range"] = film_range_exits(res)  # [T249]: [] when every film stayed in its table
    return out


def figures(res, title: str) -> dict:
    """``{file name: Figure}``: moment.png (first driver's moment vs its body angle) and
    orbit.png (first journal element's orbit e/c in the bushing frame [T290])."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from jointdyn.viz import plots, style

    figs = {}
    s = res.system
    if len(res.t) < 2:
        return figs
    ds = angle_drivers(s)
    if ds:
        c = s.constraints[s.constraint_names.index(ds[0])]
        angle = post.body_angle(res, c.body_j) if c.body_j != "ground" else res.t
        fig, ax = plt.subplots(figsize=(7, 4))
        plots.moment_vs_angle(angle, post.driving_moment(res, ds[0]), ax=ax)
        ax.set_title(title)
        fig.tight_layout()
        figs["moment.png"] = fig
    js = journal_elements(s)
    if js:
        fig, ax = plt.subplots(figsize=(5, 5.4))
        plots.journal_orbit(*res.orbit(js[0], frame="bushing"), ax=ax, label=js[0], frame="bushing")
        ax.set_title(f"{title}\n{js[0]}: journal centre path, bushing frame", fontsize=9)
        style.legend_below(ax, ncol=4, y=-0.13)
        fig.tight_layout()
        figs["orbit.png"] = fig
    return figs


def write_all(od, res, cols: dict, summ: dict, title: str, digits: int = 17) -> None:
    """results.nc, timeseries.csv, summary.json and the figures into the claimed
    :class:`~jointdyn.io.rundir.OutputDir` ``od`` (each atomically; a signal between files stops
    the writing with :class:`~jointdyn.errors.Interrupted`)."""
    import matplotlib.pyplot as plt

    with od.write("results.nc") as tmp:
        res.save(tmp)
    interrupts.check()
    with od.write("timeseries.csv") as tmp:
        write_csv(tmp, cols, digits)
    interrupts.check()
    with od.write("summary.json") as tmp:
        tmp.write_text(json.dumps(summ, indent=2, default=str) + "\n", encoding="utf-8")
    for name, fig in figures(res, title).items():
        interrupts.check()
        with od.write(name) as tmp:
            fig.savefig(tmp, dpi=120, format="png")
        plt.close(fig)
