"""A journal element compiles only the laws and optional pieces its model uses [T322]."""

import json
import os
import subprocess
import sys
import textwrap

import numpy as np
from test_coldstart import LISTENER, _pair_system

from jointdyn.film.models import Finite
from jointdyn.forces.elements import NOUT, eval_forces, journal_laws, kinds_of, kinds_union
from jointdyn.forces.journal import JOURNAL, JournalBearing
from jointdyn.forces.mixed import GreenwoodTrippContact
from jointdyn.forces.thermal import LumpedOil
from jointdyn.studies.runs import model_system

R, C, L = 0.01, 5e-4, 0.04


def _present(family):
    return [c for c, v in enumerate(family) if v is not None]


def test_laws_hold_the_used_laws_and_pieces_and_join_for_shared_kinds():
    lub = model_system("slider-crank", {"joint": "alshaer2005"}, revs=0.1)[0]
    dry = model_system("slider-crank", {"joint": "dry"}, revs=0.1)[0]
    film, contact, friction, thermal, asperity, jfo = journal_laws(lub.fint)
    assert len(_present(film)) == 1 and _present(contact) == [] == _present(friction)
    assert thermal is None and asperity is None and jfo is None
    d = journal_laws(dry.fint)
    assert _present(d[0]) == [] and len(_present(d[1])) == 1
    both = kinds_union(kinds_of(lub.fint), kinds_of(dry.fint))[JOURNAL]
    assert _present(both[0]) == _present(film) and _present(both[1]) == _present(d[1])
    assert both == kinds_union(kinds_of(dry.fint), kinds_of(lub.fint))[JOURNAL]  # symmetric
    el = JournalBearing(
        "a", "A", "b", "B", R + C, R, L, 0.04, film="short",
        thermal=LumpedOil("ISO_VG46", inlet_temp=40.0, heat_capacity=20.0),
        asperity=GreenwoodTrippContact(1e-6),
    )  # fmt: skip
    pieces = journal_laws(_pair_system(el).fint)[3:]
    assert pieces == (1, 1, None)  # thermal, asperity; no jfo film
    assert kinds_union(kinds_of(lub.fint), kinds_of(_pair_system(el).fint))[JOURNAL][3:] == (1, 1, None)
    jfo = JournalBearing("a", "A", "b", "B", R + C, R, L, 0.04, film=Finite(cavitation="jfo"))
    assert journal_laws(_pair_system(jfo).fint)[3:] == (None, None, 1)


def test_bearing_with_both_pieces_gives_the_same_forces_as_every_law():
    """The specialisation with the pieces present runs the same arithmetic as the one compiled
    for every law and piece (kinds None): equal bit for bit, with the pieces acting."""
    el = JournalBearing(
        "a", "A", "b", "B", R + C, R, L, 0.04, film="short",
        thermal=LumpedOil("ISO_VG46", inlet_temp=40.0, heat_capacity=20.0),
        asperity=GreenwoodTrippContact(1e-6),
    )  # fmt: skip
    s = _pair_system(el)
    rng = np.random.default_rng(5)
    for _ in range(6):
        q = s.y0[: s.n] + rng.normal(size=s.n) * 3e-4
        qd = rng.normal(size=s.n)
        Q1, Q2 = np.zeros(s.n), np.zeros(s.n)
        o1, o2 = np.zeros((1, NOUT)), np.zeros((1, NOUT))
        eval_forces(0.0, q, qd, s.mem0, s.fint, s.freal, s.tables, Q1, o1)
        eval_forces(0.0, q, qd, s.mem0, s.fint, s.freal, s.tables, Q2, o2, kinds_of(s.fint))
        np.testing.assert_array_equal(Q1, Q2)
        np.testing.assert_array_equal(o1, o2)
    assert np.any(Q1 != 0.0)


CHILD = textwrap.dedent(
    """
    import json
    import numpy as np
    """
    + LISTENER
    + """    from jointdyn.forces.elements import NOUT, eval_forces, kinds_of
    from jointdyn.forces.journal import JournalBearing
    from test_coldstart import _pair_system
    s = _pair_system(JournalBearing.example("alshaer2005"))
    Q = np.zeros(s.n)
    eval_forces(0.0, s.y0[: s.n], s.y0[s.n :], s.mem0, s.fint, s.freal, s.tables, Q, np.zeros((1, NOUT)),
                kinds_of(s.fint))
    print(json.dumps(names))
    """
)


def test_plain_bearing_compiles_its_film_law_only(tmp_path):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path), XDG_CACHE_HOME=str(tmp_path))
    here = os.path.dirname(os.path.abspath(__file__))  # the child imports test_coldstart
    env["PYTHONPATH"] = os.pathsep.join([here, env.get("PYTHONPATH", "")])
    p = subprocess.run([sys.executable, "-c", CHILD], env=env, capture_output=True, text=True, check=True)
    cold = json.loads(p.stdout.strip().splitlines()[-1])
    assert any(n.endswith("journal.journal_element") for n in cold)
    assert any(n.endswith("kernels.pi_film_force") for n in cold)  # the alshaer2005 (π-film) kernel
    other = (
        "ott_force",
        "short_force",
        "finite_force",
        "asperity_loads",
        "thermal_step",
        "viscosity_of",
        "jfo_step",
    )
    assert not [n for n in cold if n.endswith(other) or ".contact_laws." in n or ".friction_laws." in n]
