"""Reading model files: strict TOML -> validated (Model, SimConfig), dotted ``--set`` overrides.

Parsing never evaluates code: ``tomllib`` yields plain data, names are looked up in the literal
registries, values are validated strictly (no string → number coercion, no bool as number, no
NaN/inf unless the field's default is infinite). Range checks are the dataclasses' own
``validate()``/``__post_init__`` plus ``Model.compile()``; a :class:`~jointdyn.core.checks.FieldError`
names its field, which is mapped to the file's key and line.
"""

from __future__ import annotations

import copy
import math
import re
import statistics
import tomllib

import pydantic

from jointdyn.core.checks import FieldError
from jointdyn.core.constraints import CONSTRAINTS
from jointdyn.errors import ModelError
from jointdyn.forces.elements import FORCE_ELEMENTS
from jointdyn.io.modelfile.locate import _Context, _key_path, read_toml
from jointdyn.io.modelfile.schema import (
    LAW_FIELDS,
    NAME_FIELDS,
    TOP_LEVEL,
    Schema,
    _validator_annotation,
    schemas,
    type_name,
)
from jointdyn.multibody.model import GROUND, Model
from jointdyn.simulation.simulate import SimConfig


def _tuples(v):
    """TOML arrays -> tuples (the dataclasses' array fields are tuples)."""
    if isinstance(v, list):
        return tuple(_tuples(x) for x in v)
    if isinstance(v, dict):
        return {k: _tuples(x) for k, x in v.items()}
    return v


def _valid(keys) -> str:
    return "valid keys: " + ", ".join(keys)


def _check_table(ctx: _Context, key: tuple, value, what: str) -> dict:
    if not isinstance(value, dict):
        raise ctx.error(key, f"must be a table ({what}); got {type(value).__name__} {value!r}")
    return value


def _validate(ctx: _Context, schema: Schema, table: dict, key: tuple, extra_ok=()) -> dict:
    """Unknown keys, missing keys, types and finiteness of one table; returns the values."""
    for k in table:
        if k not in schema.keys and k not in extra_ok:
            raise ctx.error(
                key + (k,), f"unknown key in {schema.title}; " + _valid(list(extra_ok) + list(schema.keys))
            )
    data = {k: _tuples(v) for k, v in table.items() if k not in extra_ok}
    try:
        obj = schema.validator.model_validate(data)
    except pydantic.ValidationError as err:
        e = err.errors()[0]
        field = e["loc"][0] if e["loc"] else None
        spec = schema.keys.get(field)
        unit = f" [{spec.unit}]" if spec is not None and spec.unit else ""
        expected = f"expected {type_name(_validator_annotation(spec))}{unit}" if spec else ""
        loc = tuple(e["loc"])
        if len(loc) > 1 and isinstance(loc[-1], int) and e["type"] in ("missing", "too_long", "too_short"):
            loc = loc[:-1]  # an array of the wrong length: report the array
            got = data
            for k in loc:
                got = got[k]
            msg = f"wrong number of components (got {len(got)}: {list(got)!r}); {expected}"
        elif e["type"] == "missing":
            msg = f"missing required key in {schema.title}; {expected}: {spec.doc if spec else ''}"
        elif e["type"] == "literal_error":
            msg = f"unknown name {e.get('input')!r}; valid names: " + ", ".join(NAME_FIELDS[field])
        else:
            got = e.get("input")
            what = (
                e["msg"]
                .rstrip(".")
                .replace("a valid tuple", "an array")
                .replace("a valid dictionary", "a table")
            )
            msg = f"{what} (got {type(got).__name__} {got!r}); {expected}"
        raise ctx.error(key + loc, msg) from None
    return {k: getattr(obj, k) for k in schema.keys}


def _field_error(ctx: _Context, key: tuple, err: Exception, names) -> ModelError:
    """Turn a dataclass's range error into an error keyed to the field: a
    :class:`~jointdyn.core.checks.FieldError` names its field. Transitional: the laws, elements and
    ``SimConfig`` that still raise a plain ``ValueError("Cls.field = v [unit]: must be ...")``
    are keyed by the name before `` = `` (remove once they all call ``jointdyn.core.checks.check``)."""
    msg = str(err)
    field = err.field if isinstance(err, FieldError) else _legacy_field(msg)
    if field in names:
        return ctx.error(key + (field,), msg)
    return ctx.error(key, msg)


def _legacy_field(msg: str) -> str | None:
    m = re.search(r"(?:^|[\s:])(?:\w+\.)?(\w+) = ", msg)
    return m.group(1) if m else None


def _law(ctx: _Context, value, key: tuple, family: str):
    registry = LAW_FIELDS[family]
    if value is None:
        return None
    if family in NAME_FIELDS and isinstance(value, str):  # a film model by name: its defaults
        if value not in registry:
            raise ctx.error(key, f"unknown name {value!r}; valid names: " + ", ".join(registry))
        return value
    value = _check_table(
        ctx, key, value, "{ law = <name>, ... } with law one of " + ", ".join(sorted(registry))
    )
    if "law" not in value:
        raise ctx.error(
            key + ("law",),
            f"missing required key 'law' ({family} law name); valid names: " + ", ".join(sorted(registry)),
        )
    name = value["law"]
    if not isinstance(name, str) or name not in registry:
        raise ctx.error(
            key + ("law",), f"unknown {family} law {name!r}; valid names: " + ", ".join(sorted(registry))
        )
    schema = schemas()[family][name]
    vals = _validate(ctx, schema, value, key, extra_ok=("law",))
    try:
        return registry[name](**vals)
    except (ValueError, TypeError) as err:
        raise _field_error(ctx, key, err, schema.keys) from None


def _item(ctx: _Context, family: str, name: str, table, model: Model):
    key = (family, name)
    registry = CONSTRAINTS if family == "joints" else FORCE_ELEMENTS
    table = _check_table(ctx, key, table, f"type = <name>, ...; type one of {sorted(registry)}")
    typ = table.get("type")
    if typ is None:
        raise ctx.error(key + ("type",), "missing required key 'type'; valid types: " + ", ".join(registry))
    if not isinstance(typ, str) or typ not in registry:
        other = FORCE_ELEMENTS if family == "joints" else CONSTRAINTS
        hint = (
            (
                f" ({typ!r} is a{' force element' if family == 'joints' else ' joint'}: put it under "
                f"[{'elements' if family == 'joints' else 'joints'}.{name}])"
            )
            if typ in other
            else ""
        )
        raise ctx.error(
            key + ("type",),
            f"unknown {family[:-1] if family == 'joints' else 'element'} type "
            f"{typ!r}{hint}; valid types: " + ", ".join(registry),
        )
    schema = schemas()[family][typ]
    vals = _validate(ctx, schema, table, key, extra_ok=("type",))
    for f in LAW_FIELDS:
        if f in vals:
            vals[f] = _law(ctx, vals[f], key + (f,), f)
    bodies = [GROUND] + list(model.bodies)
    for side in ("i", "j"):
        b = vals.get(f"body_{side}")
        if b is not None and b not in bodies:
            raise ctx.error(key + (f"body_{side}",), f"unknown body {b!r}; bodies are " + ", ".join(bodies))
    if vals.get("body_i") is not None and vals.get("body_i") == vals.get("body_j"):
        raise ctx.error(
            key + ("body_j",), f"joins body {vals['body_i']!r} to itself (body_i and body_j must differ)"
        )
    for side in ("i", "j"):
        p = vals.get(f"point_{side}")
        if p is not None:
            b = vals[f"body_{side}"]
            pts = model.ground_points if b == GROUND else model.bodies[b].points
            if p not in pts:
                where = "[ground.points]" if b == GROUND else f"bodies.{b}.points"
                raise ctx.error(
                    key + (f"point_{side}",),
                    f"body {b!r} has no point {p!r}; points in {where}: " + (", ".join(pts) or "(none)"),
                )
    try:
        item = registry[typ](**vals)
        if hasattr(item, "validate"):
            item.validate()
    except (ValueError, TypeError) as err:
        raise _field_error(ctx, key, err, schema.keys) from None
    return item


def build(
    doc: dict, source: str = "<model>", text: str = "", overridden: dict | None = None, assemble: bool = True
) -> tuple[Model, SimConfig]:
    """Validate a parsed model document and build (Model, SimConfig).

    ``source``/``text`` only serve error messages (file name and line numbers). With
    ``assemble`` the model is compiled once, so an unassemblable mechanism is reported here.
    """
    model, _, config = _build(doc, source, text, overridden, assemble)
    return model, config


def _build(doc, source, text, overridden, assemble):
    ctx = _Context(source, text, overridden)
    if not doc:
        raise ctx.error(
            (),
            "the file is empty; a model file needs at least [bodies.<name>] and "
            "[simulation] (see docs/model_files.md)",
        )
    for k in doc:
        if k not in TOP_LEVEL:
            raise ctx.error((k,), "unknown top-level table; valid tables: " + ", ".join(TOP_LEVEL))
    for k in ("bodies", "simulation"):
        if k not in doc:
            raise ctx.error(
                (k,),
                f"missing required table [{k}]; "
                + (
                    "add at least one [bodies.<name>] with mass and inertia"
                    if k == "bodies"
                    else "add [simulation] with at least t_end [s]"
                ),
            )
    sch = schemas()
    mvals = _validate(
        ctx, sch["model"], _check_table(ctx, ("model",), doc.get("model", {}), "name, gravity"), ("model",)
    )
    model = Model(**mvals)
    ground = _validate(
        ctx, sch["ground"], _check_table(ctx, ("ground",), doc.get("ground", {}), "points"), ("ground",)
    )
    for p, xy in ground["points"].items():
        model.add_ground_point(p, xy)
    bodies = _check_table(ctx, ("bodies",), doc["bodies"], "one sub-table per body")
    if not bodies:
        raise ctx.error(("bodies",), "no bodies; add at least one [bodies.<name>] with mass and inertia")
    for name, table in bodies.items():
        key = ("bodies", name)
        if name == GROUND:
            raise ctx.error(
                key, "the name 'ground' is reserved for the fixed frame; put its points in [ground.points]"
            )
        vals = _validate(ctx, sch["body"], _check_table(ctx, key, table, "mass, inertia, ..."), key)
        try:
            model.add_body(name, **vals)
        except ModelError as err:
            raise _field_error(ctx, key, err, sch["body"].keys) from None
    _check_mass_ratio(ctx, model)
    seen: dict[str, str] = {}
    for family in ("joints", "elements"):
        for name, table in _check_table(ctx, (family,), doc.get(family, {}), "one sub-table each").items():
            if name in seen:
                raise ctx.error(
                    (family, name),
                    f"duplicate name: {seen[name]}.{name} already exists "
                    "(joint and element names share one namespace)",
                )
            seen[name] = family
            model.add(name, _item(ctx, family, name, table, model))
    svals = _validate(
        ctx,
        sch["simulation"],
        _check_table(ctx, ("simulation",), doc["simulation"], "t_end, ..."),
        ("simulation",),
    )
    try:
        config = SimConfig(**svals)
    except ValueError as err:
        raise _field_error(ctx, ("simulation",), err, sch["simulation"].keys) from None
    system = None
    if assemble:
        try:
            system = model.compile()
        except ModelError as err:
            # transitional: Model.compile names the element in its message text
            m = re.match(r"element '([^']*)': (.*)", str(err))
            if m and m.group(1) in seen:
                raise ctx.error((seen[m.group(1)], m.group(1)), m.group(2)) from None
            raise ctx.error(("joints",), f"{err}") from None
    return model, system, config


#: largest ratio of the mass-matrix diagonal entries (masses [kg], inertias [kg·m²]) [T143]
MAX_MASS_RATIO = 1e12


def _check_mass_ratio(ctx: _Context, model: Model) -> None:
    """Masses and inertias spanning more than ``MAX_MASS_RATIO`` leave the constraint Schur
    complement Φ_q M⁻¹ Φ_qᵀ without significant digits [T143]; name the extreme entry."""
    entries = [(b.mass, ("bodies", n, "mass")) for n, b in model.bodies.items()]
    entries += [(b.inertia, ("bodies", n, "inertia")) for n, b in model.bodies.items()]
    (lo, klo), (hi, khi) = min(entries), max(entries)
    if hi > MAX_MASS_RATIO * lo:
        mid = statistics.median_low(math.log10(v) for v, _ in entries)  # the typical entry
        (v, key), (w, other) = (
            ((hi, khi), (lo, klo)) if math.log10(hi) - mid >= mid - math.log10(lo) else ((lo, klo), (hi, khi))
        )
        raise ctx.error(
            key,
            f"{v:.3g} vs {'.'.join(other)} = {w:.3g}: masses and inertias [kg, kg·m²] must "
            f"span at most a factor {MAX_MASS_RATIO:.0e} (double precision then keeps ~4 digits of "
            "the constraint forces); check the units",
        )


# -- overrides ---------------------------------------------------------------------------------
def _parse_value(text: str):
    """A TOML value (scalar, array or inline table); a bare word is taken as a string."""
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        if re.fullmatch(r"[A-Za-z_][A-Za-z0-9_\-]*", text.strip()):
            return text.strip()
        raise


def _valid_keys(doc: dict, path: tuple) -> list[str] | None:
    """Keys allowed under ``path`` (None: any name, e.g. new points)."""
    sch = schemas()
    if not path:
        return list(TOP_LEVEL)
    top, rest = path[0], path[1:]
    if top in ("model", "simulation", "ground") and not rest:
        return list(sch[top].keys)
    if top == "ground" and rest == ("points",):
        return None
    if top == "bodies":
        if not rest:
            return list(doc.get("bodies", {}))
        if len(rest) == 1:
            return list(sch["body"].keys)
        if rest[1:] == ("points",):
            return None
    if top in ("joints", "elements"):
        if not rest:
            return list(doc.get(top, {}))
        typ = doc.get(top, {}).get(rest[0], {}).get("type")
        s = sch[top].get(typ)
        if len(rest) == 1:
            return ["type"] + (list(s.keys) if s else [])
        if len(rest) == 2 and rest[1] in LAW_FIELDS:
            law = doc[top][rest[0]].get(rest[1], {})
            ls = sch[rest[1]].get(law.get("law")) if isinstance(law, dict) else None
            return ["law"] + (list(ls.keys) if ls else [])
    return []


def apply_overrides(doc: dict, overrides=()) -> dict:
    """Return a copy of ``doc`` with dotted ``key=value`` assignments applied.

    Values are TOML (``0.3``, ``[0.0, -9.81]``, ``"rodas4"``, ``{ law = "coulomb", coefficient =
    0.1 }``; a bare word is a string). A path that the schema does not allow at its level is a
    :class:`ModelError` listing the valid keys there.
    """
    doc = copy.deepcopy(doc)
    for ov in overrides:
        if "=" not in ov:
            raise ModelError(f"override {ov!r}: expected dotted.key=value, e.g. bodies.crank.mass=0.3")
        lhs, rhs = ov.split("=", 1)
        path = _key_path(lhs.strip())
        if not path:
            raise ModelError(f"override {ov!r}: {lhs.strip()!r} is not a dotted key")
        try:
            value = _parse_value(rhs.strip())
        except tomllib.TOMLDecodeError as err:
            raise ModelError(
                f"override {ov!r}: the value {rhs.strip()!r} is not a TOML value ({err})"
            ) from None
        node = doc
        for i, k in enumerate(path):
            valid = _valid_keys(doc, path[:i])
            if valid is not None and k not in valid:
                at = ".".join(path[:i]) or "the top level"
                raise ModelError(
                    f"override {ov!r}: unknown key {k!r} at {at}; "
                    + (_valid(valid) if valid else "nothing can be set there")
                )
            if i == len(path) - 1:
                node[k] = value
            else:
                nxt = node.setdefault(k, {}) if k not in node else node[k]
                if not isinstance(nxt, dict):
                    raise ModelError(f"override {ov!r}: {'.'.join(path[: i + 1])} is a value, not a table")
                node = nxt
    return doc


def load_model(path, overrides=(), assemble: bool = True) -> tuple[Model, SimConfig]:
    """Read a TOML model file (plus dotted ``key=value`` overrides) into (Model, SimConfig).

    Raises :class:`ModelError` with one line naming the file, line, dotted key, unit and the
    allowed range or valid keys. With ``assemble`` the model is assembled once to check that
    it can be (a sweep's up-front check skips it: the case's run assembles it).
    """
    doc, text = read_toml(path)
    doc = apply_overrides(doc, overrides)
    return build(doc, str(path), text, _overridden(overrides), assemble)


def load_system(path, overrides=()):
    """Like :func:`load_model`, returning ``(Model, System, SimConfig)``: the assembly check
    and the run share one compilation."""
    doc, text = read_toml(path)
    doc = apply_overrides(doc, overrides)
    return _build(doc, str(path), text, _overridden(overrides), True)


def _overridden(overrides) -> dict:
    out = {}
    for ov in overrides:
        p = _key_path(ov.split("=", 1)[0].strip())
        if p:
            out[p] = ov
    return out


def with_keys(model: Model, config: SimConfig, overrides=(), source: str = "<model>", assemble: bool = True):
    """``(Model, System | None, SimConfig)`` of a built model (e.g. a shipped one) with dotted
    model-file ``key=value`` overrides applied: the model is written as its model file, the keys
    are set on that, and it is read back (the same checks and messages as a file). ``System`` is
    None without ``assemble``."""
    from jointdyn.io.modelfile.dump import dumps

    text = dumps(model, config)
    doc = apply_overrides(tomllib.loads(text), overrides)
    if not assemble:
        m, cfg = build(doc, source, text, _overridden(overrides), False)
        return m, None, cfg
    return _build(doc, source, text, _overridden(overrides), True)
