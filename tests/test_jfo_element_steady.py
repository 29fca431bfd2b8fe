"""The jfo element's film held at a fixed journal position converges to the steady mass-conserving
film, against the independent steady solvers [T306, T343, T302]."""

from __future__ import annotations

import math

import numpy as np
import pytest

from jointdyn.film.grooved import Grooves
from jointdyn.film.jfo_states import SteadyJFO
from jointdyn.film.jfo_transient import TransientFilm
from jointdyn.film.models import Finite
from jointdyn.forces.elements import NOUT, advance_memory, eval_forces
from jointdyn.forces.journal import O_INFLOW, O_SIDE, JournalBearing
from jointdyn.multibody.model import Model

R, C, L, MU, OMEGA = 0.01, 5e-5, 0.01, 0.02, 100.0  # [m, m, m, Pa·s, rad/s]; L/D = 0.5


def steady_element_force(xi, gamma, mesh, width):
    """Film force [N] (world = bushing frame: the bushing is the ground) after the element's film
    has been committed at a fixed journal position for 30 relative revolutions (Δt = 2 ms)."""
    m = Model("held journal", gravity=(0.0, 0.0))
    m.add_ground_point("O", (0.0, 0.0))
    e = (xi * C * math.cos(gamma), xi * C * math.sin(gamma))
    m.add_body("journal", 1.0, 1e-4, position=e, velocity=(0.0, 0.0, OMEGA), points={"J": (0.0, 0.0)})
    film = Finite(
        cavitation="jfo",
        supply_angle=math.degrees(gamma + math.pi) % 360.0,  # the maximum film, as SteadyJFO's line
        supply_width=width,
        cells_around=mesh[0],
        cells_half_length=mesh[1],
    )
    m.add("pin", JournalBearing("ground", "O", "journal", "J", R + C, R, L, MU, film=film, shear=False))
    s = m.compile(centre_imperfect=False)
    P = s.packed(0.0)
    n = s.y0.size // 2
    q, qd = s.y0[:n].copy(), s.y0[n:].copy()
    mem = s.mem0.copy()
    dt = 2e-3
    for k in range(int(30 * 2 * math.pi / OMEGA / dt) + 1):
        assert advance_memory(k * dt, q, qd, mem, P.fint, P.freal, P.tables, s.kinds()) == 0
    Q = np.zeros(n)
    out = np.zeros((1, NOUT))
    eval_forces(k * dt, q, qd, mem, P.fint, P.freal, P.tables, Q, out, s.kinds())  # Δt = 0: frozen content
    return np.array([Q[0], Q[1]]), out, (q, qd, mem, P, k * dt)


@pytest.mark.parametrize("xi", [0.3, 0.7])
def test_held_journal_reaches_the_steady_jfo_film(xi):
    """Against `film-force --model finite --cavitation jfo` (line-fed at the maximum film, 180 × 16
    [T343]), the mesh error: measured at 72 × 16 cells, groove 5°, |ΔF|/|F| = 9.7e-4 (ξ = 0.3),
    5.1e-4 (ξ = 0.7); the steady lubricant balance: inflow = side outflow."""
    gamma = 0.6
    F, out, _ = steady_element_force(xi, gamma, (72, 16), 5.0)
    ref = SteadyJFO().forces(xi, 0.0, gamma, 0.0, OMEGA, 0.0, MU, L, R, C)
    Fref = np.array([float(ref["Fx"]), float(ref["Fy"])])
    assert np.hypot(*(F - Fref)) <= 2e-3 * np.hypot(*Fref)
    inflow, side = out[0, O_INFLOW], out[0, O_SIDE]  # [m³/s]
    assert side > 0.0 and abs(inflow - side) <= 1e-6 * side


def test_steady_jfo_equals_reynolds_on_the_same_mesh():
    """Steady, fed at the maximum film, no re-formation inside the film: the mass-conserving film
    and Swift–Stieber's (the LCP on the same mesh and supply, [T302]) carry the same load.
    Measured: |ΔF|/|F| = 1.3e-3 at ξ = 0.6, 36 × 8 cells, groove 10°."""
    xi, gamma, mesh, width = 0.6, 0.6, (36, 8), 10.0
    F, _, _ = steady_element_force(xi, gamma, mesh, width)
    g = Grooves((math.radians(math.degrees(gamma + math.pi) % 360.0),), math.radians(width), 0.0)
    film = TransientFilm(L / (2.0 * R), g, mesh)
    e = (xi * math.cos(gamma), xi * math.sin(gamma))
    Fref = film.reynolds(e, (0.0, 0.0), OMEGA).F * MU * R**4 / C**2
    assert np.hypot(*(F - Fref)) <= 3e-3 * np.hypot(*Fref)
