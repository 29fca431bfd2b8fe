"""The model codec: :class:`~jointdyn.multibody.model.Model` ↔ plain dict ↔ TOML text.

One description of a model serves the model files (``io.modelfile``), the ``model`` attribute
of a results file (``Results.save``/``load``) and the compiled system's provenance
(``System.model_dict``). The dict has the layout of a model file (``docs/model_files.md``)::

    {"model": {"name", "gravity"}, "ground": {"points": {name: [x, y]}},
     "bodies": {name: {mass, inertia, position, angle, velocity, points}},
     "joints": {name: {"type": <CONSTRAINTS name>, <fields>}},
     "elements": {name: {"type": <FORCE_ELEMENTS name>, <fields>}}}

A field holding a law instance (``LAW_FIELDS``: contact, friction and film laws) is the table
``{"law": <registry name>, <the law's fields>}``; a film given by name stays a string. Fields
that are None are left out (they take their default, None, when read). Arrays are lists in the
dict and tuples in the dataclasses. Floats are written with ``repr`` (exact round trip).
:func:`decode` also reads the layout of the results files written before this module
(``{"name", "gravity", "bodies", "ground_points", "items"}``).
"""

from __future__ import annotations

import dataclasses
import json
import math
import numbers
import re
import tomllib

import numpy as np

from jointdyn.core.constraints import CONSTRAINTS
from jointdyn.errors import ModelError
from jointdyn.film.models import FILM_MODELS
from jointdyn.forces.contact_laws import CONTACT_LAWS
from jointdyn.forces.elements import FORCE_ELEMENTS
from jointdyn.forces.friction_laws import FRICTION_LAWS
from jointdyn.forces.mixed import ASPERITY_MODELS
from jointdyn.forces.thermal import THERMAL_MODELS

#: fields that hold a law *instance*, written as ``{ law = "<name>", ...fields }``
LAW_FIELDS = {
    "contact": CONTACT_LAWS,
    "friction": FRICTION_LAWS,
    "film": FILM_MODELS,
    "thermal": THERMAL_MODELS,
    "asperity": ASPERITY_MODELS,
}
#: the item families of a model: table name -> registry
FAMILIES = {"joints": CONSTRAINTS, "elements": FORCE_ELEMENTS}
#: the tables of the model part of a document, in file order
TABLES = ("model", "ground", "bodies", "joints", "elements")


def _names(registry: dict) -> dict:
    return {cls: name for name, cls in registry.items()}


# -- Model -> dict ------------------------------------------------------------------------------
def law_table(v) -> dict | None:
    """``{"law": name, **fields}`` of a registered law instance, None for anything else."""
    for registry in LAW_FIELDS.values():
        name = _names(registry).get(type(v))
        if name is not None:
            return {"law": name, **_fields(v)}
    return None


def encode_value(v):
    """A field value as plain data (lists, dicts, str, numbers, bools)."""
    law = law_table(v)
    if law is not None:
        return law
    if isinstance(v, np.ndarray):
        return v.tolist()
    if isinstance(v, (list, tuple)):
        return [encode_value(x) for x in v]
    if isinstance(v, dict):
        return {k: encode_value(x) for k, x in v.items()}
    if isinstance(v, np.generic):
        return v.item()
    return v


def _fields(obj) -> dict:
    values = ((f.name, getattr(obj, f.name)) for f in dataclasses.fields(obj))
    return {k: encode_value(v) for k, v in values if v is not None}


def encode_item(item) -> tuple[str, dict]:
    """(family, table) of a constraint or force element: ``{"type": name, **fields}``."""
    for family, registry in FAMILIES.items():
        name = _names(registry).get(type(item))
        if name is not None:
            return family, {"type": name, **_fields(item)}
    valid = sorted(CONSTRAINTS) + sorted(FORCE_ELEMENTS)
    raise ModelError(f"{type(item).__name__} is not a registered constraint or force element; valid: {valid}")


def encode(model) -> dict:
    """The plain-data description of ``model`` (the layout above)."""
    doc: dict = {
        "model": {"name": model.name, "gravity": list(model.gravity)},
        "ground": {"points": encode_value(model.ground_points)},
        "bodies": {n: {k: v for k, v in _fields(b).items() if k != "name"} for n, b in model.bodies.items()},
        "joints": {},
        "elements": {},
    }
    for name, item in model.items.items():
        family, table = encode_item(item)
        doc[family][name] = table
    return doc


# -- dict -> Model parts ------------------------------------------------------------------------
def decode_value(v):
    """Plain data as the dataclasses hold it: lists become tuples."""
    if isinstance(v, list):
        return tuple(decode_value(x) for x in v)
    if isinstance(v, dict):
        return {k: decode_value(x) for k, x in v.items()}
    return v


def decode_law(field: str, value):
    """The value of law field ``field``: a law instance from its table, a name as given."""
    if not isinstance(value, dict):
        return value
    registry = LAW_FIELDS[field]
    name = value.get("law")
    if name not in registry:
        raise ModelError(f"{field}: unknown {field} law {name!r}; valid names: {sorted(registry)}")
    return registry[name](**{k: decode_value(x) for k, x in value.items() if k != "law"})


def decode_item(family: str, table: dict):
    """A constraint (``family = "joints"``) or force element (``"elements"``) from its table."""
    registry = FAMILIES[family]
    typ = table.get("type")
    if typ not in registry:
        raise ModelError(f"{family}: unknown type {typ!r}; valid types: {sorted(registry)}")
    args = {
        k: decode_law(k, v) if k in LAW_FIELDS else decode_value(v) for k, v in table.items() if k != "type"
    }
    return registry[typ](**args)


def upgrade(d: dict) -> dict:
    """The layout above from a description in it or in the layout of older results files."""
    if "items" not in d:
        return {k: d.get(k, {}) for k in TABLES} | {"ground": {"points": {}, **d.get("ground", {})}}
    families = {}
    for name, item in d["items"].items():
        family = "joints" if item.get("type") in CONSTRAINTS else "elements"
        families.setdefault(family, {})[name] = item
    return {
        "model": {"name": d["name"], "gravity": d["gravity"]},
        "ground": {"points": d.get("ground_points", {})},
        "bodies": d["bodies"],
        "joints": families.get("joints", {}),
        "elements": families.get("elements", {}),
    }


def decode(d: dict) -> tuple[dict, dict, dict, dict]:
    """(``Model(**model)`` arguments, ground points, ``add_body`` arguments per body, items by
    name) of a description; ``Model.from_dict`` assembles them."""
    d = upgrade(d)
    model = {k: decode_value(v) for k, v in d["model"].items()}
    points = {k: decode_value(v) for k, v in d["ground"]["points"].items()}
    bodies = {n: {k: decode_value(v) for k, v in b.items()} for n, b in d["bodies"].items()}
    items = {n: decode_item(family, t) for family in FAMILIES for n, t in d[family].items()}
    return model, points, bodies, items


# -- dict <-> TOML text -------------------------------------------------------------------------
def _key(k: str) -> str:
    return k if re.fullmatch(r"[A-Za-z0-9_\-]+", k) else _string(k)


def _string(s: str) -> str:
    return json.dumps(s, ensure_ascii=False).replace("\x7f", "\\u007f")


def toml_value(v) -> str:
    """One value as TOML text (floats round-trip exactly; law instances as inline tables)."""
    v = encode_value(v)
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, numbers.Integral):
        return str(int(v))
    if isinstance(v, numbers.Real):
        x = float(v)
        return "nan" if math.isnan(x) else ("inf" if x > 0 else "-inf") if math.isinf(x) else repr(x)
    if isinstance(v, str):
        return _string(v)
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        items = [f"{_key(k)} = {toml_value(x)}" for k, x in v.items() if x is not None]
        return "{ " + ", ".join(items) + " }" if items else "{}"
    raise TypeError(f"cannot write {type(v).__name__} {v!r} to TOML")


def toml_table(header: str, pairs) -> list[str]:
    """The lines of table ``[header]`` with the (key, value) ``pairs`` (None values left out)."""
    return [f"[{header}]"] + [f"{_key(k)} = {toml_value(v)}" for k, v in pairs if v is not None] + [""]


def to_toml(d: dict, header: str = "", extra: dict | None = None) -> str:
    """TOML text of a description (plus ``extra`` tables, e.g. ``{"simulation": {...}}``, and
    ``header`` as leading comment lines); :func:`from_toml` reads it back equal."""
    d = upgrade(d)
    out = [f"# {line}".rstrip() for line in header.splitlines()]
    if out:
        out.append("")
    out += toml_table("model", d["model"].items())
    if d["ground"]["points"]:
        out += toml_table("ground.points", d["ground"]["points"].items())
    for family in ("bodies", "joints", "elements"):
        for name, table in d[family].items():
            out += toml_table(f"{family}.{_key(name)}", table.items())
    for name, table in (extra or {}).items():
        out += toml_table(_key(name), table.items())
    return "\n".join(out)


def from_toml(text: str) -> dict:
    """The description in TOML ``text`` (other tables, e.g. ``simulation``, are kept as read)."""
    doc = tomllib.loads(text)
    return {**doc, **upgrade(doc)}
