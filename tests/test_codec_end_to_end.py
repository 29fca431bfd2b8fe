"""End to end with a model file that is not in the repository: a four-bar whose crank pin is a
lubricated finite bearing with the Reynolds cavitation condition (a law given as a table with
parameters) and whose rocker carries a torsion spring. The model is tests/four_bar.py's. ``jointdyn run`` writes the run,
``jointdyn.load``, ``jointdyn plot --what orbit`` and ``jointdyn poincare`` read it back and give
the numbers of the run."""

import csv
import json
import math
from pathlib import Path

import numpy as np
from four_bar import FOUR_BAR, OMEGA
from typer.testing import CliRunner

import jointdyn
from jointdyn.cli import app
from jointdyn.film.models import Finite
from jointdyn.forces.torsion import TorsionSpring

runner = CliRunner()
#: 2 crank revolutions at 2000 rpm, 0.25 ms samples
SETTINGS = [
    "--set",
    "elements.pin.viscosity=0.1",
    "--set",
    "simulation.t_end=0.06",
    "--set",
    "simulation.n_out=241",
]


def _model_file(tmp_path: Path) -> Path:
    f = tmp_path / "four_bar_finite.toml"
    f.write_text(FOUR_BAR, encoding="utf-8")
    return f


def test_finite_reynolds_four_bar_runs_loads_plots_and_maps(tmp_path):
    out = tmp_path / "run"
    r = runner.invoke(app, ["run", str(_model_file(tmp_path)), "--out", str(out), *SETTINGS])
    assert r.exit_code == 0, r.output
    res = jointdyn.load(out / "results.nc")
    el = dict(zip(res.system.element_names, res.system.elements))
    assert el["pin"].film == Finite(cavitation="reynolds")
    assert type(el["spring"]) is TorsionSpring and el["spring"].stiffness == 2.0

    # the loaded orbit is the run's: timeseries.csv carries e [m] with 17 significant digits
    with open(out / "timeseries.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    for axis, col in (("ex", 0), ("ey", 1)):
        written = np.array([float(row[f"pin.{axis} [m]"]) for row in rows])
        np.testing.assert_array_equal(res.element("pin", axis), written)
        np.testing.assert_array_equal(res.orbit("pin", frame="world")[col], written / res.clearance("pin"))
    summary = json.loads((out / "summary.json").read_text())
    max_xi = summary["metrics"]["pin.xi_max"]
    assert max_xi == float(res.element("pin", "xi").max())
    assert 0.1 < max_xi < 1.0  # the film carries the crank pin's load: a real orbit, no breakdown

    r = runner.invoke(app, ["plot", str(out), "--what", "orbit"])
    assert r.exit_code == 0, r.output
    assert (out / "plot_orbit.png").stat().st_size > 0

    r = runner.invoke(app, ["poincare", str(out), "--element", "pin", "--transient-revs", "0"])
    assert r.exit_code == 0, r.output
    with open(out / "poincare.csv", newline="") as f:
        section = list(csv.DictReader(f))
    # stroboscopic at crank angle 0: t = 0, T, 2T with T = 2π/ω = 0.03 s, each an output sample
    # (dt = 0.25 ms); the csv prints 10 significant digits
    omega = OMEGA
    t = np.array([float(row["t"]) for row in section])
    np.testing.assert_allclose(t, [0.0, 2 * math.pi / omega, 4 * math.pi / omega], rtol=1e-9, atol=1e-12)
    ex, ey = res.orbit("pin", frame="bushing")  # the element's outputs rotated by −φ_i [T290, T350]
    at = [int(np.argmin(np.abs(res.t - tk))) for tk in t]
    got = np.array([[float(row["ex_bushing_over_c"]), float(row["ey_bushing_over_c"])] for row in section])
    np.testing.assert_allclose(got, np.column_stack([ex[at], ey[at]]), rtol=1e-9, atol=1e-9)
