"""The compiled backward-Euler jfo step [T304] against the sparse-LU reference step of
:class:`~jointdyn.film.jfo_transient.TransientFilm` [T300] (an independent solve of the same
cell balances), and its lubricant balance [T301] step by step."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from jointdyn.film.grooved import Grooves
from jointdyn.film.jfo_step import geometry, jfo_step, step
from jointdyn.film.jfo_transient import TransientFilm

MESH = (36, 8)


@pytest.mark.parametrize(
    "grooves, omega",
    [
        (Grooves((0.5 * math.pi,), 0.3, 0.05), 1.0),
        (Grooves((0.0, math.pi), 0.2, 0.0), 1.0),
        (Grooves((0.0, math.pi), 0.2, 0.0), -2.0),
    ],
)
def test_compiled_step_is_the_reference_step(grooves, omega):
    """40 steps of a journal on a Lissajous path (cavitated fraction 0.5–0.6, rupture and
    re-formation): pressure, fill, force, flows and content of jfo_step equal TransientFilm.step
    to 1e-12 of their scale (measured 7e-15), and so do the flows per groove (the supply cells' net
    outflows, summed per groove [T376]), with the same cavitated sets; each step's balance
    content − content⁰ = Δt·(inflow − side) holds to 1e-12 of the content."""
    f = TransientFilm(0.5, grooves, MESH)
    g = geometry(f)
    e = np.array([0.6, 0.0])
    content = f.flooded(e)
    total0 = 2.0 * float(np.sum(g.area * content))
    cav = np.zeros(content.size, np.bool_)
    warm = None
    dt = 0.01
    seen = 0.0
    for n in range(1, 41):
        t = n * dt
        e = np.array([0.6 * math.cos(3.0 * t), 0.5 * math.sin(2.0 * t)])
        s = f.step(e, omega, dt, content, warm)
        P, fill, fx, fy, inflow, side, total, net, it = jfo_step(
            e[0], e[1], omega, dt, content, cav, *g.args(), 200
        )
        assert it > 0
        F = math.hypot(*s.F)
        assert np.max(np.abs(P - s.P)) < 1e-12 * np.max(s.P)
        assert np.max(np.abs(fill - s.fill)) < 1e-12
        assert abs(fx - s.F[0]) < 1e-12 * F and abs(fy - s.F[1]) < 1e-12 * F
        assert abs(inflow - s.inflow) < 1e-12 * abs(s.side)
        assert abs(side - s.side) < 1e-12 * abs(s.side)
        per = [float(np.sum(net[f.labels == k])) for k in range(f.ngroove)]  # [T376]
        assert np.allclose(per, s.per_groove, rtol=0.0, atol=1e-12 * abs(s.side))
        assert np.all(net[~g.fixed] == 0.0)
        assert abs(total - s.content) < 1e-12 * s.content
        assert np.array_equal(cav, s.cav)
        assert abs(total - total0 - dt * (inflow - side)) < 1e-12 * total0
        seen = max(seen, float(np.mean(cav)))
        content = s.H * s.fill
        warm = s.cav
        total0 = total
    assert seen > 0.3  # the path does cavitate the film


@pytest.mark.parametrize(
    "kw, fragment",
    [
        ({"dt": 0.0}, "dt = 0.0 [s]"),
        ({"dt": math.nan}, "dt = nan [s]"),
        ({"e": (0.8, 0.7)}, "|e|/c"),
        ({"omega": math.inf}, "omega = inf [rad/s]"),
        ({"content0": np.ones(5)}, "content0"),
        ({"cav": np.zeros(288)}, "cav"),
    ],
)
def test_checked_step_names_the_bad_input(kw, fragment):
    f = TransientFilm(0.5, Grooves((0.0,), 0.2), MESH)
    g = geometry(f)
    args = {"e": (0.3, 0.1), "omega": 1.0, "dt": 0.01, "content0": f.flooded((0.3, 0.1))}
    args["cav"] = np.zeros(args["content0"].size, np.bool_)
    args.update(kw)
    with pytest.raises(ValueError, match=re.escape(fragment)):
        step(g, args["e"], args["omega"], args["dt"], args["content0"], args["cav"])


def test_checked_step_is_the_kernel():
    """The checked entry returns the kernel's result unchanged (same call, same numbers)."""
    f = TransientFilm(0.5, Grooves((0.0,), 0.2), MESH)
    g = geometry(f)
    c0 = f.flooded((0.3, 0.1))
    a = step(g, (0.5, -0.2), 1.0, 0.01, c0, np.zeros(c0.size, np.bool_))
    b = jfo_step(0.5, -0.2, 1.0, 0.01, c0, np.zeros(c0.size, np.bool_), *g.args(), 200)
    assert all(np.array_equal(x, y) for x, y in zip(a, b, strict=True))


def test_frozen_set_step():
    """max_iter = 0 solves once with the given set and keeps it [T348]: with the settled set it
    is the iterated step to the last bit; with another set (a quarter of the full cells forced
    cavitated) the set stays as given, and the cell balance content − content⁰ = Δt·(inflow −
    side) still holds to 1e-12 of the content (it holds for any set)."""
    f = TransientFilm(0.5, Grooves((0.5 * math.pi,), 0.3, 0.0), MESH)
    g = geometry(f)
    content = f.flooded((0.3, 0.1))
    cav = np.zeros(content.size, np.bool_)
    ref = jfo_step(0.6, -0.4, 1.0, 0.01, content, cav, *g.args(), 200)
    assert ref[-1] > 1 and cav.any()  # the set moved from the warm start: rupture
    frozen_cav = cav.copy()
    out = jfo_step(0.6, -0.4, 1.0, 0.01, content, frozen_cav, *g.args(), 0)
    assert np.array_equal(frozen_cav, cav)
    assert all(np.array_equal(x, y) for x, y in zip(out[:-1], ref[:-1], strict=True))
    other = cav.copy()
    other[np.flatnonzero(~cav & ~g.fixed)[::4]] = True
    given = other.copy()
    P, fill, fx, fy, inflow, side, total, net, it = jfo_step(
        0.6, -0.4, 1.0, 0.01, content, other, *g.args(), 0
    )
    assert it == 1 and np.array_equal(other, given)
    assert np.all(P[given] == 0.0) and np.all(fill[~given] == 1.0)
    total0 = 2.0 * float(np.sum(g.area * content))
    assert abs(total - total0 - 0.01 * (inflow - side)) < 1e-12 * total0
