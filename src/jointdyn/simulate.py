"""The front door: ``simulate(system, config) -> Results``."""

from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass

import numpy as np

from .dynamics import outputs
from .errors import SimulationError
from .forces.elements import FILM_BREAKDOWN
from .integrators import SOLVERS
from .integrators.common import MAX_STEPS, MEMORY_FAILED, OK, PROJECTION_FAILED, RHS_FAILED, STEP_TOO_SMALL
from .results import Results
from .system import System

_MESSAGES = {
    STEP_TOO_SMALL: "step size collapsed below 1e-14·t_end",
    MAX_STEPS: "maximum number of steps reached (raise SimConfig.max_steps)",
    RHS_FAILED: "the equations of motion could not be evaluated (singular constraint Jacobian or "
    "non-finite accelerations)",
    MEMORY_FAILED: "an element left its admissible range (e.g. film breakdown ξ ≥ 1 in a "
    "journal bearing without a contact law)",
    PROJECTION_FAILED: "projection onto the constraints failed (singular constraint Jacobian)",
}


def _message(system: System, status: int) -> str:
    if status >= FILM_BREAKDOWN:
        name = system.element_names[status - FILM_BREAKDOWN]
        return (
            f"film breakdown in element {name!r}: the journal reached the bearing wall (ξ ≥ 1, "
            f"h_min ≤ 0) and the bearing has no contact law; give it `contact=` (mixed "
            f"film/contact regime), or raise viscosity/clearance"
        )
    return _MESSAGES.get(status, f"status {status}")


def _element_hint(system: System, P, t, y, mem) -> str:
    """Point at journal elements that were at the bearing wall when the run failed."""
    from .forces.journal import ClearanceJoint, JournalBearing

    _, _, eout, _ = outputs(np.array([t]), y[None, :].copy(), mem[None].copy(), P, False)
    hints = []
    for k, (name, el) in enumerate(zip(system.element_names, system.elements)):
        if isinstance(el, (JournalBearing, ClearanceJoint)):
            cols = list(el.OUTPUTS)
            xi = float(eout[0, k, cols.index("xi")])
            h_min = float(eout[0, k, cols.index("h_min")])
            if xi > 0.99:  # near the wall the film is stiff: the usual cause of step collapse
                hints.append(
                    f"element {name!r} was at ξ = {xi:.6f} (h_min = {h_min:.3g} m)"
                    + (
                        "; the film alone cannot carry the load there — give "
                        "the bearing a contact law (mixed regime)"
                        if isinstance(el, JournalBearing) and el.contact is None
                        else ""
                    )
                )
    return ("; " + "; ".join(hints)) if hints else ""


@dataclass(frozen=True)
class SimConfig:
    """How to integrate. Times in [s]."""

    t_end: float
    """end time [s], > 0"""
    n_out: int = 1001
    """number of equally spaced output samples on [0, t_end] (≥ 2)"""
    solver: str = "auto"
    """a name in ``jointdyn.integrators.SOLVERS``, or ``"auto"``: ``rodas4`` when the system has a
    lubricated journal bearing (stiff film), else ``dopri5``"""
    rtol: float = 1e-8
    """relative tolerance [-]"""
    atol: float = 1e-10
    """absolute tolerance, applied to every state component [SI of the component]"""
    max_step: float = math.inf
    """largest step [s]"""
    first_step: float = 0.0
    """initial step [s]; 0 = automatic"""
    max_steps: int = 5_000_000
    """accepted + rejected steps before giving up"""
    baumgarte: float | None = None
    """Baumgarte rate a [1/s] [T10]; None = 0 for projecting solvers, 1000 for scipy ones"""

    def __post_init__(self):
        if not (math.isfinite(self.t_end) and self.t_end > 0):
            raise ValueError(f"SimConfig.t_end = {self.t_end!r} [s]: must be finite and > 0")
        if self.n_out < 2:
            raise ValueError(f"SimConfig.n_out = {self.n_out!r} [-]: must be ≥ 2")
        if self.solver not in SOLVERS and self.solver != "auto":
            raise ValueError(
                f"SimConfig.solver = {self.solver!r}: unknown; valid: {['auto', *sorted(SOLVERS)]}"
            )
        for name in ("rtol", "atol"):
            v = getattr(self, name)
            if not (math.isfinite(v) and 0 < v < 1):
                raise ValueError(f"SimConfig.{name} = {v!r} [-]: must be in (0, 1)")
        if not self.max_step > 0:
            raise ValueError(f"SimConfig.max_step = {self.max_step!r} [s]: must be > 0")
        if self.baumgarte is not None and not (math.isfinite(self.baumgarte) and self.baumgarte >= 0):
            raise ValueError(f"SimConfig.baumgarte = {self.baumgarte!r} [1/s]: must be ≥ 0")


def resolve_solver(system: System, name: str) -> str:
    """``"auto"`` -> ``rodas4`` if a journal bearing carries a film (stiff), else ``dopri5``."""
    if name != "auto":
        return name
    from .forces.journal import JournalBearing

    return "rodas4" if any(isinstance(e, JournalBearing) for e in system.elements) else "dopri5"


def simulate(
    system: System,
    config: SimConfig,
    progress=None,
    chunks: int = 1,
    *,
    t0: float = 0.0,
    y0: np.ndarray | None = None,
    mem0: np.ndarray | None = None,
) -> Results:
    """Integrate ``system`` from its assembled initial state over [0, config.t_end].

    ``t0`` [s], ``y0`` and ``mem0`` restart from another state: the run then covers
    [t0, t0 + config.t_end] (the time origin matters for driven systems).

    The run is split into ``chunks`` consecutive calls of the compiled integrator (state,
    element memory and step size carried over); ``progress(fraction)`` is called after each.
    Raises :class:`~jointdyn.errors.SimulationError` carrying the partial results if the
    integration fails.
    """
    solver = resolve_solver(system, config.solver)
    runner, projects, _ = SOLVERS[solver]
    a = config.baumgarte if config.baumgarte is not None else (0.0 if projects else 1000.0)
    P = system.packed(a)
    t_out = np.linspace(t0, t0 + config.t_end, config.n_out)
    parts = [p for p in np.array_split(np.arange(1, config.n_out), max(1, int(chunks))) if len(p)]
    y = np.array(system.y0 if y0 is None else y0, dtype=float)
    mem = np.array(system.mem0 if mem0 is None else mem0, dtype=float)
    Ys, MEMs = [y[None, :].copy()], [mem[None].copy()]
    stats = np.zeros(4, dtype=np.int64)
    t, h = t0, config.first_step
    status, t_reached = OK, 0.0
    t0 = time.perf_counter()
    for idx in parts:
        tc = t_out[idx]
        if projects:
            Y, MEM, nw, st, status, t_reached, h, y_fin, mem_fin = runner(
                P,
                y,
                mem,
                t,
                tc,
                config.rtol,
                config.atol,
                h,
                config.max_step,
                config.max_steps - int(stats[1] + stats[2]),
                True,
            )
        else:
            Y, MEM, nw, st, status, t_reached, _, y_fin, mem_fin = runner(
                P, y, mem, t, tc, config.rtol, config.atol, max_step=config.max_step
            )
        stats += st
        Ys.append(Y[:nw])
        MEMs.append(MEM[:nw])
        if status != OK or nw == 0:
            break
        y, mem, t = y_fin.copy(), mem_fin.copy(), tc[-1]
        if progress is not None:
            progress((t - t_out[0]) / config.t_end)
    wall = time.perf_counter() - t0
    Y = np.ascontiguousarray(np.concatenate(Ys))
    MEM = np.ascontiguousarray(np.concatenate(MEMs))
    nw = Y.shape[0]
    ts = t_out[:nw]
    qdd, lam, eout, drift = outputs(ts, Y, MEM, P, projects)
    res = Results(
        system=system,
        t=ts,
        y=Y,
        mem=MEM,
        qdd=qdd,
        lam=lam,
        eout=eout,
        drift=drift,
        stats={
            "rhs_evaluations": int(stats[0]),
            "accepted_steps": int(stats[1]),
            "rejected_steps": int(stats[2]),
            "jacobians": int(stats[3]),
        },
        wall_time=wall,
        config=asdict(config) | {"baumgarte": a, "solver": solver},
        status=int(status),
    )
    if status != OK:
        raise SimulationError(
            f"simulation of {system.name!r} failed at t = {t_reached:.9g} s "
            f"with solver {solver!r}: {_message(system, status)}; "
            f"{nw} of {len(t_out)} output samples were computed (kept in "
            f".results){_element_hint(system, P, t_reached, y_fin, mem_fin)}",
            t_reached,
            res,
        )
    bad = ~np.isfinite(res.y).all(axis=1)
    if bad.any():
        raise SimulationError(f"non-finite state at t = {ts[bad][0]:.9g} s", ts[bad][0], res)
    return res
