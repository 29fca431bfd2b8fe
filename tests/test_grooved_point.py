"""Operating point of the axially grooved bearing at a given load [T246, T342]: the inverse of the
grooved design table, checked by the dimensional force balance of the film at the solution, the
lubricant balance of `jfo` and the command line."""

from __future__ import annotations

import math

import pytest
from typer.testing import CliRunner

from jointdyn.bearing.grooved_table import grooved_equilibrium, grooved_table
from jointdyn.cli import app
from jointdyn.film.grooved import axial_grooves, film_at

R, LENGTH, C, MU, N = 0.025, 0.05, 5e-5, 0.03, 50.0  # L/D = 1 [m, m, m, Pa·s, rev/s]


def _load_at(eps: float, cavitation: str) -> float:
    """W [N] whose Sommerfeld number is the grooved table's at ε (S = (R/c)²μN/P, P = W/(2RL))."""
    S = float(
        grooved_table(cavitation, LENGTH / (2 * R), [eps], axial_grooves(2, 18.0), coefficients=False)[
            "sommerfeld"
        ][0]
    )
    return (R / C) ** 2 * MU * N * 2 * R * LENGTH / S


@pytest.mark.parametrize("cavitation", ["reynolds", "jfo"])
def test_the_operating_point_inverts_the_table_and_balances_the_load(cavitation):
    W = _load_at(0.6, cavitation)
    op = grooved_equilibrium(W, N, R, LENGTH, C, MU, cavitation, axial_grooves(2, 18.0))
    assert op["eps"] == pytest.approx(0.6, abs=1e-8)
    assert op["h_min"] == pytest.approx(C * 0.4, rel=1e-7)
    # force balance in newtons at the solution, from the film solver (F in μωR⁴/c² [T246])
    phi = math.radians(op["attitude_deg"])
    e = (op["eps"] * math.cos(phi), op["eps"] * math.sin(phi))
    F = film_at(LENGTH / (2 * R), e, (0.0, 0.0), cavitation, axial_grooves(2, 18.0))[0]
    F = F * MU * 2 * math.pi * N * R**4 / C**2
    assert F[0] == pytest.approx(-W, rel=1e-7)  # against the load (load frame: load along +e_L)
    assert abs(F[1]) <= 1e-7 * W
    # steady: what the grooves supply leaves at the ends (jfo: by mass conservation; reynolds: by
    # definition, its cavitated zone does not know where its oil goes, so no split per groove [T370])
    assert op["side_flow"] == pytest.approx(op["flow"], rel=1e-9)
    flows = op["groove_flow_1"] + op["groove_flow_2"]
    if cavitation == "jfo":
        assert flows == pytest.approx(op["flow"], rel=1e-12)  # the supply is the grooves' sum
        assert 0.0 < op["fill_min"] < 1.0  # a cavitated zone carrying partial film content
    else:
        assert math.isnan(op["groove_flow_1"]) and math.isnan(op["groove_flow_2"])


def test_a_supply_pressure_adds_flow_and_bad_input_is_named():
    W = _load_at(0.6, "jfo")
    base = grooved_equilibrium(W, N, R, LENGTH, C, MU, "jfo", axial_grooves(2, 18.0))
    fed = grooved_equilibrium(W, N, R, LENGTH, C, MU, "jfo", axial_grooves(2, 18.0), feed_pressure=2e5)
    assert fed["flow"] > 1.5 * base["flow"]
    assert fed["side_flow"] == pytest.approx(fed["flow"], rel=1e-9)
    with pytest.raises(ValueError, match=r"cannot carry it below eps = 0.99"):
        grooved_equilibrium(1e3 * W, N, R, LENGTH, C, MU, "jfo", axial_grooves(2, 18.0))
    with pytest.raises(ValueError, match=r"clearance = 0.03 \[m\]: must be < radius"):
        grooved_equilibrium(W, N, R, LENGTH, 0.03, MU, "jfo", axial_grooves(2, 18.0))
    with pytest.raises(ValueError, match=r"feed_pressure = -1.0 \[Pa\]"):
        grooved_equilibrium(W, N, R, LENGTH, C, MU, "jfo", axial_grooves(2, 18.0), feed_pressure=-1.0)


def test_bearing_table_prints_the_grooved_operating_point():
    W = _load_at(0.6, "reynolds")
    args = ["bearing-table", "--ld", "1", "--eps", "0.6", "--grooves", "2", "--load", repr(W)]
    args += ["--speed", repr(N), "--radius", repr(R), "--clearance", repr(C), "--viscosity", repr(MU)]
    r = CliRunner().invoke(app, args)
    assert r.exit_code == 0, r.output
    line = next(s for s in r.output.splitlines() if s.strip().startswith("eps ="))
    assert float(line.split("=")[1].split()[0]) == pytest.approx(0.6, abs=1e-6)
    assert "groove_flow_2" in r.output and "[m³/s]" in r.output


def test_reynolds_flows_per_groove_only_where_the_film_is_full():
    """[T370] Swift–Stieber's film does not conserve oil across a cavitated zone (the re-formation
    creates it), so with one its grooves' net flows are not the supply (they summed to −0.22 for
    +1.42 of side leakage at L/D 0.5, ε 0.3): the table gives the side leakage as the supply and no
    split per groove. Fed hard enough that no cell cavitates (P_f = 2), Reynolds' film is the
    mass-conserving one and its per-groove flows are jfo's (measured within 1.6e-5)."""
    t = grooved_table("reynolds", 0.5, [0.3], axial_grooves(2, 18.0), coefficients=False)
    assert t["side_flow_ratio"][0] == pytest.approx(1.0, rel=1e-12) and t["flow_variable"][0] > 0.0
    assert math.isnan(t["groove_flow_1"][0]) and math.isnan(t["groove_flow_2"][0])
    fed = [
        grooved_table(c, 0.5, [0.3], axial_grooves(2, 18.0, 2.0), coefficients=False)
        for c in ("reynolds", "jfo")
    ]
    for k in ("flow_variable", "groove_flow_1", "groove_flow_2"):
        assert fed[0][k][0] == pytest.approx(fed[1][k][0], rel=1e-4), k
    assert fed[0]["groove_flow_1"][0] + fed[0]["groove_flow_2"][0] == pytest.approx(
        fed[0]["flow_variable"][0], rel=1e-12
    )
