"""``jointdyn bearing-table``: CSV columns, operating point, one-line errors [T77]."""

import csv
import io
import math

import pytest
from typer.testing import CliRunner

from jointdyn.bearing.design import COEFFICIENT_COLUMNS, COLUMNS, bearing_table
from jointdyn.cli import app

runner = CliRunner()


def test_table_csv_matches_the_function(tmp_path):
    out = tmp_path / "t.csv"
    r = runner.invoke(app, ["bearing-table", "--ld", "0.5", "--eps", "0.2,0.6", "--out", str(out)])
    assert r.exit_code == 0, r.output
    rows = list(csv.DictReader(io.StringIO(out.read_text())))
    assert tuple(rows[0]) == COLUMNS + COEFFICIENT_COLUMNS and len(rows) == 2
    tab = bearing_table("finite", "reynolds", 0.5, [0.2, 0.6])
    for i, row in enumerate(rows):
        for c in COLUMNS + COEFFICIENT_COLUMNS:  # written with 6 significant digits
            assert float(row[c]) == pytest.approx(tab[c][i], rel=1e-5)


def test_grooved_jfo_table(tmp_path):
    """--grooves 2 --cavitation jfo: the grooved columns (flow per groove, fill) and k/c; the
    feed pressure in Pa enters as P_f = p_f c²/(6μωR²) [T245]."""
    out = tmp_path / "g.csv"
    args = ["bearing-table", "--ld", "0.5", "--eps", "0.6", "--cavitation", "jfo", "--grooves", "2"]
    args += ["--feed-pressure", "2e5", "--speed", "50", "--radius", "0.05", "--clearance", "5e-5"]
    args += ["--viscosity", "0.02", "--out", str(out)]
    r = runner.invoke(app, args)
    assert r.exit_code == 0, r.output
    row = next(csv.DictReader(io.StringIO(out.read_text())))
    from jointdyn.film.grooved import axial_grooves

    feed = 2e5 * 5e-5**2 / (6 * 0.02 * 2 * math.pi * 50 * 0.05**2)
    tab = bearing_table("finite", "jfo", 0.5, [0.6], grooves=axial_grooves(2, 18.0, feed))
    for c in ("sommerfeld", "groove_flow_1", "groove_flow_2", "fill_min", "kxy", "cyy"):
        assert float(row[c]) == pytest.approx(tab[c][0], rel=1e-5), c
    assert float(row["groove_flow_1"]) + float(row["groove_flow_2"]) == pytest.approx(
        float(row["flow_variable"]), rel=1e-5
    )


def test_operating_point_printed():
    args = ["bearing-table", "--ld", "1", "--eps", "0.5", "--load", "2000", "--speed", "30"]
    args += ["--radius", "0.02", "--clearance", "4e-5", "--viscosity", "0.03"]
    r = runner.invoke(app, args)
    assert r.exit_code == 0, r.output
    assert "power_loss" in r.output and "[W]" in r.output and "h_min" in r.output


@pytest.mark.parametrize(
    "extra, msg",
    [
        (["--ld", "1", "--eps", "1.5"], "eps = 1.5 [-]: must be in (0, 1)"),
        (["--ld", "0", "--eps", "0.5"], "L/D = 0.0 [-]: must be finite and > 0"),
        (["--ld", "1", "--cavitation", "elrod"], "cavitation = 'elrod': must be one of gumbel, reynolds"),
        (["--ld", "1", "--grooves", "2", "--groove-width", "190"], "groove width = 190 [deg]"),
        (["--ld", "1", "--grooves", "2", "--feed-pressure", "-1"], "--feed-pressure -1.0 [Pa]"),
        (["--ld", "1", "--grooves", "2", "--feed-pressure", "1e5"], "--feed-pressure > 0 needs --speed"),
        (["--ld", "1", "--feed-pressure", "1e5"], "--feed-pressure needs --grooves"),
        (
            ["--ld", "1", "--cavitation", "jfo", "--model", "long"],
            "closed forms exist for gumbel and reynolds",
        ),
        (["--ld", "1", "--eps", "x"], "--eps 'x'"),
        (["--ld", "1", "--load", "100"], "--load needs --speed"),
        (
            [
                "--ld",
                "1",
                "--load",
                "0",
                "--speed",
                "30",
                "--radius",
                "0.02",
                "--clearance",
                "4e-5",
                "--viscosity",
                "0.03",
            ],
            "load = 0.0 [N]: must be finite and > 0",
        ),
        (
            [
                "--ld",
                "1",
                "--load",
                "2e7",
                "--speed",
                "30",
                "--radius",
                "0.02",
                "--clearance",
                "4e-5",
                "--viscosity",
                "0.03",
            ],
            "cannot carry it below eps = 0.999",
        ),
    ],
)
def test_bad_input_exit_2_one_line(extra, msg):
    r = runner.invoke(app, ["bearing-table", *extra])
    assert r.exit_code == 2
    assert msg in r.output.replace("\n", " ")


def test_film_names_work_as_table_models_on_the_command_line():
    """issue 29: `bearing-table --model` takes the film names (alshaer2005 = the long bearing with
    Gümbel's condition [T21]) as aliases: the same table as the table model's own name."""
    base = ["bearing-table", "--ld", "1", "--eps", "0.3,0.6"]
    a = runner.invoke(app, [*base, "--model", "alshaer2005"])
    b = runner.invoke(app, [*base, "--model", "long", "--cavitation", "gumbel"])
    assert a.exit_code == 0 and b.exit_code == 0, a.output + b.output
    assert a.output == b.output and a.output.startswith("eps,ld,sommerfeld,attitude_deg")
