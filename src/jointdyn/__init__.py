"""jointdyn: planar multibody dynamics with ideal, clearance and lubricated joints.

The front door::

    from jointdyn import SimConfig, load, simulate, slider_crank

    res = simulate(slider_crank("alshaer2005").compile(), SimConfig(t_end=0.048, n_out=2881))
    res.save("run.nc")
    res = load("run.nc")  # Results again: res.element(...), jointdyn.post.* work on it

Note: ``jointdyn.simulate`` is the function; the module is ``sys.modules["jointdyn.simulate"]``
(``from jointdyn.simulation.simulate import SimConfig`` keeps working).
"""

from __future__ import annotations

_NUMBA_OPT = 1
"""LLVM optimisation level of the compiled kernels unless ``NUMBA_OPT`` is set (numba's default
is 3). Measured [T171]: level 1 compiles the first run ≈ 10–20 % faster and runs the kernels
faster (small loops over a few coordinates gain nothing from -O3's unrolling and
vectorisation); IEEE semantics are kept at every level, so trajectories are bit-identical."""


def _numba_opt() -> None:
    import os

    if "NUMBA_OPT" in os.environ:
        return
    import numba
    from numba.core.config import _OptLevel

    numba.config.OPT = _OptLevel(_NUMBA_OPT)


def _numba_cache_dir() -> None:
    """Key numba's on-disk cache to a hash of this package's sources.

    numba invalidates a cached function only when *its own* file changes, not when a compiled
    function it calls (in another module) does; a stale cache then silently runs old code. A
    cache directory per source hash makes every edit or upgrade start clean. An explicit
    ``NUMBA_CACHE_DIR`` is respected (e.g. the cold-start benchmark)."""
    import hashlib
    import os
    from pathlib import Path

    _numba_opt()
    if os.environ.get("NUMBA_CACHE_DIR"):
        return
    h = hashlib.sha1()
    h.update(os.environ.get("NUMBA_OPT", "jointdyn").encode())  # code of another opt level
    root = Path(__file__).parent
    for f in sorted(root.rglob("*.py")):
        h.update(f.relative_to(root).as_posix().encode())
        h.update(f.read_bytes())
    base = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "jointdyn"
    try:
        target = base / f"numba-{h.hexdigest()[:16]}"
        target.mkdir(parents=True, exist_ok=True)
    except OSError:  # read-only home: fall back to numba's default (__pycache__)
        return
    import numba

    numba.config.CACHE_DIR = str(target)


_numba_cache_dir()

from importlib.metadata import PackageNotFoundError as _PNF  # noqa: E402
from importlib.metadata import version as _v  # noqa: E402

from jointdyn import post  # noqa: E402
from jointdyn.errors import ModelError, PhysicsWarning, SimulationError  # noqa: E402
from jointdyn.models.slider_crank import slider_crank  # noqa: E402
from jointdyn.multibody.model import Model  # noqa: E402
from jointdyn.multibody.system import System  # noqa: E402
from jointdyn.simulation.results import Results  # noqa: E402
from jointdyn.simulation.simulate import SimConfig, simulate  # noqa: E402

try:
    __version__ = _v("jointdyn")
except _PNF:  # pragma: no cover - running from an uninstalled source tree
    __version__ = "unknown"

load = Results.load


def __getattr__(name: str):
    # model files (pydantic, ~0.15 s to import) only when used: the CLI's shipped models skip it
    if name == "load_model":
        from jointdyn.io.modelfile import load_model

        return load_model
    raise AttributeError(f"module 'jointdyn' has no attribute {name!r}")


__all__ = [
    "Model",
    "ModelError",
    "PhysicsWarning",
    "Results",
    "SimConfig",
    "SimulationError",
    "System",
    "__version__",
    "load",
    "load_model",
    "post",
    "simulate",
    "slider_crank",
]
