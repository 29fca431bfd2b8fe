"""One path for every run: :func:`run` compiles a model once, simulates it, derives the output
contract (:mod:`jointdyn.studies.outputs`) and writes it into a claimed directory. The CLI
(``jointdyn run``, shipped model or model file), sweeps and the reproduction use it;
:func:`run_shipped` runs a shipped model (:mod:`jointdyn.models.catalog`) with its own headline
columns and summary.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np

from jointdyn.core import interrupts
from jointdyn.errors import Interrupted, SimulationError
from jointdyn.models.catalog import shipped
from jointdyn.simulation.simulate import SimConfig, simulate
from jointdyn.studies import outputs


def _columns(res, headline: dict[str, np.ndarray], units: dict[str, str]) -> dict[str, np.ndarray]:
    """Headline columns (with units) followed by every system column (time not repeated)."""
    cols = {outputs.header("time", "s"): res.t}
    cols.update({outputs.header(k, units[k]): v for k, v in headline.items() if k != "t"})
    cols.update({k: v for k, v in outputs.system_columns(res).items() if k not in cols})
    return cols


def run(
    model,
    config: SimConfig,
    out=None,
    *,
    progress: Callable[[float], None] | None = None,
    headline: Callable | None = None,
    extra_summary: Callable | None = None,
    title: str = "",
    files: dict[str, str] | None = None,
    meta: dict | None = None,
    aliases: dict[str, str] | None = None,
):
    """Compile ``model`` (once), simulate it and, with ``out`` (a claimed
    :class:`~jointdyn.io.rundir.OutputDir`), write the output contract and the manifest.

    ``headline(res) -> ({name: array}, {name: unit})`` puts model-specific columns first;
    ``extra_summary(res, headline_columns, metrics) -> dict`` adds model-specific entries to the
    summary (``metrics``: :func:`jointdyn.studies.metrics.metrics`, with the ``aliases``); ``files``
    are extra text files (name -> content, e.g. the resolved ``model.toml``); ``meta`` goes
    into ``Results.meta`` (provenance saved with the results). Returns
    ``(results, headline columns, summary)``. On a failure or interruption the partial results
    (if any) are written with their status and the error is re-raised.
    """
    system = model.compile() if hasattr(model, "compile") else model
    from jointdyn.studies.memory import check_memory

    check_memory(system, config.n_out)

    def on_progress(f: float) -> None:
        interrupts.check()
        if progress is not None:
            progress(f)

    try:
        res = simulate(system, config, progress=on_progress)  # signals every ~0.05 s [T142]
    except SimulationError as err:
        if err.results is not None:
            err.results.meta.update(meta or {})
        if out is not None:
            status = "interrupted" if isinstance(err, Interrupted) else "failed"
            _write_partial(out, err, status, headline, title, files, aliases)
        raise
    res.meta.update(meta or {})
    head, units = headline(res) if headline else ({}, {})
    summ = outputs.summary(res, aliases=aliases)
    if extra_summary is not None:
        summ.update(extra_summary(res, head, summ["metrics"]))
    if out is not None:
        try:
            _write(out, res, _columns(res, head, units), summ, title, files)
        except Interrupted as err:
            out.finish("interrupted", f"{err} while writing the results")
            raise
        except BaseException as err:  # e.g. a file there that jointdyn did not write
            out.finish("failed", f"{type(err).__name__}: {err} while writing the results")
            raise
        out.finish("complete")
    return res, head, summ


def _write(out, res, cols, summ, title, files) -> None:
    for name, text in (files or {}).items():
        with out.write(name) as tmp:
            tmp.write_text(text, encoding="utf-8")
    outputs.write_all(out, res, cols, summ, title)


def _write_partial(out, err: SimulationError, status: str, headline, title, files, aliases) -> None:
    """Write what a failed or interrupted run computed, then the manifest with its status."""
    interrupts.acknowledge()  # a further signal stops this writing, not the first one
    res = err.results
    reason = str(err)
    try:
        if res is not None and len(res.t) >= 2:
            status = "partial" if status == "failed" else status  # something was computed
            res.meta["status"] = status
            head, units = headline(res) if headline else ({}, {})
            summ = outputs.summary(res, status=status, aliases=aliases) | {"reason": reason}
            _write(out, res, _columns(res, head, units), summ, title + f" ({status})", files)
    except Exception as werr:  # the first error is the one to report
        reason += f"; writing the partial results failed too: {werr}"
    finally:
        out.finish(status, reason, t_reached=getattr(err, "t", None))


def run_shipped(
    name: str,
    variant: str | None = None,
    revs: float = 4.0,
    out=None,
    progress=None,
    model_kw: dict | None = None,
    keys=(),
    **cfg_kw,
):
    """Simulate the shipped model ``name`` (its ``variant``, checked builder arguments
    ``model_kw``, dotted model-file ``keys`` ``a.b=VALUE`` set on the built model, run settings
    ``cfg_kw``) for ``revs`` revolutions of its driver; optionally write the run files. ``out`` is
    a directory path (claimed here, see :mod:`jointdyn.io.rundir`) or a claimed
    :class:`~jointdyn.io.rundir.OutputDir`. Returns (results, columns, summary)."""
    from jointdyn.io.rundir import OutputDir

    m = shipped(name)
    variant = variant or m.default_variant
    model, cfg = m.setup(variant, revs, model_kw, **cfg_kw)
    if keys:
        from jointdyn.io.modelfile import with_keys

        sim = [k for k in keys if k.strip().startswith("simulation.")]
        if sim:
            raise ValueError(
                f"--set {sim[0]!r}: a shipped model's run settings are options (--revs, --rtol, ...)"
            )
        _, model, cfg = with_keys(model, cfg, list(keys), f"{name} ({variant})")
    if out is not None and not isinstance(out, OutputDir):
        spec = {"model": name, m.variant_arg: variant, "revs": revs, **(model_kw or {}), **cfg_kw}
        spec |= {"set": list(keys)} if keys else {}
        spec = {k: v if isinstance(v, (int, float, str)) else repr(v) for k, v in spec.items()}
        out = OutputDir(Path(out), "run", spec).claim(overwrite=True)
    return run(
        model,
        cfg,
        out,
        progress=progress,
        headline=m.headline,
        extra_summary=lambda res, cols, metrics: m.summarize(res, cols, metrics, revs),
        aliases=m.aliases,
        title=m.title(variant),
    )


def prepare_model_file(path, overrides=()):
    """Load and compile a model file once: ``(model, system, config, spec)``; ``spec`` is what
    the run directory records (file, overrides, the resolved model text)."""
    from jointdyn.io.modelfile import dumps, load_system

    model, system, config = load_system(path, overrides)
    spec = {"model_file": str(path), "overrides": list(overrides), "model": dumps(model, config)}
    return model, system, config, spec


def run_model_file(path, out_dir, overrides=(), overwrite: bool = True, progress=None, prepared=None):
    """Load a model file, simulate it and write the output contract plus the resolved model
    (``model.toml``, overrides applied) into ``out_dir`` (a path, claimed here, or a claimed
    :class:`~jointdyn.io.rundir.OutputDir`). Returns the Results.

    On a :class:`~jointdyn.errors.SimulationError` the partial results are written first, then
    the error is re-raised.
    """
    from jointdyn.io.modelfile import dumps
    from jointdyn.io.rundir import OutputDir

    model, system, config, spec = prepared or prepare_model_file(path, overrides)
    header = f"resolved from {path}" + (f" with {list(overrides)}" if overrides else "")
    od = out_dir if isinstance(out_dir, OutputDir) else OutputDir(Path(out_dir), "run", spec).claim(overwrite)
    res, _, _ = run(
        system,
        config,
        od,
        progress=progress,
        title=model.name,
        files={"model.toml": dumps(model, config, header)},
        meta={"model_file": str(path), "overrides": list(overrides)},
    )
    return res


def model_system(model: str, given: dict | None = None, revs: float = 1.0):
    """``(System, SimConfig)`` of MODEL, a model file (``given``: ``{dotted.key: value}``
    overrides) or a shipped model (``given``: its variant and builder arguments by name, checked,
    plus dotted model-file keys set on the built model); a shipped model's config covers ``revs``
    revolutions of its driver."""
    from jointdyn.multibody.codec import toml_value

    given = dict(given or {})
    keys = [f"{k}={toml_value(v)}" for k, v in given.items() if "." in k]
    if str(model).endswith(".toml") or Path(str(model)).is_file():
        from jointdyn.io.modelfile import load_system

        _, system, cfg = load_system(model, keys)
        return system, cfg
    m = shipped(model)
    variant = given.pop(m.variant_arg, m.default_variant)
    args = {k: v for k, v in given.items() if "." not in k}
    built, cfg = m.setup(variant, revs, m.model_kw(variant, args))
    if keys:
        from jointdyn.io.modelfile import with_keys

        return with_keys(built, cfg, keys, f"{model} ({variant})")[1:]
    return built.compile(), cfg
