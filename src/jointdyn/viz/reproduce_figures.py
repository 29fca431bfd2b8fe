"""Figures of the reproduction of Alshaer et al. (2005): the paper's figure equivalents and the
beyond-the-paper overlay, as PNG bytes (used by :mod:`jointdyn.studies.reproduce`), drawn in a process of
their own (:func:`drawing`, [T220])."""

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

from jointdyn import post
from jointdyn.viz import plots


def _png(fig) -> bytes:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=130)
    return buf.getvalue()


PAPER = ("perfect", "dry", "ott", "alshaer2005")
#: one colour per case, the same in every figure
COLORS = {"perfect": "k", "dry": "tab:red", "ott": "tab:orange", "alshaer2005": "tab:blue"}
_MORE = ("tab:green", "tab:purple", "tab:brown", "tab:pink", "tab:olive", "tab:cyan", "tab:gray")


def _colors(names) -> dict[str, str]:
    """Paper cases keep their colour; the others get distinct ones in order."""
    extra = iter(_MORE * 3)
    return {n: COLORS[n] if n in COLORS else next(extra) for n in names}


def _last(res, revs: float):
    """The last revolution (or the whole run when it is shorter)."""
    return res.last_revolutions(min(1.0, revs))


def _deg(res):
    a = res.crank_angle()
    return np.degrees(a - a[0])


def _sheet(fig, size, *grid, **kw):
    """The report's one figure, cleared and resized to ``size`` [in], with new subplots (a new
    Figure per plot kept ≈ 3 MB each in matplotlib's native text caches, [T173])."""
    from matplotlib import rcParams

    fig.clf()
    pars = ("left", "right", "bottom", "top", "wspace", "hspace")  # clf() keeps the last tight_layout
    fig.subplots_adjust(**{k: rcParams[f"figure.subplot.{k}"] for k in pars})
    fig.set_size_inches(*size)
    return fig.subplots(*grid, **kw)


def figures(runs: dict, revs: float) -> dict[str, bytes]:
    """All report figures as PNG bytes, keyed by file name."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure()
    try:
        return _figures(fig, runs, revs)
    finally:
        plt.close(fig)


@contextmanager
def drawing(runs: dict, revs: float) -> Iterator[Callable[[], dict[str, bytes]]]:
    """Start drawing :func:`figures` in a fresh interpreter; yields a function that waits for
    them and returns them. matplotlib (≈ 70 MB with its drawing) then never shares a process
    with numba's loaded kernels (≈ 130 MB), so the reproduction's peak resident set is the larger
    of the two, not their sum [T220]; the caller goes on (e.g. with the dry ensemble) meanwhile.
    The drawing process ignores Ctrl-C and dies with its parent; a signal while waiting raises
    :class:`~jointdyn.errors.Interrupted` (the drawing is killed), a failed drawing raises
    ``RuntimeError`` with the end of its error output."""
    with tempfile.TemporaryDirectory(prefix="jointdyn-figures-") as d:
        src, dst, err = Path(d, "runs.pickle"), Path(d, "figures.pickle"), Path(d, "stderr")
        src.write_bytes(pickle.dumps((runs, revs), protocol=pickle.HIGHEST_PROTOCOL))
        root = str(Path(__file__).resolve().parents[2])  # this jointdyn, even if not installed
        code = (
            f"import sys; sys.path.insert(0, {root!r}); from {__name__} import _draw; "
            f"_draw({str(src)!r}, {str(dst)!r}, {os.getpid()})"
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
    """The drawing process: :func:`figures` of the pickled runs, pickled into ``dst``."""
    from jointdyn.core.atomic import write_bytes
    from jointdyn.io.pool import worker_init

    worker_init(parent)
    runs, revs = pickle.loads(Path(src).read_bytes())
    write_bytes(Path(dst), pickle.dumps(figures(runs, revs), protocol=pickle.HIGHEST_PROTOCOL))


def _figures(fig, runs: dict, revs: float) -> dict[str, bytes]:
    figs = {}
    col = _colors(runs)
    names = [n for n in PAPER if n in runs]
    last = {n: _last(runs[n][0], revs) for n in runs}
    one = "last revolution" if revs >= 1 else f"{revs:g} revolution"
    for n in names:
        ax = _sheet(fig, (8, 3.8))
        res = runs[n][0]
        plots.moment_vs_angle(
            res.crank_angle() - res.crank_angle()[0], post.driving_moment(res), ax=ax, color=col[n]
        )
        ax.set_title(f"crank driving moment, {revs:g} revolutions — {runs[n][3].label}", fontsize=10)
        fig.tight_layout()
        figs[f"moment_{n}.png"] = _png(fig)
    # overlay: smooth cases on their own scale, the dry joint's spikes in a panel of their own
    smooth = [n for n in names if n != "dry"]
    panels = 2 if "dry" in names else 1
    axs = _sheet(fig, (8, 3.6 * panels), panels, 1, sharex=True, squeeze=False)
    for n in smooth:
        r = last[n]
        axs[0, 0].plot(
            _deg(r),
            post.driving_moment(r),
            color=col[n],
            lw=1.2 if n != "perfect" else 1.8,
            ls="--" if n == "perfect" else "-",
            label=runs[n][3].label,
            zorder=3 if n == "perfect" else 2,
        )
    axs[0, 0].set_title(f"crank driving moment, {one}", fontsize=10)
    if panels == 2:
        for n in ("perfect", "dry"):
            if n in runs:
                r = last[n]
                axs[1, 0].plot(
                    _deg(r),
                    post.driving_moment(r),
                    color=col[n],
                    lw=1.0,
                    ls="--" if n == "perfect" else "-",
                    label=runs[n][3].label,
                )
        axs[1, 0].set_title("dry clearance joint (own scale: impact spikes)", fontsize=10)
    for k, ax in enumerate(axs[:, 0]):
        ax.set_ylabel("moment [N·m]")
        ax.grid(True, alpha=0.3)
        # the dry spikes reach down on the left half: its legend goes lower right
        ax.legend(fontsize=8, loc="lower left" if k == 0 else "lower right")
    axs[-1, 0].set_xlabel(f"crank angle [deg], {one}")
    axs[-1, 0].set_xlim(0, 360 * min(1.0, revs))
    plots._angle_ticks(axs[-1, 0], 360 * min(1.0, revs))
    fig.tight_layout()
    figs["moment_overlay.png"] = _png(fig)
    beyond = [n for n in runs if n not in names]
    if beyond:
        ax = _sheet(fig, (8, 4.4))
        for n in ["perfect"] + beyond if "perfect" in runs else beyond:
            r = last[n]
            ax.plot(
                _deg(r),
                post.driving_moment(r),
                lw=1.0,
                label=runs[n][3].label,
                color=col[n],
                ls="--" if n == "perfect" else "-",
                zorder=3 if n == "perfect" else 2,
            )
        ax.set_title(f"beyond the paper: clearance, viscosity, finite length, shear ({one})", fontsize=10)
        ax.set_xlabel(f"crank angle [deg], {one}")
        ax.set_ylabel("moment [N·m]")
        ax.set_xlim(0, 360 * min(1.0, revs))
        plots._angle_ticks(ax, 360 * min(1.0, revs))
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8, loc="lower left")
        fig.tight_layout()
        figs["moment_beyond.png"] = _png(fig)
    for n in [n for n in runs if "piston_pin" in runs[n][0].journals()]:
        ax = _sheet(fig, (4.8, 5.2))
        ex, ey = last[n].orbit("piston_pin", frame="bushing")
        plots.journal_orbit(ex, ey, ax=ax, frame="rod", color=col[n], label="journal centre")
        ax.set_title(f"journal centre path, {one}\n{runs[n][3].label}", fontsize=9)
        ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=4, frameon=False)
        fig.tight_layout()
        figs[f"orbit_{n}.png"] = _png(fig)
    lub = [n for n in runs if runs[n][3].joint not in ("perfect", "dry")]
    if lub:
        ax = _sheet(fig, (8, 4.4))
        for n in lub:
            r = last[n]
            plots.series_vs_angle(
                np.radians(_deg(r)),
                r.element("piston_pin", "h_min") * 1e6,
                "minimum film thickness $h_{min}$ [µm]",
                ax=ax,
                label=runs[n][3].label,
                color=col[n],
            )
        ax.set_yscale("log")
        from matplotlib.ticker import FuncFormatter

        ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
        ax.set_xlabel(f"crank angle [deg], {one}")
        ax.set_title(f"minimum film thickness, {one}", fontsize=10)
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2, frameon=False)
        fig.tight_layout()
        figs["film_thickness.png"] = _png(fig)
    imp = [n for n in names if n != "perfect" and "piston_pin" in runs[n][0].journals()]
    if imp:
        axs = _sheet(fig, (8, 2.4 * len(imp) + 0.6), len(imp), 1, sharex=True, squeeze=False)
        for ax, n in zip(axs[:, 0], imp):
            r = last[n]
            f = np.hypot(r.element("piston_pin", "Fx"), r.element("piston_pin", "Fy"))
            ax.plot(_deg(r), f, color=col[n], lw=0.9)
            if "perfect" in runs:
                p = last["perfect"]
                ax.plot(
                    _deg(p),
                    np.hypot(*post.joint_reaction(p, "piston_pin").T),
                    "k--",
                    lw=0.8,
                    label="perfect joint (reaction)",
                )
                ax.legend(fontsize=7, loc="upper right")
            ax.set_title(runs[n][3].label, fontsize=9)
            ax.set_ylabel("|F| [N]")
            ax.grid(True, alpha=0.3)
        axs[-1, 0].set_xlabel(f"crank angle [deg], {one}")
        axs[-1, 0].set_xlim(0, 360 * min(1.0, revs))
        plots._angle_ticks(axs[-1, 0], 360 * min(1.0, revs))
        fig.suptitle("force on the journal (piston pin)", fontsize=10)
        fig.tight_layout()
        figs["joint_force.png"] = _png(fig)
    return figs
