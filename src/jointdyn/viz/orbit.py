"""Orbit figures: the journal-centre path e/c [-] in the clearance circle, with its start, end
and direction of travel, the frame named on the axes (bushing frame by convention, [T290]) and
a zoomed inset for a path near the centre."""

from __future__ import annotations

import numpy as np


def _axes(ax, figsize=(4.6, 4.6)):
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(figsize=figsize)
    return ax


#: an orbit whose largest e/c is below this is also drawn zoomed in an inset [-]
SMALL_ORBIT = 0.25


def direction_points(x, y, n: int = 3) -> list[tuple[int, float]]:
    """``n`` places along a path (equal arc-length spacing) and the direction of travel there:
    (sample index, angle from +x [deg]); none for a path that does not move."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    seg = np.hypot(np.diff(x), np.diff(y))
    if x.size < 2 or not np.isfinite(seg).all() or seg.sum() <= 0:
        return []
    s = np.concatenate([[0.0], np.cumsum(seg)])
    out = []
    for f in (np.arange(n) + 0.5) / n:
        i = min(int(np.searchsorted(s, f * s[-1])), x.size - 2)
        j = i + 1
        while j < x.size - 1 and seg[j - 1] == 0.0:
            j += 1
        out.append((i, float(np.degrees(np.arctan2(y[j] - y[i], x[j] - x[i])))))
    return out


def _direction_marks(ax, x, y, color, n: int = 3) -> None:
    """Arrow heads at :func:`direction_points`, drawn as rotated markers (exact on equal-aspect
    axes); the angle is kept in the line's gid for the interactive copy."""
    from matplotlib.markers import MarkerStyle
    from matplotlib.transforms import Affine2D

    for i, ang in direction_points(x, y, n):
        mark = MarkerStyle(">", transform=Affine2D().rotate_deg(ang))
        ax.plot(
            x[i], y[i], ls="none", color=color, ms=7, label="_direction", marker=mark, gid=f"direction:{ang}"
        )


def _path(ax, ex, ey, label, marks: bool, first: bool, **kw):
    """One orbit on ``ax``: the path, its direction of travel, start (○) and end (×)."""
    (line,) = ax.plot(ex, ey, label=label, **kw)
    col = line.get_color()
    if marks and len(ex):
        _direction_marks(ax, ex, ey, col)
        ax.plot(ex[0], ey[0], "o", color=col, mfc="none", ms=7, label="start" if first else "_start")
        ax.plot(ex[-1], ey[-1], "x", color=col, ms=7, label="end" if first else "_end")
    return line


def orbit_labels(ax, frame: str | None) -> None:
    """Axis labels of an orbit naming the frame of the components [T290]."""
    where = f", {frame} frame" if frame else ""
    ax.set_xlabel(f"$e_x/c$ [-]{where}")
    ax.set_ylabel(f"$e_y/c$ [-]{where}")


def journal_orbit(
    ex_over_c, ey_over_c, ax=None, label=None, frame: str | None = None, start=True, zoom=True, **kw
):
    """Journal-centre path e/c [-] inside the clearance circle (ξ = 1, dashed), with the start
    (○), the end (×) and arrow heads along the direction of travel; ``frame`` names the frame of
    the components in the axis labels (the convention is the bushing frame, [T290]). A path that
    stays within ``SMALL_ORBIT`` of the centre is also drawn zoomed in an inset (upper right)
    unless ``zoom`` is False."""
    ax = _axes(ax, figsize=(4.6, 4.6))
    ex_over_c, ey_over_c = np.asarray(ex_over_c, float), np.asarray(ey_over_c, float)
    th = np.linspace(0, 2 * np.pi, 361)
    if not getattr(ax, "_jd_circle", False):
        ax.plot(np.cos(th), np.sin(th), "k--", lw=0.8, label="clearance circle (ξ = 1)")
        ax._jd_circle = True  # type: ignore[attr-defined]
    first = not getattr(ax, "_jd_marks", False)
    if start:
        ax._jd_marks = True  # type: ignore[attr-defined]
    lw = kw.pop("lw", 0.8)
    line = _path(ax, ex_over_c, ey_over_c, label, start, first, lw=lw, **kw)
    r = float(np.nanmax(np.hypot(ex_over_c, ey_over_c))) if len(ex_over_c) else 0.0
    ax.set_aspect("equal")
    lim = max(1.1, 1.05 * r)
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ticks = [-1.0, -0.5, 0.0, 0.5, 1.0]
    ax.set_xticks(ticks)
    ax.set_yticks(ticks)
    orbit_labels(ax, frame)
    ax.grid(True, alpha=0.3)
    if zoom and len(ex_over_c) and r < SMALL_ORBIT:
        _zoom(ax, ex_over_c, ey_over_c, line, start, lw, kw)
    return ax


def clear_paths(ax) -> None:
    """Empty an orbit axes of :func:`journal_orbit` for another path: the clearance circle, the
    ticks and labels stay; the paths, their marks, the inset and its zoom box go (a report draws
    nine orbits on one axes: its ticks are made once, [T371])."""
    keep = ax.lines[0] if getattr(ax, "_jd_circle", False) else None
    for a in [*ax.lines, *ax.patches, *ax.child_axes]:
        if a is not keep:
            a.remove()
    for name in ("_jd_marks", "_jd_inset", "_jd_zoom_marks"):
        if hasattr(ax, name):
            delattr(ax, name)


def _zoom(ax, ex, ey, line, marks: bool, lw, kw) -> None:
    """Draw a small orbit again in an inset of ``ax`` (one inset per axes, limits the union of
    its paths, the zoomed square marked on the main axes)."""
    ins = getattr(ax, "_jd_inset", None)
    if ins is None:
        ins = ax.inset_axes([0.59, 0.57, 0.38, 0.38])
        ins.set_facecolor("white")
        ins.set_aspect("equal")
        ins.grid(True, alpha=0.3)
        ins.tick_params(labelsize=6)
        ins._jd_lims = []  # type: ignore[attr-defined]
        ax._jd_inset = ins  # type: ignore[attr-defined]
    kw = {k: v for k, v in kw.items() if k != "color"}
    _path(ins, ex, ey, None, marks, False, lw=lw, color=line.get_color(), **kw)
    ins._jd_lims.append((np.nanmin(ex), np.nanmax(ex), np.nanmin(ey), np.nanmax(ey)))  # type: ignore[attr-defined]
    lo_x, hi_x, lo_y, hi_y = np.array(ins._jd_lims).T  # type: ignore[attr-defined]
    cx, cy = 0.5 * (lo_x.min() + hi_x.max()), 0.5 * (lo_y.min() + hi_y.max())
    half = 0.6 * max(hi_x.max() - lo_x.min(), hi_y.max() - lo_y.min(), 1e-6)
    ins.set_xlim(cx - half, cx + half)
    ins.set_ylim(cy - half, cy + half)
    ins.set_title(f"zoom ×{1.1 / half:.3g}", fontsize=7, pad=2)
    for p in getattr(ax, "_jd_zoom_marks", ()):
        p.remove()
    from matplotlib.patches import Rectangle

    box = Rectangle((cx - half, cy - half), 2 * half, 2 * half, fill=False, ec="0.4", lw=0.6)
    ax.add_patch(box)
    ax._jd_zoom_marks = (box,)  # type: ignore[attr-defined]
