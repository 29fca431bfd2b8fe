"""One path for every run: :func:`run` compiles a model once, simulates it, derives the output
contract (:mod:`jointdyn.studies.outputs`) and writes it into a claimed directory. The CLI
(``jointdyn run``, shipped model or model file), sweeps and the reproduction use it;
:func:`run_slider_crank` adds the slider-crank's headline columns and summary.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np

from jointdyn import post
from jointdyn.core import interrupts
from jointdyn.errors import Interrupted, SimulationError
from jointdyn.models import slider_crank as sc
from jointdyn.models.slider_crank import slider_crank_config
from jointdyn.simulation.simulate import SimConfig, simulate
from jointdyn.studies import outputs

#: units of the slider-crank's derived headline columns (element outputs take the element's own)
SLIDER_CRANK_UNITS = {"crank_angle": "rad", "crank_moment": "N·m", "ex_over_c": "-", "ey_over_c": "-"}
JOINT_ELEMENT = sc.PIN  # the joint under study


def slider_crank_table(res, joint_element: str | None = None) -> dict[str, np.ndarray]:
    """Time series of a slider-crank run: t [s], crank_angle [rad, unwrapped], crank_moment
    [N·m] (the drive's moment on the crank, CCW positive), and for an imperfect piston pin
    ex_over_c, ey_over_c [-], h_min [m], joint_force [N] (magnitude on the journal),
    contact_force [N]."""
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
        "error_scale": res.config.get("error_scale", "state"),
        "wall_time_s": res.wall_time,
        **res.stats,
        "max_drift_position": float(res.drift[:, 0].max()),
        "max_drift_velocity": float(res.drift[:, 1].max()),
    }
    out.update({f"{k}_moment": v for k, v in post.stats(m[last]).items()})
    out.update({f"{k}_moment_all": v for k, v in post.stats(m).items()})
    if "ex_over_c" in cols:
        el = JOINT_ELEMENT
        xi = np.hypot(cols["ex_over_c"], cols["ey_over_c"])
        out["max_xi"] = float(xi.max())
        out["min_h_min"] = float(cols["h_min"].min())
        in_contact = cols["contact_force"] > 0
        dt = np.diff(res.t)
        out["contact_time_s"] = float(np.sum(dt * 0.5 * (in_contact[1:] + in_contact[:-1])))
        out["contact_fraction"] = out["contact_time_s"] / float(res.t[-1] - res.t[0])
        out["max_contact_force"] = float(cols["contact_force"].max())
        out["max_penetration"] = post.max_penetration(res, el)  # the continuous peak [T202]
        out["impacts"] = post.impacts(res, el)
    return out


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
):
    """Compile ``model`` (once), simulate it and, with ``out`` (a claimed
    :class:`~jointdyn.io.rundir.OutputDir`), write the output contract and the manifest.

    ``headline(res) -> ({name: array}, {name: unit})`` puts model-specific columns first;
    ``extra_summary(res, headline_columns) -> dict`` adds model-specific metrics; ``files``
    are extra text files (name -> content, e.g. the resolved ``model.toml``); ``meta`` goes
    into ``Results.meta`` (provenance saved with the results). Returns
    ``(results, headline columns, summary)``. On a failure or interruption the partial results
    (if any) are written with their status and the error is re-raised.
    """
    system = model.compile() if hasattr(model, "compile") else model
    from jointdyn.studies.options import check_memory

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
            _write_partial(out, err, status, headline, title, files)
        raise
    res.meta.update(meta or {})
    head, units = headline(res) if headline else ({}, {})
    summ = outputs.summary(res)
    if extra_summary is not None:
        summ.update(extra_summary(res, head))
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


def _write_partial(out, err: SimulationError, status: str, headline, title, files) -> None:
    """Write what a failed or interrupted run computed, then the manifest with its status."""
    interrupts.acknowledge()  # a further signal stops this writing, not the first one
    res = err.results
    reason = str(err)
    try:
        if res is not None and len(res.t) >= 2:
            status = "partial" if status == "failed" else status  # something was computed
            res.meta["status"] = status
            head, units = headline(res) if headline else ({}, {})
            summ = outputs.summary(res, status=status) | {"reason": reason}
            _write(out, res, _columns(res, head, units), summ, title + f" ({status})", files)
    except Exception as werr:  # the first error is the one to report
        reason += f"; writing the partial results failed too: {werr}"
    finally:
        out.finish(status, reason, t_reached=getattr(err, "t", None))


def _slider_crank_headline(res):
    el = JOINT_ELEMENT if JOINT_ELEMENT in res.system.element_names else None
    units = dict(SLIDER_CRANK_UNITS)
    if el is not None:  # h_min, contact_force: the element's declared units; |F| in those of Fx
        outs = type(res.system.elements[res.system.element_names.index(el)]).OUTPUTS
        units |= {"h_min": outs["h_min"], "contact_force": outs["contact_force"], "joint_force": outs["Fx"]}
    return slider_crank_table(res, el), units


def run_slider_crank(
    joint: str = "perfect",
    revs: float = 4.0,
    out=None,
    progress=None,
    model_kw: dict | None = None,
    **cfg_kw,
):
    """Simulate the benchmark slider-crank; optionally write the run files. ``out`` is a
    directory path (claimed here, see :mod:`jointdyn.io.rundir`) or a claimed
    :class:`~jointdyn.io.rundir.OutputDir`. Returns (results, columns, summary)."""
    from jointdyn.io.rundir import OutputDir

    model = sc.slider_crank(joint, **(model_kw or {}))
    cfg = slider_crank_config(joint, revs, **cfg_kw)
    if out is not None and not isinstance(out, OutputDir):
        spec = {"model": "slider-crank", "joint": joint, "revs": revs, **(model_kw or {}), **cfg_kw}
        spec = {k: v if isinstance(v, (int, float, str)) else repr(v) for k, v in spec.items()}
        out = OutputDir(Path(out), "run", spec).claim(overwrite=True)
    return run(
        model,
        cfg,
        out,
        progress=progress,
        headline=_slider_crank_headline,
        extra_summary=lambda res, cols: summarize(res, cols, revs),
        title=f"slider-crank, {joint} piston pin",
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
