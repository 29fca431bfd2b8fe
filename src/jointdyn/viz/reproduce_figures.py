"""Figures of the reproduction of Alshaer et al. (2005): the paper's figure equivalents and the
beyond-the-paper overlay, as PNG bytes (used by :mod:`jointdyn.studies.reproduce`), drawn in a process of
their own (:func:`drawing`, [T220]) from plain arrays (:func:`jointdyn.viz.reproduce_data.figure_data`):
this module imports numpy, matplotlib and jointdyn's plain drawing helpers only, so the drawing
process never loads numba or a compiled kernel [T360]."""

from __future__ import annotations

import io
import os
import pickle
import subprocess
import sys
import tempfile
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from jointdyn.viz import column_layout, orbit, plots, style

#: resolution of the report's PNGs [dots/in]
DPI = 130
#: zlib level of the report's PNGs: 3 encodes the 17 figures in 0.25 instead of 0.36 s CPU (level 6,
#: Pillow's default) for 3 % more bytes; levels 1–2 are no faster [T371]
PNG = {"compress_level": 3}


def _png(fig, dpi: float = DPI) -> bytes:
    """``fig`` as PNG bytes at ``dpi``, drawn once [T320] (laid out beforehand, [T371]); the bytes
    are identical to ``fig.savefig(buf, format="png", dpi=dpi, pil_kwargs=PNG)``."""
    import matplotlib
    from matplotlib import image
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    old = fig.dpi
    fig.dpi = dpi
    try:
        canvas.draw()
        buf = io.BytesIO()
        software = f"Matplotlib version{matplotlib.__version__}, https://matplotlib.org/"
        image.imsave(
            buf,
            canvas.buffer_rgba(),
            format="png",
            origin="upper",
            dpi=dpi,
            metadata={"Software": software},
            pil_kwargs=dict(PNG),
        )
    finally:
        fig.dpi = old
    return buf.getvalue()


PAPER = ("perfect", "dry", "ott", "alshaer2005")


def _styles(names) -> dict[str, tuple[str, str]]:
    """One (colour, dash) per case, the same in every figure and in interactive.html."""
    return style.styles(list(names))


def _sheet(fig, size, *grid, **kw):
    """The report's one figure, cleared and resized to ``size`` [in], with new subplots, laid
    out by :func:`jointdyn.viz.column_layout.column` before it is emitted; a new Figure per plot kept
    ≈ 3 MB each in matplotlib's native text caches, [T173]."""
    fig.clf()
    fig.set_layout_engine("none")
    fig.set_size_inches(*size)
    return fig.subplots(*grid, **kw)


def _again(fig):
    """The sheet's one axes, emptied for the next figure of the same kind (same size, labels and
    tick locators): its axis and tick objects are kept, which are ≈ 40 % of the cost of building a
    simple figure [T371]; its data limits start afresh."""
    (ax,) = fig.axes
    for a in [*ax.lines, *ax.patches, *ax.child_axes, *fig.legends]:
        a.remove()
    ax.relim()
    return ax


def _orbit_sheet(fig, reuse: bool):
    """The sheet's axes for an orbit: the last orbit's emptied (paths and figure legends removed,
    [T371]) or, for the first, a new 4.8 × 5.4 in sheet."""
    if not reuse:
        return _sheet(fig, (4.8, 5.4))
    ax = fig.axes[0]
    orbit.clear_paths(ax)
    for lg in fig.legends[:]:
        lg.remove()
    return ax


def _title(ax, text: str, fontsize: float) -> None:
    """The title of ``ax`` at its top edge (``y=1``): matplotlib then skips moving it above
    top tick labels, which would cost a tight box of every axis at each draw [T371]."""
    ax.set_title(text, fontsize=fontsize, y=1.0)


def figures(data: dict, revs: float) -> dict[str, bytes]:
    """All report figures of ``data`` (:func:`~jointdyn.viz.reproduce_data.figure_data`) as PNG
    bytes, keyed by file name."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure(dpi=DPI)  # measured and drawn at the PNG's resolution: one renderer [T371]
    out: dict[str, bytes] = {}
    try:
        draw_all(fig, data, revs, lambda name, f: out.__setitem__(name, _png(f, DPI)))
        return out
    finally:
        plt.close(fig)


@contextmanager
def drawing(data: dict, revs: float) -> Iterator[Callable[[], dict[str, bytes]]]:
    """Start drawing :func:`figures` of ``data`` (plain arrays and strings,
    :func:`~jointdyn.viz.reproduce_data.figure_data`) in a fresh interpreter; yields a function
    that waits for them and returns them. matplotlib (≈ 70 MB with its drawing) then never shares
    a process with numba's loaded kernels (≈ 130 MB), so the reproduction's peak resident set is
    the larger of the two, not their sum [T220]; the caller goes on (e.g. with the dry ensemble)
    meanwhile. The interpreter imports jointdyn's modules without the package's ``__init__`` (which
    loads the simulation and numba, ≈ 0.6 s CPU): only this module and what it imports [T360].
    The drawing process ignores Ctrl-C and dies with its parent; a signal while waiting raises
    :class:`~jointdyn.errors.Interrupted` (the drawing is killed), a failed drawing raises
    ``RuntimeError`` with the end of its error output."""
    with tempfile.TemporaryDirectory(prefix="jointdyn-figures-") as d:
        src, dst, err = Path(d, "data.pickle"), Path(d, "figures.pickle"), Path(d, "stderr")
        src.write_bytes(pickle.dumps((data, revs), protocol=pickle.HIGHEST_PROTOCOL))
        code = (
            f"{bare_package()}from {__name__} import _draw; _draw({str(src)!r}, {str(dst)!r}, {os.getpid()})"
        )
        with err.open("wb") as stderr:
            quiet = subprocess.DEVNULL
            proc = subprocess.Popen([sys.executable, "-c", code], stdin=quiet, stdout=quiet, stderr=stderr)
        try:
            yield lambda: _collect(proc, dst, err)
        finally:
            if proc.poll() is None:
                proc.kill()
            proc.wait()


def bare_package() -> str:
    """Python source that makes ``jointdyn`` (this one, even if not installed) an empty package of
    this directory, so that importing a module of it runs that module and its imports, not the
    package's ``__init__``."""
    pkg = str(Path(__file__).resolve().parents[1])
    return (
        f"import sys, types; _p = types.ModuleType('jointdyn'); _p.__path__ = [{pkg!r}]; "
        "sys.modules['jointdyn'] = _p; "
    )


def _collect(proc: subprocess.Popen, dst: Path, err: Path) -> dict[str, bytes]:
    from jointdyn.core import interrupts

    while True:
        try:
            proc.wait(timeout=0.1)
            break
        except subprocess.TimeoutExpired:
            interrupts.check()
    if proc.returncode != 0:
        tail = err.read_text(errors="replace").strip().splitlines()[-5:]
        raise RuntimeError(f"drawing the report figures failed (exit {proc.returncode}): " + " | ".join(tail))
    return pickle.loads(dst.read_bytes())


def _draw(src: str, dst: str, parent: int) -> None:
    """The drawing process: :func:`figures` of the pickled data, pickled into ``dst``."""
    from jointdyn.core.atomic import write_bytes
    from jointdyn.io.pool import detach

    detach(parent)
    data, revs = pickle.loads(Path(src).read_bytes())
    write_bytes(Path(dst), pickle.dumps(figures(data, revs), protocol=pickle.HIGHEST_PROTOCOL))


def _angle_axis(ax, revs: float, one: str) -> None:
    ax.set_xlabel(f"crank angle [deg], {one}")
    ax.set_xlim(0, 360 * min(1.0, revs))
    plots._angle_ticks(ax, 360 * min(1.0, revs))


def _moment(ax, d, st, **kw):
    colour, dash = st
    return ax.plot(d["deg"], d["moment"], color=colour, ls=dash, label=d["label"], **kw)


def _below(fig, ncol: int = 2):
    """One legend for the whole figure, under its axes (outside every curve), in ``ncol`` columns
    or in one when that would be wider than the figure (long labels)."""
    handles, labels = [], []
    for ax in fig.axes:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
    lg = fig.legend(handles, labels, loc="lower center", ncol=ncol, fontsize=8, frameon=False)
    if ncol > 1 and lg.get_window_extent(fig.canvas.get_renderer()).width > 0.98 * fig.bbox.width:
        lg.remove()
        fig.legend(handles, labels, loc="lower center", ncol=1, fontsize=8, frameon=False)


def _coincident(curves: dict, tol: float = 0.02) -> dict[str, str]:
    """``{name: earlier name}`` for curves within ``tol`` (relative) of an earlier one everywhere:
    drawn on top of each other, the legend says so."""
    out: dict[str, str] = {}
    names = list(curves)
    for k, n in enumerate(names):
        for m in names[:k]:
            a, b = curves[n], curves[m]
            if a.shape == b.shape and np.all(np.abs(a - b) <= tol * np.maximum(np.abs(b), 1e-300)):
                out[n] = m
                break
    return out


#: what each report figure shows (its caption in report.html)
CAPTIONS = {
    "moment_overlay": "Crank driving moment over the last revolution: the lubricated joints against the "
    "perfect joint (top) and the dry clearance joint with its impact spikes on its own scale (bottom).",
    "moment_beyond": "Crank driving moment over the last revolution for the cases beyond the paper "
    "(clearance, viscosity, finite length, film shear), with the perfect joint for reference.",
    "film_thickness": "Minimum film thickness of the lubricated piston pin over the last revolution "
    "(log scale); curves within 2 % of another are drawn dashed on top and say so in the legend.",
    "joint_force": "Magnitude of the force on the piston pin over the last revolution, against the "
    "perfect joint's reaction; the largest sampled value and the run's record are given per panel.",
}


def caption(name: str, runs: dict) -> str:
    """The caption of the report figure ``name`` (a file name without ``.png``)."""
    if name in CAPTIONS:
        return CAPTIONS[name]
    kind, _, case = name.partition("_")
    label = runs[case][3].label if case in runs else case
    if kind == "moment":
        return f"Crank driving moment over the whole run: {label}."
    if kind == "orbit":
        return (
            f"Journal-centre path e/c in the bushing (rod-eye) frame over the last revolution, inside "
            f"the clearance circle, with start, end and direction of travel: {label}."
        )
    return name


def _laid_out(emit):
    def out(name: str, fig) -> None:
        column_layout.column(fig)
        emit(name, fig)

    return out


def draw_all(fig, data: dict, revs: float, emit) -> None:
    """Draw every report figure of ``data`` (:func:`~jointdyn.viz.reproduce_data.figure_data`) on
    ``fig`` in turn; ``emit(file name, fig)`` is called after each, laid out
    (:func:`jointdyn.viz.column_layout.column`)."""
    emit = _laid_out(emit)
    st = _styles(data)
    names = [n for n in PAPER if n in data]
    one = "last revolution" if revs >= 1 else f"{revs:g} revolution"
    for k, n in enumerate(names):
        ax = _again(fig) if k else _sheet(fig, (8, 3.8))
        plots.moment_vs_angle(data[n]["angle_all"], data[n]["moment_all"], ax=ax, color=st[n][0])
        _title(ax, f"crank driving moment, {revs:g} revolutions — {data[n]['label']}", fontsize=10)
        emit(f"moment_{n}.png", fig)
    # overlay: smooth cases on their own scale, the dry joint's spikes in a panel of their own
    smooth = [n for n in names if n != "dry"]
    panels = 2 if "dry" in names else 1
    axs = _sheet(fig, (8, 3.4 * panels + 0.8), panels, 1, sharex=True, squeeze=False)
    for n in smooth:
        wide = n == "perfect"
        _moment(axs[0, 0], data[n], st[n], lw=1.8 if wide else 1.2, zorder=3 if wide else 2)
    _title(axs[0, 0], f"crank driving moment, {one}", fontsize=10)
    if panels == 2:
        for n in ("perfect", "dry"):
            if n in data:
                _moment(axs[1, 0], data[n], st[n], lw=1.0, zorder=3 if n == "perfect" else 2)
        _title(axs[1, 0], "dry clearance joint (own scale: impact spikes)", fontsize=10)
    for ax in axs[:, 0]:
        ax.set_ylabel("moment [N·m]")
        ax.grid(True, alpha=0.3)
    _angle_axis(axs[-1, 0], revs, one)
    _below(fig)
    emit("moment_overlay.png", fig)
    beyond = [n for n in data if n not in names]
    if beyond:
        ax = _sheet(fig, (8, 5.0))
        for n in ["perfect"] + beyond if "perfect" in data else beyond:
            wide = n == "perfect"
            _moment(ax, data[n], st[n], lw=1.4 if wide else 1.1, zorder=3 if wide else 2)
        _title(ax, f"beyond the paper: clearance, viscosity, finite length, shear ({one})", fontsize=10)
        ax.set_ylabel("moment [N·m]")
        _angle_axis(ax, revs, one)
        ax.grid(True, alpha=0.3)
        _below(fig)
        emit("moment_beyond.png", fig)
    for k, n in enumerate([n for n in data if "ex" in data[n]]):
        ax = _orbit_sheet(fig, reuse=k > 0)
        ex, ey = data[n]["ex"], data[n]["ey"]
        plots.journal_orbit(ex, ey, ax=ax, frame="bushing (rod-eye)", color=st[n][0], label="journal centre")
        _title(ax, f"journal centre path in the bushing frame, {one}\n{data[n]['label']}", fontsize=9)
        _below(fig)
        emit(f"orbit_{n}.png", fig)
    _film(fig, data, st, one, emit)
    _joint_force(fig, data, names, st, revs, one, emit)


def _film(fig, data, st, one, emit) -> None:
    lub = [n for n in data if "h_min" in data[n]]
    if not lub:
        return
    ax = _sheet(fig, (8, 5.4))
    h = {n: data[n]["h_min"] for n in lub}
    same = _coincident(h)
    for k, n in enumerate(lub):
        label = data[n]["label"] + (f" (within 2 % of {data[same[n]]['label']})" if n in same else "")
        plots.series_vs_angle(
            np.radians(data[n]["deg"]),
            h[n],
            "minimum film thickness $h_{min}$ [µm]",
            ax=ax,
            label=label,
            color=st[n][0],
            ls="--" if n in same else st[n][1],  # dashed on top of the curve it coincides with
            lw=1.6 if n in same else 1.1,
            zorder=2 + k,
        )
    ax.set_yscale("log")
    from matplotlib.ticker import FuncFormatter

    ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    ax.set_xlabel(f"crank angle [deg], {one}")
    _title(ax, f"minimum film thickness, {one}", fontsize=10)
    _below(fig)
    emit("film_thickness.png", fig)


def _joint_force(fig, data, names, st, revs, one, emit) -> None:
    imp = [n for n in names if n != "perfect" and "force" in data[n]]
    if not imp:
        return
    axs = _sheet(fig, (8, 2.7 * len(imp) + 1.2), len(imp), 1, sharex=True, squeeze=False)
    step = 0.0
    for ax, n in zip(axs[:, 0], imp):
        f, x = data[n]["force"], data[n]["deg"]
        ax.plot(x, f, color=st[n][0], lw=0.9, label=data[n]["label"])  # the case's name in every figure
        i = int(np.argmax(f))
        ax.plot(x[i], f[i], "v", color=st[n][0], ms=6, label="largest sample in the window")
        step = x[1] - x[0]
        if "perfect" in data:
            ax.plot(
                data["perfect"]["deg"],
                data["perfect"]["reaction"],
                "k--",
                lw=0.8,
                label="perfect joint (reaction)",
            )
        title = f"{data[n]['label']}\nthis window: largest sample {f[i] / 1e3:.3g} kN at {x[i]:.0f}°\n"
        title += data[n]["record"]
        _title(ax, title, fontsize=8)
        ax.set_ylabel("|F| [N]")
        ax.grid(True, alpha=0.3)
    _angle_axis(axs[-1, 0], revs, one)
    fig.suptitle(f"force on the journal (piston pin), magnitude, sampled every {step:.2g}°", fontsize=10)
    _below(fig)
    emit("joint_force.png", fig)
