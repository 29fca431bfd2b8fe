"""Bifurcation diagrams over one parameter of a model file or the shipped slider-crank [T131].

For each parameter value: one long run, the first ``transient_revs`` revolutions discarded,
then the stroboscopic section (phase ``section_angle`` of the revolution of the model's angle
driver, or of an explicit ``period``) of a journal's relative state over ``record_revs``
revolutions [T122]. A periodic response with period p revolutions shows p points per parameter
value, a quasi-periodic or chaotic one a cloud. A diagram file::

    [base]                      # as in a sweep file: a model file …
    file = "four_bar.toml"      # (relative to the diagram file)
    # … or the shipped model's builder/run arguments: joint = "dry", rtol = 1e-8
    [bifurcation]
    parameter = "elements.pin.viscosity"   # a model-file key (or a slider-crank builder argument)
    range = { start = 1e-4, stop = 5e-4, num = 120 }   # or: values = [...]
    transient_revs = 100
    record_revs = 60
    section_angle = 0.0         # phase of the section [deg]
    samples_per_rev = 72
    element = "pin"             # optional: default the model's first journal element
    driver = "motor"            # optional: default the model's first angle driver
    period = 0.03               # optional [s]: instead of the driver's 2π/ω
"""

from __future__ import annotations

import json
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from jointdyn.core import atomic
from jointdyn.studies.poincare import VARIABLES, section_arrays  # noqa: F401  (re-exported)

_SECTION = ("element", "driver", "period")
_KEYS = {
    "parameter",
    "values",
    "range",
    "transient_revs",
    "record_revs",
    "section_angle",
    "samples_per_rev",
    *_SECTION,
}


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
    section: dict = field(default_factory=dict)
    """optional ``element``, ``driver``, ``period`` [s] of the section (defaults: the model's)"""

    def __post_init__(self):
        from jointdyn.models.catalog import DEFAULT, shipped

        if "file" not in self.base and "." not in self.parameter:  # model-file keys: its loader checks
            m = shipped(self.base.get("model", DEFAULT))
            valid = list(m.numeric_args())
            if self.parameter not in valid:
                raise ValueError(
                    f"bifurcation.parameter = {self.parameter!r}: not a number argument of {m.name!r} "
                    f"nor a model-file key (a.b.c); valid: {valid}"
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
        doc = tomllib.loads(atomic.regular_input(path, "diagram file").read_text())
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
    if "file" in base:
        f = (path.parent / str(base["file"])).resolve()
        if not f.is_file():
            raise ValueError(f"{path}: [base].file = {base['file']!r}: no such model file ({f})")
        base["file"] = str(f)
    else:
        from jointdyn.models.catalog import DEFAULT, shipped

        try:
            shipped(base.get("model", DEFAULT))
        except ValueError as err:
            raise ValueError(f'{path}: [base] {err}, or file = "FILE.toml"') from None
    return BifurcationSpec(
        base=base,
        parameter=b["parameter"],
        values=values,
        transient_revs=int(b.get("transient_revs", 100)),
        record_revs=int(b.get("record_revs", 60)),
        section_angle=float(b.get("section_angle", 0.0)),
        samples_per_rev=int(b.get("samples_per_rev", 72)),
        scheduler=doc.get("dask", {}).get("scheduler"),
        section={k: b[k] for k in _SECTION if k in b},
    )


def sweep_spec(spec: BifurcationSpec):
    """The diagram as a sweep (:mod:`jointdyn.studies.sweep`): one case per parameter value, each
    returning its section as the array output ``poincare`` [T136]."""
    from jointdyn.studies.sweep_spec import SweepSpec

    base = {
        **spec.base,
        "revs": spec.transient_revs + spec.record_revs,
        "samples_per_rev": spec.samples_per_rev,
    }
    arrays = {
        "poincare": {
            "transient_revs": spec.transient_revs,
            "record_revs": spec.record_revs,
            "section_angle": spec.section_angle,
            **{k: None for k in _SECTION},
            **spec.section,
        }
    }
    return SweepSpec(
        base=base, grid={spec.parameter: list(spec.values)}, arrays=arrays, scheduler=spec.scheduler
    )


def run_bifurcation(
    spec: BifurcationSpec,
    out,
    workers: int | None = None,
    scheduler: str | None = None,
    progress=None,
    resume: bool = False,
    overwrite: bool = True,
):
    """Run all parameter values through the sweep machinery (:func:`jointdyn.studies.sweep.run_sweep`:
    local processes or a Dask cluster; per-case files in ``out/sweep``; ``resume`` runs only the
    values not finished by an earlier call with the same spec) and write
    ``out/bifurcation.nc``; returns the xarray Dataset (dims: the parameter, ``rev``). ``out`` is
    an output directory of kind ``bifurcation`` (:mod:`jointdyn.io.rundir`; ``overwrite``, the
    library default, replaces the files its manifest lists)."""
    import json

    from jointdyn.io.rundir import OutputDir, read_manifest
    from jointdyn.studies.sweep import run_sweep

    out = Path(out)
    sp = sweep_spec(spec)
    od = OutputDir(out, "bifurcation", {"parameter": spec.parameter, "values": list(spec.values)})
    od.claim(overwrite=overwrite, resume=resume)
    try:
        run_sweep(sp, out / "sweep", resume=resume, scheduler=scheduler, workers=workers, progress=progress)
    except BaseException as err:
        od.finish("failed", f"{type(err).__name__}: {err}")
        raise
    for name in [*(read_manifest(out / "sweep") or {}).get("files", {}), "manifest.json"]:
        od.record(f"sweep/{name}")  # the sweep's files are the diagram's (removed by --overwrite)
    results = []
    for i in range(len(spec.values)):
        r = json.loads((out / "sweep" / "cases" / f"case_{i:05d}.json").read_text(encoding="utf-8"))
        a = {k.removeprefix("poincare_"): v for k, v in r.get("arrays", {}).items()}
        results.append(a | {k: r[k] for k in ("error", "wall_time_s") if k in r})
    ds = to_dataset(spec, results)
    with od.write("bifurcation.nc") as tmp:
        ds.to_netcdf(tmp, engine="h5netcdf")
    od.finish("complete")
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


def plot_bifurcation(ds, path, variable: str = "ex_bushing_over_c", title: str = "") -> None:
    """Section values against the parameter (one dot per recorded revolution), and the median
    impacts per revolution."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    p = next(iter(ds[variable].dims))
    x = ds[p].values
    from jointdyn.models.catalog import DEFAULT, shipped

    base = json.loads(ds.attrs.get("base", "{}"))
    args = {} if "file" in base else shipped(base.get("model", DEFAULT)).numeric_args()
    unit = args.get(p, (0.0, ds[p].attrs.get("units", "")))[1]  # a model-file key: its own
    scale, unit = (1e3, "mm") if unit == "m" else (1.0, unit)
    if p == "speed":
        scale, unit = 60 / (2 * math.pi), "rpm"
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True, gridspec_kw={"height_ratios": [3, 1]})
    v = ds[variable].values
    xx = np.repeat(x[:, None], v.shape[1], axis=1)
    a1.plot((xx * scale).ravel(), v.ravel(), ",", color="k", alpha=0.6)
    a1.plot((xx * scale).ravel(), v.ravel(), ".", ms=1.2, color="k", alpha=0.4)
    # the section variables are in the bushing frame [T290, T350]; their names say so
    a1.set_ylabel(f"{variable} at phase {ds.attrs.get('section_angle_deg', 0):g}° [-]")
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
    with atomic.replacing(path) as tmp:
        fig.savefig(tmp, dpi=130, format="png")
    plt.close(fig)
