"""Kernel sets [T379]: element kernels compiled per combination of kinds, called by address, so
the compiled driver is shared by every model."""

import pickle
from dataclasses import replace

import numpy as np
import pytest
from numba import njit

from jointdyn.core import precompiled
from jointdyn.forces.elements import kinds_of
from jointdyn.forces.kernel_set import (
    SLOTS,
    call_forces,
    call_step_limit,
    compiled_address,
    kernel_addresses,
    kernel_kinds,
)
from jointdyn.integrators import driver
from jointdyn.integrators.dopri5 import DOPRI5
from jointdyn.multibody.dynamics import rhs
from jointdyn.multibody.jacobian import system_jacobian
from jointdyn.simulation.simulate import simulate
from jointdyn.studies.runs import model_system


def _system(joint):
    return model_system("slider-crank", {"joint": joint}, revs=0.05)


def test_models_of_different_kinds_share_one_compiled_loop(monkeypatch):
    """The dry joint (journal element with a contact law) and the perfect joint (no element)
    run through the same compiled dopri5 loop: one signature, not one per kinds (compiled at
    first use here: the copy compiled at install is set aside [T382])."""
    monkeypatch.setattr(precompiled, "_lookup", lambda fn, args: fn)
    systems = {joint: _system(joint) for joint in ("perfect", "dry")}
    assert kinds_of(systems["perfect"][0].fint) != kinds_of(systems["dry"][0].fint)
    for system, cfg in systems.values():
        simulate(system, replace(cfg, solver="dopri5"))
    compiled = driver.loop(DOPRI5, 0)
    assert len(compiled.signatures) == 1, compiled.signatures


def test_a_set_is_compiled_once_per_kinds_and_knows_its_kinds():
    system, _ = _system("dry")
    kinds = system.kinds()
    a, b = kernel_addresses(kinds), system.packed().kernels
    assert a is b and a.shape == (len(SLOTS),) and a.dtype == np.int64
    assert kernel_kinds(a) == kinds
    assert (np.delete(a, list(SLOTS).index("jacobian")) != 0).all()


def test_the_exact_jacobian_is_compiled_on_request_and_an_unset_slot_raises():
    """A packed system whose exact element Jacobian was never asked for raises a clear error
    when the Jacobian is called (no jump to address 0); asked for, it works."""
    system, _ = _system("ott")
    y = system.y0.copy()
    nn = y.size
    args = (0.0, y, np.empty(nn), system.mem0.copy())
    scratch = (np.empty((nn, nn)), np.empty(nn), np.empty(nn), np.empty(nn))
    P = system.packed(jacobian=True)
    unset = P.kernels.copy()
    unset[list(SLOTS).index("jacobian")] = 0  # as packed without asking for it
    with pytest.raises(RuntimeError, match="Jacobian not compiled"):
        system_jacobian(*args, P._replace(kernels=unset), *scratch)
    P = system.packed(jacobian=True)
    assert P.kernels[list(SLOTS).index("jacobian")] != 0
    assert system_jacobian(*args, P, *scratch) == 0
    assert np.isfinite(scratch[0]).all()


def test_rhs_through_the_kernel_set_equals_the_static_dispatch():
    """The right-hand side with the element forces called by address gives the bits of the
    element loop compiled with the kinds in its type (the dispatch before [T379])."""
    from jointdyn.forces.elements import NOUT, eval_forces

    system, _ = _system("alshaer2005")
    P = system.packed()
    n = system.n
    y, mem = system.y0.copy(), system.mem0.copy()
    y[n:] += 0.1  # a state off the assembled one
    Q1, Q2 = np.zeros(n), np.zeros(n)
    o1, o2 = np.zeros((system.fint.shape[0], NOUT)), np.zeros((system.fint.shape[0], NOUT))
    eval_forces(0.0, y[:n], y[n:], mem, P.fint, P.freal, P.tables, Q1, o1, system.kinds())

    @njit
    def by_address(P, y, mem, Q, out):
        call_forces(P.kernels, (0.0, y[:n], y[n:], mem, P.fint, P.freal, P.tables, Q, out))

    by_address(P, y, mem, Q2, o2)
    np.testing.assert_array_equal(Q1, Q2)
    np.testing.assert_array_equal(o1, o2)
    f = np.empty(2 * n)
    assert rhs(0.0, y, mem, P, f) == 0 and np.isfinite(f).all()


def test_a_packed_system_is_not_pickled():
    """Its kernel addresses belong to this process."""
    system, _ = _system("dry")
    with pytest.raises(TypeError, match="pickle the System"):
        pickle.dumps(system.packed())
    pickle.loads(pickle.dumps(system))  # the system itself travels


@njit
def _raising_limit(q, qd, mem, fint, freal):
    if q[0] < 0.0:
        raise ValueError("negative first coordinate")
    return 2.0 * q[0]


@njit
def _limit_by_address(kernels, q, qd, mem, fint, freal):
    return call_step_limit(kernels, (q, qd, mem, fint, freal))


def test_an_exception_in_a_kernel_reaches_the_caller():
    """The call by address uses numba's calling convention: a kernel's exception propagates
    through the compiled caller to Python with its type and message (no crash, no silent value)."""
    kernels = np.zeros(len(SLOTS), dtype=np.int64)
    kernels[list(SLOTS).index("step_limit")] = compiled_address(_raising_limit, SLOTS["step_limit"])
    q, mem, fint, freal = np.ones(3), np.zeros((1, 1)), np.zeros((1, 1), dtype=np.int64), np.zeros((1, 1))
    assert _limit_by_address(kernels, q, q, mem, fint, freal) == 2.0
    with pytest.raises(ValueError, match="negative first coordinate"):
        _limit_by_address(kernels, -q, q, mem, fint, freal)


def test_a_call_with_wrong_argument_types_is_refused_when_compiled():
    """The call checks, when its caller is compiled, that the kernel set is an int64 array and
    that each argument converts to the kernel's signature (a wrong type never reaches the
    machine code)."""
    from numba.core.errors import TypingError

    q, mem, fint, freal = np.ones(3), np.zeros((1, 1)), np.zeros((1, 1), dtype=np.int64), np.zeros((1, 1))
    with pytest.raises(TypingError, match="expected Packed.kernels"):
        _limit_by_address(np.zeros(len(SLOTS)), q, q, mem, fint, freal)
    with pytest.raises(TypingError, match="argument 2 is array\\(int64"):
        _limit_by_address(np.zeros(len(SLOTS), dtype=np.int64), q, q, fint, fint, freal)
