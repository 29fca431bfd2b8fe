"""Model files: strict TOML -> (:class:`~jointdyn.multibody.model.Model`,
:class:`~jointdyn.simulation.simulate.SimConfig`).

Layout (every table and key with its unit: ``docs/model_files.md``)::

    [model]              name, gravity = [g_x, g_y] [m/s²]
    [ground.points]      O = [x, y]  (world frame) [m]
    [bodies.<name>]      the fields of ``Body`` (mass, inertia, position, angle, velocity, points)
    [joints.<name>]      type = a name in ``CONSTRAINTS``, then that dataclass's fields
    [elements.<name>]    type = a name in ``FORCE_ELEMENTS``, then that dataclass's fields; a law
                         field is an inline table ``{ law = <name in CONTACT_LAWS or
                         FRICTION_LAWS>, <the law's fields> }``
    [simulation]         the fields of ``SimConfig``

One module per job: :mod:`.schema` (the schema, derived from the registries' dataclass fields —
there is no second schema), :mod:`.locate` (dotted key -> file line, keyed messages),
:mod:`.load` (validation, overrides, reading) and :mod:`.dump` (writing). Every problem is one
:class:`~jointdyn.errors.ModelError` line ``<file>:<line>: <dotted.key>: <what is wrong> [unit]
<allowed range or valid keys>``. Running a model file is :func:`jointdyn.studies.runs.run_model_file`.
"""

from __future__ import annotations

from jointdyn.io.modelfile.dump import dumps, save_model, toml_value
from jointdyn.io.modelfile.load import apply_overrides, build, load_model, load_system, with_keys
from jointdyn.io.modelfile.schema import (
    LAW_FIELDS,
    NAME_FIELDS,
    TOP_LEVEL,
    Key,
    Schema,
    _validator_annotation,
    schemas,
    type_name,
)

__all__ = [
    "LAW_FIELDS",
    "NAME_FIELDS",
    "TOP_LEVEL",
    "Key",
    "Schema",
    "_validator_annotation",
    "apply_overrides",
    "build",
    "dumps",
    "load_model",
    "load_system",
    "save_model",
    "schemas",
    "toml_value",
    "type_name",
    "with_keys",
]
