"""Parameter studies: many independent runs, on local processes or a Dask cluster.

A sweep file (TOML)::

    [base]                      # what is run for every case
    model = "slider-crank"      # a shipped model …
    joint = "alshaer2005"       # … with its builder arguments (clearance, viscosity, speed, …)
    revs = 4                    # crank revolutions
    [grid]                      # full factorial over these (builder or solver arguments)
    clearance = [5e-5, 1e-4, 5e-4]
    viscosity = [0.1, 0.4, 1.0]
    [zip]                       # lists of equal length, varied together (optional)
    [sample]                    # Latin-hypercube samples (optional): n, seed, ranges = {name = [lo, hi]}
    [output]
    keep_series = false         # also keep each case's time series (netCDF per case)
    [dask]
    scheduler = "tcp://127.0.0.1:8786"   # optional; same as --scheduler

Every case is written atomically to ``DIR/cases/case_NNNNN.json`` (metrics, or the error of a
failed case) as soon as it finishes; ``--resume`` skips the cases already there, so a killed
sweep recomputes at most the cases that were in flight. ``DIR/sweep.nc`` gathers all cases in
one xarray Dataset (grid parameters as coordinates when the sweep is a pure grid).
"""

from __future__ import annotations

import itertools
import json
import math
import os
import time
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

METRICS = (
    "peak_moment",
    "min_moment",
    "rms_moment",
    "max_xi",
    "min_h_min",
    "impacts",
    "energy_dissipated",
    "wall_time_s",
    "rhs_evaluations",
)
MODEL_ARGS = (
    "joint",
    "speed",
    "gravity",
    "clearance",
    "viscosity",
    "length",
    "restitution",
    "asperity_height",
)
RUN_ARGS = ("solver", "rtol", "atol", "samples_per_rev")


@dataclass(frozen=True)
class SweepSpec:
    """A parameter study (see the module docstring for the file layout)."""

    base: dict
    grid: dict = field(default_factory=dict)
    zipped: dict = field(default_factory=dict)
    sample: dict = field(default_factory=dict)
    keep_series: bool = False
    scheduler: str | None = None

    def cases(self) -> list[dict]:
        """The list of parameter dicts, one per case, in a fixed order."""
        parts = []
        if self.grid:
            keys = list(self.grid)
            parts.append([dict(zip(keys, vals)) for vals in itertools.product(*self.grid.values())])
        if self.zipped:
            lens = {len(v) for v in self.zipped.values()}
            if len(lens) != 1:
                raise ValueError(f"[zip]: all lists must have the same length; got {sorted(lens)}")
            keys = list(self.zipped)
            parts.append([dict(zip(keys, vals)) for vals in zip(*self.zipped.values())])
        if self.sample:
            parts.append(latin_hypercube(self.sample))
        cases = [{}]
        for p in parts:
            cases = [{**a, **b} for a in cases for b in p]
        return cases


def latin_hypercube(sample: dict) -> list[dict]:
    """``sample = {n, seed, ranges = {name: [lo, hi]}}`` -> n cases (scipy.stats.qmc)."""
    from scipy.stats import qmc

    unknown = set(sample) - {"n", "seed", "ranges"}
    if unknown:
        raise ValueError(f"[sample]: unknown key(s) {sorted(unknown)}; valid: ['n', 'ranges', 'seed']")
    ranges = sample["ranges"]
    names = list(ranges)
    lo = np.array([ranges[k][0] for k in names], float)
    hi = np.array([ranges[k][1] for k in names], float)
    u = qmc.LatinHypercube(d=len(names), seed=sample.get("seed", 0)).random(int(sample["n"]))
    x = qmc.scale(u, lo, hi)
    return [{k: float(v) for k, v in zip(names, row)} for row in x]


def load_sweep(path) -> SweepSpec:
    """Read a sweep file; unknown tables/keys are errors naming the valid ones."""
    path = Path(path)
    try:
        doc = tomllib.loads(path.read_text())
    except tomllib.TOMLDecodeError as err:
        raise ValueError(f"{path}: {err}") from None
    valid = {"base", "grid", "zip", "sample", "output", "dask"}
    if set(doc) - valid:
        raise ValueError(f"{path}: unknown table(s) {sorted(set(doc) - valid)}; valid: {sorted(valid)}")
    if "base" not in doc:
        raise ValueError(f"{path}: missing [base] table")
    out = doc.get("output", {})
    if set(out) - {"keep_series"}:
        raise ValueError(
            f"{path}: [output] unknown key(s) {sorted(set(out) - {'keep_series'})}; valid: ['keep_series']"
        )
    base = dict(doc["base"])
    if "file" in base:
        base["file"] = str((path.parent / base["file"]).resolve())
    spec = SweepSpec(
        base=base,
        grid=doc.get("grid", {}),
        zipped=doc.get("zip", {}),
        sample=doc.get("sample", {}),
        keep_series=bool(out.get("keep_series", False)),
        scheduler=doc.get("dask", {}).get("scheduler"),
    )
    for name in itertools.chain(spec.grid, spec.zipped, spec.sample.get("ranges", {})):
        _check_param(base, name)
    return spec


def _check_param(base: dict, name: str):
    if "file" in base:
        return  # dotted model-file paths are checked by the model-file loader
    valid = MODEL_ARGS + RUN_ARGS + ("revs",)
    if name not in valid:
        raise ValueError(f"sweep parameter {name!r} is not a slider-crank argument; valid: {list(valid)}")


def run_case(base: dict, params: dict, series_path: str | None = None) -> dict:
    """Run one case (in a worker process); returns its metrics. Never raises: a failure is
    returned as ``{"error": message}``."""
    from . import post
    from .runs import run_slider_crank

    t0 = time.perf_counter()
    try:
        merged = {**base, **params}
        if "file" in merged:
            from .config import load_model
            from .simulate import simulate

            # every [base] key besides file/model and every swept parameter is a dotted override
            extra = {k: v for k, v in merged.items() if k not in ("file", "model")}
            overrides = [f"{k}={json.dumps(v)}" for k, v in extra.items()]
            model, cfg = load_model(merged["file"], overrides)
            res = simulate(model.compile(), cfg)
            metrics = {"rhs_evaluations": res.stats["rhs_evaluations"]}
        else:
            if merged.get("model", "slider-crank") != "slider-crank":
                raise ValueError(f"unknown model {merged.get('model')!r}; valid: ['slider-crank']")
            model_kw = {k: merged[k] for k in MODEL_ARGS if k in merged and k != "joint"}
            run_kw = {k: merged[k] for k in RUN_ARGS if k in merged}
            res, cols, summ = run_slider_crank(
                merged.get("joint", "perfect"), float(merged.get("revs", 4)), model_kw=model_kw, **run_kw
            )
            metrics = {
                k: summ.get(k, math.nan)
                for k in ("peak_moment", "min_moment", "rms_moment", "max_xi", "min_h_min", "rhs_evaluations")
            }
        names = res.system.element_names
        if names:  # the joint under study: "piston_pin" in the shipped model, else the first
            el = "piston_pin" if "piston_pin" in names else names[0]
            metrics["energy_dissipated"] = post.dissipated_energy(res, el)
            if "impacts" in type(res.system.elements[names.index(el)]).MEMORY:
                metrics["impacts"] = post.impacts(res, el)
        metrics["wall_time_s"] = time.perf_counter() - t0
        if series_path:
            res.save(series_path)
        return {
            k: (float(v) if isinstance(v, (int, float, np.floating, np.integer)) else v)
            for k, v in metrics.items()
        }
    except Exception as err:  # recorded, the sweep goes on
        return {"error": f"{type(err).__name__}: {err}", "wall_time_s": time.perf_counter() - t0}


def _write_atomic(path: Path, data: dict):
    tmp = path.with_suffix(path.suffix + f".tmp{os.getpid()}")
    tmp.write_text(json.dumps(data))
    os.replace(tmp, path)


def run_sweep(
    spec: SweepSpec,
    out,
    resume: bool = False,
    scheduler: str | None = None,
    workers: int | None = None,
    progress=None,
):
    """Run all cases not yet done; write per-case files and ``sweep.nc``. Returns the Dataset."""
    out = Path(out)
    cdir = out / "cases"
    cdir.mkdir(parents=True, exist_ok=True)
    cases = spec.cases()
    (out / "spec.json").write_text(
        json.dumps(
            {
                "base": spec.base,
                "grid": spec.grid,
                "zip": spec.zipped,
                "sample": spec.sample,
                "n_cases": len(cases),
            },
            default=str,
        )
    )
    todo = []
    for i in range(len(cases)):
        f = cdir / f"case_{i:05d}.json"
        if resume and f.exists():
            continue
        todo.append(i)
    if not resume:
        for f in cdir.glob("case_*.json"):
            f.unlink()
    sp = (lambda i: str(cdir / f"case_{i:05d}.nc")) if spec.keep_series else (lambda i: None)
    done = len(cases) - len(todo)
    scheduler = scheduler or spec.scheduler

    def record(i, result):
        nonlocal done
        _write_atomic(cdir / f"case_{i:05d}.json", {"case": i, "params": cases[i], **result})
        done += 1
        if progress:
            progress(done, len(cases))

    if todo and scheduler:
        from distributed import Client, as_completed

        with Client(scheduler) as client:
            futs = {client.submit(run_case, spec.base, cases[i], sp(i), pure=False): i for i in todo}
            for fut in as_completed(futs):
                record(futs[fut], fut.result())
    elif todo:
        from concurrent.futures import ProcessPoolExecutor, as_completed

        with ProcessPoolExecutor(max_workers=workers or os.cpu_count()) as ex:
            futs = {ex.submit(run_case, spec.base, cases[i], sp(i)): i for i in todo}
            for fut in as_completed(futs):
                record(futs[fut], fut.result())
    ds = gather(out, spec, cases)
    ds.to_netcdf(out / "sweep.nc", engine="h5netcdf")
    return ds


def gather(out: Path, spec: SweepSpec, cases: list[dict]):
    """Combine the per-case files into one Dataset (dims = grid parameters for pure grids)."""
    import xarray as xr

    rows = [json.loads((out / "cases" / f"case_{i:05d}.json").read_text()) for i in range(len(cases))]
    data = {
        m: np.array([r.get(m, np.nan) if not isinstance(r.get(m), str) else np.nan for r in rows], float)
        for m in METRICS
    }
    errors = np.array([r.get("error", "") for r in rows], dtype=object)
    ds = xr.Dataset(
        {m: ("case", v) for m, v in data.items()} | {"error": ("case", errors.astype(str))},
        coords={"case": np.arange(len(cases))},
    )
    for name in sorted({k for c in cases for k in c}):
        ds.coords[name] = ("case", np.array([c.get(name, np.nan) for c in cases], dtype=float))
    if spec.grid and not spec.zipped and not spec.sample:
        keys = list(spec.grid)
        ds = ds.swap_dims(case=keys[0]) if len(keys) == 1 else ds.set_index(case=keys).unstack("case")
    ds.attrs["base"] = json.dumps(spec.base, default=str)
    return ds
