"""The jfo element's film lives in the bushing frame [T306, T352]: a bearing problem run once with
the bushing at rest and once with the whole problem turning at ω_B (bushing driven at ω_B, journal
at ω_B + ω, load from a spring anchored on the bushing) gives the same orbit in the bushing frame."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from jointdyn.core.constraints import AngleDriver, Revolute
from jointdyn.film.models import Finite
from jointdyn.forces.journal import JournalBearing
from jointdyn.forces.springs import SpringDamper
from jointdyn.multibody.model import Model
from jointdyn.simulation.simulate import SimConfig, simulate

R, C, L, MU, OMEGA = 0.01, 5e-5, 0.02, 0.02, 100.0 * math.pi  # [m, m, m, Pa·s, rad/s]


def bushing_orbit(film, omega_b: float, t_end: float):
    """(e_x, e_y) [c] of the journal in the bushing frame [T290] over ``t_end`` [s] from the centre:
    bushing on a pin at its centre driven at ``omega_b``, journal free in translation and driven at
    ``omega_b`` + ω, loaded by a 2000 N spring from a point 1 m below the bushing centre in the
    bushing's frame (the load turns with the bushing)."""
    m = Model("turning bearing", gravity=(0.0, 0.0))
    m.add_ground_point("O", (0.0, 0.0))
    m.add_body("eye", 1.0, 1e-3, velocity=(0.0, 0.0, omega_b), points={"C": (0.0, 0.0), "K": (0.0, -1.0)})
    m.add_body("pin", 0.01, 1e-6, velocity=(0.0, 0.0, omega_b + OMEGA), points={"C": (0.0, 0.0)})
    m.add("eye_pivot", Revolute("ground", "O", "eye", "C"))
    m.add("eye_drive", AngleDriver("ground", "eye", omega=omega_b))
    m.add("pin_drive", AngleDriver("ground", "pin", omega=omega_b + OMEGA))
    m.add("load", SpringDamper("eye", "K", "pin", "C", stiffness=2000.0, damping=0.0, free_length=0.0))
    m.add("brg", JournalBearing("eye", "C", "pin", "C", R + C, R, L, MU, film=film))
    cfg = SimConfig(t_end=t_end, n_out=21, solver="radau5", rtol=1e-9, atol=1e-12)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = simulate(m.compile(centre_imperfect=False), cfg)
    return np.array(res.orbit("brg"))


@pytest.mark.parametrize(
    "film",
    [
        # slow tier: its only addition is a kernel set of its own (the spring and the Reynolds table
        # film under radau5, 43 s CPU from an empty cache [T373]); a table film sees the bushing's
        # rotation only through ω_J + ω_B − 2γ̇, checked for every film over random ω_B by
        # tests/test_film_models.py, and the element's turning frame runs here with the jfo film
        pytest.param(Finite(cavitation="reynolds"), marks=pytest.mark.slow),
        Finite(
            cavitation="jfo", supply_angle=90.0, supply_pressure=2e5, cells_around=24, cells_half_length=4
        ),
    ],
    ids=["reynolds", "jfo"],
)
def test_the_orbit_in_the_bushing_frame_does_not_depend_on_the_bushing_rotation(film):
    """Measured over 1 ms (from the centre to ξ ≈ 0.73, the film ruptured): 3.1e-5 c between
    ω_B = 0 and 100 rad/s for both films alike (over 5 ms, ξ → 0.94: 3.1e-5 c as well) — the
    Coriolis and centrifugal forces on the 10 g pin, which the turning frame adds. A frame error
    of the size of ω_B (the film turning at ω + 100 rad/s instead of ω) moves the orbit by
    0.016 c over the same 1 ms, 500 times that."""
    a = bushing_orbit(film, 0.0, 1e-3)
    b = bushing_orbit(film, 100.0, 1e-3)
    assert np.max(np.hypot(*a)) > 0.4  # the journal has left the centre
    assert np.max(np.hypot(*(a - b))) <= 1e-4
