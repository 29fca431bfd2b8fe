"""Studies on any model file: a four-bar (lubricated crank pin, torsion spring on the rocker)
written here, not shipped; metrics, sweeps and the per-revolution commands take it like the
slider-crank. The crank pin is a finite bearing with Reynolds' film end (a law given as a table
with parameters, which results files now store and load back)."""

import csv
import json
import math

import numpy as np
import pytest
from four_bar import FOUR_BAR, OMEGA
from typer.testing import CliRunner

from jointdyn.cli import app

runner = CliRunner()


@pytest.fixture
def four_bar(tmp_path):
    f = tmp_path / "four_bar.toml"
    f.write_text(FOUR_BAR)
    return f


def _run(model, out, *args):
    r = runner.invoke(app, ["run", str(model), "--out", str(out), *args])
    assert r.exit_code == 0, r.output
    return json.loads((out / "summary.json").read_text())


def test_run_summary_has_the_generic_metrics_of_a_model_file(four_bar, tmp_path):
    s = _run(four_bar, tmp_path / "run")
    m = s["metrics"]
    assert all(math.isfinite(v) for v in m.values())  # nothing stored as NaN
    assert set(m) == set(s["metric_units"]) and s["metric_units"]["motor.moment_peak"] == "N·m"
    # the motor's moment over its last revolution (2π/ω), read back from the CSV independently
    with open(tmp_path / "run" / "timeseries.csv") as fh:
        rows = list(csv.DictReader(fh))
    t = np.array([float(r["time [s]"]) for r in rows])
    lam = np.array([float(r["lambda.motor[0] [N·m]"]) for r in rows])
    last = t >= t[-1] - 2 * math.pi / OMEGA - 1e-12
    assert last.sum() == 361  # one revolution = the whole run here: every sample
    assert m["motor.moment_peak"] == lam[last].max() and m["motor.moment_min"] == lam[last].min()
    assert m["motor.moment_rms"] == pytest.approx(np.sqrt(np.mean(lam[last] ** 2)), rel=1e-12)
    # per element: declared outputs max/min/RMS, events; the spring has no contact memory
    xi = np.array([float(r["pin.xi [-]"]) for r in rows])
    assert m["pin.xi_max"] == xi.max() and 0 < m["pin.xi_max"] < 1
    assert m["pin.impacts"] == 0 and "spring.impacts" not in m
    assert m["spring.moment_rms"] > 0 and m["spring.energy_max"] >= m["spring.energy_min"] >= 0
    # the slider-crank's short names are its own aliases, not metrics of other models
    assert "peak_moment" not in m and "max_xi" not in s


def test_sweep_over_a_model_file_key_equals_the_single_runs(four_bar, tmp_path):
    from jointdyn.studies.sweep import load_sweep, run_sweep

    spec = tmp_path / "sweep.toml"
    spec.write_text(f'[base]\nfile = "{four_bar}"\n[grid]\n"elements.pin.viscosity" = [0.05, 0.1]\n')
    ds = run_sweep(load_sweep(spec), tmp_path / "sweep", workers=1)
    assert (ds["error"] == "").all()
    for mu in (0.05, 0.1):
        s = _run(four_bar, tmp_path / f"run_{mu}", "--set", f"elements.pin.viscosity={mu}")
        case = ds.sel({"elements.pin.viscosity": mu})
        names = [v for v in ds.data_vars if v not in ("error", "wall_time_s", "rhs_evaluations")]
        assert set(names) == set(s["metrics"])
        for k in names:  # same model, same parameters, same code: identical numbers
            assert float(case[k]) == s["metrics"][k], k
        assert ds["motor.moment_peak"].attrs["units"] == "N·m"
    # more viscous film: the journal runs closer to the centre
    assert float(ds["pin.xi_max"].sel({"elements.pin.viscosity": 0.1})) < float(
        ds["pin.xi_max"].sel({"elements.pin.viscosity": 0.05})
    )


def test_asking_for_a_metric_the_model_lacks_is_one_line():
    from jointdyn.studies.metrics import pick

    with pytest.raises(ValueError, match="'peak_moment': does not exist for four-bar; its metrics: a.b"):
        pick({"a.b": 1.0}, "peak_moment", "four-bar")


def _longer(four_bar, revs: int, spr: int = 72) -> list[str]:
    """--set overrides that run FOUR_BAR for ``revs`` motor revolutions at ``spr`` samples each."""
    return [
        "--set",
        f"simulation.t_end={revs * 2 * math.pi / OMEGA!r}",
        "--set",
        f"simulation.n_out={revs * spr + 1}",
    ]


def test_poincare_and_spectrum_of_a_model_file_run(four_bar, tmp_path):
    out = tmp_path / "run"
    _run(four_bar, out, *_longer(four_bar, 3))
    r = runner.invoke(app, ["poincare", str(out), "--transient-revs", "1"])
    assert r.exit_code == 0, r.output
    rows = (out / "poincare.csv").read_text().splitlines()
    assert rows[0].startswith("t,ex_bushing_over_c") and len(rows) == 1 + 3  # the motor at 2π, 4π, 6π
    t = [float(x.split(",")[0]) for x in rows[1:]]
    assert t == pytest.approx([2 * math.pi / OMEGA * k for k in (1, 2, 3)], rel=1e-12)
    r = runner.invoke(app, ["spectrum", str(out), "--transient-revs", "1", "--body", "rocker"])
    assert r.exit_code == 0, r.output
    head = (out / "spectrum.csv").read_text().splitlines()[0]
    assert head == "harmonic,drive_moment,body_x_acceleration,joint_force"
    r = runner.invoke(app, ["poincare", str(out), "--element", "spring"])
    assert r.exit_code == 2 and "not a journal element" in r.output and "['pin']" in r.output


def test_bifurcation_over_a_model_file_key(four_bar, tmp_path):
    import xarray as xr

    from jointdyn.studies.poincare import section_arrays
    from jointdyn.studies.saved_runs import load_run

    f = tmp_path / "b.toml"
    f.write_text(
        f'[base]\nfile = "{four_bar.name}"\n[bifurcation]\nparameter = "elements.pin.viscosity"\n'
        "values = [0.05, 0.1]\ntransient_revs = 1\nrecord_revs = 2\nsamples_per_rev = 72\n"
    )
    out = tmp_path / "bif"
    r = runner.invoke(app, ["bifurcation", str(f), "--out", str(out), "--workers", "1"])
    assert r.exit_code == 0, r.output
    ds = xr.load_dataset(out / "bifurcation.nc", engine="h5netcdf")
    assert (ds["error"] == "").all() and ds["ex_bushing_over_c"].shape == (2, 2)
    # each value's section is the one of a direct run of 3 revolutions at that viscosity
    run = tmp_path / "direct"
    _run(four_bar, run, "--set", "elements.pin.viscosity=0.1", *_longer(four_bar, 3))
    direct = section_arrays(load_run(run), 1, 2, 0.0)
    np.testing.assert_allclose(
        ds["ex_bushing_over_c"].values[1], direct["ex_bushing_over_c"], rtol=0, atol=1e-12
    )


def test_lyapunov_and_ensemble_count_the_model_files_revolutions(four_bar, tmp_path):
    out = tmp_path / "lyap"
    args = ["lyapunov", str(four_bar), "--revs", "1", "--per-rev", "8", "--transient-revs", "0"]
    r = runner.invoke(app, [*args, "--discard", "0", "--rtol", "1e-6", "--atol", "1e-9", "--out", str(out)])
    assert r.exit_code == 0, r.output
    s = json.loads((out / "summary.json").read_text())
    assert s["tau"] == 2 * math.pi / OMEGA / 8 and s["segments"] == 8  # the motor's period / per-rev
    assert s["time_scale_s"] == 1 / OMEGA
    r = runner.invoke(
        app,
        # 5e-8: at 1e-6 the force-resolution guard refuses the finite film's force as noise [T111]
        ["ensemble", str(four_bar), "--rtols", "5e-8", "--revs", "3", "--transient-revs", "1"]
        + ["--samples-per-rev", "72", "--workers", "1", "--out", str(tmp_path / "ens")],
    )
    assert r.exit_code == 0, r.output
    e = json.loads((tmp_path / "ens" / "ensemble.json").read_text())
    assert e["bands"]["peak_moment"]["n"] == 2 and e["bands"]["impacts"]["n"] == 2
    assert e["settings"]["model"] == str(four_bar)


def test_a_model_without_an_angle_driver_says_so_in_one_line(tmp_path):
    motor = FOUR_BAR[FOUR_BAR.index("[joints.motor]") : FOUR_BAR.index("[joints.rocker_pin]")]
    f = tmp_path / "free.toml"
    f.write_text(FOUR_BAR.replace(motor, ""))  # the crank swings freely under gravity
    r = runner.invoke(app, ["ensemble", str(f), "--out", str(tmp_path / "e")])
    assert r.exit_code == 2 and "no angle driver" in r.output
    r = runner.invoke(app, ["lyapunov", str(f), "--out", str(tmp_path / "l")])
    assert r.exit_code == 2 and "no angle driver" in r.output and "--tau" in r.output


def test_run_slider_crank_speed_in_rpm(tmp_path):
    from jointdyn.studies.runs import run_shipped
    from jointdyn.units import rpm

    out = tmp_path / "sc"
    r = runner.invoke(app, ["run", "slider-crank", "--speed", "3000", "--revs", "1", "--out", str(out)])
    assert r.exit_code == 0, r.output
    s = json.loads((out / "summary.json").read_text())
    assert s["t_end"] == pytest.approx(60 / 3000, rel=1e-14)  # one crank revolution at 3000 rpm
    _, _, lib = run_shipped("slider-crank", "perfect", 1.0, model_kw={"speed": rpm(3000)})
    assert s["peak_moment"] == lib["peak_moment"] == lib["metrics"]["drive.moment_peak"]
    r = runner.invoke(app, ["run", "slider-crank", "--speed", "0", "--out", str(tmp_path / "z")])
    assert r.exit_code == 2 and "--speed" in r.output and "rpm" in r.output
