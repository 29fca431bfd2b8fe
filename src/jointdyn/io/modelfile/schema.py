"""Model-file schema, derived from the registries' dataclass fields (no second schema).

Each table kind (``[model]``, ``[ground]``, ``[bodies.*]``, ``[joints.*]`` per constraint type,
``[elements.*]`` per force element type, contact/friction law inline tables, ``[simulation]``)
gets a :class:`Schema`: its keys (name, type hint, default, docstring with the unit) and a strict
pydantic validator built once from ``dataclasses.fields`` (``Model.__init__``'s signature for
``[model]``).
"""

from __future__ import annotations

import ast
import dataclasses
import inspect
import itertools
import math
import re
import typing
from functools import cache
from typing import Annotated, Any, Literal

import pydantic

from jointdyn.core.constraints import CONSTRAINTS
from jointdyn.film.models import FILM_MODELS
from jointdyn.forces.contact_laws import CONTACT_LAWS
from jointdyn.forces.elements import FORCE_ELEMENTS
from jointdyn.forces.friction_laws import FRICTION_LAWS
from jointdyn.forces.mixed import ASPERITY_MODELS
from jointdyn.forces.thermal import THERMAL_MODELS
from jointdyn.integrators import SOLVERS
from jointdyn.multibody.codec import LAW_FIELDS
from jointdyn.multibody.model import Body, Model
from jointdyn.simulation.simulate import SimConfig

TOP_LEVEL = ("model", "ground", "bodies", "joints", "elements", "simulation")
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
        "film": {n: _dataclass_schema(c, f"film law = {n!r}") for n, c in FILM_MODELS.items()},
        "thermal": {n: _dataclass_schema(c, f"thermal law = {n!r}") for n, c in THERMAL_MODELS.items()},
        "asperity": {n: _dataclass_schema(c, f"asperity law = {n!r}") for n, c in ASPERITY_MODELS.items()},
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
