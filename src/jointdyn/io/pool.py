"""Local worker processes that stop when the run is interrupted [T142].

Used by the sweep (:mod:`jointdyn.studies.sweep`) and the ensembles (:mod:`jointdyn.studies.ensemble`):
workers ignore Ctrl-C and die with their parent; the parent polls the signal record while it
waits, and on any exception (an interrupt, a failed case) kills the workers at once instead of
waiting for the cases in flight.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable


def worker_init(parent: int, kinds: tuple | None = None) -> None:
    """Worker processes ignore Ctrl-C (the parent stops them) and die with their parent
    (Linux ``PR_SET_PDEATHSIG``), so a killed run leaves no orphans; they pack their systems for
    the parent's shared ``kinds`` too, if any (its compiled kernels, from the cache) [T322, T341]."""
    from jointdyn.multibody.system import share_kinds_in_process

    share_kinds_in_process(kinds)

    from jointdyn.io.rundir import close_inherited

    close_inherited()
    detach(parent)


def detach(parent: int) -> None:
    """This process ignores Ctrl-C (``parent`` stops it) and dies with ``parent`` (Linux
    ``PR_SET_PDEATHSIG``); imports nothing of jointdyn (the figure-drawing process [T360])."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG = 1
    except (OSError, AttributeError):  # pragma: no cover - not Linux
        pass
    if os.getppid() != parent:  # the parent died before prctl took effect
        os._exit(1)


def run_local(fn: Callable, calls: Iterable[tuple], workers: int | None, record: Callable) -> None:
    """Run ``fn(*args)`` for every ``(key, args)`` of ``calls`` on ``workers`` processes (None:
    all cores), calling ``record(key, result)`` in the parent as each finishes; raises
    :class:`~jointdyn.errors.Interrupted` within ≈ 0.25 s of a SIGINT/SIGTERM (workers killed)."""
    from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

    from jointdyn.core import interrupts
    from jointdyn.multibody.system import shared_kinds_now

    ex = ProcessPoolExecutor(
        max_workers=workers or os.cpu_count(),
        initializer=worker_init,
        initargs=(os.getpid(), shared_kinds_now()),
    )
    try:
        pending = {ex.submit(fn, *args): key for key, args in calls}
        while pending:
            finished, _ = wait(pending, timeout=0.25, return_when=FIRST_COMPLETED)
            for fut in finished:
                record(pending.pop(fut), fut.result())
            interrupts.check()
    except BaseException:
        for p in list(getattr(ex, "_processes", {}).values()):  # stop the workers now
            p.kill()
        # let the pool's manager thread see the dead workers and close its pipes now: at exit,
        # CPython 3.11's concurrent.futures._python_exit can otherwise write to a wake-up pipe
        # that thread is closing (OSError EBADF printed as an ignored exception); shutdown()
        # drops the executor's reference to the thread, so take it first
        manager = getattr(ex, "_executor_manager_thread", None)
        ex.shutdown(wait=False, cancel_futures=True)
        if manager is not None:
            manager.join(timeout=5.0)
        raise
    ex.shutdown(wait=True)
