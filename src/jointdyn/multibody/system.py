"""The compiled, frozen form of a model (flat arrays for the compiled kernels) and the state."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np


class Packed(NamedTuple):
    """What the compiled kernels receive (see :mod:`jointdyn.multibody.dynamics`), read by field name."""

    minv: np.ndarray
    """(n,) inverse masses and inertias [1/kg, 1/(kg·m²)]"""
    q0_force: np.ndarray
    """(n,) constant generalised forces (gravity) [N, N·m]"""
    cint: np.ndarray
    """constraint integer table (``joints.constraints`` layouts)"""
    creal: np.ndarray
    """constraint real table [SI]"""
    fint: np.ndarray
    """force-element integer table (``forces.elements`` layouts)"""
    freal: np.ndarray
    """force-element real table [SI]"""
    tables: np.ndarray
    """(n_tables, rows, 2) film and force tables"""
    n_rows: int
    """number of constraint rows m"""
    stab: np.ndarray
    """(1,) Baumgarte rate a [1/s]"""
    ws: np.ndarray
    """preallocated float workspace (``dynamics.workspace_size``)"""
    kernels: np.ndarray
    """(4,) int64 addresses of the element kernels compiled for the system's kinds
    (``forces.kernel_set``, [T379]): process-local, so a packed system is not pickled"""

    def __reduce__(self):
        raise TypeError(
            "a packed system holds this process's kernel addresses: pickle the System and pack it again"
        )


_SHARED_KINDS: ContextVar[tuple | None] = ContextVar("jointdyn_shared_kinds", default=None)


@contextmanager
def shared_kinds(*systems: System) -> Iterator[None]:
    """Inside the block, every system is packed for the union of its own element kinds and those
    of ``systems`` [T341]: a command that runs several models (e.g. a mechanism with ideal joints
    and with a journal bearing) compiles one kernel set for them instead of one each. The
    results are the same (a kind without elements is never entered); the kernels compiled are
    the union's, so a later command running one of the models alone compiles its own set."""
    from jointdyn.forces.elements import kinds_of, kinds_union

    kinds = _SHARED_KINDS.get()
    for s in systems:
        own = kinds_of(s.fint)
        kinds = own if kinds is None else kinds_union(kinds, own)
    token = _SHARED_KINDS.set(kinds)
    try:
        yield
    finally:
        _SHARED_KINDS.reset(token)


def shared_kinds_now() -> tuple | None:
    """The kinds of the enclosing :func:`shared_kinds` block, or None (for worker processes)."""
    return _SHARED_KINDS.get()


def share_kinds_in_process(kinds: tuple | None) -> None:
    """A worker process's systems are packed for ``kinds`` as well (its parent's
    :func:`shared_kinds_now`), so it loads the kernels its parent compiled [T322]."""
    if kinds is not None:
        _SHARED_KINDS.set(kinds)


@dataclass(frozen=True)
class System:
    """Frozen, compiled mechanism. Build it with :meth:`jointdyn.multibody.model.Model.compile`.

    Arrays (SI): ``minv`` (n,) inverse masses/inertias [1/kg, 1/(kg·m²)], ``q0_force`` (n,)
    constant generalised forces (gravity) [N, N·m], constraint tables ``cint``/``creal``,
    force-element tables ``fint``/``freal``, film ``tables`` (3-D), ``y0`` the assembled initial
    state [q, q̇] and ``mem0`` the initial element memory.
    """

    name: str
    body_names: tuple[str, ...]
    constraint_names: tuple[str, ...]
    constraint_rows: tuple[tuple[int, int], ...]
    element_names: tuple[str, ...]
    constraints: tuple
    elements: tuple
    minv: np.ndarray
    q0_force: np.ndarray
    cint: np.ndarray
    creal: np.ndarray
    fint: np.ndarray
    freal: np.ndarray
    tables: np.ndarray
    n_rows: int
    y0: np.ndarray
    mem0: np.ndarray
    gravity: tuple[float, float]
    model_dict: dict = field(default_factory=dict, compare=False)

    #: the compiled arrays (:meth:`arrays`): with the model they give back the System without
    #: compiling (``Model.recompose``)
    ARRAYS = ("minv", "q0_force", "cint", "creal", "fint", "freal", "tables", "y0", "mem0")

    def arrays(self) -> dict[str, np.ndarray]:
        """The compiled arrays by name (``ARRAYS``)."""
        return {k: getattr(self, k) for k in self.ARRAYS}

    @property
    def n(self) -> int:
        """Number of coordinates (3 per moving body)."""
        return self.minv.shape[0]

    def packed(self, baumgarte: float = 0.0, jacobian: bool = False) -> Packed:
        """The arrays handed to the compiled kernels, with a fresh workspace; ``jacobian``: with
        the exact element Jacobian compiled (the stiff methods ask for it themselves)."""
        from jointdyn.forces.kernel_set import kernel_addresses
        from jointdyn.multibody.dynamics import workspace_size

        ws = np.zeros(workspace_size(self.n, self.n_rows, self.fint.shape[0]))
        return Packed(
            self.minv,
            self.q0_force,
            self.cint,
            self.creal,
            self.fint,
            self.freal,
            self.tables,
            int(self.n_rows),
            np.array([float(baumgarte)]),
            ws,
            kernel_addresses(self.kinds(), jacobian),
        )

    def kinds(self) -> tuple:
        """The element kinds its kernels are compiled for: its own, joined with those of an
        enclosing :func:`shared_kinds` block [T175, T341]."""
        from jointdyn.forces.elements import kinds_of, kinds_union

        own, shared = kinds_of(self.fint), _SHARED_KINDS.get()
        return own if shared is None else kinds_union(own, shared)

    def degrees_of_freedom(self, t: float = 0.0) -> int:
        """n − rank Φ_q at the assembled state y0 (drivers count as constraints) [T286]."""
        from jointdyn.core.constraints import eval_constraints
        from jointdyn.core.precompiled import call

        n, m = self.n, int(self.n_rows)
        if m == 0:
            return n
        q, qd = self.y0[:n].copy(), self.y0[n:].copy()
        J = np.zeros((m, n))
        call(eval_constraints, t, q, qd, self.cint, self.creal, np.zeros(m), J, np.zeros(m), np.zeros(m))
        return n - int(np.linalg.matrix_rank(J))

    def coordinate_labels(self) -> list[str]:
        return [f"{b}.{c}" for b in self.body_names for c in ("x", "y", "phi")]

    def body_index(self, name: str) -> int:
        return self.body_names.index(name)

    def rows_of(self, constraint: str) -> slice:
        """Rows of λ belonging to a named constraint."""
        try:
            a, b = self.constraint_rows[self.constraint_names.index(constraint)]
        except ValueError:
            names = list(self.constraint_names)
            raise KeyError(f"no constraint named {constraint!r}; have {names}") from None
        return slice(a, b)
