"""CLI commands that read saved files or registries: plot, plot-sweep, animate, film-force, list.

A missing, empty, truncated or foreign input file is one line on stderr (exit 2).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import typer
from rich.markup import escape
from rich.table import Table

from jointdyn.cli.common import _one_line_errors, app, console
from jointdyn.film.models import FILM_MODELS

PLOTS = ("moment", "orbit", "film", "contact", "energy")


def _load(path: Path, what: str, needs: tuple[str, ...]):
    """A saved Dataset, or one ValueError line saying why it cannot be used."""
    from jointdyn.simulation.results import load

    if not path.exists():
        raise ValueError(f"{path}: does not exist")
    if path.is_dir():
        raise ValueError(f"{path}: is a directory; expected {what}")
    if path.stat().st_size == 0:
        raise ValueError(f"{path}: is empty (0 bytes); the run that wrote it did not finish")
    try:
        ds = load(path)
    except Exception as err:  # h5py/netCDF raise many types for damaged files
        first = (str(err).splitlines() or [type(err).__name__])[0]
        raise ValueError(f"{path}: cannot be read as {what} ({type(err).__name__}: {first})") from None
    missing = [v for v in needs if v not in ds.variables]
    if missing:
        raise ValueError(f"{path}: not {what} (no {', '.join(missing)})")
    return ds


def _status_warning(directory: Path) -> None:
    from jointdyn.io.rundir import read_manifest

    m = read_manifest(directory)
    if m is None:
        typer.echo(f"warning: {directory} has no manifest.json: the run did not finish", err=True)
    elif m.get("status") != "complete":
        typer.echo(f"warning: {directory}: status {m.get('status')} ({m.get('reason', '')})", err=True)


def _save(fig, target: Path) -> None:
    """A figure into ``target``: added to the manifest of a run or sweep directory, written on
    its own elsewhere (:func:`jointdyn.io.rundir.output_file`)."""
    import matplotlib.pyplot as plt

    from jointdyn.io.derived import output_file

    try:
        with output_file(target) as tmp:
            fig.savefig(tmp, dpi=120, format="png")
    finally:
        plt.close(fig)


def _results_file(directory: Path) -> Path:
    return directory / "results.nc" if directory.is_dir() else directory


@app.command("plot")
def plot_cmd(
    directory: Path = typer.Argument(..., help="a run directory with results.nc (or the file)"),
    what: str = typer.Option(
        "moment", help="what to draw: " + ", ".join(PLOTS) + ", pressure (with --at ANGLE)"
    ),
    out: Path = typer.Option(
        None, help="PNG file (default DIR/plot_<what>.png; never the run's own figures)"
    ),
    last_revs: float = typer.Option(None, "--last-revs", help="only the last N crank revolutions [-]"),
    x: str = typer.Option("angle", help="x axis: angle (crank angle [deg]) or time [s]"),
    frame: str = typer.Option("bushing", help="orbit frame: bushing or world"),
    overlay: list[Path] = typer.Option(
        [], help="further run directories drawn on the same axes (repeatable)"
    ),
    element: str = typer.Option(None, help="one journal element (default: all)"),
    at: float = typer.Option(
        None, "--at", help="with --what pressure: crank angle [deg] from the run's start"
    ),
):
    """Plot a saved run: driving moment, journal orbit, film thickness, contact force, energy."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from jointdyn.viz import plots

    with _one_line_errors():
        if what == "pressure":
            return _pressure_plot(directory, at, element, out)
        if what not in PLOTS:
            raise ValueError(f"--what {what!r}: valid: {list(PLOTS) + ['pressure']}")
        if x not in ("angle", "time"):
            raise ValueError(f"--x {x!r}: valid: ['angle', 'time']")
        if frame not in ("bushing", "world"):
            raise ValueError(f"--frame {frame!r}: valid: ['bushing', 'world']")
        if last_revs is not None and not (math.isfinite(last_revs) and last_revs > 0):
            raise ValueError(f"--last-revs {last_revs!r} [-]: must be finite and > 0")
        runs = []
        for d in (directory, *overlay):
            f = _results_file(d)
            runs.append(_load(f, "a jointdyn results file", ("q", "lam")))
            if f.parent == d:
                _status_warning(d)
        fig, ax = plt.subplots(figsize=(5.4, 5.4) if what == "orbit" else (8, 4.5))
        kw = dict(x=x, last_revs=last_revs, frame=frame, element=element)
        if overlay:
            kw["labels"] = [Path(d).name for d in (directory, *overlay)]
        try:
            plots.run_figure(runs if overlay else runs[0], what, ax=ax, **kw)
        except (KeyError, IndexError) as err:
            plt.close(fig)
            raise ValueError(f"{directory}: cannot draw {what!r} ({err})") from None
        fig.tight_layout()
        f = _results_file(directory)
        target = out or f.parent / f"plot_{what}.png"
        _save(fig, target)
    console.print(f"wrote {escape(str(target))}")


def _pressure_plot(directory: Path, at, element, out) -> None:
    """``jointdyn plot DIR --what pressure --at ANGLE``: the film pressure around a bearing."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from jointdyn.forces.journal import JournalBearing
    from jointdyn.simulation.results import Results

    if at is None or not math.isfinite(at):
        raise ValueError("--what pressure needs --at ANGLE: the crank angle [deg] of the sample to draw")
    f = _results_file(directory)
    _load(f, "a jointdyn results file", ("q", "lam"))
    res = Results.load(f)
    bearings = [
        n for n, e in zip(res.system.element_names, res.system.elements) if isinstance(e, JournalBearing)
    ]
    if not bearings:
        raise ValueError(f"{f}: the run has no lubricated bearing")
    name = element or bearings[0]
    if name not in bearings:
        raise ValueError(f"--element {name!r}: not a lubricated bearing of the run; valid: {bearings}")
    from jointdyn.viz.bearing_plot import pressure_figure_at

    fig = pressure_figure_at(res, name, at)
    target = out or f.parent / f"plot_pressure_{at:g}deg.png"
    _save(fig, target)
    plt.close(fig)
    console.print(f"wrote {escape(str(target))}")


@app.command("plot-sweep")
def plot_sweep(
    directory: Path = typer.Argument(..., help="a sweep output directory"),
    metric: str = typer.Option("peak_moment", help="metric to draw (a variable of sweep.nc)"),
    out: Path = typer.Option(None, help="PNG file (default DIR/<metric>.png)"),
):
    """Heat map (two grid parameters) or line plot (one) of a sweep metric."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from jointdyn.viz import plots

    with _one_line_errors():
        f = directory / "sweep.nc" if directory.is_dir() else directory
        ds = _load(f, "a jointdyn sweep file", ("error",))
        if metric not in ds:
            raise ValueError(f"--metric {metric!r}: not in the sweep; have {sorted(ds.data_vars)}")
        fig, ax = plt.subplots(figsize=(6, 4.5))
        try:
            plots.sweep_metric(ds[metric], ax=ax)
        except (KeyError, ValueError, TypeError) as err:
            plt.close(fig)
            raise ValueError(f"{f}: cannot draw {metric!r} ({err})") from None
        fig.tight_layout()
        target = out or f.parent / f"{metric}.png"
        _save(fig, target)
    console.print(f"wrote {escape(str(target))}")


@app.command("animate")
def animate_cmd(
    directory: Path = typer.Argument(..., help="a run directory with results.nc (or the file)"),
    out: Path = typer.Option(Path("anim.gif"), help="anim.gif (pillow) or anim.mp4 (needs ffmpeg)"),
    frames: int = typer.Option(120, help="number of frames [-] (2 … 5000)"),
):
    """Animate a saved run: the mechanism moving, journal orbits (e/c) in insets. Cost: the
    static figure is drawn once and each frame redraws only the moving parts (≈ 0.05 s CPU per
    frame; 120 frames of a 4-revolution run ≈ 7 s CPU with loading)."""
    from jointdyn.viz.animate import MAX_FRAMES, animate

    with _one_line_errors():
        if not 2 <= frames <= MAX_FRAMES:
            raise ValueError(f"--frames = {frames} [-]: must be 2 … {MAX_FRAMES}")
        if out.suffix.lower() not in (".gif", ".mp4"):
            raise ValueError(f"--out {out}: must end in .gif or .mp4")
        f = _results_file(directory)
        _load(f, "a jointdyn results file", ("q", "lam", "element_outputs"))
        from jointdyn.io.derived import output_file

        with output_file(out) as tmp:  # the temporary name keeps the suffix (the writer's choice)
            animate(f, tmp, frames=frames)
    console.print(f"wrote {escape(str(out))}")


def _film_force_help() -> str:
    from jointdyn.film.table import units

    cols = ", ".join(f"{c} [{u}]" for c, u in units().items())
    return (
        "Film forces for a table of bearing states: appends Fr, Ft, Fx, Fy [N] (force on the "
        f"journal). Columns (SI, global rates), from film_forces(): {cols}."
    )


@app.command("film-force", help=_film_force_help())
def film_force_cmd(
    states: Path = typer.Argument(..., help="CSV with a header naming the state columns listed above"),
    model: str = typer.Option("alshaer2005", help="film model: " + ", ".join(FILM_MODELS)),
    cavitation: str = typer.Option(
        None,
        help="finite model: gumbel (default), reynolds (Swift–Stieber) or jfo (mass-conserving, steady: "
        "fed at the maximum film, 0 < xi <= 0.99, ξ̇ on frozen content)",
    ),
    out: Path = typer.Option(None, help="output CSV (default: stdout)"),
):
    from jointdyn.film.table import film_force_table

    with _one_line_errors():
        if cavitation is not None:
            if model != "finite":
                raise ValueError(f"--cavitation: applies to the 'finite' model only (got --model {model!r})")
            if cavitation == "jfo":  # the steady line-fed film, state by state [T343]
                from jointdyn.film.jfo_states import SteadyJFO

                model = SteadyJFO()
            else:
                from jointdyn.film.models import Finite

                model = Finite(cavitation=cavitation)
        if out is None:
            film_force_table(states, model, None)
            return
        from jointdyn.io.derived import output_file

        with output_file(out, "film-force") as tmp:  # a run directory's lock and manifest [T338]
            film_force_table(states, model, tmp)


def _doc(obj) -> str:
    """The first paragraph of a docstring, on one line (never cut mid-sentence)."""
    text = (obj.__doc__ or "").strip().split("\n\n")[0]
    return " ".join(text.split())


@app.command("list")
def list_registries(
    as_json: bool = typer.Option(False, "--json", help="print the registries as JSON"),
):
    """Show the registries: constraints, force elements, film/contact/friction laws, solvers,
    models and the film-force columns."""
    from jointdyn.core.constraints import CONSTRAINTS
    from jointdyn.film.models import FILM_MODELS
    from jointdyn.film.table import columns, units
    from jointdyn.forces.contact_laws import CONTACT_LAWS
    from jointdyn.forces.elements import FORCE_ELEMENTS
    from jointdyn.forces.friction_laws import FRICTION_LAWS
    from jointdyn.integrators import SOLVERS
    from jointdyn.models.catalog import SHIPPED

    regs = {
        "constraints": {k: _doc(v) for k, v in CONSTRAINTS.items()},
        "force elements": {k: _doc(v) for k, v in FORCE_ELEMENTS.items()},
        "film models": {k: _doc(v) for k, v in FILM_MODELS.items()},
        "contact laws": {k: _doc(v) for k, v in CONTACT_LAWS.items()},
        "friction laws": {k: _doc(v) for k, v in FRICTION_LAWS.items()},
        "solvers": {k: d for k, (_, _, d) in SOLVERS.items()},
        "models": {k: f"{m.variant_arg}: " + ", ".join(m.variants()) for k, m in SHIPPED.items()},
        "film-force columns": {c: f"[{u}]" for c, u in units().items() if c in columns()},
    }
    if as_json:
        typer.echo(json.dumps(regs, indent=2, ensure_ascii=False))
        return
    for title, entries in regs.items():
        tab = Table(title=title, expand=False)
        tab.add_column("name", no_wrap=True)
        tab.add_column("description", overflow="fold")
        for k, v in entries.items():
            tab.add_row(escape(k), escape(v))
        console.print(tab)
