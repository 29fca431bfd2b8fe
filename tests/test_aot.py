"""The step loops and model-independent kernels compiled ahead of time at install [T382]: built
for the argument types a run passes, the same arithmetic as the just-in-time functions, used only
when built from these sources, and a clear fallback otherwise.

The tests that need the module skip where it is absent or stale (a checkout edited since its
``pip install -e .``); on a fresh install (CI) they run."""

from __future__ import annotations

import numpy as np
import pytest

from jointdyn.core import precompiled
from jointdyn.forces.kernel_set import INDEX
from jointdyn.integrators import aot, driver
from jointdyn.integrators.radau5 import RADAU5
from jointdyn.models.slider_crank import slider_crank, slider_crank_config
from jointdyn.multibody.dynamics import outputs
from jointdyn.simulation.simulate import simulate

built = pytest.mark.skipif(not aot._module(), reason=aot.status())


_USED: set = set()


def _just_in_time(fn, args):
    _USED.add(fn)
    return fn


def test_every_call_of_a_run_has_the_types_its_copy_was_built_for(monkeypatch):
    """A π-film and a dry run (radau5 with the exact Jacobian, dopri5) call every function that has
    a copy, each with exactly the argument types the copy is built for (a field added to the packed
    system or to the work record would change both or fail here)."""
    seen = []

    def spy(fn, args):
        seen.append((fn, aot.types_of(args), tuple(map(aot._key, args))))
        return aot.compiled(fn, args)

    monkeypatch.setattr(precompiled, "_lookup", spy)
    for joint in ("alshaer2005", "dry"):
        simulate(slider_crank(joint).compile(), slider_crank_config(joint, revs=0.02, samples_per_rev=200))
    names = aot._names()
    assert {names[fn] for fn, *_ in seen if fn in names} == set(aot.entries())
    for fn, types, keys in seen:
        if fn in names:  # numba's types, and the faster key the choice is made by
            assert types == aot._built_types(names[fn]) and keys == aot._built_keys(names[fn]), names[fn]


@built
def test_a_run_through_the_copies_equals_the_just_in_time_run(monkeypatch):
    """Same arithmetic: the π-film (radau5, exact Jacobian) and dry (dopri5) slider-crank give
    bit-identical states, multipliers, accelerations and element outputs either way."""
    for joint in ("alshaer2005", "dry"):
        system = slider_crank(joint).compile()
        cfg = slider_crank_config(joint, revs=0.1, samples_per_rev=360)
        a = simulate(system, cfg)
        monkeypatch.setattr(precompiled, "_lookup", _just_in_time)
        b = simulate(system, cfg)
        monkeypatch.setattr(precompiled, "_lookup", aot.compiled)
        for name in ("y", "lam", "qdd", "eout"):
            assert np.array_equal(getattr(a, name), getattr(b, name)), (joint, name)
        assert a.stats == b.stats
    loops = {fn for name, (fn, _) in aot.entries().items() if name.startswith("drive_")}
    assert loops <= _USED  # the second run of each went through the just-in-time loop
    assert all(fn.signatures for fn in loops)


@built
def test_an_error_raised_in_a_copy_reaches_python():
    """An exception raised in compiled code under the copy (here the call of an element Jacobian
    that was never compiled) reaches Python with its type and message."""
    system = slider_crank("alshaer2005").compile()
    P = system.packed(jacobian=True)
    unset = P.kernels.copy()
    unset[INDEX["jacobian"]] = 0
    t_out = np.linspace(0.0, 1e-4, 3)
    w = driver.new_work(RADAU5, system.y0, system.mem0, 0.0, t_out, 0.0, True)
    args = (P._replace(kernels=unset), t_out, 1e-6, 1e-9, 1.0, 100, True, 100, w)
    fn = aot.compiled(driver.loop(RADAU5, 1), args)
    assert fn is not driver.loop(RADAU5, 1)
    with pytest.raises(RuntimeError, match="Jacobian not compiled"):
        fn(*args)


@built
def test_other_argument_types_go_to_the_just_in_time_function():
    """A call whose types differ from the copy's (a Fortran-ordered array) is not converted: it
    goes to the just-in-time function, which compiles for it."""
    P = aot._packed()
    args = (np.zeros(2), np.zeros((2, 2)), np.zeros((2, 1, 1)), P, False)
    assert aot.compiled(outputs, args) is not outputs
    fortran = (np.zeros(2), np.asfortranarray(np.zeros((2, 2))), np.zeros((2, 1, 1)), P, False)
    assert aot.compiled(outputs, fortran) is outputs
    readonly = np.zeros(2)
    readonly.flags.writeable = False
    assert aot.compiled(outputs, (readonly, *args[1:])) is outputs
    assert aot.compiled(outputs, (np.zeros(2, np.float32), *args[1:])) is outputs


def test_a_module_built_from_other_sources_is_not_used(monkeypatch):
    """Built from other sources or by another numba (its key differs): not used, and said so."""
    monkeypatch.setattr(aot, "build_key", lambda: -1)
    aot._module.cache_clear()
    try:
        assert not aot._module()
        args = (np.zeros(2), np.zeros((2, 2)), np.zeros((2, 1, 1)), aot._packed(), False)
        assert aot.compiled(outputs, args) is outputs
        assert "compile at first use" in aot.status()
    finally:
        monkeypatch.undo()
        aot._module.cache_clear()
