"""Re-open a saved run (``results.nc`` of ``jointdyn run``) as a Results object."""

from __future__ import annotations

from pathlib import Path


def load_run(directory):
    """:class:`~jointdyn.simulation.results.Results` of ``DIR/results.nc`` (or of the file given)."""
    from jointdyn.simulation.results import Results

    path = Path(directory)
    path = path / "results.nc" if path.is_dir() else path
    if not path.exists():
        raise ValueError(f"{path}: no results file (run `jointdyn run … --out DIR` first)")
    return Results.load(path)
