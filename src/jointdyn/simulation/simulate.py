"""The front door: ``simulate(system, config) -> Results``."""

from __future__ import annotations

import math
import numbers
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass, fields

import numpy as np

from jointdyn.core import interrupts
from jointdyn.core.precompiled import call
from jointdyn.errors import Interrupted, PhysicsWarning, SimulationError
from jointdyn.forces.elements import FILM_BREAKDOWN, JFO_FAILED, THERMAL_RANGE
from jointdyn.integrators import SOLVERS
from jointdyn.integrators.accuracy import check_force_resolution
from jointdyn.integrators.common import (
    FORCE_UNRESOLVED,
    INTERRUPTED,
    MAX_STEPS,
    MEMORY_FAILED,
    OK,
    PROJECTION_FAILED,
    RHS_FAILED,
    STEP_TOO_SMALL,
)
from jointdyn.integrators.driver import IOUT, RUNNING, Stepper, T, drive, method_tolerances, new_work
from jointdyn.integrators.radau5 import RADAU5, costly_jacobian
from jointdyn.integrators.weights import AUTO_CLEARANCE_RATIO, clearance_scale
from jointdyn.multibody.dynamics import outputs
from jointdyn.multibody.system import System
from jointdyn.simulation.results import Results

_MESSAGES = {
    STEP_TOO_SMALL: "step size collapsed below 1e-14·t_end",
    MAX_STEPS: "maximum number of steps reached (raise SimConfig.max_steps)",
    RHS_FAILED: "the equations of motion could not be evaluated (singular constraint Jacobian or "
    "non-finite accelerations)",
    MEMORY_FAILED: "an element left its admissible range (e.g. film breakdown ξ ≥ 1 in a "
    "journal bearing without a contact law)",
    PROJECTION_FAILED: "projection onto the constraints failed (singular constraint Jacobian)",
    INTERRUPTED: "interrupted by a signal",
    FORCE_UNRESOLVED: "an element force is not resolved by the tolerances",
}
FORCE_RESOLUTION = 0.1
"""largest accepted δF/peak |F| of an element [-] [T111]: measured 3.5e-5 … 8e-3 on the paper's
and the c = 0.05 mm cases at their tolerances; 0.2 already gives 1 % error in the crank moment"""
SLICE_SECONDS = 0.05
"""target wall time of one call of the compiled driver [s] (signals and progress are handled
between calls, so this bounds the reaction time)"""


def _message(system: System, status: int) -> str:
    if status >= JFO_FAILED:
        name = system.element_names[status - JFO_FAILED]
        return f"element {name!r}: the jfo film's active set did not settle on an accepted step [T307]"
    if status >= THERMAL_RANGE:
        name = system.element_names[status - THERMAL_RANGE]
        th = system.elements[status - THERMAL_RANGE].thermal
        return (
            f"element {name!r}: the oil temperature left the viscosity law's range of {th.oil} "
            f"[T311]; raise thermal.mass_flow or thermal.h_A, or shorten the run"
        )
    if status >= FILM_BREAKDOWN:
        name = system.element_names[status - FILM_BREAKDOWN]
        return (
            f"film breakdown in element {name!r}: the journal reached the bearing wall (ξ ≥ 1, "
            f"or h_min below the gap the tolerances resolve [T115]) and the bearing has no "
            f"contact law; give it `contact=` (mixed film/contact regime), or raise "
            f"viscosity/clearance"
        )
    return _MESSAGES.get(status, f"status {status}")


def _element_hint(system: System, P, t, y, mem) -> str:
    """What the elements that declare ``failure_hint`` say about the state where the run failed."""
    _, _, eout, _ = call(outputs, np.array([t]), y[None, :].copy(), mem[None].copy(), P, False)
    hints = []
    for k, (name, el) in enumerate(zip(system.element_names, system.elements)):
        hint = getattr(el, "failure_hint", None)
        if hint is not None:
            hints.append(hint(name, {o: float(v) for o, v in zip(el.OUTPUTS, eout[0, k])}))
    hints = [h for h in hints if h]
    return ("; " + "; ".join(hints)) if hints else ""


def _force_resolution_message(system: System, ts, Y, MEM, eout, P, config, ysc=None, rtol=None) -> str:
    """'' if every element force is resolved by the tolerances [T111], else why not (``ysc``,
    ``rtol``: the error test's fixed scales and rtol, [T186]; the advice is in config.rtol)."""
    rtol = config.rtol if rtol is None else rtol
    worst = check_force_resolution(ts, Y, MEM, eout, P, rtol, config.atol, ysc=ysc)
    if worst is None:
        return ""
    k, dF, peak, t = worst
    if not (peak > 0 and dF / peak > FORCE_RESOLUTION):  # an element that never carried load: no noise
        return ""
    ratio = dF / peak
    factor = ratio / 0.01  # δF scales with the tolerances: aim at 1 % of the peak
    rtol_needed = config.rtol / factor
    msg = (
        f"the force of element {system.element_names[k]!r} is noise at these tolerances: at "
        f"t = {t:.6g} s a state error the error control accepts (rtol = {config.rtol:g}, atol = "
        f"{config.atol:g}) changes it by up to {dF:.3g} N, {ratio:.3g} × its peak {peak:.3g} N, so "
        f"it and every reaction carrying it (e.g. a driving moment) would be wrong; the element is "
        f"too stiff (e.g. huge viscosity or tiny clearance) for these tolerances"
    )
    if ratio >= 1.0:
        msg += " (its computed peak is itself dominated by this noise: the factor below is a lower bound)"
    if rtol_needed >= 1e-13:
        return msg + f": lower rtol and atol by ≈ {factor:.2g}× (rtol ≈ {rtol_needed:.1g})"
    return msg + (
        f"; resolving it would need rtol ≈ {rtol_needed:.1g}, below double precision in absolute "
        f"coordinates: the joint is effectively rigid — model it as an ideal joint"
    )


JACOBIANS = ("finite-differences", "exact")
ERROR_SCALES = ("auto", "state", "clearance")


RTOL_MIN = 1e-14  # smallest relative tolerance [-]: ~45 ulp of float64 [T288]


@dataclass(frozen=True)
class SimConfig:
    """How to integrate. Times in [s]."""

    t_end: float
    """end time [s], > 0"""
    n_out: int = 1001
    """number of equally spaced output samples on [0, t_end] (≥ 2)"""
    solver: str = "auto"
    """a name in ``jointdyn.integrators.SOLVERS``, or ``"auto"``: ``radau5`` when the system has a
    lubricated journal bearing (stiff film), else ``dopri5`` [T116]"""
    rtol: float = 1e-8
    """relative tolerance [-], in [1e-14, 1) (relative to what: ``error_scale``)"""
    atol: float = 1e-10
    """absolute tolerance, applied to every state component [SI of the component]"""
    max_step: float = math.inf
    """largest step [s]"""
    first_step: float = 0.0
    """initial step [s], ≥ 0; 0 = automatic"""
    max_steps: int = 5_000_000
    """accepted + rejected steps before giving up"""
    baumgarte: float | None = None
    """Baumgarte rate a [1/s] [T10]; None = 0 for projecting solvers, 1000 for scipy ones"""
    jacobian: str = "exact"
    """system Jacobian of the compiled stiff solvers (rodas4, ros34pw2, radau5): ``exact`` (chain
    rule through the elements' exact Jacobians [T98–T104]; elements without one are differenced,
    with a warning naming them) or ``finite-differences`` (forward differences, the reference)"""
    error_scale: str = "auto"
    """what rtol is relative to in the error test: ``state`` (atol + rtol·|y_i|), ``clearance``
    (atol + rtol·Y_i with fixed scales from the smallest journal clearance, [T186]: rtol is a
    fraction of the clearance; needs a journal element and rodas4, ros34pw2 or radau5) or ``auto``:
    when ``solver="auto"`` picks radau5 (a lubricated bearing), clearance scales at
    ``AUTO_CLEARANCE_RATIO`` (300) × rtol — rtol = 1e-8 is 3e-6 of the clearance, [T188] — else
    ``state``"""

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
        if not self.rtol >= RTOL_MIN:  # below ~100 ulp no step passes the error test [T288]
            raise ValueError(f"SimConfig.rtol = {self.rtol!r} [-]: must be in [{RTOL_MIN:g}, 1) (float64)")
        if not (math.isfinite(self.first_step) and self.first_step >= 0):
            raise ValueError(
                f"SimConfig.first_step = {self.first_step!r} [s]: must be finite and ≥ 0 (0 = automatic)"
            )
        if not (isinstance(self.max_steps, numbers.Integral) and self.max_steps >= 1):
            raise ValueError(f"SimConfig.max_steps = {self.max_steps!r} [-]: must be an integer ≥ 1")
        if not self.max_step > 0:
            raise ValueError(f"SimConfig.max_step = {self.max_step!r} [s]: must be > 0")
        if self.baumgarte is not None and not (math.isfinite(self.baumgarte) and self.baumgarte >= 0):
            raise ValueError(f"SimConfig.baumgarte = {self.baumgarte!r} [1/s]: must be ≥ 0")
        if self.error_scale not in ERROR_SCALES:
            raise ValueError(
                f"SimConfig.error_scale = {self.error_scale!r}: unknown; valid: {list(ERROR_SCALES)}"
            )
        if self.jacobian not in JACOBIANS:
            raise ValueError(f"SimConfig.jacobian = {self.jacobian!r}: unknown; valid: {list(JACOBIANS)}")


def resolve_solver(system: System, name: str) -> str:
    """``"auto"`` -> ``radau5`` if an element declares itself stiff (``STIFF``: a journal bearing's
    film), else ``dopri5`` (choice measured with ``python -m benchmarks.work_precision`` [T116])."""
    if name != "auto":
        return name
    return "radau5" if any(getattr(e, "STIFF", False) for e in system.elements) else "dopri5"


def _transient_film(system: System) -> bool:
    """Whether an element of ``system`` has the transient jfo film [T306]."""
    from jointdyn.film.models import Finite, film_model

    for e in system.elements:
        film = getattr(e, "film", None)
        try:
            fm = film_model(film) if film is not None else None
        except (ValueError, TypeError):
            continue
        if isinstance(fm, Finite) and fm.transient:
            return True
    return False


def _integrate_compiled(
    stepper, P, y0, mem0, config, t_out, progress, step_budget, ysc=None, rtol=None, costly=False
):
    """Drive a compiled solver in slices of bounded wall time; returns (Work, status). ``ysc``,
    ``rtol``: fixed error scales and the rtol they go with (None: |y_i| and config.rtol) [T186];
    ``costly``: the system's Jacobian is costly (radau5 keeps it longer [T349])."""
    exact = config.jacobian == "exact"
    w = new_work(stepper, y0, mem0, t_out[0], t_out, config.first_step, exact, ysc)
    if costly and stepper is RADAU5:
        costly_jacobian(w)
    rtol, atol = method_tolerances(stepper, config.rtol if rtol is None else rtol, config.atol)
    budget = int(step_budget) if step_budget else 16
    status = RUNNING  # the first call of drive() starts the integration (one compiled call less)
    while status == OK or status == RUNNING:
        tc = time.perf_counter()
        status = drive(stepper, P, t_out, rtol, atol, config.max_step, config.max_steps, True, budget, w)
        dt = time.perf_counter() - tc
        if status != RUNNING:
            if status == OK and _report(progress, 1.0):
                status = INTERRUPTED
            break
        if interrupts.received() is not None or _report(
            progress, (float(w.ctl[T]) - t_out[0]) / config.t_end
        ):
            status = INTERRUPTED
            break
        if not step_budget:  # aim at SLICE_SECONDS per call; the budget never changes the result
            budget = int(min(max(budget * min(4.0, SLICE_SECONDS / max(dt, 1e-6)), 16), 1_000_000))
    return w, status


def simulate(
    system: System,
    config: SimConfig,
    progress: Callable[[float], object] | None = None,
    step_budget: int | None = None,
    *,
    t0: float = 0.0,
    y0: np.ndarray | None = None,
    mem0: np.ndarray | None = None,
) -> Results:
    """Integrate ``system`` from its assembled initial state over [0, config.t_end].

    ``t0`` [s], ``y0`` and ``mem0`` restart from another state: the run then covers
    [t0, t0 + config.t_end] (the time origin matters for driven systems).

    The compiled solvers run in slices of ≈ ``SLICE_SECONDS`` wall time (or of ``step_budget``
    step attempts, if given); between slices ``progress(fraction of t_end)`` is called and
    SIGINT/SIGTERM are checked. Slicing never changes the trajectory (all step-control state is
    carried over).

    Raises :class:`~jointdyn.errors.Interrupted` (with the partial results and the signal name)
    after SIGINT/SIGTERM, :class:`~jointdyn.errors.SimulationError` carrying the partial
    results if the integration fails.
    """
    if not hasattr(system, "y0"):  # e.g. a Model: an AttributeError 'y0' named nothing useful
        hint = "; call its .compile() first" if hasattr(system, "compile") else ""
        raise TypeError(f"system: expected a compiled System, got a {type(system).__name__}{hint}")
    with interrupts.catching():
        y = np.array(system.y0 if y0 is None else y0, dtype=float)
        mem = np.array(system.mem0 if mem0 is None else mem0, dtype=float)
        return _simulate(system, config, progress, step_budget, t0, y, mem)


def _report(progress, fraction) -> bool:
    """Call ``progress``; True if it raised Interrupted (a caller polling the same signal
    record): the run then stops here and keeps its partial results."""
    if progress is not None:
        try:
            progress(fraction)
        except Interrupted:
            return True
    return False


def _simulate(system, config, progress, step_budget, t_start, y0, mem0) -> Results:
    solver = resolve_solver(system, config.solver)
    runner, projects, _ = SOLVERS[solver]
    a = config.baumgarte if config.baumgarte is not None else (0.0 if projects else 1000.0)
    P = system.packed(a)
    t_out = np.linspace(t_start, t_start + config.t_end, config.n_out)
    compiled = runner if isinstance(runner, Stepper) else None
    if config.jacobian == "exact" and compiled is not None and compiled.reuse is not None:
        from jointdyn.forces.element_jacobians import differenced_laws, fallback_elements

        fd = fallback_elements(system)
        if fd:
            warnings.warn(
                f"jacobian='exact': no exact Jacobian for elements {fd}; they are differenced numerically",
                stacklevel=3,
            )
        laws = differenced_laws(system)
        if laws:
            warnings.warn(
                f"jacobian='exact': no exact Jacobian for {laws}; differenced by central differences of "
                "the kernel [T229]",
                stacklevel=3,
            )
    ysc, rtol = None, config.rtol
    if config.error_scale == "clearance":
        if compiled is None or not compiled.stiff:
            stiff = [k for k, (r, _, _) in SOLVERS.items() if isinstance(r, Stepper) and r.stiff]
            raise ValueError(
                f"SimConfig.error_scale = 'clearance' needs solver {', '.join(stiff[:-1])} or {stiff[-1]}, "
                f"not {solver!r}"
            )
        ysc = clearance_scale(system, config.t_end)
    elif config.error_scale == "auto" and config.solver == "auto" and solver == "radau5":
        ysc, rtol = clearance_scale(system, config.t_end), AUTO_CLEARANCE_RATIO * config.rtol  # [T188]
    t0 = time.perf_counter()
    if compiled is not None:
        w, status = _integrate_compiled(
            compiled, P, y0, mem0, config, t_out, progress, step_budget, ysc, rtol, _transient_film(system)
        )
        nw, stats = int(w.ictl[IOUT]), w.stats
        Y, MEM = w.Y[:nw], w.MEM[:nw]
        t_reached, y_fin, mem_fin = float(w.ctl[T]), w.y, w.mem
    else:
        last = [t0, 0.0]

        def stop(t):  # polled at every right-hand side: report progress every SLICE_SECONDS
            if interrupts.received() is not None:
                return True
            if time.perf_counter() - last[0] > SLICE_SECONDS:
                last[0], last[1] = time.perf_counter(), max(last[1], (t - t_out[0]) / config.t_end)
                return _report(progress, last[1])
            return False

        Y, MEM, nw, stats, status, t_reached, _, y_fin, mem_fin = runner(
            P,
            y0.copy(),
            mem0.copy(),
            t_start,
            t_out,
            config.rtol,
            config.atol,
            max_step=config.max_step,
            stop=stop,
        )
        if status == OK and _report(progress, 1.0):
            status = INTERRUPTED
    wall = time.perf_counter() - t0
    Y = np.ascontiguousarray(Y[:nw])
    MEM = np.ascontiguousarray(MEM[:nw])
    ts = t_out[:nw]
    qdd, lam, eout, drift = call(outputs, ts, Y, MEM, P, projects)  # [T382]
    signal_name = interrupts.received()
    if signal_name is not None and status == OK:  # a signal during the post-processing
        status = INTERRUPTED
    unresolved = ""
    if status == OK:
        unresolved = _force_resolution_message(system, ts, Y, MEM, eout, P, config, ysc, rtol)
        if unresolved:
            status = FORCE_UNRESOLVED
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
        }
        # a compiled method's own counters (driver Work.stats[4:]; radau5: LU pairs, Newton iterations
        # and failures)
        | {k: int(v) for k, v in zip(compiled.stats if compiled else (), stats[4:])},
        wall_time=wall,
        config={f.name: getattr(config, f.name) for f in fields(config)}
        | {"baumgarte": a, "solver": solver}
        # what the error test did, resolved like the solver: the scale and the rtol relative to
        # it (rtol itself stays as given; under "auto" they differ by AUTO_CLEARANCE_RATIO) [T188]
        | {"error_scale": "state" if ysc is None else "clearance", "error_rtol": rtol},
        status=int(status),
    )
    if status == INTERRUPTED:
        raise Interrupted(
            f"simulation of {system.name!r} interrupted by {signal_name or 'a signal'} at "
            f"t = {t_reached:.9g} s; {nw} of {len(t_out)} output samples were computed (kept in .results)",
            t_reached,
            res,
            signal=signal_name or "SIGINT",
        )
    if status == FORCE_UNRESOLVED:
        raise SimulationError(unresolved, float(t_out[-1]), res)
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
    from jointdyn.simulation.ranges import film_range_exits, range_message

    for d in film_range_exits(res):  # [T249]
        warnings.warn(range_message(d), PhysicsWarning, stacklevel=3)
    return res
