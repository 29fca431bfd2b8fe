"""The transient mass-conserving film and the orbit of a dynamically loaded journal [T300–T303]:
the steady limit against the steady jfo / Swift–Stieber solvers, the lubricant balance of a
dynamically loaded run, first-order convergence in the time step, bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest

from jointdyn.film.fv import assemble
from jointdyn.film.grooved import Grooves, axial_grooves, equilibrium
from jointdyn.film.jfo import solve_jfo, transport
from jointdyn.film.jfo_transient import TransientFilm, balance_error, orbit

MESH = (36, 8)
ONE_GROOVE = Grooves((0.5 * math.pi,), math.radians(20.0))


def _pulsating(t):
    """Load on the journal rotating at half the shaft speed, its magnitude pulsating 1.8 : 0.2."""
    return (1.0 + 0.8 * math.cos(t)) * np.array([math.cos(0.5 * t), math.sin(0.5 * t)])


def test_one_long_step_is_the_steady_jfo_film():
    """A backward-Euler step of Δt → ∞ leaves the frozen-content steady problem of [T241]: with
    the journal held at e, one step of Δt = 1e9 s from any content equals solve_jfo's field on the
    same mesh (transport with Ω = ω, no squeeze) to 1e-8 of its peak."""
    g = axial_grooves(2, 20.0)
    f = TransientFilm(0.5, g, MESH)
    e = (0.5, 0.4)
    c0 = 0.3 * f.flooded(e)
    s = f.step(e, 1.0, 1e9, c0)
    assert f.residual(s, e, 1.0, 1e9, c0) < 1e-13
    prob, H = f.film(e)
    P, fill, *_ = solve_jfo(prob, 0.0, 0.0, f.fixed, omega=1.0)
    assert np.max(np.abs(s.P - P)) < 1e-8 * np.max(P)
    assert np.max(np.abs(s.fill - fill)) < 1e-8
    assert 0.2 < np.mean(s.cav) < 0.8  # a cavitated film with re-formation at the grooves
    assert np.array_equal(transport(prob, 0.0, 0.0, 1.0).diagonal() > 0.0, np.ones(H.size, bool))


@pytest.mark.parametrize("law", ["jfo", "reynolds"])
def test_steady_load_reaches_the_steady_equilibrium(law):
    """Constant load and speed: the orbit of the massless journal settles on the steady
    equilibrium of grooved.equilibrium (same mesh, same grooves, load along the load line) from
    an off-equilibrium start (backward Euler's fixed point is the steady solution whatever Δt);
    measured after 30 s at ω = 1 rad/s in 60 steps: |Δε| ≤ 1.3e-9, |Δφ| ≤ 4.3e-9 rad."""
    g = axial_grooves(2, 20.0)
    phi, W, *_ = equilibrium(0.5, 0.6, law, g, MESH)
    times = np.linspace(0.0, 30.0, 61)
    r = orbit(TransientFilm(0.5, g, MESH), lambda t: 1.0, lambda t: (W, 0.0), times, (0.3, 0.1), law)
    e = r["e"][-1]
    assert abs(math.hypot(*e) - 0.6) < 1e-8
    assert abs(math.atan2(e[1], e[0]) - phi) < 1e-8


def test_balance_of_a_dynamically_loaded_run_closes_to_round_off():
    """Pulsating, rotating load over two shaft revolutions: Σ Δt·(inflow − side outflow) equals
    the content change to round-off [T301] while the cavitated zone grows, shrinks and re-forms
    (its fraction changes by > 0.1; the content leaves the flooded start by > 5 %; the squeeze
    pushes oil back into the ambient-pressure groove for part of the cycle: inflow < 0)."""
    times = np.linspace(0.0, 4.0 * math.pi, 61)
    r = orbit(TransientFilm(0.5, ONE_GROOVE, MESH), lambda t: 1.0, _pulsating, times, (0.3, 0.0))
    assert balance_error(r) < 1e-13
    cav = r["cavitated"][1:]
    assert cav.max() - cav.min() > 0.1
    assert abs(np.min(r["content"]) / r["content"][0] - 1.0) > 0.05
    assert np.all(r["side"][1:] > 0.0) and np.min(r["inflow"][1:]) < 0.0 < np.max(r["inflow"][1:])
    assert np.allclose(np.sum(r["per_groove"], axis=1)[1:], r["inflow"][1:], rtol=1e-12)


@pytest.mark.slow
def test_orbit_converges_first_order_in_the_step():
    """Backward Euler: the orbit's gap between Δt and Δt/2 halves with Δt (measured over 180,
    360, 720 steps per two revolutions: gaps 0.017, 0.0092, ratio 1.85 tending to 2; the test:
    120, 240, 480 steps)."""
    f = TransientFilm(0.5, ONE_GROOVE, MESH)
    es = []
    for n in (120, 240, 480):
        times = np.linspace(0.0, 4.0 * math.pi, n + 1)
        es.append(orbit(f, lambda t: 1.0, _pulsating, times, (0.3, 0.0))["e"][:: n // 120])
    d1, d2 = np.max(np.abs(es[1] - es[0])), np.max(np.abs(es[2] - es[1]))
    assert 1.6 < d1 / d2 < 2.4


def test_bad_input_is_named():
    f = TransientFilm(0.5, ONE_GROOVE, MESH)
    c = f.flooded((0.1, 0.0))
    with pytest.raises(ValueError, match=r"dt = .* \[s\]"):
        f.step((0.1, 0.0), 1.0, 0.0, c)
    with pytest.raises(ValueError, match=r"\|e\|/c .* must be < 1"):
        f.step((1.0, 0.1), 1.0, 0.1, c)
    with pytest.raises(ValueError, match="law = 'gumbel'"):
        orbit(f, lambda t: 1.0, _pulsating, [0.0, 1.0], (0.1, 0.0), law="gumbel")
    with pytest.raises(ValueError, match=r"mass = -1.0 \[s\]"):
        orbit(f, lambda t: 1.0, _pulsating, [0.0, 1.0], (0.1, 0.0), mass=-1.0)
    with pytest.raises(ValueError, match=r"max_move = 0.0 \[c\]"):
        orbit(f, lambda t: 1.0, _pulsating, [0.0, 1.0], (0.1, 0.0), max_move=0.0)
    with pytest.raises(ValueError, match=r"times \[s\]"):
        orbit(f, lambda t: 1.0, _pulsating, [1.0, 0.0], (0.1, 0.0))
    with pytest.raises(ValueError, match=r"mesh = .* \[-\]"):
        TransientFilm(0.5, ONE_GROOVE, (4, 8))
    with pytest.raises(ValueError, match="L/D"):
        TransientFilm(-1.0, ONE_GROOVE, MESH)
    assert assemble(0.0, 0.5, *MESH, kappa=0.0).area.size == MESH[0] * MESH[1]


@pytest.mark.slow
def test_big_end_page_is_current():
    """The numbers of docs/user-guide/big-end.md are those ``docs/_gen_big_end.py`` computes now
    (≈ 1 min CPU)."""
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "docs" / "_gen_big_end.py"
    spec = importlib.util.spec_from_file_location("_gen_big_end", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    assert mod.main(["--check"]) == 0, "run python docs/_gen_big_end.py"
