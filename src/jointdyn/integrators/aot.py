"""The step loops and the model-independent kernels compiled ahead of time, at install [T382].

Since [T379] the packed system has one numba type for every model (the element code is reached
by address), so the step loop of a method (:func:`jointdyn.integrators.driver.loop`: the driver
with the method's attempt, the right-hand side, the system Jacobian, the projection and the
accepted-step hooks) is the same machine code for every model, and so are the output samples,
the accuracy guard's resolution check and the assembly's projection. :func:`build` compiles them
once, when the package is built (``setup.py``, numba's ``pycc``), into the extension module
``jointdyn.integrators._loops``; a first run then compiles only its model's kernel set. The
kernel sets stay compiled at first use and are called by address from the compiled loop exactly
as from the just-in-time one.

The module is used only when it was built from these sources, by this numba, for this CPU
(:func:`build_key`, exported by the module as ``key``), and for a call whose argument types are
those it was built for (:func:`compiled`; callers use :func:`jointdyn.core.precompiled.call`);
otherwise the function is compiled just in time as before. Building needs a C compiler; where
the build fails the package installs without the module and runs just in time. :func:`status`
says which case holds (``jointdyn cache info``).
"""

from __future__ import annotations

import hashlib
from functools import cache

import numpy as np

from jointdyn.core.precompiled import register

#: (method, exact Jacobian) of the loops compiled ahead of time: the defaults of the shipped
#: models (dopri5 for perfect and dry joints, radau5 with the exact Jacobian for films)
LOOPS = (("dopri5", 0), ("radau5", 1))
MODULE = "jointdyn.integrators._loops"


def build_key() -> int:
    """A 62-bit integer of the package sources (as the kernel cache's, [T225]), the numba version
    and the CPU: a module built from other sources, by another numba or for another kind of
    machine is not used."""
    import numba

    from jointdyn.core.compiled import _source_hash

    h = hashlib.sha1(f"{_source_hash()} numba {numba.__version__} {_host_cpu()}".encode())
    return int.from_bytes(h.digest()[:8], "little") >> 2


def _host_cpu() -> str:
    """This machine's CPU name and features: the module is compiled for them (as numba's own
    cache is), so a checkout shared with another kind of machine compiles there instead."""
    from llvmlite import binding

    return f"{binding.get_host_cpu_name()} {binding.get_host_cpu_features().flatten()}"


def _steppers() -> dict:
    from jointdyn.integrators import SOLVERS

    return {name: SOLVERS[name][0] for name, _ in LOOPS}


def _packed():
    """A packed system of the types ``System.packed`` builds (values irrelevant)."""
    from jointdyn.multibody.system import Packed

    f, i = np.zeros(1), np.zeros(1, dtype=np.int64)
    f2, i2, f3 = np.zeros((1, 1)), np.zeros((1, 1), dtype=np.int64), np.zeros((1, 1, 1))
    return Packed(f, f, i2, f2, i2, f2, f3, 0, f, f, i)


@cache
def entries() -> dict:
    """Export name -> (the just-in-time function, sample arguments of the types its callers
    pass): the loops of :data:`LOOPS` (``driver.drive``) and the functions called from Python once
    per run or per model (the output samples, the accuracy guard, the assembly)."""
    from jointdyn.core.constraints import eval_constraints
    from jointdyn.integrators.accuracy import worst_resolution
    from jointdyn.integrators.driver import loop, new_work
    from jointdyn.multibody.dynamics import outputs, project_positions, project_velocities
    from jointdyn.multibody.jacobian import jacobian_work_size

    P, t = _packed(), np.zeros(2)
    f1, f2, f3, i1, i2 = np.zeros(1), np.zeros((1, 1)), np.zeros((1, 1, 1)), np.zeros(1, np.int64), P.cint
    out: dict = {}
    for name, exact in LOOPS:
        stepper = _steppers()[name]
        fn = loop(stepper, exact)
        w = new_work(stepper, np.zeros(2), np.zeros((1, 1)), 0.0, t, 0.0)  # the same types with exact
        out[f"{fn.py_func.__qualname__}_{exact}"] = (fn, (P, t, 0.0, 0.0, 0.0, 0, True, 0, w))
    out["outputs"] = (outputs, (f1, f2, f3, P, True))
    out["worst_resolution"] = (worst_resolution, (f1, f2, f3, P, 0.0, 0.0, i1, f1))
    out["project_positions"] = (project_positions, (0.0, f1, f1, f1, i2, f2, 0, 0.0, 0))  # assembly
    out["project_velocities"] = (project_velocities, (0.0, f1, f1, f1, i2, f2, 0))
    out["eval_constraints"] = (eval_constraints, (0.0, f1, f1, i2, f2, f1, f2, f1, f1))
    out["jacobian_work_size"] = (jacobian_work_size, (0, 0, 0))
    return out


def types_of(args: tuple) -> tuple:
    """The numba types of a call's arguments."""
    from numba import typeof

    return tuple(typeof(a) for a in args)


_SCALARS = {float: "f8", np.float64: "f8", int: "i8", np.int64: "i8", bool: "b1", np.bool_: "b1"}


def _key(a):
    """What determines the numba type of ``a``, found faster than ``numba.typeof`` (≈ 6 µs per
    array: a loop's 40 arrays would cost 0.25 ms per call): an array's dtype, dimensions, layout
    (numba's rule: C, else F, else A), writeability and alignment; a named tuple's class and
    fields; a float, integer or boolean scalar; anything else, its numba type."""
    if isinstance(a, np.ndarray):
        f = a.flags
        layout = "C" if f.c_contiguous else "F" if f.f_contiguous else "A"
        return (type(a), a.dtype.str, a.ndim, layout, f.writeable, f.aligned)
    if isinstance(a, tuple) and hasattr(a, "_fields"):
        return (type(a), *map(_key, a))
    kind = _SCALARS.get(type(a))
    if kind is not None:
        return kind
    from numba import typeof

    return typeof(a)


@cache
def _built_types(name: str) -> tuple:
    return types_of(entries()[name][1])


@cache
def _built_keys(name: str) -> tuple:
    return tuple(map(_key, entries()[name][1]))


@cache
def _names() -> dict:
    return {fn: name for name, (fn, _) in entries().items()}


_unusable = ["built from other sources, by another numba or for another CPU"]


@cache
def _module():
    """The compiled module if present, loadable and built for these sources, this numba and this
    CPU; None if absent, False if not usable (the reason in ``_unusable``)."""
    import importlib

    try:
        mod = importlib.import_module(MODULE)
    except ModuleNotFoundError:
        return None
    except Exception as err:  # present but not loadable here: compile at first use, and say why
        _unusable[0] = f"present but not loadable ({err})"
        return False
    return mod if mod.key() == build_key() else False


def status() -> str:
    """One line: whether the functions compiled ahead of time are used, and if not, why."""
    mod = _module()
    loops = ", ".join(f"{n}{' (exact Jacobian)' if e else ''}" for n, e in LOOPS)
    if mod is None:
        return f"not built at install: the step loops ({loops}) compile at first use"
    if mod is False:
        return f"{_unusable[0]}: the step loops ({loops}) compile at first use"
    return f"compiled at install: the step loops ({loops}), the output samples and the assembly"


def compiled(fn, args: tuple):
    """The ahead-of-time copy of the just-in-time function ``fn`` for a call with ``args``, or
    ``fn`` itself (no module, a stale one, no copy of ``fn``, other argument types)."""
    mod = _module()
    name = _names().get(fn) if mod else None
    if name is None or tuple(map(_key, args)) != _built_keys(name):
        return fn
    return getattr(mod, name)


register(compiled)  # core.precompiled.call goes through the copies from now on


def build(output: str) -> None:
    """Compile :func:`entries` into the extension module file ``output`` (numba's ``pycc``)."""
    import os

    import numba
    from numba.pycc import CC

    cc = CC(MODULE.rsplit(".", 1)[1])
    cc.output_dir = os.path.dirname(os.path.abspath(output))
    cc.output_file = os.path.basename(output)
    cc.target_cpu = "host"  # this machine's CPU model and its features (pycc's default: generic)
    key = build_key()
    cc.export("key", numba.int64())(lambda: key)
    for name, (fn, _) in entries().items():
        cc.export(name, _built_types(name))(fn.py_func)
    from numba.core import config

    from jointdyn.core.compiled import OPT_LEVEL

    saved, config.OPT = config.OPT, config._OptLevel(OPT_LEVEL)  # the level of the kernels [T171]
    try:
        cc.compile()
    finally:
        config.OPT = saved
