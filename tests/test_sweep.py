"""Sweeps: local executor vs a real Dask LocalCluster; kill -9 and resume; spec parsing."""

import json
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from jointdyn.studies.sweep import SweepSpec, load_sweep, run_sweep

BASE = {"model": "slider-crank", "joint": "perfect", "revs": 0.25, "samples_per_rev": 90}


def test_grid_cases_and_lhs(tmp_path):
    spec = SweepSpec(base=BASE, grid={"speed": [100.0, 200.0], "gravity": [0.0, 9.81, 20.0]})
    cases = spec.cases()
    assert len(cases) == 6 and cases[0] == {"speed": 100.0, "gravity": 0.0}
    spec = SweepSpec(base=BASE, sample={"n": 8, "seed": 3, "ranges": {"speed": [100.0, 500.0]}})
    x = np.sort([c["speed"] for c in spec.cases()])
    # Latin hypercube: exactly one sample per stratum of width 50 rad/s
    assert np.all(np.floor((x - 100.0) / 50.0) == np.arange(8))


def test_local_and_dask_executors_give_identical_results(tmp_path):
    distributed = pytest.importorskip("distributed", reason="the [dist] extra is needed for Dask sweeps")
    spec = SweepSpec(base=BASE, grid={"speed": [200.0, 400.0], "gravity": [0.0, 9.81]})
    local = run_sweep(spec, tmp_path / "local", workers=2)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, host="127.0.0.1", dashboard_address=None, processes=True
    ) as cluster:
        dask = run_sweep(spec, tmp_path / "dask", scheduler=cluster.scheduler_address)
    for m in ("peak_moment", "min_moment", "rms_moment"):
        np.testing.assert_array_equal(local[m].values, dask[m].values)  # same compiled code, same inputs
    assert local["peak_moment"].dims == ("speed", "gravity")
    # higher speed, larger inertial moment (∝ ω²): a physical sanity check of the grid layout
    assert float(local["peak_moment"].sel(speed=400.0, gravity=0.0)) > 3.5 * float(
        local["peak_moment"].sel(speed=200.0, gravity=0.0)
    )
    # units travel with the data: metrics and the builder arguments on the axes
    assert local["peak_moment"].attrs["units"] == "N·m" and local["drive.moment_rms"].attrs["units"] == "N·m"
    assert "min_h_min" not in local  # a perfect joint has no film: the metric is absent, not NaN
    assert local["speed"].attrs["units"] == "rad/s"


def test_failed_case_is_recorded_and_sweep_goes_on(tmp_path):
    spec = SweepSpec(base=BASE, zipped={"rtol": [1e-8, 5.0]})  # rtol = 5 is invalid
    ds = run_sweep(spec, tmp_path / "s", workers=1)
    assert ds["error"].values[0] == "" and "rtol" in ds["error"].values[1]
    assert np.isfinite(ds["peak_moment"].values[0]) and np.isnan(ds["peak_moment"].values[1])


def test_killed_sweep_resumes_without_recomputing(tmp_path):
    sweep_file = tmp_path / "sweep.toml"
    sweep_file.write_text(
        # 40 revolutions: ≈ 60 ms a case, so the 16 cannot all land between two polls (at 2
        # revolutions the faster kernels finished every case before the kill)
        '[base]\nmodel = "slider-crank"\njoint = "perfect"\nrevs = 40.0\nsamples_per_rev = 360\n'
        "[grid]\nspeed = [" + ", ".join(f"{100.0 + 10 * i}" for i in range(16)) + "]\n"
    )
    out = tmp_path / "out"
    code = (
        f"from jointdyn.studies.sweep import load_sweep, run_sweep; "
        f"run_sweep(load_sweep({str(sweep_file)!r}), {str(out)!r}, workers=1)"
    )
    proc = subprocess.Popen([sys.executable, "-c", code], start_new_session=True)
    cdir = out / "cases"
    t0 = time.time()
    while time.time() - t0 < 120 and len(list(cdir.glob("case_*.json"))) < 3:
        time.sleep(0.05)
    os.killpg(proc.pid, signal.SIGKILL)  # the runner and its worker processes
    proc.wait()
    before = {f.name: f.stat().st_mtime_ns for f in cdir.glob("case_*.json")}
    assert 3 <= len(before) < 16
    for f in cdir.glob("case_*.json"):
        json.loads(f.read_text())  # atomic writes: every file present is complete
    ds = run_sweep(load_sweep(sweep_file), out, resume=True, workers=2)
    after = {f.name: f.stat().st_mtime_ns for f in cdir.glob("case_*.json")}
    assert len(after) == 16 and all(after[k] == v for k, v in before.items())  # none recomputed
    assert np.all(np.isfinite(ds["peak_moment"].values))


def test_bad_sweep_files(tmp_path):
    f = tmp_path / "s.toml"
    f.write_text('[base]\nmodel = "slider-crank"\n[grid]\nclearence = [1e-4]\n')
    with pytest.raises(ValueError, match="clearence.*valid"):
        load_sweep(f)
    f.write_text("[base]\n[gird]\nx = [1]\n")
    with pytest.raises(ValueError, match="unknown table.*gird"):
        load_sweep(f)
