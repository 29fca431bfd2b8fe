"""Re-open a saved run (``results.nc`` of ``jointdyn run``) as a Results object."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

_JOINT_TYPES = ("revolute", "translational", "angle_driver")


def model_document(model_dict: dict) -> dict:
    """The model-file document (tables model/ground/bodies/joints/elements) of a
    ``Model.to_dict()`` dictionary (as stored in the ``model`` attribute of results.nc)."""
    items = model_dict.get("items", {})

    def clean(v):
        if isinstance(v, dict):
            return {k: clean(x) for k, x in v.items() if x is not None}
        return v

    return {
        "model": {
            "name": model_dict.get("name", "model"),
            "gravity": list(model_dict.get("gravity", (0, 0))),
        },
        "ground": {"points": model_dict.get("ground_points", {})},
        "bodies": clean(model_dict.get("bodies", {})),
        "joints": {k: clean(v) for k, v in items.items() if v.get("type") in _JOINT_TYPES},
        "elements": {k: clean(v) for k, v in items.items() if v.get("type") not in _JOINT_TYPES},
        "simulation": {"t_end": 1.0},
    }


def load_run(directory):
    """Results of ``DIR/results.nc`` with the System rebuilt from the stored model. The element
    memory is not stored in results.nc: ``mem`` is zero (quantities that need it, such as the
    impact counter, are unavailable from a reloaded run)."""
    from ..config import build
    from ..results import Results, load

    path = Path(directory)
    path = path / "results.nc" if path.is_dir() else path
    if not path.exists():
        raise ValueError(f"{path}: no results file (run `jointdyn run … --out DIR` first)")
    ds = load(path)
    model, _ = build(model_document(json.loads(ds.attrs["model"])), source=str(path), assemble=False)
    system = model.compile()
    n = system.n
    t = ds["time"].values
    y = np.concatenate([ds["q"].values, ds["qd"].values], axis=1)
    if y.shape[1] != 2 * n:
        raise ValueError(f"{path}: stored coordinates ({y.shape[1] // 2}) do not match the model ({n})")
    return Results(
        system=system,
        t=t,
        y=y,
        mem=np.zeros((t.size, *system.mem0.shape)),
        qdd=ds["qdd"].values,
        lam=ds["lam"].values,
        eout=ds["element_outputs"].values,
        drift=np.stack([ds["drift_position"].values, ds["drift_velocity"].values], axis=1),
        stats=json.loads(ds.attrs.get("stats", "{}")),
        wall_time=float(ds.attrs.get("wall_time_s", 0.0)),
        config=json.loads(ds.attrs.get("config", "{}")),
    )
