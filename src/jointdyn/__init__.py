"""jointdyn: planar multibody dynamics with ideal, clearance and lubricated joints.

The front door::

    from jointdyn import SimConfig, load, simulate, slider_crank

    res = simulate(slider_crank("alshaer2005").compile(), SimConfig(t_end=0.048, n_out=2881))
    res.save("run.nc")
    res = load("run.nc")  # Results again: res.element(...), jointdyn.post.* work on it

Note: ``jointdyn.simulate`` is the function; its module is :mod:`jointdyn.simulation.simulate`.
Importing jointdyn changes no global state (numba's settings apply to jointdyn's own kernels
only, :mod:`jointdyn.core.compiled`).
"""

from __future__ import annotations

from jointdyn.core import compiled as _compiled

_compiled.install()  # numba settings for jointdyn's own kernels only, before any is defined [T225]

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
