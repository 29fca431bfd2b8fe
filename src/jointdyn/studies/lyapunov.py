"""Largest Lyapunov exponent by two-trajectory renormalisation (Benettin et al. 1980) [T125–T128].

A reference and a perturbed trajectory are integrated over segments of length τ; after each
segment the distance d_k of the perturbed state from the reference (weighted norm [T126]) is
measured, ln(d_k/δ₀) accumulated and the perturbation scaled back to δ₀ along its current
direction [T125]. λ₁ = Σ ln(d_k/δ₀) / Σ τ. Contact events need no special treatment in this
finite-difference form: both trajectories resolve their own impacts with the integrator's
step control, and the element memory of the perturbed trajectory (contact flag, onset
velocity) is renormalised with its state when both are in the same contact phase [T127]. The
uncertainty is the standard error of batch means of the per-segment rates [T128].

The core :func:`benettin` works on any flow given as callables; :func:`system_lyapunov` wraps
a :class:`~jointdyn.multibody.system.System` integrated by :func:`~jointdyn.simulation.simulate.simulate`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from jointdyn.core import atomic


@dataclass(frozen=True)
class LyapunovResult:
    """λ₁ [1/s] with its standard error [1/s] from ``batches`` batch means, the per-segment
    stretching rates [1/s] and the running estimate at the segment end times [s]."""

    exponent: float
    stderr: float
    batches: int
    segment_rates: np.ndarray
    times: np.ndarray
    running: np.ndarray
    info: dict = field(default_factory=dict)

    def summary(self) -> dict:
        return {
            "largest_lyapunov_exponent": self.exponent,
            "largest_lyapunov_exponent_stderr": self.stderr,
            "batches": self.batches,
            "segments": int(self.segment_rates.size),
            "averaging_time_s": float(self.times[-1] - self.times[0] + self.info.get("tau", 0.0))
            if self.times.size
            else 0.0,
            **self.info,
        }


def batch_stderr(rates: np.ndarray, batches: int) -> tuple[float, int]:
    """Standard error of the mean of ``rates`` from ``batches`` contiguous batch means [T128]
    (correlated segments are averaged within a batch). Returns (stderr, batches used)."""
    rates = np.asarray(rates, float)
    b = min(int(batches), rates.size)
    if b < 2:
        return math.inf, b
    means = np.array([p.mean() for p in np.array_split(rates, b)])
    return float(means.std(ddof=1) / math.sqrt(b)), b


def benettin(
    advance,
    difference,
    renormalise,
    ref,
    pert,
    t0: float,
    tau: float,
    n_segments: int,
    d0: float,
    discard_segments: int = 0,
    batches: int = 10,
    info: dict | None = None,
) -> LyapunovResult:
    """Two-trajectory renormalisation [T125].

    advance(state, t, t + τ) -> state; difference(ref, pert) -> distance [norm units];
    renormalise(ref, pert, factor) -> pert with its deviation from ref scaled by ``factor``.
    ``pert`` must start at distance ``d0`` from ``ref``. The first ``discard_segments`` rates
    (alignment with the most unstable direction) are left out of the average."""
    if not (math.isfinite(tau) and tau > 0):
        raise ValueError(f"tau = {tau!r} [s]: must be finite and > 0")
    if n_segments <= discard_segments + 1:
        raise ValueError(f"n_segments = {n_segments!r} [-]: must exceed discard_segments + 1")
    if not (math.isfinite(d0) and d0 > 0):
        raise ValueError(f"d0 = {d0!r} [norm units]: must be > 0")
    rates = np.empty(n_segments)
    t = t0
    for k in range(n_segments):
        ref = advance(ref, t, t + tau)
        pert = advance(pert, t, t + tau)
        t += tau
        d = difference(ref, pert)
        if not (math.isfinite(d) and d > 0):
            raise FloatingPointError(f"segment {k}: distance {d!r} (trajectories coincide or diverged)")
        rates[k] = math.log(d / d0) / tau
        pert = renormalise(ref, pert, d0 / d)
    used = rates[discard_segments:]
    times = t0 + tau * np.arange(discard_segments + 1, n_segments + 1)
    running = np.cumsum(used) / np.arange(1, used.size + 1)
    se, b = batch_stderr(used, batches)
    return LyapunovResult(
        float(used.mean()), se, b, used, times, running, {"tau": tau, "d0": d0, **(info or {})}
    )


# --- mechanisms -------------------------------------------------------------------------------


def _weights(system, time_scale: float) -> np.ndarray:
    n = system.n
    return np.concatenate([np.ones(n), np.full(n, time_scale)])


def system_lyapunov(
    system,
    tau: float,
    n_segments: int,
    *,
    transient: float = 0.0,
    d0: float = 1e-8,
    time_scale: float = 1.0,
    solver: str = "auto",
    rtol: float = 1e-10,
    atol: float = 1e-13,
    discard_segments: int = 10,
    batches: int = 10,
    seed: int = 1,
    t0: float = 0.0,
) -> LyapunovResult:
    """λ₁ [1/s] of a mechanism along the trajectory from its initial state (after
    ``transient`` [s]). The deviation norm [T126] is ‖(Δq, time_scale·Δq̇)‖₂ with coordinates in
    [m] and [rad] and ``time_scale`` [s] (e.g. 1/ω of the drive); ``d0`` [norm units] is the
    renormalised separation, τ [s] the segment length; the initial deviation is a seeded random
    direction projected onto the constraints [T11]."""
    from jointdyn.errors import SimulationError
    from jointdyn.integrators.common import FORCE_UNRESOLVED
    from jointdyn.multibody.dynamics import project
    from jointdyn.simulation.simulate import SimConfig, resolve_solver, simulate

    if not (math.isfinite(time_scale) and time_scale > 0):
        raise ValueError(f"time_scale = {time_scale!r} [s]: must be finite and > 0")
    if not (math.isfinite(transient) and transient >= 0):
        raise ValueError(f"transient = {transient!r} [s]: must be ≥ 0")
    if system.degrees_of_freedom() == 0:  # its motion is prescribed: no exponent to estimate [T286]
        raise ValueError(
            f"model {system.name!r} has no degree of freedom (every coordinate is prescribed by its "
            "joints and drivers): it has no Lyapunov exponent; use a model with a clearance joint"
        )
    solver = resolve_solver(system, solver)
    w = _weights(system, time_scale)
    P = system.packed(0.0)
    slots = _contact_slots(system)

    def advance(state, ta, tb):
        y, mem = state
        cfg = SimConfig(t_end=tb - ta, n_out=2, solver=solver, rtol=rtol, atol=atol)
        try:
            res = simulate(system, cfg, t0=ta, y0=y, mem0=mem)
        except SimulationError as err:
            # only the end state is used: the force-resolution guard [T111], which judges a force
            # against its peak over the (here two) samples, may object to a grazing contact of
            # a few 0.01 N at a segment's end although the integration completed
            if err.results is None or err.results.status != FORCE_UNRESOLVED:
                raise
            res = err.results
        return res.y[-1].copy(), res.mem[-1].copy()

    def difference(a, b):
        return float(np.linalg.norm(w * (b[0] - a[0])))

    t = t0
    ref = (system.y0.copy(), system.mem0.copy())
    if transient > 0:
        ref = advance(ref, t, t + transient)
        t += transient

    def renormalise(a, b, f):
        y = a[0] + f * (b[0] - a[0])
        project(t_now[0], y, P, 1e-14)
        mem = b[1].copy()
        for k, ic, ov in slots:  # same contact phase: scale the onset velocity with the state [T127]
            if a[1][k, ic] == b[1][k, ic]:
                mem[k, ov] = a[1][k, ov] + f * (b[1][k, ov] - a[1][k, ov])
        return y, mem

    rng = np.random.default_rng(seed)
    dy = rng.standard_normal(ref[0].size) / w
    y = ref[0] + 1e-3 * d0 * dy / np.linalg.norm(w * dy)
    project(t, y, P, 1e-14)
    d = float(np.linalg.norm(w * (y - ref[0])))
    if not d > 0:
        raise ValueError("the random initial deviation vanished on projection onto the constraints")
    y = ref[0] + (d0 / d) * (y - ref[0])
    pert = (y, ref[1].copy())

    t_now = [t]

    def advance_tracked(state, ta, tb):
        t_now[0] = tb
        return advance(state, ta, tb)

    info = {
        "solver": solver,
        "rtol": rtol,
        "atol": atol,
        "time_scale_s": time_scale,
        "transient_s": transient,
    }
    return benettin(
        advance_tracked,
        difference,
        renormalise,
        ref,
        pert,
        t,
        tau,
        n_segments,
        d0,
        discard_segments,
        batches,
        info,
    )


def _contact_slots(system) -> list[tuple[int, int, int]]:
    """(element index, in_contact slot, onset_velocity slot) of elements with contact memory."""
    out = []
    for k, el in enumerate(system.elements):
        mem = list(getattr(type(el), "MEMORY", {}))
        if "in_contact" in mem and "onset_velocity" in mem:
            out.append((k, mem.index("in_contact"), mem.index("onset_velocity")))
    return out


# --- ordinary differential equations (validation against published values) -------------------


def ode_lyapunov(
    f,
    x0: np.ndarray,
    tau: float,
    n_segments: int,
    *,
    transient: float = 0.0,
    d0: float = 1e-8,
    rtol: float = 1e-11,
    atol: float = 1e-13,
    discard_segments: int = 10,
    batches: int = 10,
    seed: int = 1,
) -> LyapunovResult:
    """λ₁ of ẋ = f(t, x) with the same renormalisation core [T125] (scipy DOP853; Euclidean
    norm). Used to validate :func:`benettin` on published chaotic flows."""
    from scipy.integrate import solve_ivp

    def advance(x, ta, tb):
        sol = solve_ivp(f, (ta, tb), x, method="DOP853", rtol=rtol, atol=atol)
        if not sol.success:
            raise FloatingPointError(sol.message)
        return sol.y[:, -1]

    x = np.asarray(x0, float)
    t = 0.0
    if transient > 0:
        x = advance(x, 0.0, transient)
        t = transient
    dx = np.random.default_rng(seed).standard_normal(x.size)
    pert = x + d0 * dx / np.linalg.norm(dx)
    return benettin(
        advance,
        lambda a, b: float(np.linalg.norm(b - a)),
        lambda a, b, fac: a + fac * (b - a),
        x,
        pert,
        t,
        tau,
        n_segments,
        d0,
        discard_segments,
        batches,
        {"rtol": rtol, "atol": atol},
    )


def plot_running(result: LyapunovResult, path, title: str = "") -> None:
    """Running estimate of λ₁ against time with the final value ± 2 standard errors."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(result.times, result.running, lw=1.2, label="running estimate")
    lam, se = result.exponent, result.stderr
    ax.axhline(lam, color="C3", lw=1, label=f"λ₁ = {lam:.4g} ± {se:.2g} 1/s (1 s.e.)")
    if math.isfinite(se):
        ax.axhspan(lam - 2 * se, lam + 2 * se, color="C3", alpha=0.15, label="± 2 s.e.")
    ax.axhline(0.0, color="0.5", lw=0.8)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("λ₁ estimate [1/s]")
    ax.set_title(title)
    ax.legend(fontsize=8)
    fig.tight_layout()
    with atomic.replacing(path) as tmp:
        fig.savefig(tmp, dpi=120, format="png")
    plt.close(fig)
