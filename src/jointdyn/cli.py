"""Command-line interface (thin shell over the library)."""

from __future__ import annotations

from pathlib import Path

import typer
from rich.console import Console
from rich.table import Table

app = typer.Typer(help="jointdyn: planar mechanisms with ideal, clearance and lubricated joints.",
                  no_args_is_help=True, add_completion=False)
console = Console()


def _progress(description: str):
    from rich.progress import BarColumn, Progress, TimeElapsedColumn, TimeRemainingColumn

    return Progress("[progress.description]{task.description}", BarColumn(),
                    "[progress.percentage]{task.percentage:>3.0f}%", TimeElapsedColumn(),
                    TimeRemainingColumn(), console=console, transient=False)


@app.command()
def run(
    model: str = typer.Argument(..., help="shipped model name: slider-crank"),
    joint: str = typer.Option("perfect", help="piston-pin joint kind"),
    revs: float = typer.Option(4.0, help="crank revolutions to simulate [-]"),
    out: Path = typer.Option(Path("out/run"), help="output directory"),
    solver: str = typer.Option(None, help="integrator (default per joint kind); see `jointdyn list`"),
    rtol: float = typer.Option(1e-8, help="relative tolerance [-]"),
    atol: float = typer.Option(1e-10, help="absolute tolerance [SI]"),
):
    """Simulate a shipped mechanism and write results.nc, timeseries.csv, summary.json, PNGs."""
    from .errors import SimulationError
    from .runs import run_slider_crank

    if model != "slider-crank":
        raise typer.BadParameter(f"unknown model {model!r}; valid: ['slider-crank']", param_hint="MODEL")
    try:
        with _progress("run") as prog:
            task = prog.add_task(f"slider-crank ({joint})", total=1.0)
            res, cols, summary = run_slider_crank(
                joint, revs, out=out, progress=lambda f: prog.update(task, completed=f),
                solver=solver, rtol=rtol, atol=atol)
    except (ValueError, SimulationError) as err:
        console.print(f"[red]error:[/red] {err}")
        raise typer.Exit(2)
    tab = Table(title=f"slider-crank, {joint} piston pin ({revs:g} rev)")
    tab.add_column("quantity")
    tab.add_column("value", justify="right")
    for k, v in summary.items():
        tab.add_row(k, f"{v:.6g}" if isinstance(v, float) else str(v))
    console.print(tab)
    console.print(f"wrote {out}/results.nc, timeseries.csv, summary.json, moment.png")


@app.command("list")
def list_registries():
    """Show the registries: constraints, force elements, solvers, models."""
    from .forces.elements import FORCE_ELEMENTS
    from .integrators import SOLVERS
    from .joints.constraints import CONSTRAINTS
    from .models.slider_crank import JOINTS

    for title, reg in (("constraints", CONSTRAINTS), ("force elements", FORCE_ELEMENTS)):
        tab = Table(title=title)
        tab.add_column("name")
        tab.add_column("description")
        for k, v in reg.items():
            tab.add_row(k, (v.__doc__ or "").strip().splitlines()[0])
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
