"""Model files: strict TOML -> (:class:`~jointdyn.model.Model`, :class:`~jointdyn.simulate.SimConfig`).

Layout (every table and key with its unit: ``docs/model_files.md``)::

    [model]              name, gravity = [g_x, g_y] [m/s²]
    [ground.points]      O = [x, y]  (world frame) [m]
    [bodies.<name>]      the fields of ``Body`` (mass, inertia, position, angle, velocity, points)
    [joints.<name>]      type = a name in ``CONSTRAINTS``, then that dataclass's fields
    [elements.<name>]    type = a name in ``FORCE_ELEMENTS``, then that dataclass's fields; a law
                         field is an inline table ``{ law = <name in CONTACT_LAWS or
                         FRICTION_LAWS>, <the law's fields> }``
    [simulation]         the fields of ``SimConfig``

There is no second schema (ARCHITECTURE rule 5): the validators are pydantic models built (once,
on first use) from the registries' dataclass fields (``dataclasses.fields`` + their type hints;
``Model.__init__``'s signature for ``[model]``), and range checks are the dataclasses' own
``validate()``/``__post_init__`` plus ``Model.compile()`` (assembly). This module only adds what a
file needs: the dotted key, the line number, the unit (from the field's docstring) and the list
of valid keys or names. Every problem is one :class:`~jointdyn.errors.ModelError` line
``<file>:<line>: <dotted.key>: <what is wrong> [unit] <allowed range or valid keys>``.

Parsing never evaluates code: ``tomllib`` yields plain data, names are looked up in the literal
registries, values are validated strictly (no string → number coercion, no bool as number, no
NaN/inf unless the field's default is infinite).
"""

from __future__ import annotations

import ast
import copy
import dataclasses
import inspect
import itertools
import json
import math
import numbers
import re
import tomllib
import typing
from functools import cache
from pathlib import Path
from typing import Annotated, Any, Literal

import pydantic

from .errors import ModelError
from .forces.contact_laws import CONTACT_LAWS
from .forces.elements import FORCE_ELEMENTS
from .forces.film_models import FILM_MODELS
from .forces.friction_laws import FRICTION_LAWS
from .integrators import SOLVERS
from .joints.constraints import CONSTRAINTS
from .model import GROUND, Body, Model
from .simulate import SimConfig, simulate

TOP_LEVEL = ("model", "ground", "bodies", "joints", "elements", "simulation")
#: fields that hold a law *instance*: written as ``{ law = "<name>", ...fields }``
LAW_FIELDS = {"contact": CONTACT_LAWS, "friction": FRICTION_LAWS}
#: string fields that name an entry of a registry
NAME_FIELDS = {"film": FILM_MODELS, "solver": {"auto": None, **SOLVERS}}
_REQUIRED = object()


# -- schemas built from the dataclasses --------------------------------------------------------
def _attribute_docs(obj) -> dict[str, str]:
    """Attribute docstrings (a string literal right after ``name: T = ...`` in a class body, or
    after ``self.name = ...`` in a function), walking the MRO so subclasses inherit them."""
    docs: dict[str, str] = {}
    for klass in reversed(obj.__mro__) if inspect.isclass(obj) else (obj,):
        try:
            tree = ast.parse(inspect.cleandoc("\n" + inspect.getsource(klass)))
        except (OSError, TypeError, SyntaxError):
            continue
        body = tree.body[0].body if tree.body and hasattr(tree.body[0], "body") else []
        for a, b in itertools.pairwise(body):
            target = (
                a.target
                if isinstance(a, ast.AnnAssign)
                else (a.targets[0] if isinstance(a, ast.Assign) and len(a.targets) == 1 else None)
            )
            name = (
                target.id
                if isinstance(target, ast.Name)
                else target.attr
                if isinstance(target, ast.Attribute)
                else None
            )
            if (
                name
                and isinstance(b, ast.Expr)
                and isinstance(b.value, ast.Constant)
                and isinstance(b.value.value, str)
            ):
                docs[name] = " ".join(b.value.value.split())
    return docs


def _unit(doc: str) -> str:
    """The unit of a field: the last ``[...]`` of its docstring that is not a tag like [T10]."""
    units = [u for u in re.findall(r"\[([^\[\]]*)\]", doc or "") if not re.fullmatch(r"T\d+.*", u)]
    return units[-1] if units else ""


@dataclasses.dataclass(frozen=True)
class Key:
    """One key of a table: its annotation, default (``_REQUIRED`` if none) and docstring."""

    name: str
    annotation: Any
    default: Any
    doc: str

    @property
    def unit(self) -> str:
        return "-" if self.annotation is int else _unit(self.doc)

    @property
    def required(self) -> bool:
        return self.default is _REQUIRED


@dataclasses.dataclass(frozen=True)
class Schema:
    """The keys of one kind of table plus the pydantic validator built from them."""

    title: str
    keys: dict[str, Key]
    validator: Any
    cls: Any = None
    doc: str = ""


def _validator_annotation(k: Key):
    if k.name in LAW_FIELDS:  # validated separately against the law registry
        return Any
    ann = k.annotation
    if k.name in NAME_FIELDS:
        lit = Literal[tuple(NAME_FIELDS[k.name])]  # type: ignore[misc]
        return lit | None if k.default is None else lit
    if ann is float and isinstance(k.default, float) and math.isinf(k.default):
        return Annotated[float, pydantic.Field(allow_inf_nan=True)]
    return ann


def _make_schema(title: str, keys: list[Key], cls=None, doc: str = "") -> Schema:
    cfg = pydantic.ConfigDict(strict=True, extra="forbid", allow_inf_nan=False)
    fields = {k.name: (_validator_annotation(k), ... if k.required else k.default) for k in keys}
    validator = pydantic.create_model(f"{title.replace('.', '_')}_file", __config__=cfg, **fields)
    return Schema(title, {k.name: k for k in keys}, validator, cls, doc)


def _dataclass_schema(cls, title: str, skip=()) -> Schema:
    hints = typing.get_type_hints(cls)
    docs = _attribute_docs(cls)
    keys = []
    for f in dataclasses.fields(cls):
        if f.name in skip:
            continue
        default = (
            f.default
            if f.default is not dataclasses.MISSING
            else f.default_factory()
            if f.default_factory is not dataclasses.MISSING
            else _REQUIRED
        )
        keys.append(Key(f.name, hints[f.name], default, docs.get(f.name, "")))
    return _make_schema(title, keys, cls, " ".join((cls.__doc__ or "").split()))


def _model_schema() -> Schema:
    sig = inspect.signature(Model.__init__)
    hints = typing.get_type_hints(Model.__init__)
    docs = _attribute_docs(Model.__init__)
    docs.setdefault("name", "free-text name of the mechanism (provenance, plot titles) [-]")
    keys = [
        Key(p, hints[p], sig.parameters[p].default, docs.get(p, "")) for p in sig.parameters if p != "self"
    ]
    return _make_schema("model", keys, Model, "The mechanism's name and gravity (``Model.__init__``).")


def _ground_schema() -> Schema:
    points = _dataclass_schema(Body, "ground").keys["points"]
    return _make_schema(
        "ground",
        [dataclasses.replace(points, doc="named fixed points in the world frame [m]")],
        None,
        "Fixed points of the ground (the body named ``ground``) in world coordinates.",
    )


@cache
def schemas() -> dict[str, Any]:
    """All file schemas: ``model``, ``ground``, ``body``, ``simulation`` (each a
    :class:`Schema`) and ``joints``/``elements``/``contact``/``friction`` (name -> Schema)."""
    return {
        "model": _model_schema(),
        "ground": _ground_schema(),
        "body": _dataclass_schema(Body, "bodies.<name>", skip=("name",)),
        "joints": {n: _dataclass_schema(c, f"joints type = {n!r}") for n, c in CONSTRAINTS.items()},
        "elements": {n: _dataclass_schema(c, f"elements type = {n!r}") for n, c in FORCE_ELEMENTS.items()},
        "contact": {n: _dataclass_schema(c, f"contact law = {n!r}") for n, c in CONTACT_LAWS.items()},
        "friction": {n: _dataclass_schema(c, f"friction law = {n!r}") for n, c in FRICTION_LAWS.items()},
        "simulation": _dataclass_schema(SimConfig, "simulation"),
    }


def type_name(ann) -> str:
    """Human name of an annotation as it is written in a file."""
    origin, args = typing.get_origin(ann), typing.get_args(ann)
    if ann is float:
        return "number"
    if ann is int:
        return "integer"
    if ann is str:
        return "string"
    if ann is bool:
        return "boolean"
    if ann is Any or ann is object:
        return "inline table"
    if origin is Literal:
        return "one of " + ", ".join(repr(a) for a in args)
    if origin is tuple:
        if len(args) == 2 and args[1] is Ellipsis:
            return f"array of {type_name(args[0])}s"
        if len(set(args)) == 1:
            return f"array of {len(args)} {type_name(args[0])}s"
        return "array [" + ", ".join(type_name(a) for a in args) + "]"
    if origin is dict:
        return f"table of name = {type_name(args[1])}"
    if origin is typing.Union or type(ann).__name__ == "UnionType":
        rest = [a for a in args if a is not type(None)]
        return " or ".join(type_name(a) for a in rest) + " (omit for none)"
    if origin is Annotated:
        return type_name(args[0])
    return getattr(ann, "__name__", str(ann))


# -- locating keys in the text -----------------------------------------------------------------
def _key_path(src: str) -> tuple | None:
    """The key path of a TOML key expression (``a.b``, ``"x y".c``), parsed by tomllib itself."""
    try:
        d = tomllib.loads(f"{src} = 0")
    except tomllib.TOMLDecodeError:
        return None
    path = []
    while isinstance(d, dict) and len(d) == 1:
        k = next(iter(d))
        path.append(k)
        d = d[k]
    return tuple(path)


_HEADER = re.compile(r"^\[\s*([^\[\]]+?)\s*\]")
_KEYLINE = re.compile(
    r"^((?:[A-Za-z0-9_\-]+|\"[^\"]*\"|'[^']*')(?:\s*\.\s*(?:[A-Za-z0-9_\-]+|\"[^\"]*\"|'[^']*'))*)\s*="
)


def _line_index(text: str) -> dict[tuple, int]:
    """Map key paths (tables and keys) to their first line number (1-based)."""
    index: dict[tuple, int] = {}
    current: tuple = ()
    for n, line in enumerate(text.splitlines(), 1):
        s = line.strip()
        if not s or s.startswith("#"):
            continue
        m = _HEADER.match(s)
        if m and not s.startswith("[["):
            p = _key_path(m.group(1))
            if p is not None:
                current = p
                for i in range(1, len(p) + 1):
                    index.setdefault(p[:i], n)
            continue
        m = _KEYLINE.match(s)
        if m:
            p = _key_path(m.group(1))
            if p is not None:
                for i in range(1, len(p) + 1):
                    index.setdefault(current + p[:i], n)
    return index


class _Context:
    """Where a document came from, for error messages."""

    def __init__(self, source: str, text: str = "", overridden: dict | None = None):
        self.source = source
        self.index = _line_index(text) if text else {}
        self.overridden = overridden or {}

    def where(self, key: tuple) -> str:
        for i in range(len(key), 0, -1):
            if key[:i] in self.overridden:
                return f"{self.source} (--set {self.overridden[key[:i]]})"
        for i in range(len(key), 0, -1):
            if key[:i] in self.index:
                return f"{self.source}:{self.index[key[:i]]}"
        return self.source

    def error(self, key: tuple, msg: str) -> ModelError:
        dotted = ".".join(str(k) for k in key) if key else "(file)"
        text = " ".join(f"{self.where(tuple(key))}: {dotted}: {msg}".split())
        return ModelError(text)


# -- validation --------------------------------------------------------------------------------
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
    """Turn a dataclass ``ValueError`` ("Cls.field = v [unit]: must be ...") into a keyed error."""
    msg = str(err)
    m = re.search(r"(?:^|[\s:])(?:\w+\.)?(\w+) = ", msg)
    if m and m.group(1) in names:
        return ctx.error(key + (m.group(1),), msg)
    return ctx.error(key, msg)


def _law(ctx: _Context, value, key: tuple, family: str):
    registry = LAW_FIELDS[family]
    if value is None:
        return None
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
    if assemble:
        try:
            model.compile()
        except ModelError as err:
            m = re.match(r"element '([^']*)': (.*)", str(err))
            if m and m.group(1) in seen:
                raise ctx.error((seen[m.group(1)], m.group(1)), m.group(2)) from None
            raise ctx.error(("joints",), f"{err}") from None
    return model, config


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


# -- reading -----------------------------------------------------------------------------------
def _read(path) -> tuple[dict, str]:
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ModelError(f"{path}: no such model file") from None
    except UnicodeDecodeError as err:
        raise ModelError(f"{path}: not a UTF-8 text file ({err.reason} at byte {err.start})") from None
    try:
        return tomllib.loads(text), text
    except tomllib.TOMLDecodeError as err:
        msg = str(err)
        m = re.search(r"\(at line (\d+), column (\d+)\)", msg)
        line = int(m.group(1)) if m else None
        bare = re.sub(r"\s*\(at (line \d+, column \d+|end of document)\)", "", msg)
        key = ""
        if line is not None:
            src = text.splitlines()[line - 1].strip() if line <= len(text.splitlines()) else ""
            h = _HEADER.match(src)
            k = _KEYLINE.match(src)
            p = _key_path(h.group(1)) if h else None
            if p is None and k:
                table = ()
                for prev in text.splitlines()[: line - 1]:
                    hh = _HEADER.match(prev.strip())
                    if hh and _key_path(hh.group(1)) is not None:
                        table = _key_path(hh.group(1))
                p = table + (_key_path(k.group(1)) or ())
            key = ".".join(p) + ": " if p else ""
        if "twice" in bare or "overwrite" in bare:
            bare = f"duplicate name: TOML forbids defining a key or table twice ({bare})"
        loc = f"{path}:{line}" if line is not None else f"{path}"
        raise ModelError(" ".join(f"{loc}: {key}invalid TOML: {bare}".split())) from None


def load_model(path, overrides=()) -> tuple[Model, SimConfig]:
    """Read a TOML model file (plus dotted ``key=value`` overrides) into (Model, SimConfig).

    Raises :class:`ModelError` with one line naming the file, line, dotted key, unit and the
    allowed range or valid keys. The model is assembled once to check that it can be.
    """
    doc, text = _read(path)
    doc = apply_overrides(doc, overrides)
    overridden = {}
    for ov in overrides:
        p = _key_path(ov.split("=", 1)[0].strip())
        if p:
            overridden[p] = ov
    return build(doc, str(path), text, overridden)


# -- writing -----------------------------------------------------------------------------------
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
    Path(path).write_text(dumps(model, config, header), encoding="utf-8")


# -- running -----------------------------------------------------------------------------------
_LAMBDA_UNITS = {"revolute": ("N", "N"), "translational": ("N", "N·m"), "angle_driver": ("N·m",)}


def write_timeseries(results, path) -> None:
    """CSV of time, all coordinates, velocities and multipliers (SI, units in the header)."""
    import numpy as np

    s = results.system
    units = {"x": "m", "y": "m", "phi": "rad"}
    cols = ["time [s]"]
    cols += [f"{lab} [{units[lab.rsplit('.', 1)[1]]}]" for lab in s.coordinate_labels()]
    cols += [f"{lab}_dot [{units[lab.rsplit('.', 1)[1]]}/s]" for lab in s.coordinate_labels()]
    names = {cls: n for n, cls in CONSTRAINTS.items()}
    for name, c, (a, b) in zip(s.constraint_names, s.constraints, s.constraint_rows):
        u = _LAMBDA_UNITS.get(names.get(type(c)), ())
        cols += [f"lambda.{name}[{r}]" + (f" [{u[r]}]" if r < len(u) else "") for r in range(b - a)]
    data = np.column_stack([results.t, results.q, results.qd, results.lam])
    np.savetxt(path, data, delimiter=",", header=",".join(cols), comments="", fmt="%.17g")


def run_model_file(path, out_dir, overrides=()):
    """Load a model file, simulate it and write ``results.nc``, ``timeseries.csv`` and the
    resolved model (``model.toml``, overrides applied) into ``out_dir``. Returns the Results.

    On a :class:`~jointdyn.errors.SimulationError` the partial results are written first, then
    the error is re-raised.
    """
    from .errors import SimulationError

    model, config = load_model(path, overrides)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    save_model(
        model,
        config,
        out / "model.toml",
        header=f"resolved from {path}" + (f" with {list(overrides)}" if overrides else ""),
    )
    system = model.compile()
    try:
        res = simulate(system, config)
    except SimulationError as err:
        if err.results is not None:
            err.results.meta["model_file"] = str(path)
            err.results.save(out / "results.nc")
            write_timeseries(err.results, out / "timeseries.csv")
        raise
    res.meta["model_file"] = str(path)
    res.meta["overrides"] = list(overrides)
    res.save(out / "results.nc")
    write_timeseries(res, out / "timeseries.csv")
    return res
