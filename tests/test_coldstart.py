"""First run: a run compiles only its own method, and the compiled driver is found in the
on-disk cache by the next process (its cache key must not depend on the process)."""

import json
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from jointdyn.forces.elements import FORCE_ELEMENTS
from jointdyn.integrators import SOLVERS
from jointdyn.integrators.driver import Stepper, loop

# a child script's prelude: records the name of every function numba compiles in `names`
LISTENER = """
    from numba.core import event as ev
    names = []
    class L(ev.Listener):
        def on_start(self, e):
            pass
        def on_end(self, e):
            f = e.data["dispatcher"].py_func
            names.append(f.__module__ + "." + f.__qualname__)
    ev.register("numba:compile", L())
"""

CHILD = textwrap.dedent(
    """
    import json, sys
    """
    + LISTENER
    + """    from jointdyn.models import slider_crank as sc
    from jointdyn.models.slider_crank import slider_crank_config
    from jointdyn.simulation.simulate import simulate
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
    """A method without a Jacobian (dopri5) has one loop; every stiff method one per Jacobian kind,
    each under its own name (its own cache entries), built once."""
    steppers = [r for r, _, _ in SOLVERS.values() if isinstance(r, Stepper)]
    loops = {(s.name, exact): loop(s, exact) for s in steppers for exact in (0, 1)}
    assert loop(SOLVERS["dopri5"][0], 1) is loops["dopri5", 0]
    distinct = {id(f) for f in loops.values()}
    assert len(distinct) == sum(2 if s.reuse is not None else 1 for s in steppers) == 1 + 3 * 2
    assert all(loop(s, 1) is loops[s.name, 1] for s in steppers)  # built once
    names = {f.py_func.__qualname__ for f in loops.values()}
    assert len(names) == len(steppers) and all(f"drive_{s.name}_" in " ".join(names) for s in steppers)


@pytest.mark.slow
def test_dopri5_run_compiles_no_stiff_method_and_is_cached(tmp_path):
    cold = _compiled("dopri5", str(tmp_path))
    assert [n for n in cold if ".drive_" in n] == [n for n in cold if ".drive_dopri5_" in n] != []
    assert any(n.endswith("attempt_dopri5") for n in cold)
    stiff = ("rodas4", "ros34pw2", "radau5", "system_jacobian", "system_jacobian_into", "fd_jacobian")
    assert not [n for n in cold if n.rsplit(".", 1)[0].endswith(stiff[:3]) or n.endswith(stiff[3:])]
    # a model without force elements compiles no element kind and no journal hook [T175]
    journal = (
        "journal_element",
        "penetration",
        "film_force",
        "contact_force",
        "_journal_memory",
        "_journal_step_limit",
    )
    assert not [n for n in cold if n.endswith(journal)]
    # a second process finds everything in the cache: nothing is compiled again
    assert _compiled("dopri5", str(tmp_path)) == []


# ------------------------------------------------------------------ element kinds [T175]
KINDS_CHILD = textwrap.dedent(
    """
    import json, sys
    import numpy as np
    """
    + LISTENER
    + """    from jointdyn.forces.elements import NOUT, eval_forces, kinds_of
    from jointdyn.forces.springs import SpringDamper
    from jointdyn.multibody.model import Model
    m = Model("oscillator", gravity=(0.0, 0.0))
    m.add_ground_point("O", (0.0, 0.0))
    m.add_body("b", 0.2, 1e-3, position=(0.11, 0.0), points={"c": (0.0, 0.0)})
    m.add("spring", SpringDamper("ground", "O", "b", "c", stiffness=1e3, damping=1.0, free_length=0.1))
    s = m.compile()
    Q = np.zeros(s.n)
    eval_forces(0.0, s.y0[:3], s.y0[3:], s.mem0, s.fint, s.freal, s.tables, Q, np.zeros((1, NOUT)),
                kinds_of(s.fint))
    print(json.dumps(names))
    """
)


def test_kinds_tuple_marks_the_codes_present():
    from jointdyn.forces.elements import FORCE_KERNELS, NINT, kinds_of
    from jointdyn.forces.journal import JOURNAL
    from jointdyn.forces.springs import SPRING_DAMPER

    # every registered element type has a compiled kernel for the dispatch
    assert {cls.code for cls in FORCE_ELEMENTS.values()} <= set(FORCE_KERNELS)
    fint = np.zeros((3, NINT), dtype=np.int64)
    fint[:, 0] = [JOURNAL, SPRING_DAMPER, JOURNAL]
    k = kinds_of(fint)
    assert len(k) == max(FORCE_KERNELS) + 1
    assert [c for c, v in enumerate(k) if v is not None] == sorted({JOURNAL, SPRING_DAMPER})
    assert all(v is None for v in kinds_of(fint[:0]))  # no elements (a perfect joint): no kind
    fint[0, 0] = max(FORCE_KERNELS) + 7
    with pytest.raises(ValueError, match="no registered kernel"):
        kinds_of(fint)


def test_spring_model_compiles_only_the_spring_and_is_cached(tmp_path):
    """A model with one spring–damper compiles its kernel and none of the other kinds (journal,
    film, contact, tables, torsion); a second process loads the specialisation from the cache."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path), XDG_CACHE_HOME=str(tmp_path))

    def compiled():
        p = subprocess.run(
            [sys.executable, "-c", KINDS_CHILD], env=env, capture_output=True, text=True, check=True
        )
        return json.loads(p.stdout.strip().splitlines()[-1])

    cold = compiled()
    assert any(n.endswith("elements.eval_forces") for n in cold)
    assert any(n.endswith("springs.spring_damper") for n in cold)
    other = (
        "journal_element",
        "film_force",
        "contact_force",
        "tabulated_force",
        "torsion_spring",
        "harmonic_torque",
    )
    assert not [n for n in cold if n.endswith(other)]
    assert compiled() == []


def _pair_system(element):
    import warnings

    from jointdyn.errors import PhysicsWarning
    from jointdyn.multibody.model import Model

    m = Model("pair", gravity=(0.0, 0.0))
    m.add_body("a", 1.0, 1e-3, position=(0.0, 0.0), points={"A": (0.03, -0.01)})
    m.add_body("b", 1.0, 1e-3, position=(0.05, -0.035), points={"B": (-0.02, 0.015)})
    m.add("el", element)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PhysicsWarning)
        return m.compile(centre_imperfect=False)


@pytest.mark.parametrize(
    "name", sorted(__import__("jointdyn.forces.elements").forces.elements.FORCE_ELEMENTS)
)
def test_kind_specialisation_gives_the_same_forces_as_all_kinds(name):
    """The dispatch over the kinds present runs the same kernel as the one over every kind: equal
    bit for bit (the same floating-point operations in the same order)."""
    from jointdyn.forces.elements import NOUT, eval_forces, kinds_of

    s = _pair_system(FORCE_ELEMENTS[name].example())
    rng = np.random.default_rng(3)
    acts = False
    for _ in range(8):
        q = s.y0[: s.n] + rng.normal(size=s.n) * 1e-3  # ~ a clearance: dry joints in contact too
        qd = rng.normal(size=s.n)
        Q1, Q2 = np.zeros(s.n), np.zeros(s.n)
        o1, o2 = np.zeros((1, NOUT)), np.zeros((1, NOUT))
        eval_forces(0.01, q, qd, s.mem0, s.fint, s.freal, s.tables, Q1, o1)
        eval_forces(0.01, q, qd, s.mem0, s.fint, s.freal, s.tables, Q2, o2, kinds_of(s.fint))
        acts = acts or bool(np.any(Q1 != 0.0))
        np.testing.assert_array_equal(Q1, Q2)
        np.testing.assert_array_equal(o1, o2)
    assert acts  # the element acts at some of these states: the comparison is not of zeros
