"""What the user describes: bodies with named points, ideal joints and force elements.

A :class:`Model` is mutable and holds no numerics; :meth:`Model.compile` validates it,
assembles a consistent initial state (position and velocity analysis) and returns a frozen
:class:`~jointdyn.multibody.system.System`.

Conventions (also in docs/theory.md, "Conventions"): SI units; angles in rad, counter-clockwise
positive; body frames at the centre of mass; the ground is the body named ``"ground"`` whose
points are given in world coordinates.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from jointdyn.core.constraints import CONSTRAINTS, Revolute, constraint_table, eval_constraints
from jointdyn.core.precompiled import call
from jointdyn.errors import ModelError
from jointdyn.forces import elements as fe
from jointdyn.multibody import codec
from jointdyn.multibody.dynamics import project_positions, project_velocities

GROUND = "ground"


def _check_finite(owner: str, name: str, value, unit: str, positive=False):
    vals = np.atleast_1d(np.asarray(value, dtype=float))
    if not np.all(np.isfinite(vals)):
        raise ModelError(f"{owner}: {name} = {value!r} [{unit}] is not finite")
    if positive and np.any(vals <= 0):
        raise ModelError(f"{owner}: {name} = {value!r} [{unit}] must be > 0")


@dataclass
class Body:
    """A rigid body in the plane."""

    name: str
    mass: float
    """m [kg], > 0"""
    inertia: float
    """I_zz about the centre of mass [kg·m²], > 0"""
    position: tuple[float, float] = (0.0, 0.0)
    """initial guess of the centre of mass [m]"""
    angle: float = 0.0
    """initial guess of the body angle [rad]"""
    velocity: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """initial guess (ẋ, ẏ, φ̇) [m/s, m/s, rad/s]; corrected to satisfy the constraints"""
    points: dict[str, tuple[float, float]] = field(default_factory=dict)
    """named points in the body frame (origin at the centre of mass) [m]"""

    def validate(self):
        owner = f"body {self.name!r}"
        _check_finite(owner, "mass", self.mass, "kg", positive=True)
        _check_finite(owner, "inertia", self.inertia, "kg·m²", positive=True)
        _check_finite(owner, "position", self.position, "m")
        _check_finite(owner, "angle", self.angle, "rad")
        _check_finite(owner, "velocity", self.velocity, "m/s, m/s, rad/s")
        for p, xy in self.points.items():
            _check_finite(owner, f"point {p!r}", xy, "m")


class Model:
    """Builder of a planar mechanism.

    >>> m = Model("pendulum")
    >>> m.add_body("bar", mass=1.0, inertia=0.1, position=(0.5, 0.0), points={"pin": (-0.5, 0)})
    >>> m.add_ground_point("O", (0.0, 0.0))
    >>> m.add("pin", Revolute("ground", "O", "bar", "pin"))
    """

    def __init__(self, name: str = "model", gravity: tuple[float, float] = (0.0, -9.81)):
        self.name = name
        self.gravity: tuple[float, float] = (float(gravity[0]), float(gravity[1]))
        """gravitational acceleration vector [m/s²]"""
        self.bodies: dict[str, Body] = {}
        self.ground_points: dict[str, tuple[float, float]] = {}
        self.items: dict[str, Any] = {}

    # -- building -------------------------------------------------------------------------
    def add_body(
        self,
        name: str,
        mass: float,
        inertia: float,
        position=(0.0, 0.0),
        angle=0.0,
        velocity=(0.0, 0.0, 0.0),
        points=None,
    ) -> Body:
        if name == GROUND or name in self.bodies:
            raise ModelError(f"body name {name!r} is {'reserved' if name == GROUND else 'already used'}")
        body = Body(name, mass, inertia, tuple(position), angle, tuple(velocity), dict(points or {}))
        body.validate()
        self.bodies[name] = body
        return body

    def add_ground_point(self, name: str, xy) -> None:
        _check_finite("ground", f"point {name!r}", xy, "m")
        self.ground_points[name] = (float(xy[0]), float(xy[1]))

    def add(self, name: str, item) -> None:
        """Add a constraint (see ``CONSTRAINTS``) or force element (``FORCE_ELEMENTS``)."""
        if name in self.items:
            raise ModelError(f"element name {name!r} is already used")
        kinds = tuple(CONSTRAINTS.values()) + tuple(fe.FORCE_ELEMENTS.values())
        if not isinstance(item, kinds):
            raise ModelError(
                f"{name!r}: {type(item).__name__} is not a known constraint or force "
                f"element; valid: {sorted(CONSTRAINTS) + sorted(fe.FORCE_ELEMENTS)}"
            )
        self.items[name] = item

    # -- lookup ---------------------------------------------------------------------------
    def _body_index(self, owner: str):
        names = list(self.bodies)

        def index(body: str) -> int:
            if body == GROUND:
                return -1
            if body not in self.bodies:
                raise ModelError(f"{owner}: unknown body {body!r}; bodies are {[GROUND] + names}")
            return names.index(body)

        return index

    def _point_of(self, owner: str):
        def point(body: str, p: str):
            pts = self.ground_points if body == GROUND else self.bodies[body].points
            if p not in pts:
                raise ModelError(f"{owner}: body {body!r} has no point {p!r}; its points are {sorted(pts)}")
            return pts[p]

        return point

    def _angle_of(self, body: str) -> float:
        return 0.0 if body == GROUND else float(self.bodies[body].angle)

    # -- compile --------------------------------------------------------------------------
    def compile(self, position_tol: float = 1e-12, max_iter: int = 50, centre_imperfect: bool = True):
        """Validate, assemble the initial state and return a frozen System.

        Position analysis: Gauss–Newton on Φ = 0 from the bodies' guesses (M-weighted minimal
        correction). Velocity analysis: the M-weighted projection of the guessed velocities on
        Φ_q q̇ = −Φ_t [T11]. With ``centre_imperfect`` (default) imperfect joints (bearings,
        clearance joints) are assembled centred: during the analysis they act as ideal revolute
        joints (e = 0, ė = 0); otherwise the bodies' given positions and velocities set e and ė.
        """
        if not self.bodies:
            raise ModelError("the model has no bodies")
        for b in self.bodies.values():
            b.validate()
        constraints, elements = self._split()
        for n, c in constraints + elements:
            bi, bj = c.body_i, c.body_j
            index = self._body_index(f"element {n!r}")
            index(bi), index(bj)
            if bi == bj:
                raise ModelError(f"element {n!r}: joins body {bi!r} to itself")
            for side in ("i", "j"):
                p = getattr(c, f"point_{side}", None)
                if p is not None:
                    self._point_of(f"element {n!r}")(getattr(c, f"body_{side}"), p)
            if hasattr(c, "validate"):
                try:
                    c.validate()
                except ValueError as err:
                    raise ModelError(f"element {n!r}: {err}") from None
        index = self._body_index("model")
        point_of = self._point_of("model")
        cint, creal, rows = constraint_table([c for _, c in constraints], index, point_of, self._angle_of)
        fint, freal, tables, mem0 = fe.element_tables([e for _, e in elements], index, point_of)

        nb = len(self.bodies)
        minv = np.empty(3 * nb)
        q0f = np.zeros(3 * nb)
        q = np.empty(3 * nb)
        qd = np.empty(3 * nb)
        for k, b in enumerate(self.bodies.values()):
            minv[3 * k : 3 * k + 3] = (1.0 / b.mass, 1.0 / b.mass, 1.0 / b.inertia)
            q0f[3 * k : 3 * k + 2] = (b.mass * self.gravity[0], b.mass * self.gravity[1])
            q[3 * k : 3 * k + 3] = (b.position[0], b.position[1], b.angle)
            qd[3 * k : 3 * k + 3] = b.velocity

        # assembly constraints: the ideal ones plus imperfect joints treated as revolute
        asm = [c for _, c in constraints] + [
            Revolute(e.body_i, e.point_i, e.body_j, e.point_j)
            for _, e in elements
            if centre_imperfect and getattr(e, "centred", False)
        ]
        acint, acreal, am = constraint_table(asm, index, point_of, self._angle_of)
        if am > 3 * nb:
            raise ModelError(f"over-constrained: {am} constraint equations for {3 * nb} coordinates")
        y0 = np.concatenate([q, qd])
        if centre_imperfect:
            _warn_off_centre(elements, index, point_of, q, qd, cint, creal, rows)
        _assemble(y0, acint, acreal, am, minv, position_tol, max_iter)
        return self._system(
            constraints,
            elements,
            dict(minv=minv, q0_force=q0f, cint=cint, creal=creal, fint=fint, freal=freal, tables=tables),
            y0,
            mem0,
        )

    def _split(self) -> tuple[list, list]:
        """(name, constraint) and (name, force element) pairs, each in the order added."""
        constraints = [(n, c) for n, c in self.items.items() if type(c) in CONSTRAINTS.values()]
        elements = [(n, e) for n, e in self.items.items() if type(e) in fe.FORCE_ELEMENTS.values()]
        return constraints, elements

    def _system(self, constraints, elements, arrays: dict, y0, mem0):
        from jointdyn.multibody.system import System

        rows, r = [], 0
        for _, c in constraints:
            rows.append((r, r + c.rows))
            r += c.rows
        return System(
            name=self.name,
            body_names=tuple(self.bodies),
            constraint_names=tuple(n for n, _ in constraints),
            constraint_rows=tuple(rows),
            element_names=tuple(n for n, _ in elements),
            constraints=tuple(c for _, c in constraints),
            elements=tuple(e for _, e in elements),
            n_rows=r,
            y0=y0,
            mem0=mem0,
            gravity=self.gravity,
            model_dict=self.to_dict(),
            **arrays,
        )

    def recompose(self, arrays: dict):
        """The System that :meth:`compile` made of this model, from its arrays as
        :meth:`~jointdyn.multibody.system.System.arrays` gave them (a results file stores them):
        no assembly, no film tables, no compiled code. ``ModelError`` if they do not fit the
        model (a different number of bodies, constraint rows or elements)."""
        constraints, elements = self._split()
        names = ("minv", "q0_force", "cint", "creal", "fint", "freal", "tables")
        a = {k: np.asarray(arrays[k]) for k in names}
        expect = {
            "minv": (3 * len(self.bodies),),
            "cint": (len(constraints),),
            "fint": (len(elements),),
            "y0": (6 * len(self.bodies),),
            "mem0": (len(elements),),
        }
        for k, shape in expect.items():
            got = np.shape(arrays[k])[: len(shape)]
            if got != shape:
                have = np.shape(arrays[k])
                raise ModelError(f"compiled array {k!r} has shape {have}; the model needs {shape}")
        y0, mem0 = np.array(arrays["y0"], dtype=float), np.array(arrays["mem0"], dtype=float)
        return self._system(constraints, elements, a, y0, mem0)

    def to_dict(self) -> dict:
        """Plain-data description (the layout of a model file, :mod:`jointdyn.multibody.codec`)."""
        return codec.encode(self)

    @classmethod
    def from_dict(cls, d: dict) -> Model:
        """The model described by ``d`` (:meth:`to_dict`, or the ``model`` attribute of a
        results file of any version)."""
        kwargs, points, bodies, items = codec.decode(d)
        m = cls(**kwargs)
        for p, xy in points.items():
            m.add_ground_point(p, xy)
        for n, b in bodies.items():
            m.add_body(n, **b)
        for n, item in items.items():
            m.add(n, item)
        return m


def _assemble(y, cint, creal, m, minv, tol, max_iter):
    """Position analysis (Gauss–Newton, M-weighted) and velocity analysis in place, with the
    compiled projection the integrators use [T11]."""
    if m == 0:
        return
    n = y.shape[0] // 2
    q, qd = y[:n], y[n:]
    res = call(project_positions, 0.0, q, qd, minv, cint, creal, m, tol, max_iter)  # [T382]
    if res < 0.0:
        raise ModelError(
            "position analysis failed: the constraint Jacobian is singular "
            "(redundant constraints or a locked configuration)"
        )
    if not res <= tol:
        raise ModelError(
            f"the mechanism cannot be assembled: position analysis did not converge "
            f"in {max_iter} iterations (max |Φ| = {res:.3g} [m or rad]); check lengths "
            f"and the initial guesses of body positions/angles"
        )
    Phi, J, Phit, gam = np.empty(m), np.empty((m, n)), np.empty(m), np.empty(m)
    call(eval_constraints, 0.0, q, qd, cint, creal, Phi, J, Phit, gam)
    if np.linalg.matrix_rank(J @ np.diag(minv) @ J.T) < m or not call(
        project_velocities, 0.0, q, qd, minv, cint, creal, m
    ):
        raise ModelError(
            "the constraint Jacobian is rank deficient at the assembled position "
            "(redundant constraints or a singular configuration)"
        )


def _warn_off_centre(elements, index, point_of, q, qd, cint, creal, rows) -> None:
    """Warn when the given positions satisfy the ideal joints and deliberately put a journal off
    centre (1 % … 100 % of its clearance): assembly centres it [T289]."""
    phi = np.zeros(rows)
    J, gam = np.zeros((rows, len(q))), np.zeros(rows)
    call(eval_constraints, 0.0, q, qd, cint, creal, phi, J, np.zeros(rows), gam)
    if np.abs(phi).max(initial=0.0) > 1e-9:
        return  # a rough guess that the assembly corrects anyway: nothing deliberate to report
    for name, e in elements:
        c = getattr(e, "clearance", None)
        if not getattr(e, "centred", False) or not c:
            continue
        ends = []
        for side in ("i", "j"):
            body = getattr(e, f"body_{side}")
            px, py = point_of(body, getattr(e, f"point_{side}"))
            k = index(body)
            if k < 0:
                ends.append((px, py))
                continue
            x, y, a = q[3 * k : 3 * k + 3]
            ends.append((x + np.cos(a) * px - np.sin(a) * py, y + np.sin(a) * px + np.cos(a) * py))
        off = float(np.hypot(ends[1][0] - ends[0][0], ends[1][1] - ends[0][1]))
        if 0.01 * c < off < c:
            import warnings

            warnings.warn(
                f"element {name!r}: the given positions put the journal {off / c:.3g} c off centre; it "
                "is assembled centred (e = 0); Model.compile(centre_imperfect=False) keeps the offset",
                stacklevel=3,
            )
