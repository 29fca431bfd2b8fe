"""Disk space (issue 28, campaign family "long runs, resources"): a run whose files cannot fit is
refused before work, naming the limit; a disk that fills while the results are written gives one
line, a 'failed' manifest and keeps the files already written."""

from __future__ import annotations

import errno
import json
import shutil
from collections import namedtuple

from typer.testing import CliRunner

from jointdyn.cli import app
from jointdyn.studies import memory, outputs

runner = CliRunner()
RUN = ["run", "slider-crank", "--joint", "dry", "--revs", "0.05", "--samples-per-rev", "200"]
Usage = namedtuple("Usage", "total used free")


def _lines(r) -> list[str]:
    err = r.stderr if hasattr(r, "stderr") else r.output
    assert "Traceback" not in err, err
    return [ln for ln in err.splitlines() if ln.strip()]


def test_a_run_that_cannot_fit_on_disk_is_refused_before_work(tmp_path, monkeypatch):
    real = shutil.disk_usage
    monkeypatch.setattr(memory.shutil, "disk_usage", lambda p: Usage(*real(p)[:2], 10_000))
    r = runner.invoke(app, [*RUN, "--out", str(tmp_path / "r")])
    (line,) = _lines(r)
    assert r.exit_code == 2
    assert "--revs × --samples-per-rev: 11 output samples write ≈" in line and "GiB are free on" in line
    assert not (tmp_path / "r").exists()


def test_the_estimate_bounds_the_files_written(tmp_path):
    """The estimate [T331] is an upper bound of what a run writes (results.nc + timeseries.csv)."""
    from jointdyn.io.modelfile import load_system

    r = runner.invoke(app, ["run", "examples/slider_crank_dry.toml", "--out", str(tmp_path / "r")])
    assert r.exit_code == 0, r.output
    _, system, cfg = load_system("examples/slider_crank_dry.toml")
    written = sum((tmp_path / "r" / f).stat().st_size for f in ("results.nc", "timeseries.csv"))
    need = memory.check_disk(system, cfg.n_out, tmp_path)
    assert written < need < 2 * written


def test_a_full_disk_while_writing_is_one_line_and_keeps_what_was_written(tmp_path, monkeypatch):
    def full(path, *a, **k):
        raise OSError(errno.ENOSPC, "No space left on device", str(path))

    monkeypatch.setattr(outputs, "write_csv", full)
    out = tmp_path / "r"
    r = runner.invoke(app, [*RUN, "--out", str(out)])
    (line,) = _lines(r)
    assert r.exit_code == 2 and "No space left on device" in line
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["status"] == "failed" and "No space left on device" in manifest["reason"]
    assert (out / "results.nc").is_file() and not (out / "timeseries.csv").exists()
    assert sorted(p.name for p in out.iterdir() if p.name.startswith(".") and "tmp" in p.name) == []
