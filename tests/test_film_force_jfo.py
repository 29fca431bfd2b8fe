"""`film-force --model finite --cavitation jfo`: the steady line-fed mass-conserving film state by
state [T343], against the design table's jfo film on its own (clustered) mesh, mirror symmetry in
the sliding speed, scaling, the frame rotation and bad input."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from jointdyn.bearing.design import finite_steady
from jointdyn.cli import app
from jointdyn.film.jfo_states import SteadyJFO

R, C, MU, W = 0.025, 5e-5, 0.03, 100.0  # [m, m, Pa·s, rad/s]


@pytest.mark.parametrize("ld", [0.5, 1.0])
def test_steady_jfo_forces_equal_the_design_tables_film(ld):
    """Load and attitude against `bearing-table`'s jfo film (supply at the maximum film, 144×16
    clustered mesh [T80] vs the uniform 180×16 mesh here): measured ≤ 9.9e-4 and ≤ 0.0085°."""
    x = np.array([0.2, 0.6, 0.9, 0.97])
    F = SteadyJFO().forces(x, 0.0, 0.0, 0.0, W, 0.0, MU, 2 * R * ld, R, C)
    for k, xi in enumerate(x):
        d = finite_steady(float(xi), ld, "jfo")
        load = math.hypot(d["Fr"], d["Ft"]) * MU * W * R**4 / C**2  # units μωR⁴/c² [T74]
        assert math.hypot(F["Fr"][k], F["Ft"][k]) == pytest.approx(load, rel=2e-3)
        att = math.degrees(math.atan2(F["Ft"][k], -F["Fr"][k]))
        assert att == pytest.approx(math.degrees(math.atan2(d["Ft"], -d["Fr"])), abs=0.02)


def test_mirror_symmetry_scaling_and_frame():
    f = SteadyJFO().forces
    a = f(0.7, 0.3, 0.4, 5.0, 120.0, 10.0, MU, 0.05, R, C)
    # Ω = ω_J + ω_B − 2γ̇ = 120 rad/s; the mirror image θ → −θ reverses the sliding and keeps the
    # squeeze: F_r kept, F_t reversed
    b = f(0.7, 0.3, 0.4, -5.0, -120.0, -10.0, MU, 0.05, R, C)
    assert float(b["Fr"]) == pytest.approx(float(a["Fr"]), rel=1e-9)
    assert float(b["Ft"]) == pytest.approx(-float(a["Ft"]), rel=1e-9)
    # only Ω matters for the sliding, not how it is made up [T20]
    c = f(0.7, 0.3, 0.4, 0.0, 60.0, 60.0, MU, 0.05, R, C)
    assert float(c["Fr"]) == pytest.approx(float(a["Fr"]), rel=1e-9)
    d = f(0.7, 0.3, 0.4, 5.0, 120.0, 10.0, 2 * MU, 0.05, R, C)  # linear in μ
    assert float(d["Ft"]) == pytest.approx(2 * float(a["Ft"]), rel=1e-12)
    g = 0.4  # F_x, F_y: (F_r, F_t) rotated by γ [T27]
    assert float(a["Fx"]) == pytest.approx(float(a["Fr"]) * math.cos(g) - float(a["Ft"]) * math.sin(g))
    assert float(a["Fy"]) == pytest.approx(float(a["Fr"]) * math.sin(g) + float(a["Ft"]) * math.cos(g))


def test_the_command_writes_the_forces_and_names_a_bad_row(tmp_path):
    cols = "xi,xi_dot,gamma,gamma_dot,omega_journal,omega_bearing,viscosity,length,radius,clearance"
    src = tmp_path / "s.csv"
    src.write_text(f"{cols}\n0.6,0,0.3,0,{W},0,{MU},0.05,{R},{C}\n0.8,0.1,1.0,2.0,{W},0,{MU},0.05,{R},{C}\n")
    out = tmp_path / "f.csv"
    r = CliRunner().invoke(
        app, ["film-force", str(src), "--model", "finite", "--cavitation", "jfo", "--out", str(out)]
    )
    assert r.exit_code == 0, r.output
    rows = list(csv.DictReader(out.open()))
    ref = SteadyJFO().forces(0.6, 0.0, 0.3, 0.0, W, 0.0, MU, 0.05, R, C)
    assert float(rows[0]["Fy"]) == pytest.approx(float(ref["Fy"]), rel=1e-9)
    src.write_text(f"{cols}\n0.6,0,0.3,0,{W},0,{MU},0.05,{R},{C}\n0.995,0,0,0,{W},0,{MU},0.05,{R},{C}\n")
    r = CliRunner().invoke(app, ["film-force", str(src), "--model", "finite", "--cavitation", "jfo"])
    assert r.exit_code == 2
    assert "row 2: xi = 0.995 [-]: the steady jfo film needs 0 < xi <= 0.99" in r.output
