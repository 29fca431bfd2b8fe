"""Command-line interface (thin shell over the library)."""

from __future__ import annotations

from pathlib import Path

import typer
from rich.console import Console
from rich.markup import escape
from rich.table import Table

app = typer.Typer(
    help="jointdyn: planar mechanisms with ideal, clearance and lubricated joints.",
    no_args_is_help=True,
    add_completion=False,
)
console = Console()


def _progress(description: str):
    from rich.progress import BarColumn, Progress, TimeElapsedColumn, TimeRemainingColumn

    return Progress(
        "[progress.description]{task.description}",
        BarColumn(),
        "[progress.percentage]{task.percentage:>3.0f}%",
        TimeElapsedColumn(),
        TimeRemainingColumn(),
        console=console,
        transient=False,
    )


def _joint_kw(joint, clearance, viscosity, length, friction, contact, asperity_height) -> dict:
    """Builder arguments of the shipped slider-crank from CLI options (SI)."""
    from .forces.contact_laws import LankaraniNikravesh, journal_bearing_stiffness
    from .forces.friction_laws import Ambrosio
    from .models import slider_crank as sc

    if joint == "perfect":
        return {}
    kw = {"clearance": clearance}
    if friction > 0:
        kw["friction"] = Ambrosio(coefficient=friction)
    if joint != "dry":
        kw.update(viscosity=viscosity, length=length, asperity_height=asperity_height)
        if contact:
            rb = sc.JOURNAL_RADIUS + clearance
            K = journal_bearing_stiffness(rb, sc.JOURNAL_RADIUS, sc.YOUNG, sc.POISSON, sc.YOUNG, sc.POISSON)
            kw["contact"] = LankaraniNikravesh(stiffness=K, exponent=1.5, restitution=sc.RESTITUTION)
    return kw


@app.command()
def run(
    model: str = typer.Argument(..., help="shipped model name (slider-crank) or a model file FILE.toml"),
    joint: str = typer.Option("perfect", help="piston-pin joint kind"),
    revs: float = typer.Option(4.0, help="crank revolutions to simulate [-]"),
    out: Path = typer.Option(Path("out/run"), help="output directory"),
    solver: str = typer.Option(None, help="integrator (default per joint kind); see `jointdyn list`"),
    rtol: float = typer.Option(1e-8, help="relative tolerance [-]"),
    atol: float = typer.Option(1e-10, help="absolute tolerance [SI]"),
    clearance: float = typer.Option(0.5e-3, help="radial clearance c of an imperfect joint [m]"),
    viscosity: float = typer.Option(0.4, help="lubricant dynamic viscosity [Pa·s]"),
    length: float = typer.Option(0.04, help="bearing length [m]"),
    friction: float = typer.Option(
        0.0, help="Ambrósio friction coefficient of contact (0 = frictionless) [-]"
    ),
    contact: bool = typer.Option(
        False, help="lubricated joint: add Lankarani–Nikravesh asperity contact (mixed regime)"
    ),
    asperity_height: float = typer.Option(0.0, help="mixed regime: contact starts at h_min < this [m]"),
    set_: list[str] = typer.Option([], "--set", help="model file override a.b.c=VALUE (repeatable)"),
):
    """Simulate a shipped mechanism or a model file; write results.nc, timeseries.csv and more."""
    from .errors import ModelError, SimulationError
    from .runs import run_slider_crank

    if model.endswith(".toml"):
        from .config import run_model_file

        try:
            res = run_model_file(model, out, overrides=set_)
        except (ModelError, ValueError, SimulationError) as err:
            console.print(f"[red]error:[/red] {escape(str(err))}", soft_wrap=True)
            raise typer.Exit(2) from None
        console.print(
            f"{res.system.name}: {len(res.t)} samples, {res.stats['rhs_evaluations']} RHS evaluations, "
            f"{res.wall_time:.3f} s; wrote {out}/results.nc, timeseries.csv, model.toml"
        )
        return
    if set_:
        raise typer.BadParameter("--set applies to model files only", param_hint="--set")
    if model != "slider-crank":
        raise typer.BadParameter(f"unknown model {model!r}; valid: ['slider-crank']", param_hint="MODEL")
    try:
        with _progress("run") as prog:
            task = prog.add_task(f"slider-crank ({joint})", total=1.0)
            res, cols, summary = run_slider_crank(
                joint,
                revs,
                out=out,
                progress=lambda f: prog.update(task, completed=f),
                model_kw=_joint_kw(joint, clearance, viscosity, length, friction, contact, asperity_height),
                solver=solver,
                rtol=rtol,
                atol=atol,
            )
    except (ValueError, SimulationError) as err:
        console.print(f"[red]error:[/red] {escape(str(err))}", soft_wrap=True)
        raise typer.Exit(2) from None
    tab = Table(title=f"slider-crank, {joint} piston pin ({revs:g} rev)")
    tab.add_column("quantity")
    tab.add_column("value", justify="right")
    for k, v in summary.items():
        tab.add_row(k, f"{v:.6g}" if isinstance(v, float) else str(v))
    console.print(tab)
    console.print(f"wrote {out}/results.nc, timeseries.csv, summary.json, moment.png")


@app.command()
def reproduce(
    paper: str = typer.Argument(..., help="which paper: alshaer2005"),
    out: Path = typer.Option(Path("out/alshaer2005"), help="output directory"),
    quick: bool = typer.Option(False, help="1 revolution instead of 4 (CI smoke run)"),
    beyond: bool = typer.Option(True, help="also run the beyond-the-paper cases"),
):
    """Run the paper's comparison (perfect, dry, Ott, π-film) and write figures + report.html."""
    from .errors import SimulationError
    from .reproduce import BEYOND_CASES, PAPER_CASES, reproduce_alshaer2005, summary_markdown

    if paper != "alshaer2005":
        raise typer.BadParameter(f"unknown paper {paper!r}; valid: ['alshaer2005']", param_hint="PAPER")
    cases = PAPER_CASES + (BEYOND_CASES if beyond else ())
    try:
        with _progress("reproduce") as prog:
            tasks = {c.name: prog.add_task(c.name, total=1.0) for c in cases}
            runs = reproduce_alshaer2005(
                out,
                quick=quick,
                beyond=beyond,
                progress=lambda name, f: prog.update(tasks[name], completed=f),
            )
    except (ValueError, SimulationError) as err:
        console.print(f"[red]error:[/red] {escape(str(err))}", soft_wrap=True)
        raise typer.Exit(2) from None
    console.print(summary_markdown(runs))
    console.print(f"wrote {out}/report.html, summary.csv, <case>.csv and the figures")


@app.command()
def sweep(
    spec: Path = typer.Argument(
        ..., help="sweep file (TOML): [base], [grid]/[zip]/[sample], [output], [dask]"
    ),
    out: Path = typer.Option(Path("out/sweep"), help="output directory"),
    resume: bool = typer.Option(False, help="keep finished cases, run only the missing ones"),
    scheduler: str = typer.Option(
        None, help="Dask scheduler address tcp://HOST:PORT (default: local processes)"
    ),
    workers: int = typer.Option(None, help="local worker processes (default: all cores)"),
):
    """Run a parameter study; writes DIR/cases/*.json per case and DIR/sweep.nc."""
    from .sweep import load_sweep, run_sweep

    try:
        sp = load_sweep(spec)
        n = len(sp.cases())
        with _progress("sweep") as prog:
            task = prog.add_task(f"{n} cases", total=n)
            ds = run_sweep(
                sp,
                out,
                resume=resume,
                scheduler=scheduler,
                workers=workers,
                progress=lambda done, total: prog.update(task, completed=done),
            )
    except ValueError as err:
        console.print(f"[red]error:[/red] {escape(str(err))}", soft_wrap=True)
        raise typer.Exit(2) from None
    failed = int((ds["error"] != "").sum())
    console.print(f"wrote {out}/sweep.nc ({n} cases, {failed} failed)")


@app.command("plot-sweep")
def plot_sweep(
    directory: Path = typer.Argument(..., help="a sweep output directory"),
    metric: str = typer.Option("peak_moment", help="metric to draw"),
    out: Path = typer.Option(None, help="PNG file (default DIR/<metric>.png)"),
):
    """Heat map (two grid parameters) or line plot (one) of a sweep metric."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from . import plots
    from .results import load

    ds = load(directory / "sweep.nc")
    if metric not in ds:
        console.print(
            f"[red]error:[/red] metric {metric!r} not in the sweep; have {sorted(ds.data_vars)}",
            soft_wrap=True,
        )
        raise typer.Exit(2) from None
    fig, ax = plt.subplots(figsize=(6, 4.5))
    plots.sweep_metric(ds[metric], ax=ax)
    fig.tight_layout()
    target = out or directory / f"{metric}.png"
    fig.savefig(target, dpi=120)
    console.print(f"wrote {target}")


@app.command("animate")
def animate_cmd(
    directory: Path = typer.Argument(..., help="a run directory with results.nc"),
    out: Path = typer.Option(Path("anim.gif"), help="anim.gif (pillow) or anim.mp4 (needs ffmpeg)"),
    frames: int = typer.Option(120, help="number of frames"),
):
    """Animate a saved run: the mechanism moving, journal orbits (e/c) in insets."""
    from .animate import animate

    f = directory / "results.nc" if directory.is_dir() else directory
    if not f.exists():
        console.print(f"[red]error:[/red] {escape(str(f))} does not exist", soft_wrap=True)
        raise typer.Exit(2) from None
    console.print(f"wrote {animate(f, out, frames=frames)}")


@app.command("plot")
def plot_cmd(
    directory: Path = typer.Argument(..., help="a run directory with results.nc"),
    what: str = typer.Option("moment", help="moment | orbit | film | contact | energy"),
    out: Path = typer.Option(None, help="PNG (default DIR/<what>.png)"),
):
    """Plot a saved run: driving moment, journal orbit, film thickness, contact force, energy."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from . import plots
    from .results import load

    ds = load(directory / "results.nc")
    choices = ("moment", "orbit", "film", "contact", "energy")
    if what not in choices:
        console.print(f"[red]error:[/red] --what {what!r}: valid: {list(choices)}", soft_wrap=True)
        raise typer.Exit(2) from None
    fig, ax = plt.subplots(figsize=(7, 4.5))
    try:
        plots.saved_run(ds, what, ax=ax)
    except ValueError as err:
        console.print(f"[red]error:[/red] {escape(str(err))}", soft_wrap=True)
        raise typer.Exit(2) from None
    fig.tight_layout()
    target = out or directory / f"{what}.png"
    fig.savefig(target, dpi=120)
    console.print(f"wrote {target}")


FILM_COLUMNS = (
    "xi",
    "xi_dot",
    "gamma",
    "gamma_dot",
    "omega_journal",
    "omega_bearing",
    "viscosity",
    "length",
    "radius",
    "clearance",
)


@app.command("film-force")
def film_force_cmd(
    states: Path = typer.Argument(
        ..., help="CSV with columns " + ", ".join(FILM_COLUMNS) + " (SI, global rates)"
    ),
    model: str = typer.Option("alshaer2005", help="film model name (see `jointdyn list`)"),
    out: Path = typer.Option(None, help="output CSV (default: stdout)"),
):
    """Film forces for a table of bearing states: appends Fr, Ft, Fx, Fy [N] (force on the journal)."""
    import csv
    import sys

    import numpy as np

    from .forces.film_models import FILM_MODELS, film_forces

    try:
        if model not in FILM_MODELS:
            raise ValueError(f"--model {model!r} is unknown; valid: {sorted(FILM_MODELS)}")
        with open(states, newline="") as f:
            rows = list(csv.DictReader(f))
        if not rows:
            raise ValueError(f"{states}: no data rows")
        missing = [c for c in FILM_COLUMNS if c not in rows[0]]
        if missing:
            raise ValueError(f"{states}: missing column(s) {missing}; required: {list(FILM_COLUMNS)}")
        data = {}
        for c in FILM_COLUMNS:
            vals = []
            for i, r in enumerate(rows):
                try:
                    vals.append(float(r[c]))
                except ValueError:
                    raise ValueError(
                        f"{states}: row {i + 1}, column {c!r}: {r[c]!r} is not a number"
                    ) from None
            data[c] = np.array(vals)
        for c, v in data.items():
            bad = np.flatnonzero(~np.isfinite(v))
            if bad.size:
                raise ValueError(
                    f"{states}: row {bad[0] + 1}, column {c!r}: non-finite value {float(v[bad[0]])!r}"
                )
        F = film_forces(model, *(data[c] for c in FILM_COLUMNS))
    except (ValueError, OSError) as err:
        console.print(f"[red]error:[/red] {escape(str(err))}", soft_wrap=True)
        raise typer.Exit(2) from None
    fh = open(out, "w", newline="") if out else sys.stdout
    w = csv.writer(fh)
    w.writerow(list(rows[0].keys()) + ["Fr", "Ft", "Fx", "Fy"])
    for i, r in enumerate(rows):
        w.writerow(list(r.values()) + [f"{F[k][i]:.10g}" for k in ("Fr", "Ft", "Fx", "Fy")])
    if out:
        fh.close()


from .bearing.cli import bearing_table_cmd  # noqa: E402

app.command("bearing-table")(bearing_table_cmd)


@app.command("list")
def list_registries():
    """Show the registries: constraints, force elements, film/contact/friction laws, solvers, models."""
    from .forces.contact_laws import CONTACT_LAWS
    from .forces.elements import FORCE_ELEMENTS
    from .forces.film_models import FILM_MODELS
    from .forces.friction_laws import FRICTION_LAWS
    from .integrators import SOLVERS
    from .joints.constraints import CONSTRAINTS
    from .models.slider_crank import JOINTS

    for title, reg in (
        ("constraints", CONSTRAINTS),
        ("force elements", FORCE_ELEMENTS),
        ("film models", FILM_MODELS),
        ("contact laws", CONTACT_LAWS),
        ("friction laws", FRICTION_LAWS),
    ):
        tab = Table(title=title)
        tab.add_column("name")
        tab.add_column("description")
        for k, v in reg.items():
            tab.add_row(k, escape((v.__doc__ or "").strip().splitlines()[0]))
        console.print(tab)
    tab = Table(title="solvers")
    tab.add_column("name")
    tab.add_column("description")
    for k, (_, _, d) in SOLVERS.items():
        tab.add_row(k, d)
    console.print(tab)
    console.print(f"models: slider-crank (joints: {', '.join(JOINTS)})")


def main():  # pragma: no cover
    app()
