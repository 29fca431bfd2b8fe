"""Viscosity–temperature laws, the effective-temperature heat balance [T273–T277] and the
``stribeck`` / ``bearing-table --oil`` commands."""

import csv
import math
from pathlib import Path

import pytest
from typer.testing import CliRunner

from jointdyn.bearing.design import equilibrium
from jointdyn.bearing.thermal import effective_temperature
from jointdyn.cli import app
from jointdyn.film.viscosity import MICROREYN, OILS, SAE, oil_by_name

runner = CliRunner()
DATA = Path(__file__).parent / "data"


def test_walther_law_through_its_two_points_and_monotone():
    for name, oil in OILS.items():
        if name.startswith("ISO"):
            nu40, nu100 = oil.law.nu40, oil.law.nu100
            assert oil.law.kinematic(40.0) == pytest.approx(nu40, rel=1e-12)
            assert oil.law.kinematic(100.0) == pytest.approx(nu100, rel=1e-12)
            assert oil.viscosity(40.0) == pytest.approx(oil.density(40.0) * nu40 * 1e-6, rel=1e-12)
        mus = [oil.viscosity(t) for t in range(0, 151, 10)]
        assert all(a > b for a, b in zip(mus, mus[1:]))
        assert oil.temperature_of(oil.viscosity(73.0)) == pytest.approx(73.0, abs=1e-8)


def test_sae_grades_are_seireg_fits_in_si():
    for g, (mu0, b) in SAE.items():
        for tf in (100.0, 140.0, 200.0):  # Shigley Table 12-1: μ = μ₀ exp(b/(T_F + 95)) [μreyn]
            ref = mu0 * math.exp(b / (tf + 95.0)) * MICROREYN
            assert oil_by_name(f"SAE {g}").viscosity((tf - 32.0) / 1.8) == pytest.approx(ref, rel=1e-12)


def test_bad_oil_and_temperature_name_the_parameter():
    with pytest.raises(ValueError, match="unknown grade; valid: ISO_VG22, ISO_VG32"):
        oil_by_name("ISO_VG47")
    with pytest.raises(ValueError, match=r"temperature = 200.0 \[°C\]: the viscosity law of ISO_VG46"):
        oil_by_name("ISO_VG46").viscosity(200.0)


def _case(oil="SAE_30"):
    inch, lbf = 0.0254, 4.4482216152605
    return dict(
        load=500 * lbf, speed=30.0, radius=0.75 * inch, length=1.5 * inch, clearance=0.0015 * inch
    ), oil_by_name(oil)


@pytest.mark.parametrize("oil", ["SAE_30", "ISO_VG68"])
def test_effective_temperature_closes_the_heat_balance(oil):
    g, o = _case(oil)
    t_in = 43.0
    op = effective_temperature(**g, oil=o, inlet_temp=t_in)
    # independent path: the SI operating point at μ(T_eff) and the heat carried by the oil
    ref = equilibrium(
        g["load"], g["speed"], g["radius"], g["length"], g["clearance"], o.viscosity(op["t_eff"])
    )
    assert ref["eps"] == pytest.approx(op["eps"], rel=1e-7)
    rho_cp = o.density(op["t_eff"]) * o.specific_heat
    dT = ref["power_loss"] / (rho_cp * (ref["flow"] - 0.5 * ref["side_flow"]))
    assert op["t_eff"] == pytest.approx(t_in + 0.5 * dT, abs=1e-6)
    assert op["delta_t"] == pytest.approx(dT, rel=1e-6)


def test_shigley_si_temperature_rise_constant():
    # Shigley's SI heat balance ΔT = 8.30·P[MPa]·(r/c)f / ((1 − ½Q_s/Q)·Q/(rcNl)) assumes
    # ρ = 861 kg/m³, c_p = 1760 J/(kg·K); the SAE oils carry these constants
    g, o = _case("SAE_20")
    op = effective_temperature(**g, oil=o, inlet_temp=38.0)
    P = g["load"] / (2 * g["radius"] * g["length"])
    fvar = op["friction_torque"] / (g["load"] * g["clearance"])
    q = op["flow"] / (g["radius"] * g["clearance"] * g["speed"] * g["length"])
    shigley = 8.30 * P / 1e6 * fvar / ((1 - 0.5 * op["side_flow"] / op["flow"]) * q)
    assert op["delta_t"] == pytest.approx(shigley, rel=2e-3)


def test_stribeck_command_writes_csv_and_figure(tmp_path):
    out = tmp_path / "s.csv"
    args = "--radius 0.025 --length 0.025 --clearance 25e-6 --load 3000 --oil ISO_VG46 --temperature 60"
    r = runner.invoke(
        app, ["stribeck", *args.split(), "--speeds", "2,40,160,3000", "--mesh", "96,12", "--out", str(out)]
    )
    assert r.exit_code == 0, r.output
    rows = list(csv.DictReader(out.open()))
    assert list(rows[0]) == [
        "speed_rpm",
        "friction_torque",
        "friction_coefficient",
        "h_min",
        "eps",
        "asperity_load_fraction",
        "hersey",
    ]
    f = [float(x["friction_coefficient"]) for x in rows]
    assert f.index(min(f)) == 2
    assert (tmp_path / "s.png").stat().st_size > 10_000
    bad = runner.invoke(
        app, ["stribeck", *args.split(), "--speeds", "10", "--roughness", "-1e-6,0", "--out", str(out)]
    )
    assert bad.exit_code == 2 and "sigma1 = -1e-06 [m]" in bad.output


def test_bearing_table_reports_the_effective_temperature():
    a = "--ld 1 --eps 0.5 --load 2000 --speed 25 --radius 0.025 --clearance 30e-6 --oil ISO_VG46 --inlet-temp 40"
    r = runner.invoke(app, ["bearing-table", *a.split()])
    assert r.exit_code == 0, r.output
    assert "t_eff = " in r.output and "delta_t = " in r.output
    r = runner.invoke(app, ["bearing-table", *a.split(), "--viscosity", "0.03"])
    assert r.exit_code == 2 and "not both" in r.output


def _textbook_case():
    rows = [r for r in open(DATA / "shigley_effective_temperature.csv") if not r.startswith("#")]
    return next(csv.DictReader(rows))


def _chart_procedure(g, oil, t_in):
    """The textbook's hand iteration with the Raimondi–Boyd l/d = 1 table (log–log interpolation in
    S) and Shigley's SI heat balance ΔT = 8.30·P[MPa]·(r/c)f/((1 − ½Q_s/Q)·Q/(rcNl)) [T276]."""
    import numpy as np
    from scipy.optimize import brentq

    rb = [r for r in open(DATA / "raimondi_boyd_1958.csv") if not r.startswith("#")]
    tab = sorted((r for r in csv.DictReader(rb) if r["ld"] == "1"), key=lambda r: float(r["sommerfeld"]))
    lnS = np.log([float(r["sommerfeld"]) for r in tab])

    def col(name, S):
        return float(np.exp(np.interp(math.log(S), lnS, np.log([float(r[name]) for r in tab]))))

    P = g["load"] / (2 * g["radius"] * g["length"])

    def residual(t):
        S = (g["radius"] / g["clearance"]) ** 2 * oil.viscosity(t) * g["speed"] / P
        x = col("friction_variable", S) / ((1 - 0.5 * col("side_flow_ratio", S)) * col("flow_variable", S))
        return t - t_in - 0.5 * 8.30 * P / 1e6 * x

    return brentq(residual, t_in, t_in + 80.0, xtol=1e-9)


def test_textbook_effective_temperature_within_2_K():
    row = _textbook_case()
    g = dict(
        load=float(row["load_N"]),
        speed=float(row["speed_rps"]),
        radius=float(row["radius_m"]),
        length=float(row["length_m"]),
        clearance=float(row["clearance_m"]),
    )
    oil, t_in = oil_by_name(row["oil"]), float(row["inlet_temp_C"])
    op = effective_temperature(**g, oil=oil, inlet_temp=t_in)  # finite Reynolds film [T277]
    assert abs(op["t_eff"] - float(row["t_eff_C"])) < 2.0  # measured: 67.07 vs 67.1 °C
    assert op["sommerfeld"] == pytest.approx(float(row["sommerfeld"]), rel=0.02)
    assert op["viscosity"] == pytest.approx(float(row["viscosity_Pas"]), rel=0.02)
    # the same procedure by hand from the Raimondi–Boyd table (the book's charts): 67.0 °C
    assert abs(op["t_eff"] - _chart_procedure(g, oil, t_in)) < 2.0
    # and through the command line
    a = (
        f"--ld 1 --eps 0.5 --load {g['load']} --speed {g['speed']} --radius {g['radius']}"
        f" --clearance {g['clearance']} --oil {row['oil']} --inlet-temp {t_in}"
    )
    r = runner.invoke(app, ["bearing-table", *a.split()])
    assert r.exit_code == 0, r.output
    assert f"t_eff = {op['t_eff']:.2f}" in r.output
