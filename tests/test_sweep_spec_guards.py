"""Sweep specs checked before any case runs (issue 28, campaign family "sweeps"): inline-table
values reach the model file as the same table, names that cannot become sweep.nc variables are
refused before work."""

from __future__ import annotations

from pathlib import Path

import pytest

from jointdyn.studies.sweep import load_sweep, run_sweep
from jointdyn.studies.sweep_spec import load_file_case, validate

EXAMPLE = Path(__file__).parents[1] / "examples" / "slider_crank_dry.toml"
FRICTION = [
    {"law": "coulomb", "coefficient": 0.1, "regularization_velocity": 1e-4},
    {"law": "coulomb", "coefficient": 0.2, "regularization_velocity": 1e-4},
]


def _sweep(tmp_path, model: Path, grid: str) -> Path:
    f = tmp_path / "s.toml"
    f.write_text(f'[base]\nfile = "{model}"\nrevs = 0.05\n[grid]\n{grid}\n')
    return f


def test_inline_table_values_reach_the_model_as_tables(tmp_path):
    """Before: every case failed with "... is not a TOML value" (the value went as JSON)."""
    grid = (
        '"elements.piston_pin.friction" = ['
        + ", ".join(
            f'{{ law = "coulomb", coefficient = {d["coefficient"]}, regularization_velocity = 1e-4 }}'
            for d in FRICTION
        )
        + "]"
    )
    spec = load_sweep(_sweep(tmp_path, EXAMPLE, grid))
    cases, invalid = validate(spec)
    assert invalid == {}
    for case, want in zip(cases, FRICTION):
        model, _, _ = load_file_case({**spec.base, **case}, assemble=False)
        fr = model.items["piston_pin"].friction
        assert (fr.coefficient, fr.regularization_velocity) == (want["coefficient"], 1e-4)


def test_a_slash_in_an_element_name_is_refused_before_any_case(tmp_path):
    """Before: every case ran, then writing sweep.nc failed ("Forward slashes ... not allowed")."""
    text = EXAMPLE.read_text().replace("[elements.piston_pin]", '[elements."pin/x"]')
    model = tmp_path / "m.toml"
    model.write_text(text)
    spec = load_sweep(_sweep(tmp_path, model, '"simulation.rtol" = [1e-7, 1e-8]'))
    with pytest.raises(ValueError, match=r"element or joint name 'pin/x': '/' cannot be in a sweep.nc"):
        run_sweep(spec, tmp_path / "out")
    assert not (tmp_path / "out").exists()


def test_a_slash_in_a_parameter_name_is_refused(tmp_path):
    spec = load_sweep(_sweep(tmp_path, EXAMPLE, '"bodies.a/b.mass" = [0.1, 0.2]'))
    with pytest.raises(ValueError, match=r"sweep parameter name 'bodies.a/b.mass'"):
        validate(spec)
