"""Ctrl-C during the compute of the film-table commands (issue 28, "long runs, resources,
signals"): before, SIGINT inside a compiled film solve surfaced as numba's "SystemError:
CPUDispatcher(...) returned a result with an exception set" traceback, exit 1; now the signal is
recorded and checked per ε or speed: one line, exit 130, nothing written [T332]."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

SRC = Path(__file__).parents[1] / "src"
COMMANDS = {
    "bearing-table": ["bearing-table", "--ld", "1", "--eps", "0.1:0.95:5000"],
    "stribeck": [
        "stribeck", "--load", "2000", "--radius", "0.02", "--length", "0.02", "--clearance", "2e-5",
        "--viscosity", "0.02", "--speeds", ",".join(str(10 + 10 * i) for i in range(400)),
    ],
}  # fmt: skip


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_ctrl_c_while_computing_is_one_line(tmp_path, name):
    out = tmp_path / "t.csv"
    p = subprocess.Popen(
        [sys.executable, "-c", "import jointdyn_entry as e; e.main()", *COMMANDS[name], "--out", str(out)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=os.environ | {"PYTHONPATH": str(SRC)},
    )
    time.sleep(8.0)  # past the imports (≈ 1.2 s of CPU) into the film solves
    assert p.poll() is None, p.communicate()
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=120)
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert p.returncode == 130 and "Traceback" not in err and len(lines) == 1, err
    assert lines[0].startswith("interrupted by SIGINT")
    assert not out.exists() and not list(tmp_path.glob(".*tmp*"))


def test_ctrl_c_while_a_finite_table_is_built_is_one_line(tmp_path):
    """``film-force --model finite`` builds its film table on first use (≈ 50 s with Reynolds'
    condition): before, the recorded Ctrl-C was checked only after the whole build, then the
    forces were written and the command exited 0; now it is checked per ξ row of the table
    [T336]. A cache directory without film tables (the compiled kernels linked in) makes the
    build cold."""
    from jointdyn.core.compiled import cache_base

    cache = tmp_path / "cache" / "jointdyn"
    cache.mkdir(parents=True)
    for p in cache_base().glob("numba-*"):
        (cache / p.name).symlink_to(p)
    states = tmp_path / "states.csv"
    states.write_text(
        "xi,xi_dot,gamma,gamma_dot,omega_journal,omega_bearing,viscosity,length,radius,clearance\n"
        "0.5,0,0,0,500,0,0.01,0.04,0.01,5e-5\n"
    )
    out = tmp_path / "f.csv"
    argv = ["film-force", str(states), "--model", "finite", "--cavitation", "reynolds", "--out", str(out)]
    # the signal is sent once the build is inside its third ξ row: the child announces each row
    # on stdout (a wrapper that only prints); a fixed sleep raced the build on a quiet machine
    code = (
        "import sys, jointdyn_entry as e, jointdyn.film.finite as f\n"
        "unit = f._fv_unit\n"
        "def announced(*a, **k):\n"
        "    print('row', flush=True)\n"
        "    return unit(*a, **k)\n"
        "f._fv_unit = announced\n"
        "sys.argv = ['jointdyn', *sys.argv[1:]]\n"
        "e.main()\n"
    )
    p = subprocess.Popen(
        [sys.executable, "-c", code, *argv],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=os.environ | {"PYTHONPATH": str(SRC), "XDG_CACHE_HOME": str(tmp_path / "cache")},
    )
    for _ in range(3):
        assert p.stdout.readline().strip() == "row", p.communicate()
    p.send_signal(signal.SIGINT)
    t0 = time.monotonic()
    rest, err = p.communicate(timeout=120)
    waited = time.monotonic() - t0
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert p.returncode == 130 and "Traceback" not in err and len(lines) == 1, err
    assert lines[0].startswith("interrupted by SIGINT") and waited < 15.0, (waited, err)
    rows = 3 + len([ln for ln in rest.splitlines() if ln == "row"])
    assert rows < 40, f"the build ran all {rows} rows: the signal was not checked per row"
    assert not out.exists() and not list(tmp_path.glob(".*tmp*"))
    assert not list((cache / "finite_tables").glob("*"))  # no partial table cached
