"""Calls through the copy of a kernel compiled ahead of time, where one is installed [T382].

Python code calls such a kernel as ``call(fn, *args)``. The module that holds the compiled copies
(:mod:`jointdyn.integrators.aot`, a higher layer: it knows the step loops) registers its lookup
here when it is imported, which ``import jointdyn`` does; before that, or for a kernel or
argument types without a copy, ``call`` is ``fn(*args)`` (compiled at first use)."""

from __future__ import annotations

from collections.abc import Callable

_lookup: Callable | None = None


def register(lookup: Callable) -> None:
    """``lookup(fn, args) -> the callable to use`` for every later :func:`call`."""
    global _lookup
    _lookup = lookup


def call(fn: Callable, *args):
    """``fn(*args)``, through its ahead-of-time copy where there is one for these argument types."""
    return (fn if _lookup is None else _lookup(fn, args))(*args)
