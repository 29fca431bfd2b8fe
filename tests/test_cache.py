"""jointdyn's kernel cache is keyed to the content of the sources [T225]: a second process loads
what the first compiled, a reinstall of unchanged sources (new file times) keeps it, an edit
starts a new one; ``jointdyn cache info|clear`` shows and empties it."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

from typer.testing import CliRunner

from jointdyn.cli import app

PKG = Path(__file__).resolve().parents[1] / "src" / "jointdyn"
PROBE = """
import numpy as np
from numba.core import event
import jointdyn.film.kernels as k

n = []


class Count(event.Listener):
    def on_start(self, ev):
        n.append(1)

    def on_end(self, ev):
        pass


event.register("numba:compile", Count())
k.ott_force(0.5, 0.1, 100.0, 0.1, 0.01, 0.02, 1e-4, np.zeros(0), np.zeros((1, 2)))
print(len(n))
"""


def _compilations(src: Path, cache: Path) -> int:
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_OPT", "NUMBA_CACHE_DIR")}
    env.update(XDG_CACHE_HOME=str(cache), PYTHONPATH=str(src))
    out = subprocess.run([sys.executable, "-c", PROBE], env=env, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-3000:]
    return int(out.stdout.split()[-1])


def test_the_cache_is_keyed_to_the_content_of_the_sources(tmp_path):
    src = tmp_path / "src"
    shutil.copytree(PKG, src / "jointdyn", ignore=shutil.ignore_patterns("__pycache__"))
    cache = tmp_path / "cache"
    assert _compilations(src, cache) > 0  # an empty cache: compiled
    assert _compilations(src, cache) == 0  # loaded from the cache
    later = time.time() + 1000.0
    for f in src.rglob("*.py"):  # a reinstall of the same sources: every file time changes
        os.utime(f, (later, later))
    assert _compilations(src, cache) == 0
    kernels = src / "jointdyn" / "film" / "kernels.py"
    kernels.write_text(kernels.read_text() + "\n# an edit\n")
    assert _compilations(src, cache) > 0  # new sources, new cache directory
    assert len(list((cache / "jointdyn").glob("numba-*"))) == 2


def test_cache_info_and_clear(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    base = tmp_path / "jointdyn"
    from jointdyn.core.compiled import cache_root

    stale = base / "numba-0000000000000000"
    (stale / "sub").mkdir(parents=True)
    (stale / "sub" / "f.nbc").write_bytes(b"x" * 1000)
    (base / "finite_tables").mkdir()
    (base / "finite_tables" / "t.npy").write_bytes(b"y" * 500)
    (base / "notes.txt").write_text("not jointdyn's cache")
    cache_root().mkdir(parents=True)
    runner = CliRunner()
    info = runner.invoke(app, ["cache", "info"], terminal_width=200)
    assert info.exit_code == 0, info.output
    assert (
        "stale kernels" in info.output and "film tables" in info.output and cache_root().name in info.output
    )
    r = runner.invoke(app, ["cache", "clear", "--stale"])
    assert r.exit_code == 0 and "removed 1 cache directories" in r.output, r.output
    assert not stale.exists() and (base / "finite_tables").exists() and cache_root().exists()
    r = runner.invoke(app, ["cache", "clear"])
    assert r.exit_code == 0 and "removed 2 cache directories" in r.output, r.output
    assert not (base / "finite_tables").exists() and not cache_root().exists()
    assert (base / "notes.txt").read_text() == "not jointdyn's cache"  # only its own directories
