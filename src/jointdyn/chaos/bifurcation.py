"""Bifurcation diagrams of the shipped slider-crank over one builder parameter [T131].

For each parameter value: one long run, the first ``transient_revs`` revolutions discarded,
then the stroboscopic section (crank angle ``section_angle``) of the journal's relative state
over ``record_revs`` revolutions [T122]. A periodic response with period p revolutions shows p
points per parameter value, a quasi-periodic or chaotic one a cloud. A diagram file::

    [base]                      # slider-crank builder/run arguments, as in a sweep file
    joint = "dry"
    rtol = 1e-8
    [bifurcation]
    parameter = "clearance"     # a numeric builder argument (jointdyn.options.builder_args())
    range = { start = 1e-4, stop = 5e-4, num = 120 }   # or: values = [...]
    transient_revs = 100
    record_revs = 60
    section_angle = 0.0         # crank angle of the section [deg]
    samples_per_rev = 72
"""

from __future__ import annotations

import math
import os
import time
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

VARIABLES = ("ex_over_c", "ey_over_c", "exdot_over_cw", "eydot_over_cw")
_KEYS = {"parameter", "values", "range", "transient_revs", "record_revs", "section_angle", "samples_per_rev"}


@dataclass(frozen=True)
class BifurcationSpec:
    """What to run: ``base`` builder/run arguments, the swept ``parameter`` and its ``values``
    (SI), revolutions, section angle [deg] and output samples per revolution."""

    base: dict
    parameter: str
    values: tuple
    transient_revs: int = 100
    record_revs: int = 60
    section_angle: float = 0.0
    samples_per_rev: int = 72
    scheduler: str | None = field(default=None, compare=False)

    def __post_init__(self):
        from ..options import builder_args

        valid = list(builder_args())
        if self.parameter not in valid:
            raise ValueError(
                f"bifurcation.parameter = {self.parameter!r}: not a builder argument; valid: {valid}"
            )
        if len(self.values) < 1 or not all(math.isfinite(v) for v in self.values):
            raise ValueError("bifurcation.values [SI]: need at least one finite value")
        if self.transient_revs < 0 or self.record_revs < 1:
            raise ValueError(
                f"bifurcation.transient_revs/record_revs = {self.transient_revs}/{self.record_revs} [rev]: "
                "need ≥ 0 and ≥ 1"
            )
        if self.samples_per_rev < 4:
            raise ValueError(f"bifurcation.samples_per_rev = {self.samples_per_rev!r} [-]: must be ≥ 4")


def load_bifurcation(path) -> BifurcationSpec:
    """Read a diagram file (see the module docstring); unknown keys are errors."""
    path = Path(path)
    try:
        doc = tomllib.loads(path.read_text())
    except tomllib.TOMLDecodeError as err:
        raise ValueError(f"{path}: {err}") from None
    if set(doc) - {"base", "bifurcation", "dask"}:
        raise ValueError(
            f"{path}: unknown table(s) {sorted(set(doc) - {'base', 'bifurcation', 'dask'})}; "
            "valid: ['base', 'bifurcation', 'dask']"
        )
    b = dict(doc.get("bifurcation", {}))
    if set(b) - _KEYS:
        raise ValueError(
            f"{path}: [bifurcation] unknown key(s) {sorted(set(b) - _KEYS)}; valid: {sorted(_KEYS)}"
        )
    if "parameter" not in b:
        raise ValueError(f"{path}: [bifurcation] needs `parameter`")
    if ("values" in b) == ("range" in b):
        raise ValueError(f"{path}: [bifurcation] needs exactly one of `values` or `range`")
    if "range" in b:
        r = b["range"]
        if set(r) - {"start", "stop", "num"} or not {"start", "stop", "num"} <= set(r):
            raise ValueError(f"{path}: [bifurcation] range needs start, stop, num")
        values = tuple(float(v) for v in np.linspace(r["start"], r["stop"], int(r["num"])))
    else:
        values = tuple(float(v) for v in b["values"])
    base = dict(doc.get("base", {}))
    if base.get("model", "slider-crank") != "slider-crank":
        raise ValueError(f"{path}: [base] model = {base.get('model')!r}; only 'slider-crank' is supported")
    return BifurcationSpec(
        base=base,
        parameter=b["parameter"],
        values=values,
        transient_revs=int(b.get("transient_revs", 100)),
        record_revs=int(b.get("record_revs", 60)),
        section_angle=float(b.get("section_angle", 0.0)),
        samples_per_rev=int(b.get("samples_per_rev", 72)),
        scheduler=doc.get("dask", {}).get("scheduler"),
    )


def run_point(
    base: dict,
    parameter: str,
    value: float,
    transient_revs: int,
    record_revs: int,
    section_angle_deg: float,
    samples_per_rev: int,
) -> dict:
    """One parameter value (in a worker process). Never raises: returns {"error": ...}."""
    from ..models.slider_crank import SPEED, slider_crank
    from ..options import builder_args, run_args
    from ..runs import slider_crank_config
    from ..simulate import simulate
    from .poincare import journal_section

    t0 = time.perf_counter()
    try:
        merged = {**base, parameter: value}
        model_kw = {k: merged[k] for k in builder_args() if k in merged}
        run_kw = {k: merged[k] for k in run_args() if k in merged and k not in ("revs", "samples_per_rev")}
        joint = merged.get("joint", "dry")
        speed = float(model_kw.get("speed", SPEED))
        revs = transient_revs + record_revs
        cfg = slider_crank_config(joint, revs, samples_per_rev=samples_per_rev, speed=speed, **run_kw)
        res = simulate(slider_crank(joint, **model_kw).compile(), cfg)
        T = 2 * math.pi / abs(speed)
        sec = journal_section(
            res, section_angle=math.radians(section_angle_deg), transient=transient_revs * T
        )
        cnt = (
            res.memory("piston_pin", "impacts") if "impacts" in type(res.system.elements[0]).MEMORY else None
        )
        out = {k: np.asarray(sec.values[k])[:record_revs].tolist() for k in VARIABLES}
        if cnt is not None:
            idx = np.arange(transient_revs, revs + 1) * samples_per_rev
            out["impacts_per_rev"] = np.diff(cnt[idx]).tolist()
        out["wall_time_s"] = time.perf_counter() - t0
        return out
    except Exception as err:  # recorded, the diagram goes on
        return {"error": f"{type(err).__name__}: {err}", "wall_time_s": time.perf_counter() - t0}


def run_bifurcation(
    spec: BifurcationSpec, out, workers: int | None = None, scheduler: str | None = None, progress=None
):
    """Run all parameter values on local processes (or a Dask cluster) and write
    ``out/bifurcation.nc``; returns the xarray Dataset (dims: the parameter, ``rev``)."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    args = [
        (
            spec.base,
            spec.parameter,
            v,
            spec.transient_revs,
            spec.record_revs,
            spec.section_angle,
            spec.samples_per_rev,
        )
        for v in spec.values
    ]
    results: list[dict] = [{}] * len(args)
    scheduler = scheduler or spec.scheduler
    done = 0
    if scheduler:
        from distributed import Client, as_completed

        with Client(scheduler) as client:
            futs = {client.submit(run_point, *a, pure=False): i for i, a in enumerate(args)}
            for fut in as_completed(futs):
                results[futs[fut]] = fut.result()
                done += 1
                if progress:
                    progress(done, len(args))
    else:
        from concurrent.futures import ProcessPoolExecutor, as_completed

        with ProcessPoolExecutor(max_workers=workers or os.cpu_count()) as ex:
            futs = {ex.submit(run_point, *a): i for i, a in enumerate(args)}
            for fut in as_completed(futs):
                results[futs[fut]] = fut.result()
                done += 1
                if progress:
                    progress(done, len(args))
    ds = to_dataset(spec, results)
    ds.to_netcdf(out / "bifurcation.nc", engine="h5netcdf")
    return ds


def to_dataset(spec: BifurcationSpec, results: list[dict]):
    """Dataset with the section variables (parameter × rev), impacts per revolution, errors."""
    import json

    import xarray as xr

    n, r = len(spec.values), spec.record_revs
    data = {k: np.full((n, r), np.nan) for k in (*VARIABLES, "impacts_per_rev")}
    for i, res in enumerate(results):
        for k in data:
            v = np.asarray(res.get(k, []), float)[:r]
            data[k][i, : v.size] = v
    p = spec.parameter
    ds = xr.Dataset(
        {k: ((p, "rev"), v) for k, v in data.items()}
        | {
            "error": (p, np.array([res.get("error", "") for res in results], dtype=str)),
            "wall_time_s": (p, np.array([res.get("wall_time_s", np.nan) for res in results], float)),
        },
        coords={
            p: np.asarray(spec.values, float),
            "rev": np.arange(spec.transient_revs, spec.transient_revs + r),
        },
    )
    ds.attrs.update(
        {
            "base": json.dumps(spec.base, default=str),
            "section_angle_deg": spec.section_angle,
            "transient_revs": spec.transient_revs,
            "record_revs": spec.record_revs,
            "samples_per_rev": spec.samples_per_rev,
        }
    )
    return ds


PARAM_UNITS = {
    "speed": "rad/s",
    "gravity": "m/s²",
    "clearance": "m",
    "viscosity": "Pa·s",
    "length": "m",
    "restitution": "-",
    "asperity_height": "m",
}


def plot_bifurcation(ds, path, variable: str = "ex_over_c", title: str = "") -> None:
    """Section values against the parameter (one dot per recorded revolution), and the median
    impacts per revolution."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    p = next(iter(ds[variable].dims))
    x = ds[p].values
    scale, unit = (
        (1e3, "mm") if p in ("clearance", "length", "asperity_height") else (1.0, PARAM_UNITS.get(p, ""))
    )
    if p == "speed":
        scale, unit = 60 / (2 * math.pi), "rpm"
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True, gridspec_kw={"height_ratios": [3, 1]})
    v = ds[variable].values
    xx = np.repeat(x[:, None], v.shape[1], axis=1)
    a1.plot((xx * scale).ravel(), v.ravel(), ",", color="k", alpha=0.6)
    a1.plot((xx * scale).ravel(), v.ravel(), ".", ms=1.2, color="k", alpha=0.4)
    a1.set_ylabel(f"{variable} at crank angle {ds.attrs.get('section_angle_deg', 0):g}° [-]")
    a1.set_title(title or f"bifurcation diagram over {p}")
    imp = ds["impacts_per_rev"].values
    if np.isfinite(imp).any():
        a2.plot(x * scale, np.nanmedian(imp, axis=1), "-", lw=1, color="C3", label="median")
        a2.fill_between(
            x * scale,
            np.nanquantile(imp, 0.05, axis=1),
            np.nanquantile(imp, 0.95, axis=1),
            color="C3",
            alpha=0.2,
            label="5–95 %",
        )
        a2.legend(fontsize=8)
    a2.set_ylabel("impacts / rev [-]")
    a2.set_xlabel(f"{p} [{unit}]")
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)
