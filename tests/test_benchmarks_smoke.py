"""The benchmark command runs on a tiny case (no timing assertions: speed lives in benchmarks/)."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.__main__ import main  # noqa: E402


def test_benchmark_quick_runs(capsys):
    rows = main(["--quick", "--cases", "perfect"])
    assert rows and rows[0]["rhs_evaluations"] > 0 and rows[0]["err_M/peak"] < 1e-6
    assert "| case | solver |" in capsys.readouterr().out
