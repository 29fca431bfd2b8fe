"""One kernel set for several models [T341]: the union of element kinds, same arithmetic."""

import numpy as np

from jointdyn.forces.elements import kinds_of, kinds_union
from jointdyn.multibody.system import shared_kinds
from jointdyn.simulation.simulate import simulate
from jointdyn.studies.runs import model_system


def _system(joint):
    return model_system("slider-crank", {"joint": joint}, revs=0.1)


def test_union_takes_present_kinds_and_keeps_own_identities():
    assert kinds_union((None, 1, None), (None, None, 1)) == (None, 1, 1)
    assert kinds_union((None, "a"), (None, "b")) == (None, "a")  # own identity kept
    assert kinds_union((None, 1), (None, 1, 1)) == (None, 1)  # another registry: own kinds


def test_perfect_run_compiled_for_the_journal_kinds_is_bit_identical():
    perfect, cfg = _system("perfect")
    dry, _ = _system("dry")
    own = kinds_of(perfect.fint)
    assert all(k is None for k in own)  # no force elements
    alone = simulate(perfect, cfg)
    with shared_kinds(dry):
        shared = perfect.kinds()
        assert shared == kinds_union(own, kinds_of(dry.fint)) != own
        together = simulate(perfect, cfg)
    assert perfect.kinds() == own  # the block ends with its context
    for name in ("t", "y", "qdd", "lam", "drift"):
        np.testing.assert_array_equal(getattr(together, name), getattr(alone, name), err_msg=name)
    assert together.stats["rhs_evaluations"] == alone.stats["rhs_evaluations"]


def test_worker_processes_pack_for_the_parents_shared_kinds():
    """Pool workers started inside a shared_kinds block use its kinds (so they load the kernels
    the parent compiled) [T322]; outside one, none."""
    from jointdyn.io.pool import run_local
    from jointdyn.multibody.system import shared_kinds_now

    dry, _ = _system("dry")
    got = {}
    with shared_kinds(dry):
        run_local(shared_kinds_now, [("in", ())], 1, got.__setitem__)
        assert got["in"] == kinds_of(dry.fint)
    run_local(shared_kinds_now, [("out", ())], 1, got.__setitem__)
    assert got["out"] is None
