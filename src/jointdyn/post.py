"""Derived quantities from results (pure functions of a :class:`~jointdyn.results.Results`)."""

from __future__ import annotations

import numpy as np

from .joints.constraints import Revolute


def driving_moment(res, driver: str = "drive") -> np.ndarray:
    """Moment the named angle driver applies to its body, CCW positive [N·m] (= its λ) [T7]."""
    return res.multipliers(driver)[:, 0]


def joint_reaction(res, joint: str) -> np.ndarray:
    """Reaction force of a revolute joint on its body i, world frame, (n_t, 2) [N] [T5].

    Body j receives the opposite force."""
    c = res.system.constraints[res.system.constraint_names.index(joint)]
    if not isinstance(c, Revolute):
        raise TypeError(f"{joint!r} is a {type(c).__name__}, not a Revolute joint")
    return res.multipliers(joint)


def body_angle(res, body: str) -> np.ndarray:
    """Unwrapped body angle [rad]."""
    return res.coordinate(body, "phi")


def window(res, t_from: float | None = None):
    """Boolean mask of samples with t ≥ t_from [s] (all if None)."""
    return np.ones_like(res.t, dtype=bool) if t_from is None else res.t >= t_from - 1e-12


def stats(x: np.ndarray) -> dict:
    """peak (max), min and RMS of a series."""
    return {"peak": float(np.max(x)), "min": float(np.min(x)), "rms": float(np.sqrt(np.mean(x * x)))}


def count_events(flag: np.ndarray) -> int:
    """Number of rising edges of a 0/1 series (e.g. contact onsets between samples)."""
    f = np.asarray(flag) > 0.5
    return int(np.count_nonzero(f[1:] & ~f[:-1]) + (1 if f.size and f[0] else 0))


def impacts(res, element: str) -> int:
    """Contact onsets of a journal element counted over the accepted steps (its ``impacts``
    memory slot at the last sample) [-]."""
    m = res.memory(element, "impacts")
    return int(m[-1]) if m.size else 0


def max_penetration(res, element: str) -> float:
    """Largest contact penetration of a journal element over the accepted steps [m] (0 if it
    never touched)."""
    m = res.memory(element, "max_penetration")
    return float(m[-1]) if m.size else 0.0


def dissipated_energy(res, element: str) -> float:
    """Energy the element removed from the mechanism over the run, −∫ power dt [J]
    (trapezoidal rule on the output samples)."""
    return float(-np.trapezoid(res.element(element, "power"), res.t))
