"""Simulation results: time-first arrays plus provenance; save as netCDF, export CSV."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from importlib.metadata import version as _pkg_version

import numpy as np

from .forces.journal import OUTPUTS as _JOURNAL_OUTPUTS
from .system import System

# labels of the saved "output" dimension: the journal elements' outputs (the widest declaration;
# other elements' columns are named by their class's OUTPUTS, see Results.element)
OUT_COLUMNS = tuple(_JOURNAL_OUTPUTS)


def _version() -> str:
    try:
        return _pkg_version("jointdyn")
    except Exception:  # pragma: no cover - running from a source tree
        return "unknown"


@dataclass
class Results:
    """Arrays are time-first: ``t`` (n_t,) [s], ``y`` (n_t, 2n) = [q, q̇] (SI), ``qdd`` (n_t, n),
    ``lam`` (n_t, m) multipliers (meaning per constraint type, see ``joints.constraints``),
    ``eout`` (n_t, n_elements, len(OUT_COLUMNS)) element outputs, ``drift`` (n_t, 2) =
    max |Φ| [m or rad] and max |Φ̇| [m/s or rad/s]."""

    system: System
    t: np.ndarray
    y: np.ndarray
    mem: np.ndarray
    qdd: np.ndarray
    lam: np.ndarray
    eout: np.ndarray
    drift: np.ndarray
    stats: dict
    wall_time: float
    config: dict
    status: int = 0
    meta: dict = field(default_factory=dict)

    @property
    def q(self) -> np.ndarray:
        return self.y[:, : self.system.n]

    @property
    def qd(self) -> np.ndarray:
        return self.y[:, self.system.n :]

    def coordinate(self, body: str, which: str) -> np.ndarray:
        """Time series of ``body``'s ``x``, ``y`` or ``phi`` [m or rad]."""
        return self.q[:, 3 * self.system.body_index(body) + {"x": 0, "y": 1, "phi": 2}[which]]

    def multipliers(self, constraint: str) -> np.ndarray:
        """λ rows of a named constraint, (n_t, rows)."""
        return self.lam[:, self.system.rows_of(constraint)]

    def _element(self, name: str):
        names = self.system.element_names
        if name not in names:
            raise KeyError(f"no force element named {name!r}; elements are {list(names)}")
        k = names.index(name)
        return k, type(self.system.elements[k])

    def element(self, name: str, output: str) -> np.ndarray:
        """Time series of output ``output`` of force element ``name`` (see the element class's
        ``OUTPUTS``, which also gives the unit)."""
        k, cls = self._element(name)
        if output not in cls.OUTPUTS:
            valid = list(cls.OUTPUTS)
            raise KeyError(f"element {name!r} ({cls.__name__}) has no output {output!r}; valid: {valid}")
        return self.eout[:, k, list(cls.OUTPUTS).index(output)]

    def memory(self, name: str, slot: str) -> np.ndarray:
        """Time series of memory slot ``slot`` of force element ``name`` (see the element
        class's ``MEMORY``), as stored at the output samples."""
        k, cls = self._element(name)
        if slot not in cls.MEMORY:
            valid = list(cls.MEMORY)
            raise KeyError(f"element {name!r} ({cls.__name__}) has no memory slot {slot!r}; valid: {valid}")
        return self.mem[:, k, list(cls.MEMORY).index(slot)]

    def to_dataset(self):
        """xarray Dataset with the provenance in its attributes."""
        import xarray as xr

        s = self.system
        coords = {
            "time": self.t,
            "coordinate": s.coordinate_labels(),
            "row": self._row_labels(),
            "element": list(s.element_names),
            "output": list(OUT_COLUMNS),
        }
        ds = xr.Dataset(
            {
                "q": (("time", "coordinate"), self.q),
                "qd": (("time", "coordinate"), self.qd),
                "qdd": (("time", "coordinate"), self.qdd),
                "lam": (("time", "row"), self.lam),
                "element_outputs": (("time", "element", "output"), self.eout),
                "drift_position": ("time", self.drift[:, 0]),
                "drift_velocity": ("time", self.drift[:, 1]),
            },
            coords=coords,
        )
        ds["time"].attrs["units"] = "s"
        ds.attrs.update(self._provenance())
        return ds

    def save(self, path) -> None:
        """Write netCDF4 with h5netcdf directly (the same layout and attributes as
        :meth:`to_dataset`; ~10× faster to start than going through xarray's writer)."""
        import h5netcdf
        import h5py

        s = self.system
        labels = {
            "coordinate": s.coordinate_labels(),
            "row": self._row_labels(),
            "element": list(s.element_names),
            "output": list(OUT_COLUMNS),
        }
        with h5netcdf.File(path, "w") as f:
            f.dimensions = {"time": len(self.t), **{k: len(v) for k, v in labels.items()}}
            v = f.create_variable("time", ("time",), float)
            v[:] = self.t
            v.attrs["units"] = "s"
            for k, vals in labels.items():
                if vals:
                    f.create_variable(k, (k,), h5py.string_dtype())[:] = np.array(vals, dtype=object)
            for name, dims, arr in (
                ("q", ("time", "coordinate"), self.q),
                ("qd", ("time", "coordinate"), self.qd),
                ("qdd", ("time", "coordinate"), self.qdd),
                ("lam", ("time", "row"), self.lam),
                ("element_outputs", ("time", "element", "output"), self.eout),
                ("drift_position", ("time",), self.drift[:, 0]),
                ("drift_velocity", ("time",), self.drift[:, 1]),
            ):
                f.create_variable(name, dims, float)[...] = arr
            f.attrs.update(self._provenance())

    def _row_labels(self) -> list[str]:
        s = self.system
        return [
            f"{n}[{r - a}]" for n, (a, b) in zip(s.constraint_names, s.constraint_rows) for r in range(a, b)
        ]

    def _provenance(self) -> dict:
        s = self.system
        return {
            "jointdyn_version": _version(),
            "model": json.dumps(s.model_dict, default=list),
            "config": json.dumps(self.config, default=str),
            "stats": json.dumps(self.stats),
            "wall_time_s": self.wall_time,
            "status": self.status,
            "meta": json.dumps(self.meta, default=str),
        }


def load(path):
    """Read a results file written by :meth:`Results.save` as an xarray Dataset."""
    import xarray as xr

    return xr.load_dataset(path, engine="h5netcdf")
