"""Simulation results: time-first arrays plus provenance; save/load as netCDF, export to xarray.

Array layout is **time-first**: ``res.y[i]`` is the state at ``res.t[i]``, shape (n_t, 2n). This is
the transpose of scipy's ``solve_ivp(...).y`` (state-first, (2n, n_t)); use ``res.y.T`` where
scipy's layout is expected.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field, replace
from importlib.metadata import version as _pkg_version
from pathlib import Path

import numpy as np

from jointdyn.core import atomic
from jointdyn.forces.elements import memory_slots as _memory_slots
from jointdyn.forces.elements import output_slots
from jointdyn.multibody.model import Model
from jointdyn.multibody.system import System
from jointdyn.simulation.saved import load_arrays, load_dataset

#: netCDF variables of the archival layout: name -> (dimensions, unit)
_VARIABLES = {
    "q": (("time", "coordinate"), "m or rad (per coordinate, see coordinate_unit)"),
    "qd": (("time", "coordinate"), "m/s or rad/s (per coordinate, see coordinate_unit)"),
    "qdd": (("time", "coordinate"), "m/s² or rad/s² (per coordinate, see coordinate_unit)"),
    "lam": (("time", "row"), "N or N·m (per constraint row: force of a position row, moment of a driver)"),
    "element_outputs": (("time", "element", "output"), "per element type, see attribute element_units"),
    "element_memory": (("time", "element", "memory"), "per element type, see attribute element_units"),
    "drift_position": (("time",), "m or rad (max |Φ|)"),
    "drift_velocity": (("time",), "m/s or rad/s (max |Φ̇|)"),
}


def _version() -> str:
    try:
        return _pkg_version("jointdyn")
    except Exception:  # pragma: no cover - running from a source tree
        return "unknown"


@dataclass
class Results:
    """One run. Arrays are **time-first** (row i belongs to ``t[i]``; scipy's ``sol.y`` is the
    transpose): ``t`` (n_t,) [s], ``y`` (n_t, 2n) = [q, q̇] (SI), ``qdd`` (n_t, n), ``lam``
    (n_t, m) multipliers (meaning per constraint type, see ``joints.constraints``), ``eout``
    (n_t, n_elements, 8) element outputs and ``mem`` (n_t, n_elements, 4) element memory (read
    both by name with :meth:`element` and :meth:`memory`), ``drift`` (n_t, 2) = max |Φ| [m or rad]
    and max |Φ̇| [m/s or rad/s]."""

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

    # -- arrays by name -----------------------------------------------------------------------
    @property
    def q(self) -> np.ndarray:
        """Coordinates (n_t, n) [m, m, rad per body]."""
        return self.y[:, : self.system.n]

    @property
    def qd(self) -> np.ndarray:
        """Velocities (n_t, n) [m/s, m/s, rad/s per body]."""
        return self.y[:, self.system.n :]

    def coordinate(self, body: str, which: str) -> np.ndarray:
        """Time series of ``body``'s ``x``, ``y`` [m] or ``phi`` [rad]."""
        axes = {"x": 0, "y": 1, "phi": 2}
        if body not in self.system.body_names:
            raise KeyError(f"no body named {body!r}; bodies are {list(self.system.body_names)}")
        if which not in axes:
            raise KeyError(f"coordinate {which!r}: valid: {list(axes)}")
        return self.q[:, 3 * self.system.body_index(body) + axes[which]]

    def multipliers(self, constraint: str) -> np.ndarray:
        """λ rows of a named constraint, (n_t, rows)."""
        if constraint not in self.system.constraint_names:
            valid = list(self.system.constraint_names)
            raise KeyError(f"no constraint named {constraint!r}; constraints are {valid}")
        return self.lam[:, self.system.rows_of(constraint)]

    def _element(self, name: str):
        names = self.system.element_names
        if name not in names:
            raise KeyError(f"no force element named {name!r}; elements are {list(names)}")
        k = names.index(name)
        return k, type(self.system.elements[k])

    def element(self, name: str, output: str) -> np.ndarray:
        """Time series of output ``output`` of force element ``name`` (see the element's output
        slots, ``forces.elements.output_slots``, which also give the unit)."""
        k, cls = self._element(name)
        if output not in (valid := list(output_slots(self.system.elements[k]))):  # its first slots
            raise KeyError(f"element {name!r} ({cls.__name__}) has no output {output!r}; valid: {valid}")
        return self.eout[:, k, valid.index(output)]

    def memory(self, name: str, slot: str) -> np.ndarray:
        """Time series of memory slot ``slot`` of force element ``name`` (see the element
        class's ``MEMORY``), as stored at the output samples."""
        k, cls = self._element(name)
        if slot not in _memory_slots(self.system.elements[k]):
            valid = list(_memory_slots(self.system.elements[k]))
            raise KeyError(f"element {name!r} ({cls.__name__}) has no memory slot {slot!r}; valid: {valid}")
        return self.mem[:, k, list(cls.MEMORY).index(slot)]

    # -- convenience ----------------------------------------------------------------------------
    def journals(self) -> list[str]:
        """Names of the journal elements: those whose class declares an ``ORBIT`` (clearance
        joints and journal bearings)."""
        s = self.system
        return [n for n, e in zip(s.element_names, s.elements) if getattr(type(e), "ORBIT", None)]

    def clearance(self, name: str) -> float:
        """Radial clearance c = R_B − R_J of journal element ``name`` [m]."""
        k, cls = self._element(name)
        if name not in self.journals():
            raise KeyError(f"element {name!r} ({cls.__name__}) has no clearance; journals: {self.journals()}")
        return float(self.system.elements[k].clearance)

    def orbit(self, name: str, frame: str = "bushing") -> tuple[np.ndarray, np.ndarray]:
        """Journal-centre path of element ``name`` as (e_x/c, e_y/c) [-].

        ``frame="world"``: eccentricity components in the world frame (as the kernel writes them);
        ``frame="bushing"``: rotated into the frame of the bushing body (body i) [T14]."""
        c = self.clearance(name)
        x, y = self._element(name)[1].ORBIT
        ex, ey = self.element(name, x) / c, self.element(name, y) / c
        if frame == "world":
            return ex, ey
        if frame != "bushing":
            raise ValueError(f"frame = {frame!r}: valid: ['bushing', 'world']")
        body = self.system.elements[self.system.element_names.index(name)].body_i
        if body == "ground":
            return ex, ey
        phi = self.coordinate(body, "phi")
        cs, sn = np.cos(phi), np.sin(phi)
        return cs * ex + sn * ey, -sn * ex + cs * ey

    def driver(self) -> str:
        """Name of the first angle driver (the crank drive of a mechanism)."""
        for n, c in zip(self.system.constraint_names, self.system.constraints):
            if getattr(type(c), "DRIVES_ANGLE", False):
                return n
        names = list(self.system.constraint_names)
        raise KeyError(f"{self.system.name!r} has no angle driver; constraints: {names}")

    def crank_angle(self) -> np.ndarray:
        """Unwrapped angle of the body the first angle driver turns [rad]."""
        c = self.system.constraints[self.system.constraint_names.index(self.driver())]
        return self.coordinate(c.body_j, "phi")

    def last_revolutions(self, n: float = 1.0) -> Results:
        """The samples of the last ``n`` revolutions [-] of the driven body, as a new
        :class:`Results` (same system and provenance). Needs an angle driver."""
        if not (math.isfinite(n) and n > 0):
            raise ValueError(f"last_revolutions: n = {n!r} [revolutions]: must be > 0")
        a = self.crank_angle()
        span = abs(a[-1] - a[0])
        if n * 2 * np.pi > span * (1 + 1e-9):
            have = span / (2 * np.pi)
            raise ValueError(f"last_revolutions: n = {n!r} [revolutions]: must be ≤ {have:.6g} (the run)")
        # 1e-9 rad: the driver is exact to the constraint tolerance; keeps the sample at exactly n revs
        keep = np.abs(a[-1] - a) <= n * 2 * np.pi + 1e-9
        return self.select(keep)

    def select(self, index) -> Results:
        """A new :class:`Results` with only the samples ``index`` (mask, slice or integers)."""
        return replace(
            self,
            t=self.t[index],
            y=self.y[index],
            mem=self.mem[index],
            qdd=self.qdd[index],
            lam=self.lam[index],
            eout=self.eout[index],
            drift=self.drift[index],
        )

    def __repr__(self) -> str:
        s = self.system
        t = f"t = {self.t[0]:.4g}…{self.t[-1]:.4g} s, {len(self.t)} samples" if len(self.t) else "no samples"
        return (
            f"<Results {s.name!r}: {t}; {len(s.body_names)} bodies, {len(s.constraint_names)} "
            f"constraints, elements {list(s.element_names)}; solver {self.config.get('solver')!r}, "
            f"{self.stats.get('accepted_steps', '?')} steps, {self.wall_time:.3g} s, status {self.status}>"
        )

    def _repr_html_(self) -> str:
        import html

        s = self.system
        rows = [
            ("model", s.name),
            ("time", f"{self.t[0]:.6g} … {self.t[-1]:.6g} s ({len(self.t)} samples)" if len(self.t) else "–"),
            ("bodies", ", ".join(s.body_names)),
            ("constraints", ", ".join(s.constraint_names)),
            ("elements", ", ".join(f"{n} ({type(e).__name__})" for n, e in zip(s.element_names, s.elements))),
            (
                "solver",
                f"{self.config.get('solver')}, rtol {self.config.get('rtol')}, error scale "
                f"{self.config.get('error_scale', 'state')} (rtol {self.config.get('error_rtol')} of it)",
            ),
            ("steps", ", ".join(f"{k} {v}" for k, v in self.stats.items())),
            ("wall time", f"{self.wall_time:.3g} s"),
            ("status", str(self.status)),
        ]
        th = "<th style='text-align:left'>"
        body = "".join(f"<tr>{th}{k}</th><td>{html.escape(v)}</td></tr>" for k, v in rows)
        return f"<table><caption>jointdyn Results</caption>{body}</table>"

    # -- xarray / pandas ------------------------------------------------------------------------
    def to_dataset(self):
        """The archival layout of ``results.nc`` as an xarray Dataset (generic ``element_outputs``
        / ``element_memory`` arrays; names and units per element in the attribute
        ``element_units``). For named per-element variables use :meth:`to_xarray`."""
        import xarray as xr

        coords = self._coords()
        data = {k: (dims, arr) for k, (dims, arr) in self._arrays().items()}
        ds = xr.Dataset(data, coords={k: (k, v) for k, v in coords.items()})
        ds = ds.assign_coords(coordinate_unit=("coordinate", self._coordinate_units()))
        ds["time"].attrs["units"] = "s"
        for k, (_, unit) in _VARIABLES.items():
            ds[k].attrs["units"] = unit
        ds.attrs.update(self._provenance())
        return ds

    def to_xarray(self):
        """Tidy xarray Dataset on ``time`` [s]: one variable per body coordinate
        (``crank.x`` [m], ``crank.phi`` [rad], ``crank.x_dot`` …), per constraint row
        (``drive.lambda`` …), per element output (``piston_pin.xi`` …, names and units from the
        element's output slots) and memory slot (``piston_pin.memory.impacts`` …, from
        ``MEMORY``); every variable has a ``units`` attribute."""
        import xarray as xr

        s = self.system
        v: dict = {}
        units = {"x": "m", "y": "m", "phi": "rad"}
        for b in s.body_names:
            for j, (c, u) in enumerate(units.items()):
                i = 3 * s.body_index(b) + j
                v[f"{b}.{c}"] = (self.q[:, i], u)
                v[f"{b}.{c}_dot"] = (self.qd[:, i], f"{u}/s")
                v[f"{b}.{c}_ddot"] = (self.qdd[:, i], f"{u}/s²")
        for n, c in zip(s.constraint_names, s.constraints):
            lam = self.multipliers(n)
            lu = _lambda_units(c)
            for r in range(lam.shape[1]):
                v[f"{n}.lambda" + (f"[{r}]" if lam.shape[1] > 1 else "")] = (lam[:, r], lu[r])
        for k, (n, e) in enumerate(zip(s.element_names, s.elements)):
            for j, (o, u) in enumerate(output_slots(e).items()):  # the first slots, in order
                v[f"{n}.{o}"] = (self.eout[:, k, j], u)
            used = _memory_slots(e)
            for j, (o, u) in enumerate(type(e).MEMORY.items()):
                if o in used and j < self.mem.shape[-1]:
                    v[f"{n}.memory.{o}"] = (self.mem[:, k, j], u)
        v["drift_position"] = (self.drift[:, 0], "m or rad")
        v["drift_velocity"] = (self.drift[:, 1], "m/s or rad/s")
        ds = xr.Dataset({k: ("time", a) for k, (a, _) in v.items()}, coords={"time": self.t})
        for k, (_, u) in v.items():
            ds[k].attrs["units"] = u
        ds["time"].attrs["units"] = "s"
        ds.attrs.update(self._provenance())
        return ds

    def to_dataframe(self, element: str | None = None):
        """pandas DataFrame indexed by ``time`` [s]: with ``element``, that element's outputs and
        memory (columns named as in ``OUTPUTS``/``MEMORY``, units in ``df.attrs["units"]``);
        without, every variable of :meth:`to_xarray`."""
        ds = self.to_xarray()
        if element is not None:
            k, cls = self._element(element)
            el = self.system.elements[k]
            names = [
                f"{element}.{o}" for o in [*output_slots(el), *(f"memory.{m}" for m in _memory_slots(el))]
            ]
            ds = ds[names].rename({n: n.removeprefix(f"{element}.") for n in names})
        df = ds.to_dataframe()
        df.attrs["units"] = {k: ds[k].attrs["units"] for k in ds.data_vars} | {"time": "s"}
        return df

    # -- files ----------------------------------------------------------------------------------
    def save(self, path) -> None:
        """Write ``path`` (netCDF4 via h5netcdf, the layout of :meth:`to_dataset`) safely
        (:func:`jointdyn.core.atomic.replacing`: an exclusive temporary file in the same
        directory, renamed over ``path`` when complete; a link or special file is refused, a
        character device such as ``/dev/null`` written into). Every variable carries a
        Fletcher-32 checksum, verified by :meth:`load`."""
        import h5netcdf
        import h5py

        coords = self._coords()
        with atomic.replacing(Path(path), devices=True, option="path") as tmp:
            with h5netcdf.File(tmp, "w") as f:
                f.dimensions = {"time": len(self.t), **{k: len(v) for k, v in coords.items() if k != "time"}}
                v = f.create_variable("time", ("time",), float, fletcher32=True)
                v[:] = self.t
                v.attrs["units"] = "s"
                for k, vals in coords.items():
                    if k != "time" and vals:
                        var = f.create_variable(k, (k,), h5py.string_dtype())
                        var[:] = np.array(vals, dtype=object)
                if coords["coordinate"]:
                    cu = f.create_variable("coordinate_unit", ("coordinate",), h5py.string_dtype())
                    cu[:] = np.array(self._coordinate_units(), dtype=object)
                for name, (dims, arr) in self._arrays().items():
                    var = f.create_variable(name, dims, float, fletcher32=True)
                    var[...] = arr
                    var.attrs["units"] = _VARIABLES[name][1]
                f.attrs.update(self._provenance())
                _write_arrays(f.create_group("system"), self.system.arrays())

    @classmethod
    def load(cls, path) -> Results:
        """Read a file written by :meth:`save` back into :class:`Results`: the system is the
        stored model description with the stored compiled arrays (nothing is compiled; files
        without them, written before they were stored, compile the model). Raises
        ``ValueError`` (one line) on a corrupt or foreign file."""
        return cls.from_dataset(load_dataset(path), source=str(path), arrays=load_arrays(path))

    @classmethod
    def from_dataset(cls, ds, source: str = "dataset", arrays: dict | None = None) -> Results:
        """:class:`Results` from the archival Dataset (:meth:`to_dataset`, a loaded ``results.nc``);
        ``arrays``: the system's compiled arrays (``System.arrays``), else the model is compiled."""
        need = {"q", "qd", "qdd", "lam", "element_outputs", "drift_position", "drift_velocity"}
        if not need <= set(ds.data_vars) or "model" not in ds.attrs:
            raise ValueError(f"{source}: not a jointdyn results file (needs variables {sorted(need)})")
        model = Model.from_dict(json.loads(ds.attrs["model"]))
        system = model.compile() if arrays is None else model.recompose(arrays)
        nt, ne = ds.sizes["time"], len(system.element_names)
        mem = (
            ds["element_memory"].values
            if "element_memory" in ds
            else np.zeros((nt, ne, system.mem0.shape[-1]))
        )
        return cls(
            system=system,
            t=ds["time"].values,
            y=np.concatenate([ds["q"].values, ds["qd"].values], axis=1),
            mem=_shaped(mem, (nt, ne, system.mem0.shape[-1])),
            qdd=ds["qdd"].values,
            lam=_shaped(ds["lam"].values, (nt, system.n_rows)),
            eout=_shaped(ds["element_outputs"].values, (nt, ne, ds.sizes.get("output", 0))),
            drift=np.stack([ds["drift_position"].values, ds["drift_velocity"].values], axis=1),
            stats=json.loads(ds.attrs.get("stats", "{}")),
            wall_time=float(ds.attrs.get("wall_time_s", math.nan)),
            config=json.loads(ds.attrs.get("config", "{}")),
            status=int(ds.attrs.get("status", 0)),
            meta=json.loads(ds.attrs.get("meta", "{}")),
        )

    # -- helpers --------------------------------------------------------------------------------
    def _coords(self) -> dict[str, list]:
        s = self.system
        named = zip(s.constraint_names, s.constraint_rows)
        rows = [f"{n}[{r - a}]" for n, (a, b) in named for r in range(a, b)]
        return {
            "time": list(self.t),
            "coordinate": s.coordinate_labels(),
            "row": rows,
            "element": list(s.element_names),
            "output": _labels(self._output_names(), self.eout.shape[-1], "col"),
            "memory": _labels((), self.mem.shape[-1], "slot"),
        }

    def _output_names(self) -> tuple:
        """Labels of the ``output`` dimension: the ``OUTPUTS`` the elements' classes declare when
        they all declare the same, else none (``col0``, … ; per element in ``element_units``)."""
        kinds = {tuple(type(e).OUTPUTS) for e in self.system.elements}
        return kinds.pop() if len(kinds) == 1 else ()

    def _coordinate_units(self) -> list[str]:
        return ["m", "m", "rad"] * len(self.system.body_names)

    def _arrays(self) -> dict:
        return {
            "q": (_VARIABLES["q"][0], self.q),
            "qd": (_VARIABLES["qd"][0], self.qd),
            "qdd": (_VARIABLES["qdd"][0], self.qdd),
            "lam": (_VARIABLES["lam"][0], self.lam),
            "element_outputs": (_VARIABLES["element_outputs"][0], self.eout),
            "element_memory": (_VARIABLES["element_memory"][0], self.mem),
            "drift_position": (("time",), self.drift[:, 0]),
            "drift_velocity": (("time",), self.drift[:, 1]),
        }

    def _row_labels(self) -> list[str]:
        return self._coords()["row"]

    def _provenance(self) -> dict:
        s = self.system
        pairs = zip(s.element_names, s.elements)
        units = {n: {"outputs": output_slots(e), "memory": type(e).MEMORY} for n, e in pairs}
        return {
            "jointdyn_version": _version(),
            "model": json.dumps(s.model_dict, default=list),
            "config": json.dumps(self.config, default=str),
            "stats": json.dumps(self.stats),
            "wall_time_s": self.wall_time,
            "status": self.status,
            "meta": json.dumps(self.meta, default=str),
            "element_units": json.dumps(units),
        }


def _write_arrays(group, arrays: dict) -> None:
    """The compiled arrays into a netCDF group, one dimension per axis, checksummed."""
    for k, a in arrays.items():
        a = np.asarray(a)
        dims = tuple(f"{k}_{i}" for i in range(a.ndim))
        group.dimensions.update(dict(zip(dims, a.shape)))
        var = group.create_variable(k, dims, a.dtype, fletcher32=True)
        var[...] = a


def _labels(names, width: int, prefix: str) -> list[str]:
    """``names`` cut or padded (``prefix0``, ``prefix1``, …) to ``width`` labels."""
    return [names[i] if i < len(names) else f"{prefix}{i}" for i in range(width)]


def _shaped(a: np.ndarray, shape: tuple) -> np.ndarray:
    """``a`` as stored, or reshaped to ``shape`` when a dimension was empty in the file."""
    return a if a.ndim == len(shape) else np.asarray(a).reshape(shape)


def _lambda_units(c) -> list[str]:
    """Unit of each λ row of a constraint, as its class declares (``LAMBDA_UNITS``; else N)."""
    return list(getattr(type(c), "LAMBDA_UNITS", ("N",) * type(c).rows))


def load(path):
    """Read a file written by :meth:`Results.save` as an xarray Dataset (the archival layout).
    Kept for the command line; ``jointdyn.load(path)`` / :meth:`Results.load` return
    :class:`Results`."""
    return load_dataset(path)
