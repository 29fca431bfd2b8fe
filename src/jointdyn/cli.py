"""Command-line interface (thin shell over the library).

Every command checks all its inputs before any work, writes its outputs atomically, and ends
a problem with one line on stderr and a non-zero exit code: 2 bad input or output path, 1 a
failed simulation (partial results written with their status), 130 Ctrl-C (SIGINT), 143
SIGTERM — never a traceback.
"""

from __future__ import annotations

import contextlib
import os
import time
import warnings
from pathlib import Path

import typer
from numba.core import event
from rich.console import Console
from rich.markup import escape
from rich.table import Table

from . import options


class _Command(typer.Typer):
    """The ``jointdyn`` program. Run as the program (``app()`` without arguments: the console
    script, ``python -m jointdyn``) it ends the process once the command and the ``atexit``
    handlers are done, without the interpreter's teardown of the compiled code's objects
    (≈ 0.4 s CPU of a warm one-revolution run, [T173]); called with arguments (tests,
    benchmarks) it is the ordinary typer application."""

    def __call__(self, *args, **kwargs):
        if args or kwargs:
            return super().__call__(*args, **kwargs)
        try:
            super().__call__()
            code = 0
        except SystemExit as e:
            code = e.code
        _exit(code)


def _exit(code) -> None:
    import atexit
    import sys
    import threading

    if threading.active_count() > 1:  # let the interpreter join the other threads
        raise SystemExit(code)
    if code is None:
        code = 0
    elif not isinstance(code, int):
        print(code, file=sys.stderr)
        code = 1
    atexit._run_exitfuncs()  # type: ignore[attr-defined]
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(Exception):
            stream.flush()
    os._exit(code)


app = _Command(
    help="jointdyn: planar mechanisms with ideal, clearance and lubricated joints.",
    no_args_is_help=True,
    add_completion=False,
    rich_markup_mode=None,
    pretty_exceptions_enable=False,
)
console = Console(soft_wrap=True)


def _version(value: bool) -> None:
    if value:
        from .rundir import version

        typer.echo(f"jointdyn {version()}")
        raise typer.Exit()


@app.callback()
def _main(
    version: bool = typer.Option(
        False, "--version", callback=_version, is_eager=True, help="show the version"
    ),
) -> None:
    """jointdyn: planar mechanisms with ideal, clearance and lubricated joints."""


def _fail(msg: str, code: int = 2) -> typer.Exit:
    typer.echo(f"error: {' '.join(str(msg).split())}", err=True)
    return typer.Exit(code)


def _click_exceptions() -> tuple[type[BaseException], ...]:
    """typer's own exits and usage errors: typer ≥ 0.2x vendors click (``typer.TyperException``),
    older typer re-exports the separate ``click`` package, which is then installed."""
    found: list[type[BaseException]] = [typer.Exit, typer.Abort]
    if hasattr(typer, "TyperException"):
        found.append(typer.TyperException)
    try:
        import click
    except ImportError:  # typer ≥ 0.2x does not depend on click
        return tuple(found)
    return (*found, click.ClickException)


_PASS_THROUGH = _click_exceptions()


@contextlib.contextmanager
def _one_line_errors(out: Path | None = None):
    """Map every expected failure to one stderr line and its exit code; warnings to one line."""
    from . import interrupts
    from .errors import Interrupted, SimulationError

    def show(message, category, filename, lineno, file=None, line=None):
        typer.echo(f"warning: {' '.join(str(message).split())}", err=True)

    where = f"; what was computed is in {out} (see manifest.json)" if out is not None else ""
    old = warnings.showwarning
    warnings.showwarning = show
    try:
        with interrupts.catching():
            yield
    except Interrupted as err:
        t = f" at t = {err.t:.6g} s" if err.t == err.t else ""
        typer.echo(f"interrupted by {err.signal}{t}{where}", err=True)
        raise typer.Exit(interrupts.EXIT_CODES.get(err.signal, 130)) from None
    except KeyboardInterrupt:
        typer.echo(f"interrupted by SIGINT{where}", err=True)
        raise typer.Exit(130) from None
    except SimulationError as err:
        raise _fail(f"{err}{where}", 1) from None
    except (ValueError, OSError) as err:  # ModelError, FieldError, OutputError are ValueErrors
        raise _fail(str(err) if str(err) else type(err).__name__) from None
    except _PASS_THROUGH:
        raise
    except Exception as err:  # a bug: still one line, the traceback with JOINTDYN_DEBUG=1
        if os.environ.get("JOINTDYN_DEBUG"):
            raise
        first = (str(err).splitlines() or [""])[0]
        raise _fail(
            f"internal error {type(err).__name__}: {first} (JOINTDYN_DEBUG=1 shows the traceback)", 1
        ) from None
    finally:
        warnings.showwarning = old


class _progress:
    """A rich progress display that appears at the first update (so that a run refused by
    its checks prints nothing but its one error line), or when numba starts compiling: a first
    run of a kind of model shows a "compiling" line with its elapsed time instead of a silent
    wait, and says afterwards how much of the run was compiling [T221]."""

    COMPILING = "compiling (first run of this kind of model; cached afterwards)"

    def __init__(self, description: str):
        self.description = description
        self._prog = None
        self._tasks: list = []
        self.compile_s = 0.0

    def __enter__(self):
        self._listening = event.install_listener("numba:compile", _CompileNotice(self))
        self._listening.__enter__()
        return self

    def __exit__(self, *exc):
        self._listening.__exit__(*exc)
        if self._prog is not None:
            self._prog.stop()
        if self.compile_s >= 1.0 and exc[0] is None:
            console.print(
                f"[dim]first run: {self.compile_s:.0f} s of it compiling the numerical kernels, once "
                "(later runs of this kind of model load them from the cache)[/dim]"
            )

    def add_task(self, name: str, total: float) -> int:
        self._tasks.append((name, total))
        return len(self._tasks) - 1

    def _started(self):
        if self._prog is None:
            from rich.progress import BarColumn, Progress, TimeElapsedColumn, TimeRemainingColumn

            self._prog = Progress(
                "[progress.description]{task.description}",
                BarColumn(),
                "[progress.percentage]{task.percentage:>3.0f}%",
                TimeElapsedColumn(),
                TimeRemainingColumn(),
                console=console,
                transient=False,
            )
            self._ids = [self._prog.add_task(escape(n), total=t) for n, t in self._tasks]
            self._prog.start()
        return self._prog

    def update(self, task: int, completed: float) -> None:
        self._started().update(self._ids[task], completed=completed)

    def compiling(self, seconds: float | None) -> None:
        """A top-level compilation starts (None) or ended after ``seconds`` [s]."""
        prog = self._started()
        if seconds is None:
            self._compile_task = prog.add_task(self.COMPILING, total=None)
        else:
            prog.remove_task(self._compile_task)
            self.compile_s += seconds


class _CompileNotice(event.Listener):
    """numba compile-event listener: tells ``prog`` when an outermost compilation starts and
    ends (nested compilations of callees are part of it); numba sends no event for a function
    loaded from its cache."""

    def __init__(self, prog: _progress):
        self.prog, self.depth, self.t0 = prog, 0, 0.0

    def on_start(self, ev) -> None:
        if self.depth == 0:
            self.t0 = time.perf_counter()
            self.prog.compiling(None)
        self.depth += 1

    def on_end(self, ev) -> None:
        self.depth -= 1
        if self.depth == 0:
            self.prog.compiling(time.perf_counter() - self.t0)


_RA = options.run_args()


def _arg_help(name: str, text: str) -> str:
    """Help of a slider-crank builder argument: its unit and default from the builder."""
    default, unit = options.builder_args()[name]
    return f"{text} [{unit}] (default {default:.6g})"


_JOINT_HELP = "piston-pin joint kind: " + ", ".join(options.joints())


def _solver_help() -> str:
    from .integrators import SOLVERS

    return "integrator: auto (radau5 for a lubricated joint, else dopri5), " + ", ".join(SOLVERS)


#: CLI spelling of the slider-crank builder arguments
OPTION_NAMES = {k: "--" + k.replace("_", "-") for k in (*options.builder_args(), *options.FLAGS)}
OPTION_NAMES |= {k: "--" + k.replace("_", "-") for k in ("joint", "revs", "samples_per_rev", "rtol", "atol")}


@app.command()
def run(
    model: str = typer.Argument(..., help="shipped model name (slider-crank) or a model file FILE.toml"),
    joint: str = typer.Option(None, help=_JOINT_HELP + " (default perfect)"),
    revs: float = typer.Option(None, help=f"crank revolutions to simulate [rev] (default {_RA['revs']:g})"),
    samples_per_rev: int = typer.Option(
        None, help=f"output samples per crank revolution [-] (default {_RA['samples_per_rev']})"
    ),
    out: Path = typer.Option(Path("out/run"), help="output directory (must be empty or a previous run's)"),
    overwrite: bool = typer.Option(False, help="replace jointdyn's files from a previous run in --out"),
    solver: str = typer.Option(None, help=_solver_help()),
    rtol: float = typer.Option(None, help=f"relative tolerance [-] (default {_RA['rtol']:g})"),
    atol: float = typer.Option(None, help=f"absolute tolerance [SI of each state] (default {_RA['atol']:g})"),
    clearance: float = typer.Option(
        None, help=_arg_help("clearance", "radial clearance c of an imperfect joint")
    ),
    viscosity: float = typer.Option(None, help=_arg_help("viscosity", "lubricant dynamic viscosity")),
    length: float = typer.Option(None, help=_arg_help("length", "bearing length")),
    friction: float = typer.Option(None, help="Ambrósio friction coefficient in contact [-] (default 0)"),
    contact: bool = typer.Option(False, help="lubricated joint: add Lankarani–Nikravesh asperity contact"),
    shear: bool = typer.Option(
        None,
        "--shear/--no-shear",
        help="lubricated joint: apply the film's shear torques (default: off, as the paper)",
    ),
    bushing: str = typer.Option(
        None, help="body carrying the bearing hole: rod (default, as the paper) or slider"
    ),
    asperity_height: float = typer.Option(None, help="with --contact: contact starts at h_min < this [m]"),
    restitution: float = typer.Option(
        None, help=_arg_help("restitution", "dry joint: coefficient of restitution")
    ),
    set_: list[str] = typer.Option([], "--set", help="model file override a.b.c=VALUE (repeatable)"),
):
    """Simulate a shipped mechanism or a model file; write results.nc, timeseries.csv,
    summary.json, figures and manifest.json."""
    from .rundir import OutputDir

    sc_opts = {
        "joint": joint,
        "revs": revs,
        "samples_per_rev": samples_per_rev,
        "solver": solver,
        "rtol": rtol,
        "atol": atol,
        "clearance": clearance,
        "viscosity": viscosity,
        "length": length,
        "friction": friction,
        "asperity_height": asperity_height,
        "restitution": restitution,
        "shear": shear,
        "bushing": bushing,
    }
    given = {k: v for k, v in sc_opts.items() if v is not None} | ({"contact": True} if contact else {})
    is_file = model.endswith(".toml") or Path(model).is_file()
    od = None
    with _one_line_errors(out):
        if is_file:
            if given:
                names = ", ".join(OPTION_NAMES.get(k, "--" + k) for k in given)
                raise ValueError(
                    f"{names}: apply to the shipped slider-crank; for a model file use --set a.b=VALUE"
                )
            from .runs import prepare_model_file, run_model_file

            prepared = prepare_model_file(model, set_)
            options.check_memory(prepared[1], prepared[2].n_out, "simulation.n_out")
            od = OutputDir(out, "run", prepared[3]).claim(overwrite)
            with _progress("run") as prog:
                task = prog.add_task(prepared[0].name, total=1.0)
                res = run_model_file(
                    model, od, set_, prepared=prepared, progress=lambda f: prog.update(task, completed=f)
                )
            files = ", ".join([*od.files, "manifest.json"])
            console.print(
                f"{escape(res.system.name)}: {len(res.t)} samples, {res.stats['rhs_evaluations']} RHS "
                f"evaluations, {res.wall_time:.3f} s; wrote {escape(str(out))}/: {files}"
            )
            return
        if set_:
            raise ValueError("--set applies to model files only")
        if model != "slider-crank":
            raise ValueError(
                f"MODEL {model!r}: unknown shipped model and not a file; valid: slider-crank or FILE.toml"
            )
        _run_slider_crank(given, out, overwrite)


def _run_slider_crank(given: dict, out: Path, overwrite: bool) -> None:
    from .integrators import SOLVERS
    from .models.slider_crank import slider_crank
    from .rundir import OutputDir
    from .runs import run_slider_crank, slider_crank_config

    joint = given.pop("joint", "perfect")
    ra = options.run_args()
    run_kw = {k: given.pop(k) for k in ("solver", "rtol", "atol", "samples_per_rev") if k in given}
    revs = given.pop("revs", ra["revs"])
    model_kw = options.slider_crank_args(joint, given, OPTION_NAMES)
    options.check_run(
        revs, run_kw.get("samples_per_rev", ra["samples_per_rev"]), **_tols(run_kw), names=OPTION_NAMES
    )
    if run_kw.get("solver", "auto") not in ("auto", *SOLVERS):
        raise ValueError(f"--solver {run_kw['solver']!r}: unknown; valid: auto, {', '.join(SOLVERS)}")
    cfg = slider_crank_config(joint, revs, **run_kw)
    options.check_memory(slider_crank(joint, **model_kw), cfg.n_out, "--revs × --samples-per-rev")
    spec = {"model": "slider-crank", "joint": joint, "revs": revs, **run_kw} | {
        k: given[k] for k in given if k not in run_kw
    }
    od = OutputDir(out, "run", spec).claim(overwrite)
    with _progress("run") as prog:
        task = prog.add_task(f"slider-crank ({joint})", total=1.0)
        _, _, summary = run_slider_crank(
            joint,
            revs,
            out=od,
            progress=lambda f: prog.update(task, completed=f),
            model_kw=model_kw,
            **run_kw,
        )
    tab = Table(title=f"slider-crank, {joint} piston pin ({revs:g} rev)")
    tab.add_column("quantity")
    tab.add_column("value", justify="right")
    for k, v in summary.items():
        if not isinstance(v, dict):
            tab.add_row(k, f"{v:.6g}" if isinstance(v, float) else escape(str(v)))
    console.print(tab)
    console.print(f"wrote {escape(str(out))}/: {', '.join(od.files)}, manifest.json")


def _tols(run_kw: dict) -> dict:
    return {k: run_kw[k] for k in ("rtol", "atol") if k in run_kw}


@app.command()
def reproduce(
    paper: str = typer.Argument(..., help="which paper: alshaer2005"),
    out: Path = typer.Option(Path("out/alshaer2005"), help="output directory"),
    quick: bool = typer.Option(False, help="1 revolution instead of 4 (CI smoke run)"),
    beyond: bool = typer.Option(True, help="also run the beyond-the-paper cases"),
):
    """Run the paper's comparison (perfect, dry, Ott, π-film) and write figures + report.html;
    the full run also reports the dry case as a distribution (ensemble_dry.md)."""
    from .reproduce import BEYOND_CASES, PAPER_CASES, reproduce_alshaer2005, summary_markdown
    from .rundir import check_path

    with _one_line_errors():
        if paper != "alshaer2005":
            raise ValueError(f"PAPER {paper!r}: unknown; valid: alshaer2005")
        check_path(out)
        cases = PAPER_CASES + (BEYOND_CASES if beyond else ())
        with _progress("reproduce") as prog:
            names = [c.name for c in cases] + ([] if quick else ["dry ensemble"])
            tasks = {n: prog.add_task(n, total=1.0) for n in names}
            runs = reproduce_alshaer2005(
                out,
                quick=quick,
                beyond=beyond,
                progress=lambda name, f: prog.update(tasks[name], completed=f),
            )
    console.print(escape(summary_markdown(runs)))
    if (Path(out) / "ensemble_dry.md").exists():  # the dry case as a distribution (full runs)
        console.print(escape((Path(out) / "ensemble_dry.md").read_text(encoding="utf-8")))
    console.print(f"wrote {escape(str(out))}/report.html, summary.csv, <case>.csv and the figures")


@app.command()
def sweep(
    spec: Path = typer.Argument(
        ..., help="sweep file (TOML): [base], [grid]/[zip]/[sample], [output], [dask]"
    ),
    out: Path = typer.Option(
        Path("out/sweep"), help="output directory (empty, or this sweep's with --resume)"
    ),
    resume: bool = typer.Option(
        False, help="keep finished cases of the same sweep, run only the missing ones"
    ),
    overwrite: bool = typer.Option(False, help="replace jointdyn's files from a previous sweep in --out"),
    scheduler: str = typer.Option(
        None, help="Dask scheduler address tcp://HOST:PORT (default: local processes)"
    ),
    workers: int = typer.Option(None, help="local worker processes [-] (default: all cores)"),
):
    """Run a parameter study; writes DIR/cases/*.json per case, DIR/sweep.nc and DIR/manifest.json."""
    from .sweep import load_sweep, run_sweep

    with _one_line_errors(out):
        if resume and overwrite:
            raise ValueError("--resume and --overwrite exclude each other")
        if workers is not None and workers < 1:
            raise ValueError(f"--workers = {workers} [-]: must be an integer >= 1")
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
                overwrite=overwrite,
                progress=lambda done, total: prog.update(task, completed=done),
            )
    failed = int((ds["error"] != "").sum())
    console.print(f"wrote {escape(str(out))}/sweep.nc ({n} cases, {failed} failed)")


from . import cli_files  # noqa: E402  (registers plot, plot-sweep, animate, film-force, list)
from .bearing.cli import bearing_table_cmd  # noqa: E402

app.command("bearing-table")(bearing_table_cmd)

__all__ = ["app", "cli_files", "main"]


from .cli_chaos import register as _register_chaos  # noqa: E402

_register_chaos(app)


def main():  # pragma: no cover
    app()
