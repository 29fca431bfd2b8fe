"""Poincaré sections of a run: stroboscopic at a phase of an angle driver's revolution, or a
state-space plane crossing.

The section variables of a journal element are the journal's position relative to the bearing
centre, e = P_j − P_i [m], and its rate [m/s], resolved in the bushing's frame (body i) as the
orbits are [T290, T350], both from the body coordinates and velocities at the output samples
[T124] (exact at the samples, no finite differences). Sections: stroboscopic [T122] or a plane
crossing [T123].
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from jointdyn.core import atomic

#: the journal-state variables of a section: e/c and ė/(cω) in the bushing frame [T290, T350]
VARIABLES = ("ex_bushing_over_c", "ey_bushing_over_c", "exdot_bushing_over_cw", "eydot_bushing_over_cw")


def journal_relative_state(res, element: str) -> dict[str, np.ndarray]:
    """ex, ey [m] and ex_dot, ey_dot [m/s] of journal element ``element`` at the output samples,
    world frame, e = P_j − P_i [T124, T1, T2]; the bushing body's angle ``phi_i`` [rad] and rate
    ``phid_i`` [rad/s] (zero for a bushing on the ground); the clearance c [m] under key ``"c"``."""
    s = res.system
    if element not in s.element_names:
        raise KeyError(f"no force element named {element!r}; elements are {list(s.element_names)}")
    k = s.element_names.index(element)
    el = s.elements[k]
    if not hasattr(el, "clearance"):
        raise TypeError(f"element {element!r} is a {type(el).__name__}, not a journal element")
    from jointdyn.core.layout import BODY_I, BODY_J, ETA_I, ETA_J, XI_I, XI_J

    bi, bj = int(s.fint[k, BODY_I]), int(s.fint[k, BODY_J])
    xi_i, eta_i, xi_j, eta_j = (float(s.freal[k, c]) for c in (XI_I, ETA_I, XI_J, ETA_J))
    q, qd = res.q, res.qd

    def point(b, xi, eta):
        if b < 0:
            z = np.zeros_like(res.t)
            return xi + z, eta + z, z, z
        x, y, phi = q[:, 3 * b], q[:, 3 * b + 1], q[:, 3 * b + 2]
        xd, yd, phid = qd[:, 3 * b], qd[:, 3 * b + 1], qd[:, 3 * b + 2]
        sx = np.cos(phi) * xi - np.sin(phi) * eta
        sy = np.sin(phi) * xi + np.cos(phi) * eta
        return x + sx, y + sy, xd - phid * sy, yd + phid * sx  # [T1, T2]

    pix, piy, vix, viy = point(bi, xi_i, eta_i)
    pjx, pjy, vjx, vjy = point(bj, xi_j, eta_j)
    z = np.zeros_like(res.t)
    phi_i, phid_i = (z, z) if bi < 0 else (q[:, 3 * bi + 2], qd[:, 3 * bi + 2])
    e = {"ex": pjx - pix, "ey": pjy - piy, "ex_dot": vjx - vix, "ey_dot": vjy - viy}
    return e | {"phi_i": phi_i, "phid_i": phid_i, "c": el.clearance}


def bushing_frame(st: dict) -> dict[str, np.ndarray]:
    """The relative state of :func:`journal_relative_state` resolved in the bushing's frame
    [T290, T350]: u = A(φ_i)ᵀ e [m] and its time derivative u̇ = A(φ_i)ᵀ ė − φ̇_i S u [m/s]
    (S the rotation by +90°), i.e. u̇_x = (Aᵀė)_x + φ̇_i u_y, u̇_y = (Aᵀė)_y − φ̇_i u_x."""
    cs, sn, w = np.cos(st["phi_i"]), np.sin(st["phi_i"]), st["phid_i"]
    ux, uy = cs * st["ex"] + sn * st["ey"], -sn * st["ex"] + cs * st["ey"]
    ax, ay = cs * st["ex_dot"] + sn * st["ey_dot"], -sn * st["ex_dot"] + cs * st["ey_dot"]
    return {"ex": ux, "ey": uy, "ex_dot": ax + w * uy, "ey_dot": ay - w * ux}


@dataclass(frozen=True)
class Section:
    """Points of a Poincaré section: ``t`` [s] of each crossing and the section variables
    (name -> array), in the units of :func:`journal_relative_state` divided as documented by
    the producer (``ex/c`` … are dimensionless, ``ex_dot/(cω)`` too)."""

    t: np.ndarray
    values: dict
    kind: str
    description: str


def stroboscopic_indices(angle: np.ndarray, section_angle: float, tol: float = 1e-9) -> np.ndarray:
    """Sample indices where the unwrapped ``angle`` [rad] equals section_angle + 2πk (to
    ``tol`` [rad]); these exist when the output grid is commensurate with the revolution (the
    shipped runs sample ``samples_per_rev`` points per revolution from φ = 0)."""
    k = (angle - section_angle) / (2 * math.pi)
    near = np.abs(k - np.round(k)) * 2 * math.pi < tol
    return np.flatnonzero(near)


def stroboscopic(series: dict, angle: np.ndarray, section_angle: float, t: np.ndarray) -> Section:
    """Stroboscopic section at driver angle ``section_angle`` [rad] (mod 2π) [T122]. ``series`` maps
    names to arrays sampled with ``angle``. Where no sample lies on the section angle, the
    values are interpolated linearly between the two neighbouring samples."""
    idx = stroboscopic_indices(angle, section_angle)
    if idx.size >= 2:
        return Section(
            t[idx], {k: v[idx] for k, v in series.items()}, "stroboscopic", f"{section_angle:g} rad"
        )
    a0 = section_angle + 2 * math.pi * np.ceil((angle[0] - section_angle) / (2 * math.pi))
    targets = np.arange(a0, angle[-1] + 1e-12, 2 * math.pi)
    vals = {k: np.interp(targets, angle, v) for k, v in series.items()}
    return Section(np.interp(targets, angle, t), vals, "stroboscopic", f"{section_angle:g} rad (interp.)")


def plane_crossing(series: dict, key: str, level: float, t: np.ndarray, direction: int = 1) -> Section:
    """Section where ``series[key]`` crosses ``level`` upwards (direction = +1), downwards (−1)
    or both (0) [T123]; the other variables are interpolated linearly to the crossing time."""
    s = np.asarray(series[key]) - level
    up = (s[:-1] < 0) & (s[1:] >= 0)
    down = (s[:-1] > 0) & (s[1:] <= 0)
    mask = up if direction > 0 else down if direction < 0 else (up | down)
    i = np.flatnonzero(mask)
    w = s[i] / (s[i] - s[i + 1])
    vals = {k: np.asarray(v)[i] + w * (np.asarray(v)[i + 1] - np.asarray(v)[i]) for k, v in series.items()}
    return Section(
        t[i] + w * (t[i + 1] - t[i]), vals, "plane", f"{key} = {level:g}, direction {direction:+d}"
    )


def phase(res, driver: str | None = None, period: float | None = None) -> tuple[np.ndarray, float]:
    """(phase angle [rad] at the samples, ω [rad/s]) of the revolution a study uses: the
    relative angle of angle driver ``driver`` (default: the model's first) and its speed
    [T7]; or, with an explicit ``period`` T [s], the phase 2π t/T and ω = 2π/T."""
    from jointdyn.studies import period as per

    if period is not None:
        if not (math.isfinite(period) and period > 0):
            raise ValueError(f"--period = {period!r} [s]: must be finite and > 0")
        w = 2 * math.pi / period
        return w * res.t, w
    name = per.driver_name(res.system, driver)
    return per.driver_angle(res, name), 2 * math.pi / per.driver_period(res.system, name)


def journal_series(res, element: str, omega: float) -> dict[str, np.ndarray]:
    """A journal's relative state in the bushing frame [T124, T350]: e_x/c, e_y/c [-] and
    ė_x/(cω), ė_y/(cω) [-] (:func:`bushing_frame`) with ω [rad/s] the speed of the revolution
    (:func:`phase`), under the names of ``VARIABLES``."""
    st = journal_relative_state(res, element)
    c, w = st["c"], abs(omega)
    b = bushing_frame(st)
    x, y, xd, yd = VARIABLES
    return {x: b["ex"] / c, y: b["ey"] / c, xd: b["ex_dot"] / (c * w), yd: b["ey_dot"] / (c * w)}


def journal_section(
    res,
    element: str | None = None,
    driver: str | None = None,
    section_angle: float = 0.0,
    transient: float = 0.0,
    period: float | None = None,
    plane: tuple[str, float, int] | None = None,
) -> Section:
    """Poincaré section of a journal's relative state (:func:`journal_series`; ``element``
    default: the model's first journal element) after ``transient`` [s]: stroboscopic at phase
    ``section_angle`` [rad] of the revolution of :func:`phase` [T122], or, with
    ``plane = (variable, level, direction)``, where that variable crosses the level [T123]."""
    from jointdyn.studies.period import journal

    angle, w = phase(res, driver, period)
    series = journal_series(res, journal(res.system, element), w)
    if not (math.isfinite(transient) and transient >= 0):
        raise ValueError(f"transient = {transient!r} [s]: must be finite and >= 0")
    keep = res.t >= transient - 1e-12
    if np.count_nonzero(keep) < 2:  # nothing left to section: one line, not an IndexError
        raise ValueError(
            f"transient = {transient:.6g} [s]: the run ends at t = {res.t[-1]:.6g} s; discard less "
            "(--transient-revs) or run longer"
        )
    series = {k: v[keep] for k, v in series.items()}
    if plane is not None:
        key, level, direction = plane
        if key not in series:
            raise ValueError(f"plane variable {key!r}: valid: {list(series)}")
        return plane_crossing(series, key, float(level), res.t[keep], int(direction))
    return stroboscopic(series, angle[keep], section_angle, res.t[keep])


def plot_sections(sections: dict, path, title: str = "") -> None:
    """Side-by-side Poincaré maps (position ex/c–ey/c and velocity) of named sections."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = len(sections)
    fig, axes = plt.subplots(2, n, figsize=(4.2 * n, 8.2), squeeze=False)
    for ax in axes[1, 1:]:  # one velocity scale for all sections (a periodic one is a dot)
        ax.sharex(axes[1, 0])
        ax.sharey(axes[1, 0])
    for col, (name, sec) in enumerate(sections.items()):
        v = sec.values
        ax = axes[0, col]
        th = np.linspace(0, 2 * np.pi, 361)
        ax.plot(np.cos(th), np.sin(th), color="0.6", lw=0.8, label="clearance circle")
        ax.plot(v["ex_bushing_over_c"], v["ey_bushing_over_c"], ".", ms=3, color="C0")
        ax.set_aspect("equal")
        ax.set_xlabel("e_x / c [-], bushing frame")  # the section variables' frame [T290, T350]
        ax.set_ylabel("e_y / c [-], bushing frame")
        ax.set_title(f"{name}: {len(sec.t)} points")
        ax = axes[1, col]
        ax.plot(v["ex_bushing_over_c"], v["exdot_bushing_over_cw"], ".", ms=3, color="C1")
        ax.set_xlabel("e_x / c [-], bushing frame")
        ax.set_ylabel("ė_x / (c ω) [-], bushing frame")
        ax.ticklabel_format(useOffset=False)
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    with atomic.replacing(path) as tmp:
        fig.savefig(tmp, dpi=120, format="png")
    plt.close(fig)


def section_arrays(
    res,
    transient_revs: int,
    record_revs: int,
    section_angle_deg: float,
    element: str | None = None,
    driver: str | None = None,
    period: float | None = None,
) -> dict:
    """Stroboscopic section of a run's journal element (default: its first) [T122]: the four
    ``VARIABLES`` at phase ``section_angle_deg`` of the revolution (:func:`phase`) once per
    revolution for the ``record_revs`` revolutions after ``transient_revs``, and
    ``impacts_per_rev`` (from the element's onset counter) when it has contact memory. Lists of
    floats (JSON-ready)."""
    from jointdyn.studies.period import journal

    el = journal(res.system, element)
    angle, w = phase(res, driver, period)
    T = 2 * math.pi / abs(w)
    sec = journal_section(res, el, driver, math.radians(section_angle_deg), transient_revs * T, period=period)
    out = {k: np.asarray(sec.values[k])[:record_revs].tolist() for k in VARIABLES}
    if "impacts" in type(res.system.elements[res.system.element_names.index(el)]).MEMORY:
        b = stroboscopic_indices(angle, float(angle[0]))[transient_revs : transient_revs + record_revs + 1]
        out["impacts_per_rev"] = np.diff(res.memory(el, "impacts")[b]).tolist()
    return out
