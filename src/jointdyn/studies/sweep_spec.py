"""Sweep files: reading, the case list and the checks made before any case runs.

Structural problems (unknown tables or keys, a parameter that is not an argument, an empty
grid, mismatched ``[zip]`` lengths, a parameter with no effect on any joint of the sweep) refuse
the whole sweep with one line. A case whose *values* are out of range is not run: it is
recorded as a failed case with its message, and the sweep goes on with the others.
"""

from __future__ import annotations

import itertools
import json
import math
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from jointdyn.core.checks import check
from jointdyn.io.modelfile.locate import read_toml
from jointdyn.models.catalog import DEFAULT, shipped

TABLES = ("base", "grid", "zip", "sample", "output", "dask")
#: array outputs a case can return besides its scalar metrics ([output.NAME] tables): name ->
#: their keys and defaults (see :func:`jointdyn.studies.sweep.case_arrays`)
ARRAY_OUTPUTS = {
    "poincare": {
        "transient_revs": 0,
        "record_revs": 1,
        "section_angle": 0.0,
        "element": None,
        "driver": None,
        "period": None,
    }
}
#: study keys of a model-file case besides its model-file keys: the run's length in revolutions
#: of the model's first angle driver and the output samples per revolution
FILE_RUN_KEYS = ("revs", "samples_per_rev")


def file_call(merged: dict) -> tuple[str, list[str], dict]:
    """``(model file, its overrides KEY=TOML, run keys)`` of one model-file case (inline tables
    and strings written as TOML, not JSON)."""
    from jointdyn.multibody.codec import toml_value

    extra = {k: v for k, v in merged.items() if k not in ("file", "model", *FILE_RUN_KEYS)}
    overrides = [f"{k}={toml_value(v)}" for k, v in extra.items()]
    return merged["file"], overrides, {k: merged[k] for k in FILE_RUN_KEYS if k in merged}


def load_file_case(merged: dict, assemble: bool = True):
    """``(model, system or None, config)`` of one model-file case: the file with the case's
    overrides; with ``revs`` the run lasts that many revolutions of the model's angle driver at
    ``samples_per_rev`` (default 720) samples each."""
    from jointdyn.io.modelfile import load_model, load_system
    from jointdyn.studies.period import per_revolution_config

    path, overrides, rk = file_call(merged)
    if not assemble:
        model, cfg = load_model(path, overrides, assemble=False)
        return model, None, cfg
    model, system, cfg = load_system(path, overrides)
    if rk:
        if "revs" not in rk:
            raise ValueError("samples_per_rev: acts only with revs (the run's length in revolutions)")
        cfg = per_revolution_config(system, cfg, rk["revs"], rk.get("samples_per_rev", 720))
    return model, system, cfg


def model_args(model: str = DEFAULT) -> tuple[str, ...]:
    """Sweepable builder arguments of the shipped ``model`` (its variant, numbers and flags)."""
    return shipped(model).arguments()


def run_args(model: str = DEFAULT) -> tuple[str, ...]:
    """Sweepable run settings of the shipped ``model``."""
    return tuple(shipped(model).run_args())


@dataclass(frozen=True)
class SweepSpec:
    """A parameter study (see :mod:`jointdyn.studies.sweep` for the file layout)."""

    base: dict
    grid: dict = field(default_factory=dict)
    zipped: dict = field(default_factory=dict)
    sample: dict = field(default_factory=dict)
    keep_series: bool = False
    scheduler: str | None = None
    arrays: dict = field(default_factory=dict)
    """array outputs per case: {name in ``ARRAY_OUTPUTS``: {key: value}}"""

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
    if "n" not in sample or "ranges" not in sample:
        raise ValueError("[sample]: needs n (number of samples) and ranges = {name = [lo, hi]}")
    check("[sample].n", sample["n"], "-", ">= 1", integer=True)
    ranges = sample["ranges"]
    if not isinstance(ranges, dict) or not ranges:
        raise ValueError("[sample].ranges: must be a non-empty table name = [lo, hi]")
    for k, r in ranges.items():
        if not (isinstance(r, list) and len(r) == 2):
            raise ValueError(f"[sample].ranges.{k}: must be [lo, hi]; got {r!r}")
        check(f"[sample].ranges.{k}[0]", r[0], "SI", "finite")
        check(f"[sample].ranges.{k}[1]", r[1], "SI", f"> {r[0]}")
    names = list(ranges)
    lo = np.array([ranges[k][0] for k in names], float)
    hi = np.array([ranges[k][1] for k in names], float)
    u = qmc.LatinHypercube(d=len(names), seed=sample.get("seed", 0)).random(int(sample["n"]))
    x = qmc.scale(u, lo, hi)
    return [{k: float(v) for k, v in zip(names, row)} for row in x]


def load_sweep(path) -> SweepSpec:
    """Read a sweep file; unknown tables/keys are errors naming the valid ones."""
    path = Path(path)
    doc, _ = read_toml(path, "sweep file")
    if set(doc) - set(TABLES):
        raise ValueError(
            f"{path}: unknown table(s) {sorted(set(doc) - set(TABLES))}; valid: {sorted(TABLES)}"
        )
    if "base" not in doc:
        raise ValueError(f"{path}: missing [base] table")
    for t in TABLES:
        if t in doc and not isinstance(doc[t], dict):
            raise ValueError(f"{path}: {t} must be a table [{t}]")
    out = doc.get("output", {})
    valid_out = {"keep_series", *ARRAY_OUTPUTS}
    if set(out) - valid_out:
        raise ValueError(
            f"{path}: [output] unknown key(s) {sorted(set(out) - valid_out)}; valid: {sorted(valid_out)}"
        )
    arrays = {}
    for name in set(out) & set(ARRAY_OUTPUTS):
        t, keys = out[name], ARRAY_OUTPUTS[name]
        if not isinstance(t, dict) or set(t) - set(keys):
            raise ValueError(f"{path}: [output.{name}] takes only {sorted(keys)}")
        arrays[name] = {**keys, **t}
    if not isinstance(out.get("keep_series", False), bool):
        raise ValueError(f"{path}: [output].keep_series must be true or false")
    dask = doc.get("dask", {})
    if set(dask) - {"scheduler"} or not isinstance(dask.get("scheduler", ""), str):
        raise ValueError(f'{path}: [dask] takes only scheduler = "tcp://HOST:PORT"')
    base = dict(doc["base"])
    if "file" in base:
        f = (path.parent / str(base["file"])).resolve()
        if not f.is_file():
            raise ValueError(f"{path}: [base].file = {base['file']!r}: no such model file ({f})")
        base["file"] = str(f)
    for t in ("grid", "zip"):
        for k, v in doc.get(t, {}).items():
            if not isinstance(v, list):
                raise ValueError(f"{path}: [{t}].{k} must be a list of values; got {v!r}")
            if not v:
                raise ValueError(f"{path}: [{t}].{k} is empty: the sweep would have no cases")
            _check_values(path, t, k, v)
    spec = SweepSpec(
        base=base,
        grid=doc.get("grid", {}),
        zipped=doc.get("zip", {}),
        sample=doc.get("sample", {}),
        keep_series=out.get("keep_series", False),
        scheduler=dask.get("scheduler"),
        arrays=arrays,
    )
    for name in base:
        _check_param(base, name, "[base]")
    for name in itertools.chain(spec.grid, spec.zipped, spec.sample.get("ranges", {})):
        _check_param(base, name, "sweep parameter")
    return spec


MAX_CASES = 100_000  # cases in one sweep [-]: one JSON file each in DIR/cases [T285]


def _check_values(path, table: str, name: str, values: list) -> None:
    """Before any case runs [T285]: no NaN/inf (not a parameter value, and TOML's nan came back
    as the string 'NaN'), no repeated grid value (the gathered grid would have a duplicate
    coordinate and sweep.nc could not be written after every case ran)."""
    bad = [v for v in values if isinstance(v, float) and not math.isfinite(v)]
    if bad:
        raise ValueError(f"{path}: [{table}].{name} = {values!r}: {bad[0]!r} is not a parameter value")
    if table == "grid":
        keys = [json.dumps(v, sort_keys=True, default=str) for v in values]
        dup = sorted({repr(values[i]) for i, k in enumerate(keys) if keys.count(k) > 1})
        if dup:
            raise ValueError(f"{path}: [grid].{name} repeats {', '.join(dup)}: give each value once")


def _check_names(names, what: str) -> None:
    """Names that become sweep.nc variables or coordinates (``NAME.metric``) cannot hold '/'
    (the HDF5 group separator): refused before any case runs, not after all of them [T330]."""
    bad = [n for n in names if "/" in str(n)]
    if bad:
        raise ValueError(f"{what} name {bad[0]!r}: '/' cannot be in a sweep.nc variable name; rename it")


def _check_param(base: dict, name: str, where: str = "sweep parameter"):
    if "file" in base or "." in name:
        return  # dotted model-file keys are checked by the model-file loader, per case
    m = base.get("model", DEFAULT)
    valid = tuple(dict.fromkeys(("model", *model_args(m), *run_args(m))))
    if name not in valid:
        raise ValueError(
            f"{where} {name!r} is not an argument of the shipped model {m!r}; valid: {list(valid)}"
        )


def shipped_call(merged: dict, variants_in_sweep: set | None = None, check_keys: bool = True):
    """``(variant, model_kw, run_kw, revs, keys)`` of one case of a shipped model (``model``,
    default :data:`~jointdyn.models.catalog.DEFAULT`), checked
    (:meth:`~jointdyn.models.shipped.Shipped.call`); ``keys``: its dotted model-file keys as
    ``key=VALUE`` overrides, checked against the built model with ``check_keys``."""
    from jointdyn.multibody.codec import toml_value

    m = shipped(merged.get("model", DEFAULT))
    variant, model_kw, run_kw, revs = m.call(merged, variants_in_sweep)
    keys = [f"{k}={toml_value(v)}" for k, v in merged.items() if "." in k]
    if keys and check_keys:
        from jointdyn.io.modelfile import with_keys

        model, cfg = m.setup(variant, revs, model_kw, **run_kw)
        with_keys(model, cfg, keys, f"{m.name} ({variant})", assemble=False)
    return variant, model_kw, run_kw, revs, keys


def validate(spec: SweepSpec) -> tuple[list[dict], dict[int, str]]:
    """Check every case before any runs: returns (cases, {index: error} of invalid cases).
    Structural problems raise ``ValueError``; physics warnings are raised once per message."""
    cases = spec.cases()
    if not cases:
        raise ValueError("the sweep has no cases (an empty list or sample n = 0)")
    if len(cases) > MAX_CASES:  # one file per case, each checked and run: refuse before work [T285]
        raise ValueError(f"the sweep has {len(cases)} cases; at most {MAX_CASES} (split it into sweeps)")
    invalid: dict[int, str] = {}
    seen: set[str] = set()
    joints: set = set()
    if "file" not in spec.base:
        m = shipped(spec.base.get("model", DEFAULT))
        va = m.variant_arg
        joints = {c.get(va, spec.base.get(va, m.default_variant)) for c in cases}
        joints = {j for j in joints if isinstance(j, str)}
        for k in {*spec.base, *(k for c in cases for k in c)} & set(m.arguments()) - {va}:
            if not any(k in m.relevant(j) for j in joints & set(m.variants())):
                raise ValueError(f"{k!r}: no effect on any {va} of this sweep ({', '.join(sorted(joints))})")
    _check_names((k for c in cases[:1] for k in c), "sweep parameter")
    names: dict = {}
    for i, params in enumerate(cases):
        merged = {**spec.base, **params}
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                if "file" in merged:  # values and names checked here; assembly once, in the run
                    names = load_file_case(merged, assemble=False)[0].items
                else:
                    shipped_call(merged, joints)
            except ValueError as err:
                invalid[i] = f"{type(err).__name__}: {err}"
        _check_names(names, "element or joint")  # structural: the whole sweep, before any case
        for w in caught:
            if str(w.message) not in seen:
                seen.add(str(w.message))
                warnings.warn(f"case {i}: {w.message}", w.category, stacklevel=2)
    _check_invalid(spec, cases, invalid)
    return cases, invalid


def _check_invalid(spec: SweepSpec, cases: list[dict], invalid: dict[int, str]) -> None:
    """Refuse before work [T334] a sweep whose every case is invalid, and a grid value whose
    every case is invalid (an unknown key, a negative mass): the value, not a combination, is
    wrong. Combinations invalid only together stay recorded as failed cases."""
    if not invalid:
        return
    if len(invalid) == len(cases):
        raise ValueError(f"every one of the {len(cases)} cases is invalid; case 0: {invalid[0]}")

    def key(v) -> str:
        return json.dumps(v, sort_keys=True, default=str)

    for name, values in spec.grid.items():
        valid = {key(c.get(name)) for i, c in enumerate(cases) if i not in invalid}
        for v in values:
            if key(v) not in valid:
                first = next(i for i, c in enumerate(cases) if key(c.get(name)) == key(v))
                raise ValueError(f"[grid].{name} = {v!r}: every case with it is invalid; {invalid[first]}")
