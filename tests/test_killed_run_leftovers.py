"""Temporaries of a killed run (issue 28, "security and files"): removed by the next
``--overwrite``, also when the pid in their name is alive again (reused by a process started
after the file was last written) [T333]; a temporary a live process may still write stays."""

from __future__ import annotations

import os
import subprocess
import sys
import time

from typer.testing import CliRunner

from jointdyn.cli import app
from jointdyn.core import atomic

runner = CliRunner()
RUN = ["run", "slider-crank", "--joint", "perfect", "--revs", "0.05", "--samples-per-rev", "100"]


def test_overwrite_removes_a_killed_runs_temporaries_and_nothing_else(tmp_path):
    out = tmp_path / "r"
    assert runner.invoke(app, [*RUN, "--out", str(out)]).exit_code == 0
    other = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])  # a live pid
    try:
        planted = [
            out / f".results.nc.{other.pid}.0123456789abcdef.tmp.nc",  # pid reused by a live process
            out / ".timeseries.csv.4194303.00112233445566ff.tmp.csv",  # a dead pid
        ]
        hour_ago = time.time() - 3600.0  # written before `other` started: not its file
        for p in planted:
            p.write_text("half-written")
            os.utime(p, (hour_ago, hour_ago))
        live = out / f".summary.json.{os.getpid()}.fedcba9876543210.tmp.json"
        live.write_text("being written by this process")
        assert all(atomic.is_temp(p) for p in planted)
        (out / "notes.txt").write_text("mine")
        (out / ".results.nc.tmp").write_text("not a jointdyn temporary name")
        r = runner.invoke(app, [*RUN, "--out", str(out), "--overwrite"])
        assert r.exit_code == 0, r.output
    finally:
        other.kill()
        other.wait()
    assert not any(p.exists() for p in planted)
    assert (out / "notes.txt").read_text() == "mine" and (out / ".results.nc.tmp").exists()
    assert live.exists() and atomic.stale_temps(out) == []
