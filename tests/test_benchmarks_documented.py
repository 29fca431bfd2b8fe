"""CONTRIBUTING's benchmark commands in their smallest form (slow tier, no timing assertions):
each runs as a fresh process from the checkout, and a ``--write`` regenerator writes its block
into a copy of the page it names (the repository's pages are not touched). What the full commands
cost is stated in CONTRIBUTING; tests/data/documented_commands.toml records which form runs here."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

pytestmark = pytest.mark.slow


def _run(args: list[str], timeout: float = 1800) -> str:
    env = {**os.environ, "MPLBACKEND": "Agg"}
    r = subprocess.run(
        [sys.executable, "-m", *args], cwd=ROOT, env=env, capture_output=True, text=True, timeout=timeout
    )
    assert r.returncode == 0, f"python -m {' '.join(args)}: {r.stderr[-3000:]}"
    return r.stdout


def test_benchmarks_two_cases_warm():
    """`python -m benchmarks --cases perfect,dry --no-cold` with one repeat."""
    out = _run(["benchmarks", "--cases", "perfect,dry", "--no-cold", "--repeat", "1"])
    rows = [ln for ln in out.splitlines() if ln.startswith("| perfect") or ln.startswith("| dry")]
    assert {r.split("|")[1].strip() for r in rows} == {"perfect", "dry"}


def test_targets_main_job_once_warm():
    """`python -m benchmarks.targets --main-job --repeat 3` as one warm repeat."""
    out = _run(["benchmarks.targets", "--main-job", "--repeat", "1", "--no-cold"])
    assert "Machine:" in out and re.search(r"\d+(\.\d+)? s CPU", out)


def _block(text: str, name: str) -> str:
    m = re.search(rf"<!-- generated:{name} -->\n(.*?)<!-- /generated -->", text, re.S)
    assert m, f"no generated:{name} block"
    return m.group(1)


def test_end_to_end_writes_its_block_quick(tmp_path):
    """`python -m benchmarks.end_to_end --write README.md` as --quick --no-cli into a copy."""
    readme = tmp_path / "README.md"
    shutil.copy(ROOT / "README.md", readme)
    before = _block(readme.read_text(encoding="utf-8"), "speed")
    _run(["benchmarks.end_to_end", "--quick", "--no-cli", "--write", str(readme)])
    after = _block(readme.read_text(encoding="utf-8"), "speed")
    assert after != before and "alshaer2005" in after


def test_rodas4_accuracy_writes_its_block_small(tmp_path):
    """`python -m benchmarks.rodas4_accuracy --solvers rodas4,radau5,ros34pw2 --write …` on one
    clearance and two tolerances, into a copy of the integrators guide."""
    page = tmp_path / "integrators.md"
    shutil.copy(ROOT / "docs" / "user-guide" / "integrators.md", page)
    args = ["--solvers", "rodas4,radau5,ros34pw2", "--clearances", "0.5", "--rtols", "1e-6,1e-7"]
    _run(["benchmarks.rodas4_accuracy", *args, "--write", str(page)])
    after = _block(page.read_text(encoding="utf-8"), "rodas4_accuracy")
    assert all(s in after for s in ("rodas4", "radau5", "ros34pw2"))
