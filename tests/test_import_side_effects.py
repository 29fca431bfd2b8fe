"""Importing jointdyn changes no process-wide numba setting; its -O1 level and its cache
directory apply to jointdyn's own kernels only [T225]. Run in a fresh interpreter with a private
cache home, so that what numba compiles and where it caches is observed from the start."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap

PROBE = textwrap.dedent(
    """
    import json, sys
    import numba
    from numba.core import config, event

    def snapshot():
        return {k: repr(getattr(config, k)) for k in dir(config) if k.isupper()}

    before = snapshot()
    import jointdyn, jointdyn.cli, jointdyn.film.kernels as k
    after_import = snapshot()

    seen = []

    class Record(event.Listener):
        def on_start(self, ev):
            f = ev.data["dispatcher"].py_func
            seen.append((f.__module__, int(config.OPT)))

        def on_end(self, ev):
            pass

    event.register("numba:compile", Record())
    import numpy as np

    k.ott_force(0.5, 0.1, 100.0, 0.1, 0.01, 0.02, 1e-4, np.zeros(0), np.zeros((1, 2)))
    sys.path.insert(0, sys.argv[1])
    import user_kernel

    user_kernel.twice(2.0)
    print(json.dumps({
        "changed_by_import": sorted(k for k in before if before[k] != after_import[k]),
        "changed_after_compiling": sorted(k for k in before if before[k] != snapshot()[k]),
        "seen": seen,
        "cache_root": str(jointdyn.core.compiled.cache_root()),
    }))
    """
)


def test_import_leaves_numba_configuration_unchanged(tmp_path):
    (tmp_path / "user_kernel.py").write_text(
        "import numba\n\n\n@numba.njit(cache=True)\ndef twice(x):\n    return 2.0 * x\n"
    )
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_OPT", "NUMBA_CACHE_DIR")}
    env["XDG_CACHE_HOME"] = str(tmp_path / "cache")
    out = subprocess.run(
        [sys.executable, "-c", PROBE, str(tmp_path)], env=env, capture_output=True, text=True, timeout=300
    )
    assert out.returncode == 0, out.stderr[-3000:]
    r = json.loads(out.stdout.strip().splitlines()[-1])
    assert r["changed_by_import"] == []
    assert r["changed_after_compiling"] == []  # the level is restored after each compilation
    levels = dict(r["seen"])
    assert levels["jointdyn.film.kernels"] == 1  # jointdyn's kernels: -O1 [T171]
    assert levels["user_kernel"] == 3  # anybody else's: numba's default, untouched
    # jointdyn's kernels cache in its own directory; the user's function where numba puts it
    ours = [p.name for p in (tmp_path / "cache").rglob("*.nbi")]
    assert any(n.startswith("kernels.ott_force") for n in ours), ours
    assert not any(n.startswith("user_kernel") for n in ours), ours
    assert list((tmp_path / "__pycache__").glob("user_kernel.twice*.nbi"))
    assert r["cache_root"].startswith(str(tmp_path / "cache"))
