"""``jointdyn cache info`` and ``jointdyn cache clear``: what jointdyn keeps in its cache
directory (compiled kernels per source hash, finite-film tables) and emptying it [T225]."""

from __future__ import annotations

import typer
from rich.markup import escape
from rich.table import Table

from jointdyn.cli.common import _one_line_errors, _progress, app, console

cache_app = typer.Typer(
    help="Show or empty jointdyn's cache (compiled kernels, film tables).", no_args_is_help=True
)
app.add_typer(cache_app, name="cache")


def _mb(n: int) -> str:
    return f"{n / 1e6:.1f} MB"


@cache_app.command("info")
def info() -> None:
    """List the cache: compiled kernels of these sources, stale kernels of other versions, tables;
    and whether the step loops compiled at install are used [T382]."""
    from jointdyn.core.compiled import cache_base, cache_entries, cache_root
    from jointdyn.integrators import aot

    with _one_line_errors():
        entries = cache_entries()
        tab = Table(title=f"jointdyn cache: {escape(str(cache_base()))}")
        for col in ("kind", "directory", "files", "size"):
            tab.add_column(col, justify="right" if col in ("files", "size") else "left")
        for e in entries:
            tab.add_row(e["kind"], escape(e["path"].name), str(e["files"]), _mb(e["bytes"]))
        console.print(tab)
        total = sum(e["bytes"] for e in entries)
        console.print(f"total {_mb(total)}; these sources compile into {escape(cache_root().name)}")
        console.print(f"ahead of time: {escape(aot.status())}")


@cache_app.command("clear")
def clear(
    stale: bool = typer.Option(False, "--stale", help="remove only kernels compiled from other sources"),
) -> None:
    """Delete jointdyn's cache directories (the next run compiles its kernels again)."""
    from jointdyn.core.compiled import clear_cache

    with _one_line_errors():
        gone = clear_cache(stale_only=stale)
        freed = sum(e["bytes"] for e in gone)
        console.print(f"removed {len(gone)} cache directories ({_mb(freed)})")


@app.command()
def warmup(
    targets: list[str] = typer.Argument(
        None,
        help="shipped joints (perfect, dry, ott, alshaer2005, finite, short) or model files; default: all",
    ),
    processes: int = typer.Option(0, help="worker processes (0: all cores)", min=0),
) -> None:
    """Compile the kernels of the given models into the cache, in parallel processes (one short
    run each), so that their first real run loads instead of compiling."""
    from jointdyn.studies.warmup import SHIPPED
    from jointdyn.studies.warmup import warmup as run_warmup

    with _one_line_errors():
        names = list(targets or SHIPPED)
        with _progress("warm-up") as prog:
            task = prog.add_task("compiling kernels (once per version of jointdyn)", total=len(names))
            finished: list[dict] = []

            def record(r):
                finished.append(r)
                prog.update(task, completed=len(finished))

            results = run_warmup(names, processes or None, record)
        for r in sorted(results, key=lambda r: names.index(r["target"])):
            console.print(f"{escape(r['target'])}: {r['compilations']} compilations, {r['seconds']:.1f} s")
