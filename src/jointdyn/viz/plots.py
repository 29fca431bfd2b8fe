"""Figures. Each function draws on a matplotlib Axes (pass ``ax=``, or one is created) and
returns it; nothing calls ``show()``.

Array helpers (``moment_vs_angle``, ``journal_orbit``, ``series_vs_angle``, ``sweep_metric``)
take plain arrays. Run helpers take :class:`~jointdyn.simulation.results.Results` (or a loaded
``results.nc`` Dataset) and default to the crank angle on the x-axis [deg], with
``last_revs`` to keep only the last revolutions (axis then reads 0–360° per revolution),
legend names from the model and ``overlay`` for comparing runs. :func:`plot_run` writes one
figure of a run directory to ``plot_<what>.png`` and never overwrites the run's own figures.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from jointdyn.units import to_rpm
from jointdyn.viz import style
from jointdyn.viz.orbit import journal_orbit as journal_orbit  # the orbit figure, re-exported

WHATS = ("moment", "orbit", "film", "contact", "energy")
FRAMES = ("bushing", "world")


def _axes(ax, figsize=(7, 4)):
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(figsize=figsize)
    return ax


def _angle_ticks(ax, span_deg: float) -> None:
    """Crank-angle ticks: every 10°/30° on short windows, 90° up to two revolutions, 360° beyond."""
    from matplotlib.ticker import MultipleLocator

    steps = ((60, 10), (180, 30), (720, 90))
    ax.xaxis.set_major_locator(MultipleLocator(next((d for lim, d in steps if span_deg <= lim + 1e-9), 360)))


# -- array helpers --------------------------------------------------------------------------------
def moment_vs_angle(angle, moment, ax=None, label=None, **kw):
    """Crank moment [N·m] vs crank angle [rad] (axis shown in degrees)."""
    return series_vs_angle(angle, moment, "crank driving moment [N·m]", ax=ax, label=label, **kw)


def series_vs_angle(angle, values, ylabel, ax=None, label=None, **kw):
    """Any series vs crank angle [rad] (axis in degrees, ticks every 90° or 360°)."""
    ax = _axes(ax)
    deg = np.degrees(np.asarray(angle))
    ax.plot(deg, values, label=label, lw=kw.pop("lw", 1.0), **kw)
    ax.set_xlabel("crank angle [deg]")
    ax.set_ylabel(ylabel)
    if deg.size:
        ax.set_xlim(deg.min(), deg.max())
        _angle_ticks(ax, float(np.ptp(deg)))
    ax.grid(True, alpha=0.3)
    return ax


# -- runs -----------------------------------------------------------------------------------------
def _as_results(r):
    from jointdyn.simulation.results import Results

    if isinstance(r, Results):
        return r
    if isinstance(r, (str, Path)):
        p = Path(r)
        return Results.load(p / "results.nc" if p.is_dir() else p)
    return Results.from_dataset(r)


def describe(res, sep: str = "\n") -> str:
    """Title text: model and speed [rpm], then each journal's clearance [mm], viscosity [Pa·s]
    and film model (joined by ``sep``)."""
    s = res.system
    head = s.name
    try:
        c = s.constraints[s.constraint_names.index(res.driver())]
        head += f", {to_rpm(c.omega):.4g} rpm"
    except KeyError:
        pass
    parts = []
    for n, e in zip(s.element_names, s.elements):
        if hasattr(e, "clearance"):
            p = f"{n}: c = {e.clearance * 1e3:.3g} mm"
            if getattr(e, "thermal", None) is not None:
                p += f", μ(T) of {e.thermal.oil}, film {e.film}"
            elif hasattr(e, "viscosity"):
                p += f", μ = {e.viscosity:.3g} Pa·s, film {e.film}"
            parts.append(p)
    return head + (sep + sep.join(parts) if parts else "")


def _auto_revs(res, what, last_revs):
    """Orbits skip the start-up transient by default: the last revolution of runs of ≥ 2."""
    if last_revs is not None or what != "orbit":
        return last_revs or None
    try:
        a = res.crank_angle()
    except KeyError:
        return None
    return 1.0 if abs(a[-1] - a[0]) >= 4 * np.pi - 1e-9 else None


def _window(res, last_revs):
    return res.last_revolutions(last_revs) if last_revs else res


def _xvals(res, x: str, last_revs):
    """(x values, x label, is_angle): crank angle [deg] from the window start, or time [ms]."""
    if x == "angle":
        try:
            a = res.crank_angle()
        except KeyError:
            x = "time"
        else:
            return (
                np.degrees(a - a[0]),
                "crank angle [deg]" + (f", last {last_revs:g} rev." if last_revs else ""),
                True,
            )
    if x != "time":
        raise ValueError(f"x = {x!r}: valid: ['angle', 'time']")
    return res.t * 1e3, "time [ms]", False


def _driven(res) -> str:
    s = res.system
    return s.constraints[s.constraint_names.index(res.driver())].body_j


def _finish_x(ax, xs, is_angle):
    if is_angle and len(xs):
        ax.set_xlim(xs.min(), xs.max())
        _angle_ticks(ax, float(np.ptp(xs)))
    ax.grid(True, alpha=0.3)


def _label(res, name, overlay: bool, run_label):
    return f"{run_label}: {name}" if overlay else name


def _journal(res, element):
    names = res.journals()
    if not names:
        raise ValueError(f"{res.system.name!r} has no journal element (bearing or clearance joint)")
    if element is None:
        return names
    if element not in names:
        raise ValueError(f"element = {element!r}: journal elements are {names}")
    return [element]


def run_figure(
    runs, what: str, ax=None, labels=None, x="angle", last_revs=None, frame="bushing", element=None
):
    """Draw ``what`` (moment | orbit | film | contact | energy) for one run or several overlaid.

    ``runs``: a Results, Dataset, run directory, or a list of them; ``labels``: one name per
    run (default: the model names); ``x``: ``"angle"`` (crank angle [deg]) or ``"time"``;
    ``last_revs``: only the last N crank revolutions [-]; ``frame``: orbit in the ``bushing``
    or ``world`` frame; ``element``: one journal element (default all)."""
    if what not in WHATS:
        raise ValueError(f"what = {what!r}: valid: {list(WHATS)}")
    if frame not in FRAMES:
        raise ValueError(f"frame = {frame!r}: valid: {list(FRAMES)}")
    runs = [_as_results(r) for r in (runs if isinstance(runs, (list, tuple)) else [runs])]
    labels = list(labels) if labels else [r.system.name for r in runs]
    many = len(runs) > 1
    ax = _axes(ax, figsize=(5.2, 5.2) if what == "orbit" else (8, 4.5))
    ax.set_prop_cycle(style.cycle())  # Okabe–Ito colours with dash patterns, as in every figure
    revs = last_revs
    for run, lab in zip(runs, labels):
        revs = _auto_revs(run, what, last_revs)
        res = _window(run, revs)
        xs, xlabel, is_angle = _xvals(res, x, revs)
        if what == "moment":
            from jointdyn.core.constraints import AngleDriver

            drivers = [
                n
                for n, c in zip(res.system.constraint_names, res.system.constraints)
                if isinstance(c, AngleDriver)
            ]
            if not drivers:
                raise ValueError(f"{res.system.name!r} has no angle driver: no driving moment to plot")
            for d in drivers:
                name = lab if many and len(drivers) == 1 else _label(res, f"{d} moment", many, lab)
                ax.plot(xs, res.multipliers(d)[:, 0], lw=1.0, label=name)
            ax.set_ylabel("driving moment [N·m]")
        elif what == "orbit":
            for e in _journal(res, element):
                ex, ey = res.orbit(e, frame=frame)
                journal_orbit(ex, ey, ax=ax, label=_label(res, e, many, lab), frame=frame)
            continue
        elif what == "film":
            positive = True
            for k, e in enumerate(_journal(res, element)):
                h = res.element(e, "h_min") * 1e6
                positive &= bool(np.all(h > 0))
                (ln,) = ax.plot(xs, h, lw=1.0, label=_label(res, f"{e}: h_min", many, lab))
                i = int(np.argmin(h))
                ax.plot(xs[i], h[i], "v", color=ln.get_color())
                where = f"{xs[i]:.0f}°" if is_angle else f"{xs[i]:.3g} ms"
                ax.annotate(
                    f"min {h[i]:.3g} µm at {where}",
                    (xs[i], h[i]),
                    textcoords="offset points",
                    xytext=(6, 8 + 11 * k),  # stacked when several journals share the axes
                    fontsize=8,
                    color=ln.get_color(),
                )
            if positive:  # a film: log axis; a dry gap goes negative (penetration): linear
                from matplotlib.ticker import FuncFormatter

                ax.set_yscale("log")
                ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
                ax.yaxis.set_minor_formatter(
                    FuncFormatter(lambda v, _: f"{v:g}" if f"{v:g}"[0] in "25" else "")
                )
                ax.set_ylabel("minimum film thickness $h_{min}$ [µm]")
            else:
                ax.axhline(0.0, color="k", lw=0.6)
                ax.set_ylabel("gap $h_{min}$ [µm] (< 0: penetration)")
        elif what == "contact":
            els = _journal(res, element)
            with_law = [
                e
                for e in els
                if getattr(res.system.elements[res.system.element_names.index(e)], "contact", None)
            ]
            if not with_law:
                raise ValueError(
                    f"{res.system.name!r}: no journal element with a contact law ({els}); the contact force "
                    "is identically zero — plot 'film' instead"
                )
            for e in with_law:
                ax.plot(xs, res.element(e, "contact_force"), lw=0.8, label=_label(res, e, many, lab))
            ax.set_ylabel("contact normal force [N]")
        elif what == "energy":
            t = res.t
            for e in res.system.element_names:
                p = -res.element(e, "power")
                w = np.concatenate([[0.0], np.cumsum(0.5 * (p[1:] + p[:-1]) * np.diff(t))])
                ax.plot(xs, w, lw=1.0, label=_label(res, f"{e}: −∫ power dt", many, lab))
            try:
                d = res.driver()
                pw = res.multipliers(d)[:, 0] * res.qd[:, 3 * res.system.body_names.index(_driven(res)) + 2]
                w = np.concatenate([[0.0], np.cumsum(0.5 * (pw[1:] + pw[:-1]) * np.diff(t))])
                ax.plot(xs, w, "k--", lw=0.8, label=_label(res, f"{d}: net work input", many, lab))
            except KeyError:
                pass
            ax.set_ylabel("energy removed from the mechanism [J]\n(< 0: supplied), since the window start")
        ax.set_xlabel(xlabel)
        _finish_x(ax, xs, is_angle)
    if len(runs) == 1:
        window = ("\nlast revolution" if revs == 1 else f"\nlast {revs:g} revolutions") if revs else ""
        what_ = f"\njournal centre path e/c, {frame} frame" if what == "orbit" else ""
        ax.set_title(describe(runs[0]) + window + what_, fontsize=9)
    elif what == "orbit":
        ax.set_title(f"journal centre path e/c, {frame} frame", fontsize=9)
    if what == "orbit":
        style.legend_below(ax, ncol=4, y=-0.14)
    else:  # outside the data: under the axis label
        style.legend_below(ax, ncol=2, y=-0.16)
    return ax


def plot_run(directory, what: str = "moment", out=None, overlay=(), **kw) -> Path:
    """Write one figure of a run directory (and ``overlay`` directories) to ``out`` (default
    ``DIR/plot_<what>.png``; the run's own ``moment.png``/``orbit.png`` are never touched).
    Keyword arguments go to :func:`run_figure`."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    directory = Path(directory)
    dirs = [directory, *[Path(o) for o in overlay]]
    labels = kw.pop("labels", None) or [d.name for d in dirs]
    fig, ax = plt.subplots(figsize=(5.4, 5.4) if what == "orbit" else (8, 4.5))
    try:
        run_figure(dirs, what, ax=ax, labels=labels, **kw)
    except Exception:
        plt.close(fig)
        raise
    target = Path(out) if out else directory / f"plot_{what}.png"
    if target.name in ("moment.png", "orbit.png") and target.parent == directory:
        plt.close(fig)
        raise ValueError(f"out = {str(target)!r}: would overwrite the run's own figure; choose another name")
    fig.tight_layout()
    from jointdyn.io.derived import output_file

    try:
        with output_file(target) as tmp:  # in a run directory: added to its manifest
            fig.savefig(tmp, dpi=150, format=target.suffix[1:] or "png")
    finally:
        plt.close(fig)
    return target


def saved_run(ds, what: str, ax=None, **kw):
    """Draw ``what`` from a saved run (Dataset, Results or directory); see :func:`run_figure`."""
    return run_figure(ds, what, ax=ax, **kw)


# -- sweeps ---------------------------------------------------------------------------------------
#: display unit per quantity: (unit shown, factor from SI)
DISPLAY = {
    "clearance": ("µm", 1e6),
    "min_h_min": ("µm", 1e6),
    "viscosity": ("Pa·s", 1.0),
    "speed": ("rpm", 60 / (2 * np.pi)),
    "length": ("mm", 1e3),
    "gravity": ("m/s²", 1.0),
    "restitution": ("-", 1.0),
    "peak_moment": ("N·m", 1.0),
    "min_moment": ("N·m", 1.0),
    "rms_moment": ("N·m", 1.0),
    "max_xi": ("-", 1.0),
    "impacts": ("-", 1.0),
    "energy_dissipated": ("J", 1.0),
    "wall_time_s": ("s", 1.0),
}
UNITS = {k: v[0] for k, v in DISPLAY.items()}  # kept for callers of the old name


#: readable names of sweep parameters and metrics
NAMES = {
    "peak_moment": "peak crank moment",
    "min_moment": "minimum crank moment",
    "rms_moment": "RMS crank moment",
    "max_xi": "max eccentricity ratio ξ",
    "min_h_min": "minimum film thickness",
    "impacts": "impacts",
    "energy_dissipated": "energy dissipated",
    "wall_time_s": "wall time",
}


def _disp(name, values):
    unit, f = DISPLAY.get(str(name), ("", 1.0))
    label = NAMES.get(str(name), str(name).replace("_", " ")) + (f" [{unit}]" if unit else "")
    return np.asarray(values, float) * f, label


def _fmt(v) -> str:
    return f"{v:.3g}"


def sweep_metric(da, ax=None, annotate: bool | None = None):
    """Heat map of a sweep metric over two swept parameters, or a line over one, in display
    units (µm, rpm, mm), axes ascending; cells are labelled when the grid is at most 8×8."""
    ax = _axes(ax, figsize=(6.4, 5))
    da = da.sortby(list(da.dims))
    vals, vlabel = _disp(da.name, da.values)
    if da.ndim == 2:
        y, x = da.dims
        X, xl = _disp(x, da[x].values)
        Y, yl = _disp(y, da[y].values)
        m = ax.pcolormesh(np.arange(len(X) + 1), np.arange(len(Y) + 1), vals, shading="flat", cmap="viridis")
        ax.set_xticks(np.arange(len(X)) + 0.5, [_fmt(v) for v in X])
        ax.set_yticks(np.arange(len(Y)) + 0.5, [_fmt(v) for v in Y])
        if annotate or (annotate is None and len(X) <= 8 and len(Y) <= 8):
            finite = vals[np.isfinite(vals)]
            lo, hi = (finite.min(), finite.max()) if finite.size else (0.0, 1.0)
            for i in range(len(Y)):
                for j in range(len(X)):
                    v = vals[i, j]
                    light = (v - lo) / (hi - lo) > 0.6 if hi > lo else False
                    ax.text(
                        j + 0.5,
                        i + 0.5,
                        "failed" if not np.isfinite(v) else f"{v:.4g}",
                        ha="center",
                        va="center",
                        fontsize=8,
                        color="k" if light else "w",
                    )
        ax.set_xlabel(xl)
        ax.set_ylabel(yl)
        ax.figure.colorbar(m, ax=ax, label=vlabel)
    else:
        d = da.dims[0]
        X, xl = _disp(d, da[d].values)
        ax.plot(X, vals, "o-")
        ax.set_xlabel(xl)
        ax.set_ylabel(vlabel)
        ax.grid(True, alpha=0.3)
    ax.set_title(vlabel.split(" [")[0], fontsize=10)
    return ax
