"""Writing (Model, SimConfig) as a model file that :func:`~jointdyn.io.modelfile.load_model` reads back
identically: the model part is :mod:`jointdyn.multibody.codec`'s TOML text, then ``[simulation]``."""

from __future__ import annotations

import dataclasses
from pathlib import Path

from jointdyn.core import atomic
from jointdyn.multibody import codec
from jointdyn.multibody.codec import toml_value
from jointdyn.multibody.model import Model
from jointdyn.simulation.simulate import SimConfig

__all__ = ["dumps", "save_model", "toml_value"]


def dumps(model: Model, config: SimConfig, header: str = "") -> str:
    """The TOML text of (model, config); :func:`load_model` reads it back identically."""
    simulation = {f.name: getattr(config, f.name) for f in dataclasses.fields(config)}
    return codec.to_toml(model.to_dict(), header, {"simulation": simulation})


def save_model(model: Model, config: SimConfig, path, header: str = "") -> None:
    """Write (model, config) as a TOML model file (no extra dependency)."""
    atomic.write_text(Path(path), dumps(model, config, header))
