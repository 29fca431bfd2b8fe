"""Dask cluster runs that never hang [T280].

Every wait on the cluster is bounded and polls the signal record (:mod:`jointdyn.core.interrupts`)
every ``POLL`` seconds, so SIGINT/SIGTERM stop it within ≈ ``POLL``:

* :func:`connect`: the scheduler must answer within ``CONNECT_TIMEOUT`` (a closed port, a server
  that accepts and never answers, a wrong host) — else one ``ConnectionError`` line;
* :func:`run_cluster` waits for at least one worker for ``WORKER_TIMEOUT`` (telling ``notice``
  once that it waits), and, while cases run, a cluster without workers (all lost) or a scheduler
  that stops answering for as long ends the run with one ``ConnectionError`` line. Cases already
  finished were recorded by then (the sweep keeps them; ``--resume`` runs the rest).

A case whose worker died repeatedly (Dask's ``KilledWorker``) ends the run the same way: the
failure is the cluster's, not the case's, so it is not recorded as the case's result.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterable

from jointdyn.core import interrupts

CONNECT_TIMEOUT = 10.0  # [s] the scheduler answers the handshake within this
WORKER_TIMEOUT = 60.0  # [s] at least one worker within this (at start and while running)
POLL = 0.25  # [s] signal and completion polling
ASK_TIMEOUT = 5.0  # [s] one question to a running scheduler


def check_address(address: str) -> None:
    """``address``: ``tcp://`` (the default scheme) or ``tls://`` must name ``HOST:PORT`` with PORT in
    1…65535 (other schemes, e.g. ``inproc://``, are Dask's to check): refused before any connection
    attempt (Dask's own error came after the connect timeout, followed by an ignored traceback
    of its half-made client) [T335]."""
    from urllib.parse import urlsplit

    try:
        u = urlsplit(address if "://" in address else "tcp://" + address)  # Dask's default: tcp
        port = u.port
    except ValueError:
        u, port = None, None
    hostport = u is not None and bool(u.hostname) and port is not None and 0 < port < 65536
    if u is None or (u.scheme in ("tcp", "tls") and not hostport):
        raise ValueError(
            f"--scheduler {address!r}: expected tcp://HOST:PORT (PORT 1…65535), e.g. tcp://127.0.0.1:8786"
        )


def connect(address: str, timeout: float | None = None):
    """A Dask client of the scheduler at ``address`` (tcp://HOST:PORT), or one
    ``ConnectionError`` line after ``timeout`` [s] (None: ``CONNECT_TIMEOUT``); a signal stops
    the wait within ``POLL``."""
    timeout = CONNECT_TIMEOUT if timeout is None else timeout
    check_address(address)
    try:
        from distributed import Client
    except ImportError:
        raise ValueError("--scheduler needs Dask: pip install 'jointdyn[dist]'") from None
    box: dict = {}

    def attempt() -> None:
        try:
            box["client"] = Client(address, timeout=f"{timeout}s", set_as_default=False)
        except BaseException as err:  # reported below, in the caller's thread
            box["error"] = err

    th = threading.Thread(target=attempt, name="jointdyn-dask-connect", daemon=True)
    th.start()
    t0 = time.monotonic()
    while th.is_alive() and time.monotonic() - t0 < timeout + 2.0:
        th.join(POLL)
        interrupts.check()
    if "client" in box:
        return box["client"]
    err = box.get("error")
    why = (str(err).splitlines() or [""])[0] if err is not None else "no answer"
    raise ConnectionError(
        f"--scheduler {address}: cannot connect within {timeout:g} s ({why or type(err).__name__})"
    )


def close(client) -> None:
    """Close ``client`` without waiting on a scheduler that may be gone (bounded)."""
    try:
        client.close(timeout=2)
    except Exception:  # a dead scheduler: nothing left to close cleanly
        pass


def _workers(client) -> int | None:
    """Number of workers the scheduler knows; None if it does not answer within ASK_TIMEOUT."""
    try:
        return len(client.sync(client.scheduler.ncores, workers=None, callback_timeout=ASK_TIMEOUT))
    except Exception:  # OSError, TimeoutError, CommClosedError: not answering
        return None


def run_cluster(
    client,
    fn: Callable,
    calls: Iterable[tuple],
    record: Callable,
    worker_timeout: float = WORKER_TIMEOUT,
    notice: Callable[[str], None] | None = None,
) -> None:
    """Run ``fn(*args)`` for every ``(key, args)`` of ``calls`` on the cluster of ``client``,
    calling ``record(key, result)`` as each finishes. Raises ``ConnectionError`` (one line) when no
    worker is there or the scheduler does not answer for ``worker_timeout`` [s], or a case's
    worker died repeatedly; :class:`~jointdyn.errors.Interrupted` within ≈ ``POLL`` of a signal.
    The cases in flight are cancelled in every case."""
    address = getattr(client.scheduler, "address", "the scheduler")
    futs: dict = {}
    try:
        _first_worker(client, address, worker_timeout, notice)
        futs = {client.submit(fn, *args, pure=False): key for key, args in calls}
        pending = set(futs)
        last_seen = time.monotonic()  # a worker was there / the scheduler answered
        next_ask = last_seen + 2.0
        while pending:
            done = {f for f in pending if f.done()}
            got = 0
            for fut in done:
                if fut.status != "finished":
                    raise ConnectionError(_lost(address, futs[fut], fut))
                try:  # the result may sit on a worker that is gone: then it is computed again
                    result = fut.result(timeout=4 * POLL)
                except TimeoutError:
                    continue
                pending.discard(fut)
                record(futs[fut], result)
                got += 1
            if not got:
                time.sleep(POLL)
            interrupts.check()
            now = time.monotonic()
            if got:
                last_seen = now
            elif now >= next_ask:
                next_ask = now + 2.0
                n = _workers(client)
                if n:
                    last_seen = now
                elif now - last_seen > worker_timeout:
                    what = "stopped answering" if n is None else "has no worker left (all lost)"
                    raise ConnectionError(f"--scheduler {address}: {what} for {worker_timeout:g} s")
    except BaseException:
        left = [f for f in futs if f.status == "pending"]
        if left:
            try:
                client.sync(client._cancel, left, callback_timeout=2.0)  # best effort, bounded
            except Exception:  # a scheduler that is gone has nothing to cancel
                pass
        raise


def _first_worker(client, address: str, worker_timeout: float, notice) -> None:
    t0 = time.monotonic()
    told = False
    while True:
        n = _workers(client)
        if n:
            return
        if not told and notice is not None:
            notice(f"waiting for workers at {address} (up to {worker_timeout:g} s)")
            told = True
        if time.monotonic() - t0 > worker_timeout:
            what = "does not answer" if n is None else "has no worker"
            raise ConnectionError(f"--scheduler {address}: {what} after {worker_timeout:g} s")
        for _ in range(4):
            time.sleep(POLL)
            interrupts.check()


def _lost(address: str, key, fut) -> str:
    if fut.status != "error":  # "lost" / "cancelled": its worker or the scheduler forgot it
        return f"--scheduler {address}: case {key} was lost ({fut.status}: its worker is gone)"
    try:
        err = fut.exception(timeout=ASK_TIMEOUT)
    except BaseException as e:  # the scheduler is gone too
        err = e
    first = (str(err).splitlines() or [""])[0]
    return f"--scheduler {address}: case {key} was lost ({type(err).__name__}{': ' + first if first else ''})"
