"""A Dask sweep never hangs [T280, T281]: a scheduler that accepts and never answers, a
scheduler without workers, workers lost mid-sweep and a signal while waiting each end in one
line within a stated time, with the finished cases kept and resumable; a case longer than
``case_timeout`` is recorded as failed, the others run."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import threading
import time

import pytest

from jointdyn.core import interrupts
from jointdyn.errors import Interrupted
from jointdyn.io import cluster
from jointdyn.io.rundir import read_manifest
from jointdyn.studies.sweep import SweepSpec, run_sweep

distributed = pytest.importorskip("distributed", reason="the [dist] extra is needed for Dask sweeps")

BASE = {"model": "slider-crank", "joint": "perfect", "revs": 0.25, "samples_per_rev": 90}


def _cluster(n_workers: int):
    return distributed.LocalCluster(
        n_workers=n_workers, threads_per_worker=1, processes=False, dashboard_address=None
    )


def test_a_server_that_accepts_and_never_answers_is_refused_in_one_line(tmp_path, monkeypatch):
    """A TCP server that accepts the connection and never speaks: the handshake waits at most
    CONNECT_TIMEOUT (3 s here), then one ConnectionError line; no file is touched."""
    monkeypatch.setattr(cluster, "CONNECT_TIMEOUT", 3.0)
    srv = socket.socket()
    srv.bind(("127.0.0.1", 0))
    srv.listen()
    held = []
    stop = threading.Event()

    def serve():
        srv.settimeout(0.2)
        while not stop.is_set():
            try:
                held.append(srv.accept()[0])  # accept, never answer
            except OSError:
                pass

    th = threading.Thread(target=serve, daemon=True)
    th.start()
    try:
        t0 = time.monotonic()
        with pytest.raises(ConnectionError, match="cannot connect within 3 s") as err:
            run_sweep(
                SweepSpec(base=BASE, grid={"speed": [100.0]}),
                tmp_path / "s",
                scheduler=f"tcp://127.0.0.1:{srv.getsockname()[1]}",
            )
        assert time.monotonic() - t0 < 3.0 + 2 * cluster.POLL + 2.0
        assert held, "the fake server was never contacted"
        assert "\n" not in str(err.value)
        assert not (tmp_path / "s").exists()
    finally:
        stop.set()
        th.join()
        for c in held:
            c.close()
        srv.close()


def test_a_scheduler_without_workers_says_it_waits_then_stops(tmp_path):
    """LocalCluster(n_workers=0): a 'waiting for workers' notice, then one ConnectionError line
    after worker_timeout (2 s); the manifest records the failure and how to resume."""
    lines: list[str] = []
    with _cluster(0) as lc:
        t0 = time.monotonic()
        with pytest.raises(ConnectionError, match="has no worker after 2 s") as err:
            run_sweep(
                SweepSpec(base=BASE, grid={"speed": [100.0, 200.0]}),
                tmp_path / "s",
                scheduler=lc.scheduler_address,
                worker_timeout=2.0,
                notice=lines.append,
            )
        elapsed = time.monotonic() - t0
        assert len(lines) == 1 and lines[0].startswith(f"waiting for workers at {lc.scheduler_address} ")
    assert 2.0 <= elapsed < 2.0 + cluster.ASK_TIMEOUT + 2.0, elapsed
    assert "\n" not in str(err.value) and "0 of 2 cases finished" in str(err.value)
    m = read_manifest(tmp_path / "s")
    assert m["status"] == "failed" and "--resume" in m["reason"]


def test_a_signal_while_waiting_for_workers_stops_the_wait(tmp_path):
    """SIGINT during the wait for a worker (60 s allowed): Interrupted within ~POLL."""
    with _cluster(0) as lc, interrupts.catching():
        timer = threading.Timer(1.0, os.kill, (os.getpid(), signal.SIGINT))
        timer.start()
        t0 = time.monotonic()
        with pytest.raises(Interrupted):
            run_sweep(
                SweepSpec(base=BASE, grid={"speed": [100.0]}),
                tmp_path / "s",
                scheduler=lc.scheduler_address,
                worker_timeout=60.0,
            )
        assert time.monotonic() - t0 < 1.0 + cluster.ASK_TIMEOUT, "the wait ignored the signal"
        interrupts.acknowledge()  # handled: later checks outside catching() must not see it
    assert read_manifest(tmp_path / "s")["status"] == "interrupted"


def test_a_killed_worker_keeps_the_finished_cases_and_resumes(tmp_path):
    """The only worker (a separate process) is killed (SIGKILL) after the first finished case:
    one ConnectionError line (the case in flight was lost, or no worker left after
    worker_timeout), the finished cases are on disk, --resume (local
    processes) completes the sweep with the same values as an uninterrupted local run."""
    spec = SweepSpec(base=BASE | {"revs": 2.0}, grid={"speed": [100.0 + 10 * i for i in range(12)]})
    out = tmp_path / "s"
    with distributed.LocalCluster(
        n_workers=0, processes=True, dashboard_address=None, host="127.0.0.1", protocol="tcp"
    ) as lc:
        addr = lc.scheduler_address
        worker = subprocess.Popen(
            [
                sys.executable,
                "-m",
                "distributed.cli.dask_worker",
                addr,
                "--nthreads",
                "1",
                "--no-nanny",
                "--no-dashboard",
            ],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        try:
            with distributed.Client(addr, timeout=60) as c:  # the worker is up before the sweep starts
                c.wait_for_workers(1, timeout=120)  # (its start-up alone can exceed 2 s on a loaded machine)

            def progress(done, total):
                if done == 1:
                    worker.kill()

            # the case lost, all workers lost, or a scheduler too busy to answer within the timeout
            with pytest.raises(ConnectionError, match="lost|stopped answering") as err:
                run_sweep(spec, out, scheduler=addr, worker_timeout=2.0, progress=progress)
        finally:
            worker.kill()
            worker.wait()
    done = len(list((out / "cases").glob("case_*.json")))
    assert 1 <= done < 12 and f"{done} of 12 cases finished" in str(err.value)
    assert read_manifest(out)["status"] == "failed"
    ds = run_sweep(spec, out, resume=True, workers=1)
    ref = run_sweep(spec, tmp_path / "ref", workers=1)
    assert (ds["error"] == "").all()
    assert (ds["peak_moment"].values == ref["peak_moment"].values).all()
    assert read_manifest(out)["status"] == "complete"


def test_case_timeout_records_the_slow_case_and_runs_the_rest(tmp_path):
    """case_timeout = 1e-9 s: every integration exceeds it at its second progress report, each
    case is recorded as failed with the reason; the sweep itself completes."""
    ds = run_sweep(
        SweepSpec(base=BASE | {"revs": 3.0}, grid={"speed": [100.0, 200.0]}),
        tmp_path / "s",
        workers=1,
        case_timeout=1e-9,
    )
    assert all("case_timeout" in str(e) for e in ds["error"].values), ds["error"].values
    ds = run_sweep(
        SweepSpec(base=BASE, grid={"speed": [100.0, 200.0]}), tmp_path / "t", workers=1, case_timeout=600.0
    )
    assert (ds["error"] == "").all()
    with pytest.raises(ValueError, match="--case-timeout"):
        run_sweep(SweepSpec(base=BASE, grid={"speed": [100.0]}), tmp_path / "u", case_timeout=-1.0)
