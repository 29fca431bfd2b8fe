"""Command line: run, film-force, list, and clear errors for bad input."""

import csv
import json

import numpy as np
import pytest
import xarray as xr
from typer.testing import CliRunner

from jointdyn.cli import app
from jointdyn.film.models import film_forces

runner = CliRunner()


def name(header: str) -> str:
    """A CSV column's name without its unit: ``crank_moment [N·m]`` -> ``crank_moment``."""
    return header.split(" [", 1)[0]


def test_run_perfect_writes_files(tmp_path):
    out = tmp_path / "run"
    r = runner.invoke(app, ["run", "slider-crank", "--joint", "perfect", "--revs", "1", "--out", str(out)])
    assert r.exit_code == 0, r.output
    for f in ("results.nc", "timeseries.csv", "summary.json", "moment.png"):
        assert (out / f).exists()
    with open(out / "timeseries.csv") as f:
        rows = [{name(k): v for k, v in r.items()} for r in csv.DictReader(f)]
    # one output contract: time first (the slider-crank's former "t"), units in the headers
    assert list(rows[0])[:3] == ["time", "crank_angle", "crank_moment"]
    M = np.array([float(r["crank_moment"]) for r in rows])
    assert abs(M.max() - 138.62) < 0.01  # benchmark peak [T160]
    summary = json.loads((out / "summary.json").read_text())
    assert summary["peak_moment"] == pytest.approx(M.max(), rel=1e-9)  # CSV keeps 10 digits
    ds = xr.load_dataset(out / "results.nc", engine="h5netcdf")
    assert json.loads(ds.attrs["model"])["model"]["name"] == "slider-crank (perfect)"  # model-file layout
    assert ds["lam"].sizes["row"] == 9


def test_run_lubricated_has_eccentricity_columns(tmp_path):
    out = tmp_path / "lub"
    r = runner.invoke(
        app,
        [
            "run",
            "slider-crank",
            "--joint",
            "alshaer2005",
            "--revs",
            "0.25",
            "--out",
            str(out),
            "--rtol",
            "1e-7",
            "--atol",
            "1e-11",
        ],
    )
    assert r.exit_code == 0, r.output
    header = [name(h) for h in (out / "timeseries.csv").read_text().splitlines()[0].split(",")]
    assert {"ex_bushing_over_c", "ey_bushing_over_c", "h_min"} <= set(header)


def test_film_force_csv_matches_python(tmp_path):
    states = tmp_path / "s.csv"
    states.write_text(
        "xi,xi_dot,gamma,gamma_dot,omega_journal,omega_bearing,viscosity,length,radius,clearance\n"
        "0.5,20,0.3,100,523.6,0,0.4,0.04,0.01,0.0005\n0.9,-5,0.3,50,523.6,0,0.4,0.04,0.01,5e-5\n"
    )
    r = runner.invoke(app, ["film-force", str(states), "--model", "alshaer2005"])
    assert r.exit_code == 0, r.output
    rows = list(csv.DictReader(r.output.splitlines()))
    ref = film_forces(
        "alshaer2005", [0.5, 0.9], [20, -5], 0.3, [100, 50], 523.6, 0, 0.4, 0.04, 0.01, [5e-4, 5e-5]
    )
    # reference table [T164] (docs/theory.md), case 7: F_r = −78.9922102, F_t = 109.959985 N
    assert float(rows[0]["Fr"]) == -78.9922102 or abs(float(rows[0]["Fr"]) + 78.9922102) < 1e-6
    for i in range(2):
        for k in ("Fr", "Ft", "Fx", "Fy"):
            assert float(rows[i][k]) == float(f"{ref[k][i]:.10g}")


def test_film_force_bad_rows_name_row_and_column(tmp_path):
    states = tmp_path / "s.csv"
    states.write_text(
        "xi,xi_dot,gamma,gamma_dot,omega_journal,omega_bearing,viscosity,length,radius,clearance\n"
        "0.5,20,0.3,100,523.6,0,0.4,0.04,0.01,0.0005\n0.5,nan,0.3,100,523.6,0,0.4,0.04,0.01,0.0005\n"
    )
    r = runner.invoke(app, ["film-force", str(states)])
    assert r.exit_code == 2 and "row 2" in r.output and "xi_dot" in r.output
    r = runner.invoke(app, ["film-force", str(states), "--model", "sommerfeld"])
    assert r.exit_code == 2 and "valid" in r.output


def test_bad_cli_input(tmp_path):
    r = runner.invoke(app, ["run", "slider-crank", "--joint", "magic", "--out", str(tmp_path / "x")])
    assert r.exit_code == 2 and "joint" in r.output and "valid" in r.output
    r = runner.invoke(
        app, ["run", "slider-crank", "--joint", "dry", "--clearance", "-1e-4", "--out", str(tmp_path / "x")]
    )
    assert r.exit_code == 2 and "clearance" in r.output and "[m]" in r.output
    r = runner.invoke(app, ["list"])
    assert r.exit_code == 0 and "journal_bearing" in r.output and "rodas4" in r.output


def test_plot_and_animate_a_saved_run(tmp_path):
    out = tmp_path / "lub"
    r = runner.invoke(app, ["run", "slider-crank", "--joint", "dry", "--revs", "0.25", "--out", str(out)])
    assert r.exit_code == 0, r.output
    own = (out / "moment.png").read_bytes()
    for what in ("moment", "orbit", "film", "contact", "energy"):
        r = runner.invoke(app, ["plot", str(out), "--what", what])
        assert r.exit_code == 0, r.output
        assert (out / f"plot_{what}.png").stat().st_size > 5000
    assert (out / "moment.png").read_bytes() == own  # the run's own figure is never overwritten
    r = runner.invoke(app, ["plot", str(out), "--what", "stress"])
    assert r.exit_code == 2 and "valid" in r.output
    gif = tmp_path / "a.gif"
    r = runner.invoke(app, ["animate", str(out), "--out", str(gif), "--frames", "8"])
    assert r.exit_code == 0, r.output
    from PIL import Image

    assert Image.open(gif).n_frames == 8
    r = runner.invoke(app, ["animate", str(out), "--out", str(gif), "--frames", "100000000"])
    assert r.exit_code == 2 and "--frames" in r.output and "5000" in r.output  # refused before work


def test_saved_file_reads_back_as_the_in_memory_dataset(tmp_path):
    from jointdyn.simulation.results import load
    from jointdyn.studies.runs import run_shipped

    res, _, _ = run_shipped("slider-crank", "dry", 0.1)
    res.save(tmp_path / "r.nc")
    a, b = load(tmp_path / "r.nc"), res.to_dataset()
    for v in b.data_vars:
        np.testing.assert_array_equal(a[v].values, b[v].values)
    for c in b.coords:
        assert list(a[c].values) == list(b[c].values)
    assert a.attrs["model"] == b.attrs["model"] and a.attrs["config"] == b.attrs["config"]


def test_run_model_file_with_overrides(tmp_path):
    from pathlib import Path

    ex = Path(__file__).resolve().parents[1] / "examples" / "slider_crank_perfect.toml"
    out = tmp_path / "mf"
    r = runner.invoke(
        app,
        [
            "run",
            str(ex),
            "--out",
            str(out),
            "--set",
            "simulation.t_end=0.003",
            "--set",
            "simulation.n_out=31",
        ],
    )
    assert r.exit_code == 0, r.output
    assert (out / "results.nc").exists() and xr.load_dataset(out / "results.nc").sizes["time"] == 31
    r = runner.invoke(app, ["run", str(ex), "--out", str(out), "--set", "bodies.crank.mass=-1"])
    assert r.exit_code == 2 and "bodies.crank.mass" in r.output and "kg" in r.output


def test_animate_mp4(tmp_path):
    """MP4 through the ffmpeg binary of the [video] extra (installed with [dev])."""
    out = tmp_path / "run"
    assert runner.invoke(app, ["run", "slider-crank", "--revs", "0.1", "--out", str(out)]).exit_code == 0
    mp4 = tmp_path / "a.mp4"
    r = runner.invoke(app, ["animate", str(out), "--out", str(mp4), "--frames", "6"])
    assert r.exit_code == 0, r.output
    assert mp4.read_bytes()[4:8] == b"ftyp"  # an MP4 container


def test_plot_pressure_at_a_crank_angle(tmp_path):
    out = tmp_path / "lub"
    r = runner.invoke(
        app, ["run", "slider-crank", "--joint", "alshaer2005", "--revs", "0.25", "--out", str(out)]
    )
    assert r.exit_code == 0, r.output
    r = runner.invoke(app, ["plot", str(out), "--what", "pressure", "--at", "45"])
    assert r.exit_code == 0, r.output
    assert (out / "plot_pressure_45deg.png").stat().st_size > 5000
    r = runner.invoke(app, ["plot", str(out), "--what", "pressure", "--at", "500"])
    assert r.exit_code == 2 and "covers" in r.output
    r = runner.invoke(app, ["plot", str(out), "--what", "pressure"])
    assert r.exit_code == 2 and "--at" in r.output


def test_a_compiling_run_says_so_and_how_long(capsys):
    """While numba compiles (a first run) the progress display shows a "compiling" line instead
    of a silent wait, and afterwards how much of the run it was; a function loaded from numba's
    cache sends no compile event, so a warm run says nothing (numba's event API)."""
    import time

    from numba import njit

    from jointdyn import cli

    @njit  # a new function: compiled here, never cached
    def slow_to_compile(x):
        return x + 1.0

    with cli._progress("run") as prog:
        task = prog.add_task("case", 1.0)
        shown = []
        prog.compiling = lambda s, real=prog.compiling: (shown.append(s), real(s))[1]
        t0 = time.perf_counter()
        slow_to_compile(1.0)
        elapsed = time.perf_counter() - t0
        prog.update(task, 1.0)
        prog.compile_s = max(prog.compile_s, 1.0)  # the closing line is printed from 1 s on
    assert shown[0] is None and len(shown) == 2 and 0 < shown[1] <= elapsed  # start, then its duration
    # the first compilation of a fresh process includes numba's own set-up (> 1.5 s under load)
    assert f"first run: {prog.compile_s:.0f} s of it compiling" in capsys.readouterr().out

    with cli._progress("run") as prog:  # nothing compiles: no line, no note
        prog.add_task("case", 1.0)
        slow_to_compile(2.0)
    assert prog.compile_s == 0.0 and prog._prog is None


def test_progress_clocks_are_per_task():
    """Each case's bar shows its own elapsed time: a task's clock starts at its first update and
    stops when it completes (issue 29: every case showed the display's total)."""
    import time

    from jointdyn import cli

    with cli._progress("reproduce") as prog:
        a, b = prog.add_task("first", 1.0), prog.add_task("second", 1.0)
        prog.update(a, 0.0)
        time.sleep(0.3)
        prog.update(a, 1.0)  # done after ≈ 0.3 s
        prog.update(b, 0.0)
        time.sleep(0.05)
        prog.update(b, 1.0)
        tasks = {t.description: t for t in prog._prog.tasks}
    # the second case's clock never ran during the first one (sleep granularity ≪ 0.25 s)
    assert tasks["first"].elapsed >= 0.3 and tasks["second"].elapsed < 0.25


def test_film_force_to_stdout_writes_nothing_before_a_bad_first_block(tmp_path):
    """issue 29: the CSV header went to stdout before row 2's error; now the first block is
    computed before anything is written, so a failing table leaves stdout empty."""
    states = tmp_path / "s.csv"
    states.write_text(
        "xi,xi_dot,gamma,gamma_dot,omega_journal,omega_bearing,viscosity,length,radius,clearance\n"
        "0.5,20,0.3,100,523.6,0,0.4,0.04,0.01,0.0005\n0.5,nan,0.3,100,523.6,0,0.4,0.04,0.01,0.0005\n"
    )
    r = runner.invoke(app, ["film-force", str(states)])
    assert r.exit_code == 2 and "row 2" in r.stderr and "xi_dot" in r.stderr
    assert r.stdout == ""


def test_film_force_to_stdout_marks_a_table_cut_by_a_later_block(tmp_path, monkeypatch):
    """Streaming blocks of BLOCK rows: an error in a later block cannot unwrite the rows already
    printed, so the output ends with a '#' line saying the table is incomplete."""
    from jointdyn.film import table

    monkeypatch.setattr(table, "BLOCK", 1)
    states = tmp_path / "s.csv"
    states.write_text(
        "xi,xi_dot,gamma,gamma_dot,omega_journal,omega_bearing,viscosity,length,radius,clearance\n"
        "0.5,20,0.3,100,523.6,0,0.4,0.04,0.01,0.0005\n0.5,nan,0.3,100,523.6,0,0.4,0.04,0.01,0.0005\n"
    )
    r = runner.invoke(app, ["film-force", str(states)])
    assert r.exit_code == 2 and "row 2" in r.stderr
    lines = r.stdout.splitlines()
    assert lines[0].startswith("xi,") and lines[1].startswith("0.5,20,") and len(lines) == 3
    assert lines[2] == "# INCOMPLETE: film-force stopped after 1 rows (the error is on stderr)"


def test_bearing_table_says_the_gumbel_film_end_is_by_construction():
    """issue 29: `--model alshaer2005` printed theta_end_deg = 0 as if computed; a Gümbel film is
    cut at the minimum film (θ = π), so the 0 is stated as such; Reynolds' rupture of the long
    bearing is computed (θ_e − π > 0, [T78])."""
    op = ["--ld", "1", "--eps", "0.5", "--load", "4000", "--speed", "25", "--radius", "0.025"]
    op += ["--clearance", "30e-6", "--viscosity", "0.02"]
    r = runner.invoke(app, ["bearing-table", "--model", "alshaer2005", *op])
    assert r.exit_code == 0, r.output
    line = next(ln for ln in r.stderr.splitlines() if "theta_end_deg" in ln)
    assert "= 0 [deg] (by construction" in line
    r = runner.invoke(app, ["bearing-table", "--model", "long", *op])
    line = next(ln for ln in r.stderr.splitlines() if "theta_end_deg" in ln)
    assert "construction" not in line and float(line.split("=")[1].split("[")[0]) > 10.0
