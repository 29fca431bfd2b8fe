"""The metrics of a run, for any model, from one function (:func:`metrics`) [T228].

* per angle driver ``D`` (constant speed ω): its reaction moment over its last revolution,
  t ≥ t_end − 2π/|ω| (the whole run when it is shorter, or when the driver does not turn at a
  constant speed): ``D.moment_peak``, ``D.moment_min``, ``D.moment_rms`` [N·m];
* per force element ``E`` and declared output ``o`` over the whole run: ``E.o_max``,
  ``E.o_min``, ``E.o_rms`` [unit of o];
* per element with contact memory: ``E.impacts`` [-] (onsets over the accepted steps) and
  ``E.max_penetration`` [m] (peak between step ends included, [T202]); per element with a
  ``power`` output: ``E.energy_dissipated`` [J].

A metric that does not exist for a model is absent (never NaN); :func:`pick` asks for one by
name and ends a missing one with one line. A shipped model may give some metrics short names
(``aliases``: short name -> generic name, e.g. the slider-crank's ``peak_moment``).
"""

from __future__ import annotations

import math

import numpy as np

from jointdyn import post
from jointdyn.forces.elements import output_slots
from jointdyn.studies.period import angle_drivers


def _rms(x: np.ndarray) -> float:
    return float(np.sqrt(np.mean(x * x)))


def _driver_window(res, name: str) -> np.ndarray:
    """Samples of the driver's last revolution (all samples if the run is shorter)."""
    d = res.system.constraints[res.system.constraint_names.index(name)]
    if d.alpha != 0 or not (math.isfinite(d.omega) and d.omega != 0):
        return post.window(res)
    T = 2 * math.pi / abs(d.omega)
    t0, t1 = float(res.t[0]), float(res.t[-1])
    return post.window(res, t1 - T if t1 - t0 >= T else None)


def metric_units(system, aliases: dict[str, str] | None = None) -> dict[str, str]:
    """``{metric name: unit}`` of every metric :func:`metrics` gives for ``system`` (SI)."""
    units: dict[str, str] = {}
    for d in angle_drivers(system):
        units |= {f"{d}.moment_{k}": "N·m" for k in ("peak", "min", "rms")}
    for name, el in zip(system.element_names, system.elements):
        outs, mem = output_slots(el), type(el).MEMORY
        for o, u in outs.items():
            units |= {f"{name}.{o}_{k}": u for k in ("max", "min", "rms")}
        if "impacts" in mem:
            units[f"{name}.impacts"] = "-"
        if "max_penetration" in mem:
            units[f"{name}.max_penetration"] = mem["max_penetration"]
        if "power" in outs:
            units[f"{name}.energy_dissipated"] = "J"
    for short, full in (aliases or {}).items():
        if full in units:
            units[short] = units[full]
    return units


def metrics(res, aliases: dict[str, str] | None = None) -> dict[str, float]:
    """Every metric of a run (see the module docstring) as ``{name: value}`` [SI], then the
    ``aliases`` (short name -> generic name) whose generic metric exists. A run without samples
    has none."""
    out: dict[str, float] = {}
    if len(res.t) == 0:
        return out
    for d in angle_drivers(res.system):
        m = post.driving_moment(res, d)[_driver_window(res, d)]
        out |= {f"{d}.moment_{k}": v for k, v in post.stats(m).items()}
    for name, el in zip(res.system.element_names, res.system.elements):
        outs, mem = output_slots(el), type(el).MEMORY
        for o in outs:
            x = res.element(name, o)
            out |= {f"{name}.{o}_max": float(x.max()), f"{name}.{o}_min": float(x.min())}
            out[f"{name}.{o}_rms"] = _rms(x)
        if "impacts" in mem:
            out[f"{name}.impacts"] = post.impacts(res, name)
        if "max_penetration" in mem:
            out[f"{name}.max_penetration"] = post.max_penetration(res, name)
        if "power" in outs:
            out[f"{name}.energy_dissipated"] = post.dissipated_energy(res, name)
    for short, full in (aliases or {}).items():
        if full in out:
            out[short] = out[full]
    return out


def pick(values: dict[str, float], name: str, model: str = "the model") -> float:
    """The metric ``name`` of ``values`` (from :func:`metrics`); one line naming the metrics that
    exist when it does not."""
    if name not in values:
        raise ValueError(f"metric {name!r}: does not exist for {model}; its metrics: {', '.join(values)}")
    return values[name]
