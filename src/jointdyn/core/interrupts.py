"""Ctrl-C (SIGINT) and SIGTERM as a flag, checked where Python runs, never an exception raised
at an arbitrary point (which inside compiled code crashed the interpreter).

Where the flag is checked bounds the latency [T142]. ``with catching(): ...`` installs
flag-setting handlers in the main thread and restores the
previous ones on exit; :func:`check` raises :class:`~jointdyn.errors.Interrupted` once a signal
was received. Exit codes follow the shell convention 128 + signal number (130, 143).
"""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Iterator

from jointdyn.errors import Interrupted

EXIT_CODES = {"SIGINT": 130, "SIGTERM": 143}
_received: list[str] = []
_depth = [0]  # nesting of catching() (simulate() inside a CLI command): only the outermost acts


def _handler(signum, frame) -> None:
    _received.append(signal.Signals(signum).name)


@contextlib.contextmanager
def catching() -> Iterator[None]:
    """Record SIGINT/SIGTERM instead of raising (main thread only; elsewhere a no-op)."""
    if threading.current_thread() is not threading.main_thread() or _depth[0] > 0:
        yield  # in a worker thread, or inside an outer catching(): that one records
        return
    _received.clear()
    old = {s: signal.signal(s, _handler) for s in (signal.SIGINT, signal.SIGTERM)}
    _depth[0] += 1
    try:
        yield
    finally:
        _depth[0] -= 1
        for s, h in old.items():
            signal.signal(s, h)


def received() -> str | None:
    """Name of the first signal received inside :func:`catching` (None if none)."""
    return _received[0] if _received else None


def acknowledge() -> None:
    """Forget the signals received so far (after handling them), so that :func:`check` reacts
    only to a further one (e.g. a second Ctrl-C while partial results are written)."""
    _received.clear()


def check(t: float = float("nan"), results=None) -> None:
    """Raise :class:`Interrupted` if a signal was received."""
    name = received()
    if name is not None:
        raise Interrupted(f"interrupted by {name}", t, results, name)
