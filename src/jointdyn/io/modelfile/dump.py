"""Writing (Model, SimConfig) as a model file that :func:`~jointdyn.io.modelfile.load_model` reads back
identically (floats round-trip exactly; no extra dependency)."""

from __future__ import annotations

import dataclasses
import json
import math
import numbers
import re
from pathlib import Path

from jointdyn.core import atomic
from jointdyn.core.constraints import CONSTRAINTS
from jointdyn.forces.elements import FORCE_ELEMENTS
from jointdyn.io.modelfile.schema import LAW_FIELDS
from jointdyn.multibody.model import Model
from jointdyn.simulation.simulate import SimConfig


def _key(k: str) -> str:
    return k if re.fullmatch(r"[A-Za-z0-9_\-]+", k) else _string(k)


def _string(s: str) -> str:
    return json.dumps(s, ensure_ascii=False).replace("\x7f", "\\u007f")


_LAW_NAMES = {cls: name for reg in LAW_FIELDS.values() for name, cls in reg.items()}


def toml_value(v) -> str:
    """One value as TOML text (floats round-trip exactly; law instances as inline tables)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, numbers.Integral):
        return str(int(v))
    if isinstance(v, numbers.Real):
        x = float(v)
        return "nan" if math.isnan(x) else ("inf" if x > 0 else "-inf") if math.isinf(x) else repr(x)
    if isinstance(v, str):
        return _string(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if type(v) in _LAW_NAMES:
        d = {"law": _LAW_NAMES[type(v)], **{f.name: getattr(v, f.name) for f in dataclasses.fields(v)}}
        return toml_value(d)
    if isinstance(v, dict):
        items = [f"{_key(k)} = {toml_value(x)}" for k, x in v.items() if x is not None]
        return "{ " + ", ".join(items) + " }" if items else "{}"
    raise TypeError(f"cannot write {type(v).__name__} {v!r} to TOML")


def _table(header: str, pairs) -> list[str]:
    lines = [f"[{header}]"]
    lines += [f"{_key(k)} = {toml_value(v)}" for k, v in pairs if v is not None]
    return lines + [""]


def dumps(model: Model, config: SimConfig, header: str = "") -> str:
    """The TOML text of (model, config); :func:`load_model` reads it back identically."""
    out = [f"# {line}".rstrip() for line in header.splitlines()]
    if out:
        out.append("")
    out += _table("model", [("name", model.name), ("gravity", model.gravity)])
    if model.ground_points:
        out += _table("ground.points", model.ground_points.items())
    for name, b in model.bodies.items():
        out += _table(
            f"bodies.{_key(name)}",
            [(f.name, getattr(b, f.name)) for f in dataclasses.fields(b) if f.name != "name"],
        )
    types = {
        cls: (fam, n)
        for fam, reg in (("joints", CONSTRAINTS), ("elements", FORCE_ELEMENTS))
        for n, cls in reg.items()
    }
    for family in ("joints", "elements"):
        for name, item in model.items.items():
            fam, typ = types[type(item)]
            if fam == family:
                out += _table(
                    f"{family}.{_key(name)}",
                    [("type", typ)] + [(f.name, getattr(item, f.name)) for f in dataclasses.fields(item)],
                )
    out += _table("simulation", [(f.name, getattr(config, f.name)) for f in dataclasses.fields(config)])
    return "\n".join(out)


def save_model(model: Model, config: SimConfig, path, header: str = "") -> None:
    """Write (model, config) as a TOML model file (no extra dependency)."""
    atomic.write_text(Path(path), dumps(model, config, header))
