"""Regenerate docs/model_files.md from the registries' dataclasses and tests/data/bad_models/.

Run from the repository root:  python docs/_gen_model_files.py
The key tables come from ``jointdyn.io.modelfile.schemas()`` (the dataclass fields, their type hints,
defaults and docstrings); the bad-model table is the actual error each file gives.
"""

from __future__ import annotations

import math
from pathlib import Path

from jointdyn.errors import ModelError
from jointdyn.film.models import FILM_MODELS
from jointdyn.integrators import SOLVERS
from jointdyn.io import modelfile as C

ROOT = Path(__file__).resolve().parents[1]
BAD = ROOT / "tests" / "data" / "bad_models"

INTRO = '''# Model files (TOML)

A model file describes one planar mechanism and how to integrate it. It is read by
`jointdyn.io.modelfile.load_model(path, overrides=()) -> (Model, SimConfig)` and written by
`save_model(model, config, path)`; `jointdyn run FILE.toml --out DIR` (or
`jointdyn.studies.runs.run_model_file(path, out_dir, overrides)`) simulates it and writes the same files
as every run: `results.nc`, `timeseries.csv` (time, the coordinates, velocities, multipliers and
every element's outputs, units in the headers), `summary.json`, figures, `model.toml` (the
resolved model) and `manifest.json` (see [the command line](user-guide/cli.md)). Shipped
examples: `examples/*.toml`.

**SI units everywhere** (m, kg, s, rad, N); the unit of every key is in the tables below. There
is no unit conversion in a file: write 523.5987755982989 rad/s, not "5000 rpm".

```toml
[model]                       # optional: name, gravity
name = "pendulum"
gravity = [0.0, -9.81]        # [m/s²]

[ground.points]               # fixed points, world frame [m]
O = [0.0, 0.0]

[bodies.bar]                  # one table per moving body; frame at its centre of mass
mass = 1.0                    # [kg]
inertia = 0.1                 # [kg·m²]
position = [0.5, 0.0]         # initial guess [m]; the assembly corrects it
points = { pin = [-0.5, 0.0] }

[joints.pivot]                # ideal joints (constraints): type = a CONSTRAINTS name
type = "revolute"
body_i = "ground"
point_i = "O"
body_j = "bar"
point_j = "pin"

[elements.pin]                # force elements: type = a FORCE_ELEMENTS name
# type = "clearance_joint", ..., contact = { law = "lankarani_nikravesh", stiffness = 6.9e10 }

[simulation]                  # the SimConfig fields
t_end = 0.1                   # [s]
```

## Rules

- **One schema.** The keys of `[bodies.*]`, `[joints.*]`, `[elements.*]`, the `contact`/`friction`
  inline tables and `[simulation]` are the fields of the dataclasses registered in
  `CONSTRAINTS`, `FORCE_ELEMENTS`, `CONTACT_LAWS`, `FRICTION_LAWS`, `Body` and `SimConfig`
  (ARCHITECTURE rule 5); a new field or registry entry is accepted by files automatically.
  The validators are pydantic models built from those fields; the range checks are the
  dataclasses' own `validate()`/`__post_init__` and `Model.compile()`.
- **Strict.** Unknown keys, missing required keys, wrong types (a string `"1.0"` or `true`
  where a number is needed, a float where an integer is needed), arrays of the wrong length,
  NaN and ±inf (except `max_step = inf`, its default), out-of-range values, unknown
  `type`/`law`/`film`/`solver` names, unknown bodies or points, a joint from a body to itself,
  duplicate names, an empty file and a mechanism that cannot be assembled are all errors.
- **Errors are one line**: `<file>:<line>: <dotted.key>: <what> [unit] <allowed range or valid
  keys>` (a `jointdyn.errors.ModelError`). See the table at the end.
- **Optional values** (`None` in Python, e.g. `friction`, `Translational.angle`,
  `SimConfig.baumgarte`) are written by leaving the key out: TOML has no null.
- **Names**: joints and elements share one namespace; `ground` is reserved for the fixed frame.
  Tables are assembled in file order (joint order = multiplier order).
- **No code is evaluated**: `tomllib` returns plain data; names are looked up in literal dicts.
- **Bearing/journal convention**: in `clearance_joint` and `journal_bearing` the bearing
  (bushing, hole) is on `body_i`, the journal (pin) on `body_j`.

## Overrides

`load_model(path, ["bodies.crank.mass=0.35", "elements.piston_pin.contact.restitution=0.7",
"simulation.solver=rodas4"])` (the CLI's `--set`). The value is TOML (`0.3`, `[0.0, -9.81]`,
`"rodas4"`, `{ law = "coulomb", coefficient = 0.1 }`; a bare word is taken as a string). A key
not allowed at its level is an error listing the valid keys there; new names are allowed only
under `points`. Errors in an overridden value name the override instead of a line.

## Round trip

`save_model` writes every field (floats with `repr`, so they read back bit-identical; `None`
fields omitted) and `load_model` of that file gives a model with the same `Model.to_dict()` and
an equal `SimConfig` (tested in `tests/test_config.py`).
'''


#: meanings of the topology fields, which carry no docstring in the dataclasses
FALLBACK = {"body_i": "body i: a `[bodies]` name or `\"ground\"` (the bearing side of journal elements)",
            "body_j": "body j: a `[bodies]` name or `\"ground\"` (the journal side of journal elements)",
            "point_i": "a point of body i (`points` of the body, or `[ground.points]`)",
            "point_j": "a point of body j"}


def _default(k: C.Key) -> str:
    if k.required:
        return "**required**"
    d = k.default
    if d is None:
        return "omitted (None)"
    if isinstance(d, float) and math.isinf(d):
        return "inf"
    try:
        return f"`{C.toml_value(d)}`"
    except TypeError:
        return f"`{d!r}`"


def _table(schema: C.Schema, extra: list[tuple[str, str, str, str, str]] = ()) -> list[str]:
    out = ["| key | type | default | unit | meaning |", "|---|---|---|---|---|"]
    for row in extra:
        out.append("| " + " | ".join(row) + " |")
    for k in schema.keys.values():
        typ = C.type_name(C._validator_annotation(k))
        if k.name in C.NAME_FIELDS and k.name in C.LAW_FIELDS:
            typ = f"string (a {k.name} model name) or inline table `{{ law = ..., ... }}`"
        elif k.name in C.LAW_FIELDS:
            typ = f"inline table `{{ law = ..., ... }}` ({k.name} law)"
        doc = (k.doc or FALLBACK.get(k.name, "—")).replace("|", "\\|")
        out.append(f"| `{k.name}` | {typ} | {_default(k)} | {k.unit or '—'} | {doc} |")
    return out + [""]


def _first_sentence(doc: str) -> str:
    """The first paragraph of a docstring, on one line."""
    para = (doc or "").strip().split("\n\n")[0]
    return " ".join(para.split())


def reference() -> list[str]:
    s = C.schemas()
    out = ["## Reference (generated from the dataclasses by `docs/_gen_model_files.py`)", ""]
    out += ["### `[model]` (optional)", "", s["model"].doc, ""] + _table(s["model"])
    out += ["### `[ground]`", "", s["ground"].doc + " Usually written `[ground.points]`.", ""]
    out += _table(s["ground"])
    out += ["### `[bodies.<name>]`", "", s["body"].doc, ""] + _table(s["body"])
    for family, title in (("joints", "`[joints.<name>]`: ideal joints (constraints)"),
                          ("elements", "`[elements.<name>]`: force elements")):
        out += [f"### {title}", ""]
        for name, sch in s[family].items():
            out += [f"#### `type = \"{name}\"` ({sch.cls.__name__})", "", _first_sentence(sch.cls.__doc__), ""]
            out += _table(sch, [("`type`", "string", "**required**", "—", f"`\"{name}\"`")])
    for family in ("contact", "friction", "asperity", "thermal"):
        out += [f"### `{family} = {{ law = ..., ... }}`: {family} laws", ""]
        for name, sch in s[family].items():
            out += [f"#### `law = \"{name}\"` ({sch.cls.__name__})", "", _first_sentence(sch.cls.__doc__), ""]
            out += _table(sch, [("`law`", "string", "**required**", "—", f"`\"{name}\"`")])
    out += ["### Film models (`film = ...` of `journal_bearing`)", "",
            "A name (`film = \"finite\"`, the model with its defaults) or an inline table with the model's own",
            "keys (`film = { law = \"finite\", cavitation = \"reynolds\" }`).", "",
            "| name | model |", "|---|---|"]
    out += [f"| `{n}` | {_first_sentence(c.__doc__)} |" for n, c in FILM_MODELS.items()] + [""]
    for name, sch in s["film"].items():
        if sch.keys:
            out += [f"#### `law = \"{name}\"` ({sch.cls.__name__})", ""]
            out += _table(sch, [("`law`", "string", "**required**", "—", f"`\"{name}\"`")])
    out += ["### `[simulation]` (required)", "", s["simulation"].doc, ""] + _table(s["simulation"])
    out += ["Solvers (`solver = ...`):", "", "| name | description |", "|---|---|"]
    out += [f"| `{n}` | {v[2]} |" for n, v in SOLVERS.items()] + [""]
    return out


def bad_models() -> list[str]:
    out = ["## Bad model files and their errors", "",
           "Each file in `tests/data/bad_models/` has one defect; `tests/test_config.py` checks that it",
           "raises a one-line `ModelError` naming the file, the line and the key listed in",
           "`tests/data/bad_models/EXPECTED.toml`. The messages below are the actual output.", "",
           "| file | defect | error |", "|---|---|---|"]
    for p in sorted(BAD.glob("*.toml")):
        if p.name == "EXPECTED.toml":
            continue
        first = p.read_text(encoding="utf-8").splitlines()[:1]
        what = first[0].removeprefix("# bad model: ") if first and first[0].startswith("#") else "an empty file"
        try:
            C.load_model(p)
            msg = "(no error!)"
        except ModelError as err:
            msg = str(err).replace(str(p), p.name)
        msg = msg.replace("|", "\\|")
        out.append(f"| `{p.name}` | {what} | `{msg}` |")
    return out + [""]


def main() -> None:
    text = "\n".join([INTRO] + reference() + bad_models())
    (ROOT / "docs" / "model_files.md").write_text(text, encoding="utf-8")
    print(f"wrote docs/model_files.md ({len(text.splitlines())} lines)")


if __name__ == "__main__":
    main()
