"""Derived quantities from results (pure functions of a :class:`~jointdyn.simulation.results.Results`)."""

from __future__ import annotations

import numpy as np

from jointdyn.core.constraints import Revolute


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
    """Largest contact penetration of a journal element over the run, peaks between step ends
    included ([T202]) [m] (0 if it never touched)."""
    m = res.memory(element, "max_penetration")
    return float(m[-1]) if m.size else 0.0


def dissipated_energy(res, element: str) -> float:
    """Energy the element removed from the mechanism over the run, −∫ power dt [J]
    (trapezoidal rule on the output samples)."""
    return float(-np.trapezoid(res.element(element, "power"), res.t))


def film_states(res, element: str) -> dict:
    """Film state of a journal bearing at every sample: ``xi`` [-], ``xi_dot`` [1/s],
    ``xi_Omega`` [rad/s] (Ω = ω_J + ω_B − 2γ̇, [T14]), ``gamma`` [rad] (line of centres relative
    to the bushing body) and the bushing body's angle ``phi_bearing`` [rad]."""
    from jointdyn.core.layout import BODY_I, BODY_J
    from jointdyn.forces.journal import CLR, journal_kinematics

    s = res.system
    k = res._element(element)[0]
    bi, bj, fr = s.fint[k, BODY_I], s.fint[k, BODY_J], s.freal[k]
    c = fr[CLR]
    n = s.n
    out = {key: np.empty(len(res.t)) for key in ("xi", "xi_dot", "xi_Omega", "gamma", "phi_bearing")}
    for i in range(len(res.t)):
        q, qd = res.y[i, :n], res.y[i, n:]
        ex, ey, edx, edy, _, _, _, _, wi, wj = journal_kinematics(q, qd, bi, bj, fr)
        e = float(np.hypot(ex, ey))
        ux, uy = (ex / e, ey / e) if e > 0 else (1.0, 0.0)
        phi_b = q[3 * bi + 2] if bi >= 0 else 0.0
        out["xi"][i] = e / c
        out["xi_dot"][i] = (ux * edx + uy * edy) / c
        out["xi_Omega"][i] = e / c * (wj + wi) - 2.0 * (-uy * edx + ux * edy) / c
        out["gamma"][i] = np.arctan2(ey, ex) - phi_b
        out["phi_bearing"][i] = phi_b
    return out


def film_viscosity(res, element: str) -> np.ndarray:
    """Film viscosity μ [Pa·s] of journal bearing ``element`` at every sample: its constant
    ``viscosity``, or with a lumped oil temperature μ(T) from the element's memory, the value
    the film used over the step that reached the sample [T311]."""
    el = res.system.elements[res._element(element)[0]]
    if getattr(el, "thermal", None) is not None:
        return np.array(res.memory(element, "viscosity"), dtype=float)
    return np.full(len(res.t), float(el.viscosity))


def film_outputs(res, element: str) -> dict:
    """Pressure-related outputs of a lubricated bearing at every sample, from the film model it
    ran with [T76, T81–T83]: ``p_max`` [Pa], ``theta_pmax`` [deg] (angle of the peak pressure in
    the bushing frame, from the bushing's x axis, CCW), ``theta_end`` [deg] (film end/rupture,
    same frame) and ``side_flow`` [m³/s] (short and finite models; NaN for the long models,
    which have none)."""
    from jointdyn.core.layout import params_of
    from jointdyn.film.finite import finite_outputs
    from jointdyn.film.models import FILM_WIDTH, film_model, film_name
    from jointdyn.film.pi_outputs import long_pi_outputs, short_pi_outputs
    from jointdyn.forces.journal import TABLE

    k = res._element(element)[0]
    el = res.system.elements[k]
    if getattr(el, "film", None) is None:
        raise ValueError(f"element {element!r} is a {type(el).__name__}, not a lubricated JournalBearing")
    name, fm = film_name(el.film), film_model(el.film)
    st = film_states(res, element)
    mu, R, L = film_viscosity(res, element), el.journal_radius, el.length
    c = el.bearing_radius - el.journal_radius  # the clearance [m]
    p = np.zeros(FILM_WIDTH)
    p[: len(fm.PARAMS)] = params_of(fm)
    tab = res.system.tables[res.system.fint[k, TABLE]] if hasattr(fm, "table") else None  # the run's table
    nt = len(res.t)
    out = {k: np.full(nt, np.nan) for k in ("p_max", "theta_pmax", "theta_end", "side_flow")}
    for i in range(nt):
        x, a, b = min(st["xi"][i], 1.0 - 1e-9), st["xi_dot"][i], st["xi_Omega"][i]
        if name == "finite":
            pm, tp, te, qs = finite_outputs(x, a, b, mu[i], R, L, c, p, tab)
        elif name == "short":
            pm, tp, _, te, qs = short_pi_outputs(x, a, b, mu[i], R, L, c)
        else:  # long models: the π-film's pressure (Ott approximates the same film, [T165])
            pm, tp, _, te = long_pi_outputs(x, a, b, mu[i], R, c)
            qs = np.nan
        out["p_max"][i], out["side_flow"][i] = pm, qs
        # θ from the maximum film -> bushing frame: α = θ + γ + π [T76]
        for key, th in (("theta_pmax", tp), ("theta_end", te)):
            out[key][i] = np.degrees(np.mod(th + st["gamma"][i] + np.pi, 2 * np.pi))
    return out
