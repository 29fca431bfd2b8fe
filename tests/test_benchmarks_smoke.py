"""The benchmark command runs on a tiny case (no timing assertions: speed lives in benchmarks/)."""

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.__main__ import main  # noqa: E402


def test_benchmark_quick_runs(capsys):
    rows = main(["--quick", "--cases", "perfect"])
    assert rows and rows[0]["rhs_evaluations"] > 0 and rows[0]["err_M/peak"] < 1e-6
    assert "| case | solver |" in capsys.readouterr().out


@pytest.mark.slow
def test_work_precision_quick_runs(capsys):
    """benchmarks.work_precision on one clearance, two radau5 points and one of each other solver
    (no timing assertions)."""
    from benchmarks.work_precision import main as wp_main

    res = wp_main(["--quick", "--clearances", "0.5", "--repeat", "1"])
    rows = res[0.5]["rows"]
    assert {r["solver"] for r in rows} == {"radau5", "rodas4", "ros34pw2", "scipy-radau"}
    # radau5's error shrinks with rtol (measured 1.2e-4 at 1e-6, 1.2e-5 at 1e-7)
    r6, r7 = (r["error"] for r in rows if r["solver"] == "radau5")
    assert r7 < r6
    assert "wall time [s] at equal accuracy" in capsys.readouterr().out


@pytest.mark.slow
def test_rhs_ab_runs_a_tree_against_itself(capsys):
    """benchmarks.rhs_ab with the same tree on both sides prints a row per case (no timing
    assertion: the ratio of a tree to itself is only noise)."""
    from benchmarks.rhs_ab import main as ab_main

    src = str(Path(__file__).resolve().parents[1] / "src")
    ab_main([src, src, "--rounds", "1", "--n", "1000", "--cases", "perfect"])
    out = capsys.readouterr().out
    assert "| perfect |" in out and "B/A" in out


def test_kernel_set_cost_reports_every_slot(capsys):
    """benchmarks.kernel_set_cost for the perfect joint (its set is the smallest): one row per
    kernel slot and the total, from a fresh process and an empty cache (no timing assertion)."""
    from benchmarks.kernel_set_cost import main as cost_main
    from jointdyn.forces.kernel_set import SLOTS

    cost_main(["--joints", "perfect"])
    rows = [ln.split("|")[1].strip() for ln in capsys.readouterr().out.splitlines() if ln.startswith("| ")]
    assert rows[1:] == [*SLOTS, "total"]
