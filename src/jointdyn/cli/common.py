"""Shared pieces of the command-line interface: the typer application, the console, one-line
errors and the progress display with its compile notice (every command module imports these;
none imports another command module).

Every command checks all its inputs before any work, writes its outputs atomically, and ends
a problem with one line on stderr and a non-zero exit code: 2 bad input or output path, 1 a
failed simulation (partial results written with their status), 130 Ctrl-C (SIGINT), 143
SIGTERM — never a traceback.
"""

from __future__ import annotations

import contextlib
import os
import sys
import time
import warnings
from pathlib import Path

import typer
from numba.core import event
from rich.console import Console
from rich.markup import escape


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
        except KeyboardInterrupt:  # before a command's own handler (argument parsing, imports)
            print("interrupted by SIGINT", file=sys.stderr)
            code = 130
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
        from jointdyn.io.rundir import version

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
    from jointdyn.core import interrupts
    from jointdyn.errors import Interrupted, SimulationError

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
        self._running: set = set()
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
            # each task's clock starts at its own first update: per-task elapsed times
            self._ids = [self._prog.add_task(escape(n), total=t, start=False) for n, t in self._tasks]
            self._prog.start()
        return self._prog

    def update(self, task: int, completed: float) -> None:
        prog = self._started()
        tid = self._ids[task]
        if tid not in self._running:
            self._running.add(tid)
            prog.start_task(tid)
        prog.update(tid, completed=completed)

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
