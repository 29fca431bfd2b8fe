"""Derived outputs: files written into a directory another command made (``poincare``,
``spectrum``, ``plot``, ``plot-sweep``, ``animate``, ``bifurcation.png``, and the single files of
``bearing-table``, ``stribeck``, ``film-force``) join its manifest under
its lock (:mod:`jointdyn.io.rundir`); a single file elsewhere is written on its own by
:func:`jointdyn.core.atomic.replacing`."""

from __future__ import annotations

import contextlib
from pathlib import Path

from jointdyn.core import atomic
from jointdyn.io.rundir import OutputDir, read_manifest


def status_of(err: BaseException) -> str:
    """The manifest status of a command stopped by ``err``."""
    from jointdyn.errors import Interrupted

    return "interrupted" if isinstance(err, (Interrupted, KeyboardInterrupt)) else "failed"


@contextlib.contextmanager
def derived(directory, kind: str, option: str = "--out"):
    """Claim ``directory`` for derived outputs: a directory with a manifest is locked and the
    files written through the yielded :class:`OutputDir` are added to its manifest (replacing
    only files it lists); a new or empty directory becomes one of kind ``kind``; a non-empty
    directory without a manifest is refused."""
    directory = Path(directory)
    base = read_manifest(directory) if directory.is_dir() else None
    od = OutputDir(directory, kind, {}, option)
    if base is None:
        od.claim()
    else:
        od.extend()
    try:
        yield od
    except BaseException as err:
        if base is None:
            od.finish(status_of(err), str(err))
        elif od.files:
            od.finish()
        else:
            od.release()
        raise
    od.finish("complete")


@contextlib.contextmanager
def output_file(path, kind: str = "plot", option: str = "--out"):
    """A single output file: inside a directory with a manifest it is a derived output of that
    directory (:func:`derived`); anywhere else it is written safely on its own (a character
    device such as ``/dev/null`` is written into)."""
    path = Path(path)
    if str(path) not in atomic.STREAMS and read_manifest(path.parent) is not None:
        with derived(path.parent, kind, option) as od, od.write(path.name) as tmp:
            yield tmp
    else:
        with atomic.replacing(path, devices=True, option=option) as tmp:
            yield tmp
