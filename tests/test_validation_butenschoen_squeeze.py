"""Butenschön's (1976) finite-bearing tables with the mass-conserving film [T367]: the rotation
table (tests/data/butenschoen_1976.csv) with `jfo`, and the pure-squeeze table
(tests/data/butenschoen_1976_squeeze.csv) with `reynolds` and `jfo`."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from jointdyn.bearing.validation import compare_butenschoen, load_butenschoen, squeeze_quantities
from jointdyn.film.grooved import Grooves
from jointdyn.film.jfo_transient import TransientFilm

DATA = Path(__file__).parent / "data"
SQUEEZE = load_butenschoen(DATA / "butenschoen_1976_squeeze.csv")

#: printed So values that break the smooth trend of their own column (L/D, ε): our So there, from
#: the same solver that meets every other point within 0.4 %, is off by the amount given [-]
OUTLIERS = {
    (0.5, 0.1): -0.052,  # 0.9814: log So departs 6.2 % from the cubic through its four neighbours
    (0.4, 0.8): +0.250,  # 15.94: nearly L/D 1/3's 15.282 (their ratio is 1.34 at ε = 0.7)
    (0.4, 0.96): -0.020,  # 492.49: the L/D 1/2.5 column departs 2–3 % from its cubic at 0.95–0.97
    (1 / 6, 0.99): +0.433,  # 2331: below L/D 1/8's 2560.1 (So falls with L/D everywhere else)
    (0.125, -0.95): +0.041,  # 0.0085: below its neighbour at ε = −0.96 (0.0087) in a rising column
}


def _key(ld, e):
    return next((k for k in OUTLIERS if math.isclose(k[0], ld) and math.isclose(k[1], e)), None)


@pytest.fixture(scope="module")
def squeeze():
    """{cavitation: [(L/D, ε, So, Q, computed)]} over the 232 points (≈ 5 s CPU per condition)."""
    out = {}
    for cav in ("reynolds", "jfo"):
        out[cav] = [
            (ld, e, so, q, squeeze_quantities(ld, e, cav))
            for ld, p in SQUEEZE.items()
            for e, so, q in zip(p["eps"], p["So"], p["Q"], strict=True)
        ]
    return out


def test_reynolds_pure_squeeze_load_matches_the_table(squeeze):
    """``finite`` + ``reynolds``: So within 1 % at the 227 points whose printed value is smooth in
    its column (measured ≤ 0.41 %, and 0.73 % at L/D 1/2, ε 0.2, next to the outlier at ε 0.1; the
    L/D 1/8 column is printed with two significant digits, ±0.6 %), the film force on the line of
    centres; the five listed outliers are off by what is recorded, so a change there shows."""
    for ld, e, so, _, r in squeeze["reynolds"]:
        err = r["So"] / so - 1.0
        k = _key(ld, e)
        if k is None:
            assert abs(err) <= 0.01, f"L/D={ld:.4g} eps={e}: So {r['So']:.5g} vs {so} ({err:+.4f})"
        else:
            assert err == pytest.approx(OUTLIERS[k], abs=0.003), (k, err)
        # along the line of centres: against the approach (180°), with the separation (0°)
        assert abs(math.remainder(r["beta_deg"] - (180.0 if e > 0 else 0.0), 360.0)) < 1e-6


def test_jfo_pure_squeeze_approach_equals_reynolds_and_the_table(squeeze):
    """Approaching journal (ε̇ > 0), fed at the maximum film: the film is full at the supply and
    never re-forms, so `jfo` = `reynolds` (theory) and So is within 1 % of the table (the same numbers
    as `reynolds`). Separating (ε̇ < 0), the steady `jfo` state is a partly filled film behind the
    minimum film whose frozen content carries less (measured down to −42 % at L/D = 1, ε = −0.99),
    where the table (and Reynolds' condition) has the full film of an instant: that state is
    compared in the next test."""
    rey = {(ld, e): r for ld, e, _, _, r in squeeze["reynolds"]}
    n = 0
    for ld, e, so, _, r in squeeze["jfo"]:
        if e <= 0.0:
            continue
        n += 1
        assert r["So"] == pytest.approx(rey[(ld, e)]["So"], rel=1e-6)
        if _key(ld, e) is None:
            assert abs(r["So"] / so - 1.0) <= 0.01, (ld, e, r["So"], so)
    assert n == 14 * 8
    sep = [r["So"] / rey[(ld, e)]["So"] for ld, e, _, _, r in squeeze["jfo"] if e < 0.0 and ld == 1.0]
    assert min(sep) < 0.65 and max(sep) <= 1.0 + 1e-9


def test_jfo_started_full_meets_the_separation_rows():
    """[T369] The table's separating film is the full film of an instant. The transient `jfo` film
    (:class:`TransientFilm`, mesh 180 × 16, fed at ambient pressure through one cell row at the
    minimum film, the source's inlet for separation) started flooded and stepped once by backward
    Euler over Δt = 1e-5/|ε̇|: So within 1 % of the table at all 120 points with ε ≤ 0 but the listed
    outlier (measured ≤ 0.39 %, mean 0.1 %), and the same as Reynolds' condition on that film (the
    instantaneous jfo complementarity with θ_f = 1 is the Reynolds LCP; measured 2.3e-5, O(Δt))."""
    nt, nz = 180, 16
    n = 0
    for ld, p in SQUEEZE.items():
        film = TransientFilm(ld, Grooves((0.0,), 2.0 * math.pi / nt, 0.0), (nt, nz))
        for e, so in zip(p["eps"], p["So"], strict=True):
            if e > 0.0:
                continue
            n += 1
            e0, v, dt = np.array([-e, 0.0]), np.array([-1.0, 0.0]), 1e-5  # away from the minimum film
            got = np.hypot(*film.step(e0 + v * dt, 0.0, dt, film.flooded(e0)).F) / (4.0 * ld)
            k = _key(ld, e)
            if k is None:
                assert abs(got / so - 1.0) <= 0.01, (ld, e, got, so)
            else:
                assert got / so - 1.0 == pytest.approx(OUTLIERS[k], abs=0.003), (k, got / so - 1.0)
            if e < 0.0:
                rey = np.hypot(*film.reynolds(e0, v, 0.0).F) / (4.0 * ld)
                assert abs(got / rey - 1.0) <= 1e-4, (ld, e)
    assert n == 15 * 8


def test_pure_squeeze_side_flow_converges_to_the_table():
    """Q on the default (180, 16) mesh is 1.2–3.5 % below the table (measured over all points); it
    is the mesh: refining to (360, 32) moves L/D = 1, ε = 0.5 from −3.35 % to −1.8 % of 3.0839."""
    ref = 3.0839
    q = [squeeze_quantities(1.0, 0.5, "reynolds", mesh)["Q"] / ref - 1.0 for mesh in ((180, 16), (360, 32))]
    assert -0.036 < q[0] < -0.030 and -0.022 < q[1] < -0.015


def test_jfo_matches_the_rotation_table():
    """`jfo` (fed at the maximum film, as the table's bearing) against Butenschön's rotation table,
    112 points, L/D = 1 … 1/8, ε = 0.1 … 0.99: So and Q within 1 %, β within 0.15° (measured
    max 0.94 % (L/D 1/8), 0.41 %, 0.097°)."""
    res = compare_butenschoen(load_butenschoen(DATA / "butenschoen_1976.csv"), cavitation="jfo")
    for ld, r in res.items():
        assert np.max(np.abs(r["So"][2])) <= 0.01, ld
        assert np.max(np.abs(r["Q"][2])) <= 0.01, ld
        assert np.max(np.abs(r["beta_deg"][2])) <= 0.15, ld
