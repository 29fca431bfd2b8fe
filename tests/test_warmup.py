"""``jointdyn warmup``: the kernels a model's run needs are compiled by the warm-up, so the run
itself compiles nothing [T226]."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest
from typer.testing import CliRunner

from jointdyn.cli import app

RUN = """
import json
from numba.core import event
from jointdyn.studies.runs import run_shipped
n = []
class C(event.Listener):
    def on_start(self, ev): n.append(1)
    def on_end(self, ev): pass
event.register("numba:compile", C())
run_shipped("slider-crank", "perfect", revs=0.1)
print(len(n))
"""


def test_warmup_refuses_an_unknown_target_before_any_work(tmp_path):
    r = CliRunner().invoke(app, ["warmup", "perfect", str(tmp_path / "missing.toml")])
    assert r.exit_code == 2
    assert "neither a shipped joint" in r.output and "missing.toml" in r.output


@pytest.mark.slow
def test_a_run_after_warmup_compiles_nothing(tmp_path):
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_OPT", "NUMBA_CACHE_DIR")}
    env["XDG_CACHE_HOME"] = str(tmp_path)  # an empty cache
    w = subprocess.run(
        [sys.executable, "-m", "jointdyn", "warmup", "perfect", "--processes", "1"],
        env=env,
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert w.returncode == 0, w.stderr[-3000:]
    assert "perfect:" in w.stdout and " 0 compilations" not in w.stdout  # it compiled
    r = subprocess.run([sys.executable, "-c", RUN], env=env, capture_output=True, text=True, timeout=900)
    assert r.returncode == 0, r.stderr[-3000:]
    assert int(r.stdout.split()[-1]) == 0  # a longer run of the same model: all loaded


def test_targets_of_one_method_share_a_compiled_loop():
    """The warm-up's first wave takes one target per (solver, Jacobian kind) [T379]: the dry and
    perfect joints share dopri5's loop, the lubricated joints radau5's."""
    from jointdyn.studies.warmup import chain_of

    assert chain_of("perfect") == chain_of("dry") != chain_of("ott") == chain_of("alshaer2005")
    assert chain_of("perfect")[0] == "dopri5" and chain_of("ott")[0] == "radau5"
