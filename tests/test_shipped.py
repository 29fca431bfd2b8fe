"""Shipped models are catalogue records (jointdyn.models.catalog): the studies and the CLI read
the record, and model-file keys address a shipped model like a file. References: the same run
through the builder's own argument (bit-identical: the key is set on the model file of the same
built model, which reads back exactly)."""

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from jointdyn.cli import app
from jointdyn.models.catalog import DEFAULT, SHIPPED, shipped
from jointdyn.studies.runs import model_system, run_shipped

runner = CliRunner()
PIN_VISCOSITY = "elements.piston_pin.viscosity"


def test_catalogue_record_and_one_line_for_an_unknown_name():
    m = shipped(DEFAULT)
    assert DEFAULT in SHIPPED and m.variant_arg == "joint" and "dry" in m.variants()
    assert {"clearance", "viscosity", "speed"} <= set(m.numeric_args())
    with pytest.raises(ValueError, match="MODEL = 'pendulum'.*valid: slider-crank"):
        shipped("pendulum")
    r = runner.invoke(app, ["run", "pendulum", "--out", "unused"])
    assert r.exit_code == 2 and "pendulum" in r.output and "\n" not in r.output.strip()


def test_a_model_file_key_on_the_shipped_model_equals_its_builder_argument():
    _, _, by_arg = run_shipped(DEFAULT, "alshaer2005", 0.25, model_kw={"viscosity": 0.2})
    res, _, by_key = run_shipped(DEFAULT, "alshaer2005", 0.25, keys=[f"{PIN_VISCOSITY}=0.2"])
    res0, _, default = run_shipped(DEFAULT, "alshaer2005", 0.25)
    assert res.system.elements[0].viscosity == 0.2
    assert by_key["metrics"] == by_arg["metrics"]  # the same model, integrated the same way
    assert by_key["peak_moment"] != default["peak_moment"]  # and the key acted
    with pytest.raises(ValueError, match="simulation.t_end.*--revs"):
        run_shipped(DEFAULT, "perfect", 0.25, keys=["simulation.t_end=1.0"])


def test_run_set_on_the_shipped_model(tmp_path):
    out = tmp_path / "k"
    args = ["run", DEFAULT, "--joint", "alshaer2005", "--revs", "0.25", "--out", str(out)]
    r = runner.invoke(app, [*args, "--set", f"{PIN_VISCOSITY}=0.2"])
    assert r.exit_code == 0, r.output
    _, _, lib = run_shipped(DEFAULT, "alshaer2005", 0.25, model_kw={"viscosity": 0.2})
    s = json.loads((out / "summary.json").read_text())
    assert s["peak_moment"] == lib["peak_moment"]
    bad = runner.invoke(app, [*args[:-1], str(tmp_path / "b"), "--set", "elements.piston_pin.viscosty=0.2"])
    assert bad.exit_code == 2 and "viscosty" in bad.output and "viscosity" in bad.output


def test_model_system_takes_variant_arguments_and_keys():
    sys_arg, _ = model_system(DEFAULT, {"joint": "dry", "clearance": 2e-4})
    sys_key, _ = model_system(DEFAULT, {"joint": "dry", "elements.piston_pin.bearing_radius": 0.0102})
    assert sys_arg.elements[0].clearance == pytest.approx(2e-4, rel=1e-12)
    assert sys_key.elements[0].clearance == pytest.approx(2e-4, rel=1e-9)
    assert np.array_equal(sys_arg.y0, sys_key.y0)
    with pytest.raises(ValueError, match="joint = 'wet'"):
        model_system(DEFAULT, {"joint": "wet"})


def test_a_sweep_over_a_key_of_the_shipped_model_equals_the_single_runs(tmp_path):
    from jointdyn.studies.sweep import load_sweep, run_sweep

    f = tmp_path / "s.toml"
    f.write_text(
        f'[base]\nmodel = "{DEFAULT}"\njoint = "alshaer2005"\nrevs = 0.25\n'
        f'[grid]\n"{PIN_VISCOSITY}" = [0.2, 0.4]\n',
        encoding="utf-8",
    )
    ds = run_sweep(load_sweep(f), tmp_path / "out", workers=1)
    assert list(ds["error"].values) == ["", ""]
    for mu, peak in zip((0.2, 0.4), ds["peak_moment"].values):
        _, _, single = run_shipped(DEFAULT, "alshaer2005", 0.25, model_kw={"viscosity": mu})
        assert peak == single["peak_moment"]
    f.write_text(
        f'[base]\nmodel = "{DEFAULT}"\njoint = "dry"\nrevs = 0.25\n[grid]\n"elements.pin.viscosity" = [0.2]\n',
        encoding="utf-8",
    )
    with pytest.raises(ValueError, match="unknown key 'pin'"):  # a sweep of invalid cases only:
        run_sweep(load_sweep(f), tmp_path / "bad", workers=1)  # refused before any work [T334]


def test_bifurcation_spec_accepts_a_key_of_the_shipped_model(tmp_path):
    from jointdyn.studies.bifurcation import load_bifurcation

    f = tmp_path / "b.toml"
    f.write_text(
        f'[base]\njoint = "alshaer2005"\n[bifurcation]\nparameter = "{PIN_VISCOSITY}"\nvalues = [0.1]\n',
        encoding="utf-8",
    )
    assert load_bifurcation(f).parameter == PIN_VISCOSITY
    f.write_text('[base]\nmodel = "pendulum"\n[bifurcation]\nparameter = "clearance"\nvalues = [1e-4]\n')
    with pytest.raises(ValueError, match="pendulum"):
        load_bifurcation(f)
