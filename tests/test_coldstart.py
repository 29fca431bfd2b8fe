"""First run: a run compiles only its own method, and the compiled driver is found in the
on-disk cache by the next process (its cache key must not depend on the process)."""

import json
import os
import subprocess
import sys
import textwrap

import pytest

from jointdyn.integrators.driver import _ENTRIES, DOPRI5, METHODS

CHILD = textwrap.dedent(
    """
    import json, sys
    from numba.core import event as ev
    names = []
    class L(ev.Listener):
        def on_start(self, e):
            pass
        def on_end(self, e):
            f = e.data["dispatcher"].py_func
            names.append(f.__module__ + "." + f.__qualname__)
    ev.register("numba:compile", L())
    from jointdyn.models import slider_crank as sc
    from jointdyn.runs import slider_crank_config
    from jointdyn.simulate import simulate
    res = simulate(sc.slider_crank("perfect").compile(), slider_crank_config("perfect", 0.02, solver=sys.argv[1]))
    print(json.dumps(names))
    """
)


def _compiled(solver: str, cache: str) -> list[str]:
    env = dict(os.environ, NUMBA_CACHE_DIR=cache, XDG_CACHE_HOME=cache)
    p = subprocess.run(
        [sys.executable, "-c", CHILD, solver], env=env, capture_output=True, text=True, check=True
    )
    return json.loads(p.stdout.strip().splitlines()[-1])


def test_one_entry_point_per_method_and_jacobian():
    """dopri5 needs no Jacobian: one entry; every stiff method one per Jacobian kind."""
    assert {m for m, _ in _ENTRIES} == set(METHODS.values())
    assert (DOPRI5, 1) not in _ENTRIES
    assert len({id(f) for f in _ENTRIES.values()}) == len(_ENTRIES) == 1 + 3 * 2


@pytest.mark.slow
def test_dopri5_run_compiles_no_stiff_method_and_is_cached(tmp_path):
    cold = _compiled("dopri5", str(tmp_path))
    assert any(n.endswith("drive_method") for n in cold)
    assert any(n.endswith("attempt_dopri5") for n in cold)
    stiff = ("attempt_rodas4", "attempt_ros34pw2", "attempt_radau5", "system_jacobian", "rodas4.jacobian")
    assert not [n for n in cold if n.endswith(stiff)]
    # a second process finds everything in the cache: nothing is compiled again
    assert _compiled("dopri5", str(tmp_path)) == []
