"""A run that takes a ``finite`` film beyond its table (ξ > XI_MAX) is reported with the time
and ξ, as a PhysicsWarning and in ``summary.json`` [T249]."""

from __future__ import annotations

import types
import warnings

import numpy as np
import pytest

from jointdyn.film.finite import XI_MAX
from jointdyn.forces.journal import JournalBearing
from jointdyn.simulation.ranges import film_range_exits, range_message


def _fake(film, xi):
    el = JournalBearing("ground", "O", "journal", "C", 0.0105, 0.0100, 0.02, 0.05, film=film)
    t = np.linspace(0.0, 1.0, xi.size)
    sysm = types.SimpleNamespace(element_names=["pin"], elements=[el])
    return types.SimpleNamespace(system=sysm, t=t, element=lambda name, out: xi)


def test_exit_found_with_time_and_xi():
    xi = np.array([0.5, 0.9, 0.96, 0.99, 0.97, 0.8])
    (d,) = film_range_exits(_fake("finite", xi))
    assert d["element"] == "pin" and d["xi_limit"] == XI_MAX
    assert d["first_time"] == pytest.approx(0.4) and d["xi_max"] == 0.99
    assert d["time_of_max"] == pytest.approx(0.6) and d["fraction"] == pytest.approx(0.5)
    assert "t = 0.4 s" in range_message(d) and "xi_max = 0.990000" in range_message(d)


def test_no_table_range_for_the_transient_jfo_film():
    """The jfo film has no table (its mesh is solved at every step [T306]): the run of
    examples/slider_crank_jfo.toml warned "finite film beyond its table … extrapolated"."""
    from jointdyn.film.models import Finite

    xi = np.array([0.5, 0.96, 0.99])
    assert film_range_exits(_fake(Finite(cavitation="jfo"), xi)) == []
    assert len(film_range_exits(_fake(Finite(cavitation="reynolds"), xi))) == 1


def test_no_report_inside_the_range_or_for_closed_forms():
    assert film_range_exits(_fake("finite", np.array([0.2, 0.95, 0.3]))) == []
    assert film_range_exits(_fake("alshaer2005", np.array([0.2, 0.99]))) == []  # closed form


@pytest.mark.slow
def test_heavy_journal_run_warns_and_records():
    """20 kg on a 20 mm × 20 mm bearing at 10 rad/s, μ = 0.05 Pa·s: ξ passes 0.95 in the first
    10 ms (measured ξ_max 0.99997); the run warns once and the summary records the same entry."""
    from jointdyn import Model, PhysicsWarning, SimConfig, simulate
    from jointdyn.studies.outputs import summary

    m = Model("journal", gravity=(0.0, -9.81))
    m.add_ground_point("O", (0.0, 0.0))
    m.add_body("journal", 20.0, 1e-3, velocity=(0.0, 0.0, 10.0), points={"C": (0.0, 0.0)})
    m.add("pin", JournalBearing("ground", "O", "journal", "C", 0.0105, 0.0100, 0.02, 0.05, film="finite"))
    s = m.compile(centre_imperfect=False)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        res = simulate(s, SimConfig(t_end=0.1, n_out=51, solver="dopri5", rtol=1e-7))
    msgs = [
        w for w in caught if issubclass(w.category, PhysicsWarning) and "beyond its table" in str(w.message)
    ]
    assert len(msgs) == 1
    (d,) = summary(res)["film_range"]
    xi = res.element("pin", "xi")
    assert d["xi_max"] == xi.max() > XI_MAX
    assert d["first_time"] == res.t[np.argmax(xi > XI_MAX)]
