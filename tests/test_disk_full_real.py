"""A real full disk (issue 28, campaign family "long runs, resources"): runs into a 2 MiB tmpfs.
Mounting needs root (and a kernel that allows it); elsewhere these tests are skipped with the
reason, never failed. The faked versions are in tests/test_disk_guards.py."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
from collections import namedtuple

import pytest
from typer.testing import CliRunner

from jointdyn.cli import app
from jointdyn.studies import memory

runner = CliRunner()
#: 3001 samples: results.nc (≈ 1.7 MB) fits in 2 MiB, timeseries.csv (≈ 2.2 MB) then does not
RUN = ["run", "slider-crank", "--joint", "dry", "--revs", "0.05", "--samples-per-rev", "60000"]
Usage = namedtuple("Usage", "total used free")


@pytest.fixture
def small_fs(tmp_path):
    """A 2 MiB tmpfs mounted on ``tmp_path/fs``; skipped where mounting is not allowed."""
    mnt = tmp_path / "fs"
    mnt.mkdir()
    if os.geteuid() != 0 or shutil.which("mount") is None:
        pytest.skip("mounting a 2 MiB tmpfs needs root and mount(8); the faked test covers the logic")
    p = subprocess.run(
        ["mount", "-t", "tmpfs", "-o", "size=2m", "tmpfs", str(mnt)], capture_output=True, text=True
    )
    if p.returncode != 0:
        pytest.skip(f"this machine does not allow mounting a tmpfs: {p.stderr.strip()}")
    try:
        yield mnt
    finally:
        subprocess.run(["umount", str(mnt)], check=False)


def _lines(r) -> list[str]:
    err = r.stderr if hasattr(r, "stderr") else r.output
    assert "Traceback" not in err, err
    return [ln for ln in err.splitlines() if ln.strip()]


def test_a_run_too_big_for_a_real_small_file_system_is_refused_before_work(small_fs):
    r = runner.invoke(app, [*RUN, "--out", str(small_fs / "r")])
    (line,) = _lines(r)
    assert r.exit_code == 2 and "GiB are free on" in line, line
    assert not (small_fs / "r").exists()


def test_a_real_full_disk_while_writing_is_one_line_and_keeps_what_was_written(small_fs, monkeypatch):
    """The estimate is bypassed (it would refuse first, above); the file system fills for real."""
    real = shutil.disk_usage
    monkeypatch.setattr(memory.shutil, "disk_usage", lambda p: Usage(*real(p)[:2], 10**12))
    out = small_fs / "r"
    r = runner.invoke(app, [*RUN, "--out", str(out)])
    (line,) = _lines(r)
    assert r.exit_code == 2 and "No space left on device" in line, line
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["status"] == "failed" and "No space left on device" in manifest["reason"]
    assert list(manifest["files"]) == ["results.nc"] and (out / "results.nc").is_file()
    assert not (out / "timeseries.csv").exists()
    assert sorted(p.name for p in out.iterdir()) == ["manifest.json", "results.nc"]  # no temporary, no lock
    # the kept file is whole: it loads and has every sample
    from jointdyn import load

    assert len(load(out / "results.nc").t) == 3001
    # and --overwrite on the same full disk removes exactly jointdyn's files, then fails again in one line
    r = runner.invoke(app, [*RUN, "--out", str(out), "--overwrite"])
    (line,) = _lines(r)
    assert r.exit_code == 2 and "No space left on device" in line
