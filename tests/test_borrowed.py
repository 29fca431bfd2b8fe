"""Borrowed arrays (no reference counting inside compiled loops) [T208]: same data, no leak, no
early free."""

import sys
import warnings

import numpy as np
import pytest
from numba import njit
from numba.core.runtime import _nrt_python, rtsys

from jointdyn.core.borrowed import borrowed
from jointdyn.integrators.dopri5 import DOPRI5
from jointdyn.integrators.driver import drive, new_work, run, start
from jointdyn.integrators.radau5 import RADAU5
from jointdyn.models.slider_crank import slider_crank


@njit
def _write_through(a, pair):
    b = borrowed(a)
    p = borrowed(pair)
    b[1] = 7.0
    p[0][0] = 3.0
    return p[1] + b.sum()


@njit
def _sum_view(a):
    return borrowed(a)[1:].sum()


def test_borrowed_views_share_the_callers_data():
    a = np.arange(4.0)
    pair = (np.zeros(2), 5)
    out = _write_through(a, pair)
    assert a[1] == 7.0 and pair[0][0] == 3.0  # writes reach the caller's arrays: a view, not a copy
    assert out == 5 + 0.0 + 7.0 + 2.0 + 3.0
    assert _sum_view(a) == 12.0


def _dry():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return slider_crank(joint="dry").compile()


@pytest.fixture
def nrt_stats():
    """numba's allocation counters switched on for the test (off by default)."""
    was_on = _nrt_python.memsys_stats_enabled()
    _nrt_python.memsys_enable_stats()
    yield
    if not was_on:
        _nrt_python.memsys_disable_stats()


def test_driver_keeps_reference_counts_balanced(nrt_stats):
    """The step loop borrows the packed system, the work arrays and the output times: after a run
    every numba allocation is freed (no leak) and the caller's arrays keep their Python reference
    counts (nothing was released that the caller owns). RADAU5 with the exact Jacobian, simulate's
    default (the kernel set tests/test_integrators_radau5.py compiles too [T373])."""
    system = _dry()
    P = system.packed(0.0)
    t_out = np.linspace(0.0, 0.02, 41)
    for method in (DOPRI5, RADAU5):
        args = (P, system.y0, system.mem0, 0.0, t_out, 1e-6, 1e-8, 0.0, np.inf, 10**6, True)
        run(method, *args, exact_jacobian=True)  # compile
        w = new_work(method, system.y0, system.mem0, 0.0, t_out, 0.0, exact_jacobian=True)
        counts = [sys.getrefcount(a) for a in (*w, *P[:7], P.ws, t_out)]
        before = rtsys.get_allocation_stats()
        start(method, P, True, w)
        drive(method, P, t_out, 1e-6, 1e-8, np.inf, 10**6, True, 2**62, w)
        after = rtsys.get_allocation_stats()
        assert after.alloc - before.alloc == after.free - before.free  # every allocation freed
        assert after.mi_alloc - before.mi_alloc == after.mi_free - before.mi_free
        assert [sys.getrefcount(a) for a in (*w, *P[:7], P.ws, t_out)] == counts
        assert w.stats[1] > 0 and np.isfinite(w.Y).all()


def test_step_loop_and_outputs_allocate_nothing_per_step(nrt_stats):
    """The DOPRI5 loop of a dry run (projection after every accepted step included) and the output
    samples allocate a fixed number of arrays, independent of the number of steps and samples
    [T208]: the same count for a run 4× longer."""
    from jointdyn.multibody.dynamics import outputs

    system = _dry()
    P = system.packed(0.0)
    counts = []
    for t_end in (0.005, 0.02):  # 0.02 s: through the first impacts (contact and free flight)
        t_out = np.linspace(0.0, t_end, 201)
        w = new_work(DOPRI5, system.y0, system.mem0, 0.0, t_out, 0.0)
        start(DOPRI5, P, True, w)
        before = rtsys.get_allocation_stats()
        drive(DOPRI5, P, t_out, 1e-7, 1e-9, np.inf, 10**6, True, 2**62, w)
        middle = rtsys.get_allocation_stats()
        outputs(t_out, w.Y, w.MEM, P, True)
        after = rtsys.get_allocation_stats()
        counts.append((middle.alloc - before.alloc, after.alloc - middle.alloc, int(w.stats[1])))
    (loop_a, out_a, steps_a), (loop_b, out_b, steps_b) = counts
    assert steps_b > 2 * steps_a  # the longer run takes more steps …
    assert (loop_a, out_a) == (loop_b, out_b)  # … and allocates no more arrays
