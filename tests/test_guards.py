"""Physics guards and validation before work (issue 28's hostile-user campaign): each test replays
one case of the campaign table (docs/validation.md, "Hostile-user campaign") and checks the
refusal names the parameter, its unit and its range — or that the accepted input gives the
same numbers as its plain-float twin."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
import warnings
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from jointdyn.cli import app
from jointdyn.core.checks import FieldError
from jointdyn.errors import ModelError
from jointdyn.film.models import film_forces
from jointdyn.forces.journal import JournalBearing
from jointdyn.models.slider_crank import slider_crank
from jointdyn.models.slider_crank_args import slider_crank_args
from jointdyn.multibody.model import Model
from jointdyn.simulation.simulate import SimConfig

runner = CliRunner()
SRC = Path(__file__).resolve().parents[1] / "src"


def one_line(r) -> str:
    err = r.stderr if hasattr(r, "stderr") else r.output
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert "Traceback" not in err and len(lines) == 1, err
    return lines[0]


def test_asperity_height_must_be_a_roughness_not_the_gap():
    """--asperity-height 0.000499 with c = 0.0005 (1.43 kN on a nearly centred journal) is
    refused with the range [0, c/2]; c/2 itself is accepted."""
    with pytest.raises(
        FieldError, match=r"asperity_height = 0.000499 \[m\]: must be <= clearance/2 = 0.00025"
    ):
        slider_crank_args("alshaer2005", {"contact": True, "asperity_height": 0.000499})
    assert slider_crank_args("alshaer2005", {"contact": True, "asperity_height": 0.00025})
    m = Model("m")
    m.add_body("a", 1.0, 1e-3, points={"A": (0.0, 0.0)})
    m.add_body("b", 1.0, 1e-3, points={"B": (0.0, 0.0)})
    m.add("pin", JournalBearing("a", "A", "b", "B", 0.0105, 0.01, 0.04, 0.4, asperity_height=3e-4))
    with pytest.raises(ModelError, match=r"asperity_height = 0.0003 \[m\]: must be in \[0, clearance/2"):
        m.compile()


def test_film_force_refuses_clearance_above_radius_and_overflow(tmp_path):
    """film-force: c = 0.02 m > R = 0.01 m in a state table is refused naming the clearance
    (film_forces itself also serves dimensionless use, R = c = 1); ξ̇ = ω = 1e300 gave
    -inf,inf,nan,nan with exit 0 — now one line, exit 2, no output file."""
    base = dict(
        xi=0.5,
        xi_dot=0.0,
        gamma=0.0,
        gamma_dot=0.0,
        omega_journal=100.0,
        omega_bearing=0.0,
        viscosity=0.04,
        length=0.02,
        radius=0.01,
        clearance=1e-4,
    )
    assert np.isfinite(film_forces("alshaer2005", **base)["Fx"])
    big = base | {"xi": 0.9, "viscosity": 1e3, "clearance": 1e-6, "xi_dot": 1e300, "omega_journal": 1e300}
    with pytest.raises(ValueError, match="not finite"):
        film_forces("alshaer2005", **big)
    csv = tmp_path / "s.csv"
    csv.write_text(
        ",".join(base) + "\n" + ",".join(str(v) for v in (base | {"clearance": 0.02}).values()) + "\n"
    )
    r = runner.invoke(app, ["film-force", str(csv)])
    assert r.exit_code == 2 and "row 1: clearance = 0.02 [m] must be < radius = 0.01 (c < R)" in one_line(r)
    csv.write_text(",".join(base) + "\n" + ",".join(str(v) for v in big.values()) + "\n")
    out = tmp_path / "f.csv"
    r = runner.invoke(app, ["film-force", str(csv), "--out", str(out)])
    assert r.exit_code == 2 and "row 1: film force not finite" in one_line(r)
    assert not out.exists()


def test_bearing_table_names_the_clearance_and_limits_the_eps_list():
    """c > R used to blame the load; 10⁶ eccentricity ratios are refused before any solve."""
    r = runner.invoke(
        app,
        [
            "bearing-table",
            "--model",
            "short",
            "--cavitation",
            "gumbel",
            "--ld",
            "0.5",
            "--eps",
            "0.5",
            "--load",
            "1000",
            "--speed",
            "20",
            "--radius",
            "0.01",
            "--clearance",
            "0.02",
            "--viscosity",
            "0.04",
        ],
    )
    assert r.exit_code == 2 and "clearance = 0.02 [m]: must be < radius = 0.01" in one_line(r)
    t0 = time.perf_counter()
    r = runner.invoke(app, ["bearing-table", "--ld", "0.5", "--eps", "0.1:0.9:1000000"])
    assert r.exit_code == 2 and "at most 10000 values" in one_line(r)
    assert time.perf_counter() - t0 < 5.0


def test_lyapunov_refuses_a_model_without_degrees_of_freedom():
    """The perfect slider-crank (crank driven, all joints ideal) has no degree of freedom: its
    'exponent' was −11103 ± 570 1/s of pure round-off; refused. The dry one has 2 (the journal's
    offset in the clearance)."""
    from jointdyn.studies.lyapunov import system_lyapunov

    perfect = slider_crank("perfect").compile()
    assert perfect.degrees_of_freedom() == 0
    assert slider_crank("dry").compile().degrees_of_freedom() == 2
    with pytest.raises(ValueError, match="no degree of freedom"):
        system_lyapunov(perfect, 1e-3, 20)


def test_ensemble_refuses_repeated_tolerances():
    """--rtols 1e-7,1e-7 reported 'converged' with shift 0 (a group compared with itself)."""
    from jointdyn.studies.ensemble import ensemble

    t0 = time.perf_counter()
    with pytest.raises(ValueError, match="--rtols 1e-07,1e-07 .*distinct"):
        ensemble("slider-crank", {"joint": "dry"}, rtols=(1e-7, 1e-7))
    assert time.perf_counter() - t0 < 2.0  # before any run


@pytest.mark.parametrize(
    "key, value, match",
    [
        ("first_step", -1.0, r"first_step = -1.0 \[s\]: must be finite and ≥ 0"),
        ("rtol", 1e-300, r"rtol = 1e-300 \[-\]: must be in \[1e-14, 1\)"),
        ("max_steps", 0, r"max_steps = 0 \[-\]: must be an integer ≥ 1"),
    ],
)
def test_solver_settings_are_range_checked(key, value, match, tmp_path):
    """first_step = -1 and rtol = 1e-300 were accepted from model files."""
    with pytest.raises(ValueError, match=match):
        SimConfig(t_end=1.0, **{key: value})
    src = (Path(__file__).resolve().parents[1] / "examples" / "slider_crank_perfect.toml").read_text()
    f = tmp_path / "m.toml"
    line = f"{key} = {value!r}"
    f.write_text(src.replace("rtol = 1e-8", line if key == "rtol" else f"rtol = 1e-8\n{line}"))
    r = runner.invoke(app, ["run", str(f), "--out", str(tmp_path / "o")])
    line = one_line(r)
    assert r.exit_code == 2 and key in line and ("[s]" in line or "[-]" in line), line


def test_numpy_scalars_are_numbers():
    """np.float32/np.int64 arguments gave false range errors ('0.0101 must be > 0'); they are
    accepted and give the same tables as plain floats (up to float32 rounding of the input)."""

    def pair(cast):
        m = Model("m")
        m.add_body("a", 1.0, 1e-3, points={"A": (0.0, 0.0)})
        m.add_body("b", 1.0, 1e-3, points={"B": (0.0, 0.0)})
        m.add("pin", JournalBearing("a", "A", "b", "B", cast(0.0101), cast(0.01), cast(0.04), cast(0.4)))
        return m.compile()

    a, b = pair(np.float32), pair(lambda v: float(np.float32(v)))
    np.testing.assert_array_equal(a.freal, b.freal)
    from jointdyn.film.coefficients import equilibrium

    assert equilibrium("short", np.float32(0.5), np.int64(1) / 2) == equilibrium("short", 0.5, 0.5)


def test_an_off_centre_journal_is_reported():
    """Positions that satisfy the ideal joints and put the journal 0.4 c off centre were silently
    re-centred: now a warning names the element and the offset; a centred start stays silent."""

    def model(dx):
        m = Model("m")
        m.add_ground_point("O", (0.0, 0.0))
        m.add_body("j", 1.0, 1e-4, position=(dx, 0.0), points={"C": (0.0, 0.0)})
        m.add("pin", JournalBearing("ground", "O", "j", "C", 0.0105, 0.01, 0.04, 0.4))
        return m

    with pytest.warns(
        UserWarning, match=r"element 'pin': the given positions put the journal 0.4 c off centre"
    ):
        model(0.4 * 5e-4).compile()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        model(0.0).compile()
    assert model(0.4 * 5e-4).compile(centre_imperfect=False).y0[0] == pytest.approx(2e-4)


@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_signal_while_the_cli_loads_is_one_line(sig, code):
    """A signal while jointdyn and numba import: SIGINT printed the import machinery's traceback,
    SIGTERM was the default kill (−15, no line) [T355]; the console script's entry now ends with
    one line, exit 128 + signal number. The import of the CLI is held open (an import hook that
    announces it and waits), so the signal lands inside it whatever the machine's speed."""
    env = os.environ | {"PYTHONPATH": str(SRC)}
    code_ = (
        "import sys, time, jointdyn_entry as e\n"
        "class Hold:\n"
        "    def find_spec(self, name, path=None, target=None):\n"
        "        if name == 'jointdyn.cli':\n"
        "            print('ready', flush=True)\n"
        "            time.sleep(60)\n"
        "        return None\n"
        "sys.meta_path.insert(0, Hold())\n"
        "sys.argv = ['jointdyn', '--version']\n"
        "e.main()\n"
    )
    p = subprocess.Popen(
        [sys.executable, "-c", code_], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env
    )
    assert p.stdout.readline().strip() == "ready"
    p.send_signal(sig)
    _, err = p.communicate(timeout=60)
    assert p.returncode == code and "Traceback" not in err, err
    assert err.strip() == f"interrupted by {signal.Signals(sig).name} while starting"


@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_signal_between_the_import_and_the_command_guard_is_one_line(sig, code):
    """[T355] After the CLI has loaded and before a command installs its guard (its own imports,
    ≈ 0.5 s): SIGINT ended with typer's silent exit 130, SIGTERM with the default kill (−15, no
    line). The window is held open here by a command that only waits."""
    env = os.environ | {"PYTHONPATH": str(SRC)}
    code_ = (
        "import sys, time, jointdyn_entry as e, jointdyn.cli as c\n"
        "def wait():\n"
        "    print('ready', flush=True)\n"
        "    time.sleep(60)\n"
        "c.app = wait\n"
        "e.main()\n"
    )
    p = subprocess.Popen(
        [sys.executable, "-c", code_], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env
    )
    assert p.stdout.readline().strip() == "ready"
    p.send_signal(sig)
    _, err = p.communicate(timeout=60)
    assert p.returncode == code, err
    assert err.strip() == f"interrupted by {signal.Signals(sig).name}"


SWEEP = '[base]\nmodel = "slider-crank"\njoint = "perfect"\nrevs = 0.1\n[grid]\n'


@pytest.mark.parametrize(
    "grid, match",
    [
        ("speed = [100.0, 100.0]", r"\[grid\].speed repeats 100.0"),
        ("speed = [100.0, nan]", r"nan is not a parameter value"),
    ],
)
def test_sweep_values_are_checked_before_any_case(grid, match, tmp_path):
    """Repeated grid values computed every case and then failed writing sweep.nc; a TOML nan
    became the string 'NaN'. Both are refused when the file is read."""
    from jointdyn.studies.sweep import load_sweep

    f = tmp_path / "s.toml"
    f.write_text(SWEEP + grid + "\n")
    with pytest.raises(ValueError, match=match):
        load_sweep(f)


def test_a_million_case_sweep_is_refused_before_work(tmp_path):
    from jointdyn.studies.sweep import SweepSpec, run_sweep

    spec = SweepSpec(
        base={"model": "slider-crank", "joint": "perfect", "revs": 0.1},
        grid={"speed": [100.0 + i for i in range(1000)], "gravity": [float(i) for i in range(1000)]},
    )
    with pytest.raises(ValueError, match="1000000 cases; at most 100000"):
        run_sweep(spec, tmp_path / "s")
    assert not (tmp_path / "s").exists()


def test_animate_frames_has_a_stated_limit(tmp_path):
    """animate --frames 1e8 (as an integer): refused before the file is read, naming the limit."""
    r = runner.invoke(app, ["animate", str(tmp_path / "missing"), "--frames", "100000000"])
    assert r.exit_code == 2 and "--frames = 100000000 [-]: must be 2 … 5000" in one_line(r)
