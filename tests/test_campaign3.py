"""The third hostile campaign (issue 28, ``python -m benchmarks.hostile_campaign``): each test
replays one case it found — a traceback, a misleading refusal or a silent wrong exit — and checks
the one-line refusal before work naming the parameter, its unit and range [T334–T336]."""

from __future__ import annotations

import json
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from jointdyn.cli import app
from jointdyn.io import cluster
from jointdyn.models.slider_crank import slider_crank
from jointdyn.simulation.simulate import SimConfig, simulate
from jointdyn.studies.sweep_spec import SweepSpec, validate

runner = CliRunner()
DRY = str(Path(__file__).resolve().parents[1] / "examples" / "slider_crank_dry.toml")


def one_line(r) -> str:
    err = r.stderr if hasattr(r, "stderr") else r.output
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert "Traceback" not in err and "internal error" not in err and len(lines) == 1, err
    return lines[0]


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    """A complete 2-revolution dry run."""
    d = tmp_path_factory.mktemp("run") / "r"
    r = runner.invoke(app, ["run", "slider-crank", "--joint", "dry", "--revs", "2", "--out", str(d)])
    assert r.exit_code == 0, r.output
    return d


def test_poincare_transient_beyond_the_run_is_one_line(run_dir, tmp_path):
    """Was 'internal error IndexError: index 0 is out of bounds' (nothing left to section)."""
    r = runner.invoke(
        app, ["poincare", str(run_dir), "--transient-revs", "1000", "--out", str(tmp_path / "p")]
    )
    line = one_line(r)
    assert r.exit_code == 2 and "transient = " in line and "[s]" in line and "the run ends at t = " in line
    r = runner.invoke(app, ["poincare", str(run_dir), "--transient-revs", "-1", "--out", str(tmp_path / "q")])
    assert r.exit_code == 2 and "must be finite and >= 0" in one_line(r)
    assert not (tmp_path / "p").exists() and not (tmp_path / "q").exists()


def test_spectrum_checks_its_options_before_loading(run_dir, tmp_path):
    """--max-harmonic -1 was reported as a transient_revs problem (after loading the run);
    --transient-revs -1 silently took the last revolution as the start (b[-1])."""
    r = runner.invoke(app, ["spectrum", str(tmp_path / "none"), "--max-harmonic", "-1"])
    assert r.exit_code == 2 and "--max-harmonic = -1.0 [-]: must be finite and > 0" in one_line(r)
    r = runner.invoke(app, ["spectrum", str(run_dir), "--transient-revs", "-1", "--out", str(tmp_path / "s")])
    assert r.exit_code == 2 and "transient_revs = -1 [rev]: must be >= 0" in one_line(r)
    assert not (tmp_path / "s").exists()


def test_simulating_an_uncompiled_model_names_compile():
    """Was AttributeError: 'Model' object has no attribute 'y0'."""
    with pytest.raises(
        TypeError, match=r"expected a compiled System, got a Model; call its \.compile\(\) first"
    ):
        simulate(slider_crank("dry"), SimConfig(t_end=1e-3))


@pytest.mark.parametrize("address", ["banana", "tcp://host", "tcp://127.0.0.1:0", "banana:http"])
def test_a_scheduler_that_is_not_an_address_is_refused_at_once(address, tmp_path):
    """'banana' waited the 10 s connect timeout, then Dask's half-made client printed an
    'Exception ignored … TimeoutError' traceback 20 s later."""
    with pytest.raises(ValueError, match=r"expected tcp://HOST:PORT \(PORT 1…65535\)"):
        cluster.check_address(address)
    spec = tmp_path / "s.toml"
    spec.write_text(f'[base]\nfile = "{DRY}"\nrevs = 0.05\n[grid]\n"simulation.rtol" = [1e-7, 1e-8]\n')
    t0 = time.monotonic()
    r = runner.invoke(app, ["sweep", str(spec), "--scheduler", address, "--out", str(tmp_path / "o")])
    assert r.exit_code == 2 and f"--scheduler {address!r}" in one_line(r)
    assert time.monotonic() - t0 < 5.0 and not (tmp_path / "o").exists()


def test_a_sweep_whose_cases_are_all_invalid_is_refused_before_work(tmp_path):
    """An unknown key in the grid: exit 0 with 'wrote sweep.nc (2 cases, 2 failed)'."""
    spec = tmp_path / "s.toml"
    spec.write_text(f'[base]\nfile = "{DRY}"\nrevs = 0.05\n[grid]\n"bodies.crank.colour" = [1.0, 2.0]\n')
    r = runner.invoke(app, ["sweep", str(spec), "--out", str(tmp_path / "o")])
    line = one_line(r)
    assert (
        r.exit_code == 2 and "every one of the 2 cases is invalid" in line and "unknown key 'colour'" in line
    )
    assert not (tmp_path / "o").exists()


def test_a_grid_value_invalid_in_every_case_is_refused_but_a_bad_combination_is_recorded():
    """mass = -1 in a grid ran the other value and recorded the case as failed, exit 0 [T334];
    a combination invalid only together (a zipped rtol = 5, tests/test_sweep.py) still runs."""
    base = {"file": DRY, "revs": 0.05}
    spec = SweepSpec(base=base, grid={"bodies.crank.mass": [0.3, -1.0], "simulation.rtol": [1e-7, 1e-8]})
    with pytest.raises(ValueError) as e:
        validate(spec)
    msg = str(e.value)
    assert msg.startswith("[grid].bodies.crank.mass = -1.0: every case with it is invalid;")
    assert "mass = -1.0 [kg]" in msg
    cases, invalid = validate(SweepSpec(base=base, zipped={"simulation.rtol": [1e-8, 5.0]}))
    assert len(cases) == 2 and list(invalid) == [1]


def test_ld_refusal_names_the_option():
    r = runner.invoke(app, ["bearing-table", "--ld", "0", "--eps", "0.5"])
    assert r.exit_code == 2 and "ld = L/D = 0.0 [-]: must be finite and > 0" in one_line(r)


def test_a_listed_file_replaced_by_a_link_is_named_as_a_link(run_dir, tmp_path):
    """--overwrite where a file the manifest lists is now a link outside: refused (never removed
    or written through), and the message says it is a link, not 'not in its manifest'."""
    import shutil

    d = tmp_path / "r"
    shutil.copytree(run_dir, d)
    outside = tmp_path / "keep.txt"
    outside.write_text("not jointdyn's\n")
    (d / "timeseries.csv").unlink()
    (d / "timeseries.csv").symlink_to(outside)
    before = (d / "manifest.json").read_text()
    r = runner.invoke(
        app, ["run", "slider-crank", "--joint", "dry", "--revs", "0.05", "--out", str(d), "--overwrite"]
    )
    line = one_line(r)
    assert r.exit_code == 2 and "timeseries.csv, which is listed in its manifest but is now a link" in line
    assert outside.read_text() == "not jointdyn's\n" and (d / "timeseries.csv").is_symlink()
    assert (d / "manifest.json").read_text() == before
    assert json.loads(before)["status"] == "complete"


def _states(tmp_path: Path) -> Path:
    """A one-row film-force input file."""
    states = tmp_path / "states.csv"
    states.write_text(
        "xi,xi_dot,gamma,gamma_dot,omega_journal,omega_bearing,viscosity,length,radius,clearance\n"
        "0.5,0,0,0,500,0,0.01,0.04,0.01,5e-5\n"
    )
    return states


def test_single_file_writers_join_a_run_directory_manifest(run_dir, tmp_path):
    """bearing-table, stribeck and film-force --out into a run directory wrote there without its
    lock and outside its manifest (a later --overwrite kept them as foreign files) [T338]."""
    import hashlib
    import shutil

    d = tmp_path / "r"
    shutil.copytree(run_dir, d)
    states = _states(tmp_path)
    strib = ["stribeck", "--radius", "0.02", "--length", "0.02", "--clearance", "2e-5", "--viscosity", "0.05"]
    for argv in (
        ["bearing-table", "--ld", "1", "--eps", "0.5", "--out", str(d / "bt.csv")],
        [*strib, "--load", "100", "--speeds", "10,100", "--out", str(d / "st.csv")],
        ["film-force", str(states), "--out", str(d / "ff.csv")],
    ):
        r = runner.invoke(app, argv)
        assert r.exit_code == 0, r.output
    m = json.loads((d / "manifest.json").read_text())
    for name in ("bt.csv", "st.csv", "st.png", "ff.csv"):
        assert m["files"][name]["sha256"] == hashlib.sha256((d / name).read_bytes()).hexdigest()
    assert "results.nc" in m["files"] and not list(d.glob(".*"))  # the run's own files kept; no lock
    r = runner.invoke(
        app, ["run", "slider-crank", "--joint", "dry", "--revs", "0.05", "--out", str(d), "--overwrite"]
    )
    assert r.exit_code == 0, r.output
    assert not any((d / n).exists() for n in ("bt.csv", "st.csv", "st.png", "ff.csv"))  # jointdyn's: removed


def test_a_derived_output_never_replaces_the_directory_own_files(run_dir, tmp_path):
    """[T356] ``film-force --out RUN/results.nc`` replaced the run's results with a CSV and exited
    0 (the derived writer could replace any file its manifest listed). A derived file may replace
    a derived file (re-plotting), never the directory's own outputs."""
    import hashlib
    import shutil

    d = tmp_path / "r"
    shutil.copytree(run_dir, d)
    states = _states(tmp_path)
    before = {p.name: hashlib.sha256(p.read_bytes()).hexdigest() for p in d.iterdir()}
    manifest = json.loads((d / "manifest.json").read_text())
    for name in manifest["files"]:
        r = runner.invoke(app, ["film-force", str(states), "--out", str(d / name)])
        assert r.exit_code == 2, r.output
        assert f"{name} is an output of this run" in r.output and "choose another name" in r.output
    assert {p.name: hashlib.sha256(p.read_bytes()).hexdigest() for p in d.iterdir()} == before
    for _ in range(2):  # a derived file is replaced by the next derived one
        r = runner.invoke(app, ["film-force", str(states), "--out", str(d / "ff.csv")])
        assert r.exit_code == 0, r.output
    m = json.loads((d / "manifest.json").read_text())
    assert m["files"]["ff.csv"]["derived"] == "film-force"
    assert {n: e for n, e in m["files"].items() if n != "ff.csv"} == manifest["files"]
