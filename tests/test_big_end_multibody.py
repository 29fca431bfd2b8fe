"""The multibody big-end page: its generated numbers are those the engine runs give now."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest


@pytest.mark.slow
def test_big_end_multibody_page_is_current():
    """The numbers of docs/user-guide/big-end.md's multibody block are those
    ``docs/_gen_big_end_multibody.py`` computes now (the engine with the big end as finite
    gumbel, reynolds and jfo films; ≈ 30 s of CPU, most of it the jfo run)."""
    path = Path(__file__).resolve().parents[1] / "docs" / "_gen_big_end_multibody.py"
    spec = importlib.util.spec_from_file_location("_gen_big_end_multibody", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    assert mod.main(["--check"]) == 0, "run python docs/_gen_big_end_multibody.py"
