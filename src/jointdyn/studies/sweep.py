"""Parameter studies: many independent runs, on local processes or a Dask cluster.

A sweep file (TOML)::

    [base]                      # what is run for every case
    model = "slider-crank"      # a shipped model …
    joint = "alshaer2005"       # … with its builder arguments (clearance, viscosity, speed, …)
    revs = 4                    # revolutions of the model's driver
    [grid]                      # full factorial over these (builder or solver arguments)
    clearance = [5e-5, 1e-4, 5e-4]
    viscosity = [0.1, 0.4, 1.0]
    [zip]                       # lists of equal length, varied together (optional)
    [sample]                    # Latin-hypercube samples (optional): n, seed, ranges = {name = [lo, hi]}
    [output]
    keep_series = false         # also keep each case's time series (netCDF per case)
    [output.poincare]           # optional array output: each case's stroboscopic section
    transient_revs = 60         # (see case_arrays; gathered as (case, rev) variables)
    record_revs = 40
    section_angle = 0.0         # [deg]
    [dask]
    scheduler = "tcp://127.0.0.1:8786"   # optional; same as --scheduler

Every case is checked before any work (:func:`validate`). A sweep directory is owned
(:mod:`jointdyn.io.rundir`): ``spec.json`` records the spec that made it, ``--resume`` with another
spec is refused, one writer at a time. Every case is written atomically to
``DIR/cases/case_NNNNN.json`` (metrics, or the error of a failed case) as soon as it finishes;
``--resume`` skips the cases already there. ``DIR/sweep.nc`` gathers all cases in one xarray
Dataset (grid parameters as coordinates when the sweep is a pure grid), ``manifest.json`` last.
"""

from __future__ import annotations

import json
import math
import numbers
import time
import warnings
from pathlib import Path

import numpy as np

from jointdyn.core import atomic, interrupts
from jointdyn.core.atomic import OutputError
from jointdyn.errors import Interrupted
from jointdyn.io import cluster
from jointdyn.io.pool import run_local
from jointdyn.studies.sweep_spec import (
    SweepSpec,
    latin_hypercube,
    load_sweep,
    validate,
)

__all__ = [
    "SweepSpec",
    "latin_hypercube",
    "load_sweep",
    "validate",
    "run_case",
    "run_sweep",
    "gather",
]


def case_arrays(res, arrays: dict) -> dict[str, list[float]]:
    """Array outputs of one run (``[output.NAME]`` of the sweep file, ``ARRAY_OUTPUTS``):
    ``poincare`` = the stroboscopic section of a journal element (default: the first) at a phase of
    the revolution of an angle driver (default: the first) or of an explicit period, bushing
    frame [T122, T136, T350]."""
    out = {}
    if "poincare" in arrays:
        from jointdyn.studies.poincare import section_arrays

        a = arrays["poincare"]
        sec = section_arrays(
            res,
            int(a["transient_revs"]),
            int(a["record_revs"]),
            float(a["section_angle"]),
            a.get("element"),
            a.get("driver"),
            a.get("period"),
        )
        out |= {f"poincare_{k}": v for k, v in sec.items()}
    return out


def _deadline(case_timeout: float | None):
    """A progress callback that ends the case once its integration ran ``case_timeout`` [s]
    of wall time (measured from the first progress report, i.e. after compilation) [T281]."""
    if not case_timeout:
        return None
    start: list[float] = []

    def progress(fraction: float) -> None:
        now = time.perf_counter()
        start.append(now) if not start else None
        if now - start[0] > case_timeout:
            raise TimeoutError(
                f"case_timeout: integration still running after {case_timeout:g} s "
                f"({100 * fraction:.0f} % of the run done)"
            )

    return progress


def run_case(
    base: dict,
    params: dict,
    series_path: str | None = None,
    arrays: dict | None = None,
    case_timeout: float | None = None,
) -> dict:
    """Run one case (in a worker process) through :func:`jointdyn.studies.runs.run`; returns
    ``{"metrics": the run summary's metrics, "units": theirs, "rhs_evaluations", "wall_time_s"}``,
    plus ``"arrays"`` (:func:`case_arrays`) when ``arrays`` asks for them. Never raises: a
    failure (also one longer than ``case_timeout`` [s], :func:`_deadline`) is returned as
    ``{"error": message}``."""
    from jointdyn.studies import runs

    t0 = time.perf_counter()
    progress = _deadline(case_timeout)
    try:
        merged = {**base, **params}
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # reported once at validation, not per case
            if "file" in merged:
                from jointdyn.studies.sweep_spec import load_file_case

                _, system, cfg = load_file_case(merged)
                res, _, summ = runs.run(system, cfg, progress=progress)
            else:
                from jointdyn.models.catalog import DEFAULT, shipped

                # validate() refused arguments that act on no variant of the sweep; the rest that
                # do not act on this case's variant are dropped here
                from jointdyn.studies.sweep_spec import shipped_call

                m = shipped(merged.get("model", DEFAULT))
                v, model_kw, run_kw, revs, keys = shipped_call(merged, set(m.variants()), check_keys=False)
                res, _, summ = runs.run_shipped(
                    m.name, v, revs, model_kw=model_kw, keys=keys, progress=progress, **run_kw
                )
        extra = {"arrays": case_arrays(res, arrays)} if arrays else {}
        if series_path:
            with atomic.replacing(Path(series_path)) as tmp:
                res.save(tmp)
        return {
            "metrics": summ["metrics"],
            "units": summ["metric_units"],
            "rhs_evaluations": int(res.stats["rhs_evaluations"]),
            "wall_time_s": time.perf_counter() - t0,
        } | extra
    except Exception as err:  # recorded, the sweep goes on
        return {"error": f"{type(err).__name__}: {err}", "wall_time_s": time.perf_counter() - t0}


def _spec_record(spec: SweepSpec, n: int) -> dict:
    rec = {"base": spec.base, "grid": spec.grid, "zip": spec.zipped, "sample": spec.sample}
    rec |= {"keep_series": spec.keep_series, "n_cases": n} | ({"arrays": spec.arrays} if spec.arrays else {})
    if "file" in spec.base:  # the model file is part of the spec: an edited file is another sweep
        rec["file_sha256"] = atomic.sha256(spec.base["file"])
    return json.loads(json.dumps(rec, default=str))


def _check_owner(out: Path, rec: dict, resume: bool) -> None:
    """A resumed sweep must be the one that made the directory."""
    if not resume:
        return
    cdir = out / "cases"
    try:
        old = json.loads((out / "spec.json").read_text(encoding="utf-8"))
    except FileNotFoundError:
        if cdir.exists() and any(cdir.iterdir()):
            raise ValueError(
                f"--resume {out}: has case files but no spec.json; not a sweep directory"
            ) from None
        return
    except ValueError:
        raise ValueError(
            f"--resume {out}: spec.json is unreadable; use --overwrite or another --out"
        ) from None
    if old != rec:
        diff = sorted(k for k in set(old) | set(rec) if old.get(k) != rec.get(k))
        raise ValueError(
            f"--resume {out}: the directory was made by a different sweep spec (differs in "
            f"{', '.join(diff)}); resume with the same file, or use --overwrite or another --out"
        )


def run_sweep(
    spec: SweepSpec,
    out,
    resume: bool = False,
    scheduler: str | None = None,
    workers: int | None = None,
    progress=None,
    overwrite: bool = True,
    case_timeout: float | None = None,
    worker_timeout: float = cluster.WORKER_TIMEOUT,
    notice=None,
):
    """Run all cases not yet done; write per-case files, ``sweep.nc`` and the manifest.
    Returns the Dataset. ``overwrite`` (the library default; the CLI asks for ``--overwrite``)
    lets a non-empty sweep directory be replaced when not resuming. ``case_timeout`` [s]: a
    case whose integration runs longer is recorded as failed (:func:`_deadline`);
    ``worker_timeout`` [s] and ``notice`` (a callable taking one line): the Dask waits of
    :func:`jointdyn.io.cluster.run_cluster` [T280]."""
    from jointdyn.io.rundir import OutputDir, check_path

    out = check_path(out)
    if workers is not None and not (isinstance(workers, numbers.Integral) and workers >= 1):
        raise ValueError(f"--workers = {workers!r} [-]: must be an integer >= 1")
    for name, v in (("--case-timeout", case_timeout), ("--worker-timeout", worker_timeout)):
        if v is not None and not (isinstance(v, numbers.Real) and 0 < float(v) < math.inf):
            raise ValueError(f"{name} = {v!r} [s]: must be a finite number > 0")
    cases, invalid = validate(spec)
    rec = _spec_record(spec, len(cases))
    scheduler = scheduler or spec.scheduler
    client = cluster.connect(scheduler) if scheduler else None  # before any file is touched
    try:
        od = OutputDir(out, "sweep", rec).claim(overwrite=overwrite, resume=resume)
        try:
            _check_owner(out, rec, resume)
            od.adopt("spec.json")
        except BaseException:
            od.release()
            raise
        waits = {"case_timeout": case_timeout, "worker_timeout": worker_timeout, "notice": notice}
        return _run(spec, od, cases, invalid, rec, client, workers, progress, waits)
    finally:
        if client is not None:
            cluster.close(client)


def _run(spec, od, cases, invalid, rec, client, workers, progress, waits):
    out = od.path
    cdir = out / "cases"
    if cdir.is_symlink() or (cdir.exists() and not cdir.is_dir()):
        raise OutputError(f"--out {out}: cases is not a directory jointdyn made; move it")
    cdir.mkdir(exist_ok=True)
    with od.write("spec.json") as tmp:
        tmp.write_text(json.dumps(rec, indent=2, default=str) + "\n", encoding="utf-8")
    todo = [i for i in range(len(cases)) if not (cdir / f"case_{i:05d}.json").exists()]
    sp = (lambda i: str(cdir / f"case_{i:05d}.nc")) if spec.keep_series else (lambda i: None)
    done = len(cases) - len(todo)
    if spec.keep_series:
        for i in todo:  # written by the workers: known to a later --overwrite even if killed
            od.journal(f"cases/case_{i:05d}.nc")

    def record(i, result):
        nonlocal done
        with od.write(f"cases/case_{i:05d}.json") as tmp:
            tmp.write_text(
                json.dumps({"case": i, "params": cases[i], **result}, indent=2, default=str) + "\n",
                encoding="utf-8",
            )
        if spec.keep_series and (cdir / f"case_{i:05d}.nc").is_file():
            od.record(f"cases/case_{i:05d}.nc")
        done += 1
        if progress:
            progress(done, len(cases))

    for i in [i for i in todo if i in invalid]:  # checked before any work: not run
        record(i, {"error": invalid[i], "wall_time_s": 0.0})
    todo = [i for i in todo if i not in invalid]
    try:
        with interrupts.catching():
            calls = ((i, (spec.base, cases[i], sp(i), spec.arrays, waits["case_timeout"])) for i in todo)
            if todo and client is not None:
                cluster.run_cluster(client, run_case, calls, record, waits["worker_timeout"], waits["notice"])
            elif todo:
                run_local(run_case, calls, workers, record)
            ds = gather(out, spec, cases)
        with od.write("sweep.nc") as tmp:
            ds.to_netcdf(tmp, engine="h5netcdf")
    except Interrupted as err:
        od.finish("interrupted", f"{err}; {done} of {len(cases)} cases finished (continue with --resume)")
        raise
    except ConnectionError as err:  # the cluster failed, not the cases: resumable
        msg = f"{err}; {done} of {len(cases)} cases finished (continue with --resume)"
        od.finish("failed", msg)
        raise ConnectionError(msg) from None
    except BaseException as err:
        od.finish("failed", f"{type(err).__name__}: {err}")
        raise
    for i in range(len(cases)):  # this run's cases and those of the run it resumed
        for name in (f"cases/case_{i:05d}.json", f"cases/case_{i:05d}.nc"):
            if name not in od.files and (out / name).is_file():
                od.record(name)
    failed = int((ds["error"] != "").sum())
    od.finish("complete", f"{failed} of {len(cases)} cases failed" if failed else "", n_cases=len(cases))
    return ds


def gather(out: Path, spec: SweepSpec, cases: list[dict]):
    """Combine the per-case files into one Dataset (dims = grid parameters for pure grids;
    string parameters such as ``joint`` stay strings). Its variables are the metrics that the
    cases' models have (:func:`jointdyn.studies.metrics.metrics`), ``rhs_evaluations``,
    ``wall_time_s`` and ``error``; a value is missing (NaN) only where its case failed or its
    model lacks that metric (a sweep over joint kinds), never as a computed result."""
    import xarray as xr

    rows = [json.loads((out / "cases" / f"case_{i:05d}.json").read_text()) for i in range(len(cases))]
    units: dict[str, str] = {"rhs_evaluations": "-", "wall_time_s": "s"}
    for r in rows:
        units |= r.get("units", {})
    names = list(dict.fromkeys(k for r in rows for k in r.get("metrics", {})))
    data = {m: np.array([r.get("metrics", {}).get(m, np.nan) for r in rows], float) for m in names}
    data |= {m: np.array([r.get(m, np.nan) for r in rows], float) for m in ("rhs_evaluations", "wall_time_s")}
    errors = np.array([r.get("error", "") for r in rows], dtype=object)
    ds = xr.Dataset(
        {m: ("case", v) for m, v in data.items()} | {"error": ("case", errors.astype(str))},
        coords={"case": np.arange(len(cases))},
    )
    for name, a in spec.arrays.items():  # (case, rev) variables, NaN where a case failed
        keys = sorted({k for r in rows for k in r.get("arrays", {}) if k.startswith(f"{name}_")})
        for k in keys:
            v = np.full((len(rows), int(a["record_revs"])), np.nan)
            for i, r in enumerate(rows):
                x = np.asarray(r.get("arrays", {}).get(k, []), float)[: v.shape[1]]
                v[i, : x.size] = x
            ds[k] = (("case", "rev"), v)
            ds[k].attrs["units"] = "1/rev" if k.endswith("impacts_per_rev") else "-"  # e/c, ė/(cω)
        ds.coords["rev"] = np.arange(
            int(a["transient_revs"]), int(a["transient_revs"]) + int(a["record_revs"])
        )
    for name in sorted({k for c in cases for k in c}):
        vals = [c.get(name, np.nan) for c in cases]
        numeric = all(isinstance(v, numbers.Real) and not isinstance(v, bool) for v in vals)
        ds.coords[name] = (
            "case",
            np.array(vals, dtype=float) if numeric else np.array([str(v) for v in vals]),
        )
    if spec.grid and not spec.zipped and not spec.sample:
        keys = list(spec.grid)
        ds = ds.swap_dims(case=keys[0]) if len(keys) == 1 else ds.set_index(case=keys).unstack("case")
    if "file" not in spec.base:
        from jointdyn.models.catalog import DEFAULT, shipped

        units |= {k: u for k, (_, u) in shipped(spec.base.get("model", DEFAULT)).numeric_args().items()}
    for name in ds.variables:
        if name in units:
            ds[name].attrs["units"] = units[name]
    ds.attrs["base"] = json.dumps(spec.base, default=str)
    return ds
