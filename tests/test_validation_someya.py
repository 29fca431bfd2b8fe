"""Two-axial-groove bearing against Someya's Journal-Bearing Databook (1989), L/D = 0.5 and 1
[T244–T248]: Sommerfeld number, attitude and the eight dynamic coefficients, Reynolds
(Swift–Stieber) film, grooves 18° wide at ±90° from the load line, oil at ambient pressure.

Targets of issue 25: S within 3 %, attitude within 1°, k and c within 6 % of the largest
coefficient of the row. Where a target is not met the test is an ``xfail(strict=True)`` that
asserts the target (it fails today; it turns into an error the day it passes) and records the
measured max / mean in its reason; docs/validation.md has the table."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
import pytest

from jointdyn.film.grooved import axial_grooves, coefficients

DATA = Path(__file__).parent / "data" / "someya_1989_two_axial_groove.csv"


def _rows(ld):
    with open(DATA) as fh:
        rows = list(csv.DictReader(line for line in fh if not line.startswith("#")))
    return [r for r in rows if float(r["ld"]) == ld]


_CACHE: dict = {}


def errors(ld: float) -> dict:
    """Per row: relative S error, attitude error [deg], k and c errors / largest |k|, |c|."""
    if ld in _CACHE:
        return _CACHE[ld]
    g = axial_grooves(2, 18.0)
    out: dict = {"S": [], "phi": [], "k": [], "c": []}
    for r in _rows(ld):
        c = coefficients(ld, float(r["eps"]), "reynolds", g)
        # Someya's frame: x along the load, y in the direction of rotation (see the data header)
        k = np.array([c["kyy"], -c["kyx"], -c["kxy"], c["kxx"]])
        b = np.array([c["cyy"], -c["cyx"], -c["cxy"], c["cxx"]])
        kr = np.array([float(r[n]) for n in ("kxx", "kxy", "kyx", "kyy")])
        br = np.array([float(r[n]) for n in ("bxx", "bxy", "byx", "byy")])
        out["S"].append(abs(c["sommerfeld"] / float(r["S"]) - 1.0))
        out["phi"].append(abs(math.degrees(c["attitude"]) - float(r["phi_deg"])))
        out["k"].append(np.max(np.abs(k - kr)) / np.max(np.abs(kr)))
        out["c"].append(np.max(np.abs(b - br)) / np.max(np.abs(br)))
    _CACHE[ld] = {q: np.array(v) for q, v in out.items()}
    return _CACHE[ld]


TARGET = {"S": 0.03, "phi": 1.0, "k": 0.06, "c": 0.06}
#: measured max / mean (mesh 180×16, h = 2e-3) where the target is not met
MISSED = {
    (0.5, "phi"): "attitude max 1.67° / mean 0.72° (up to 1.7° low at ε ≤ 0.5)",
    (0.5, "k"): "k max 47.2 % / mean 14.1 % of the largest k (ε ≤ 0.3: Someya's k_yx about twice ours; "
    "at ε ≤ 0.1 his k_yx contradicts his own attitude and k_yy, [T368])",
    (0.5, "c"): "c max 17.8 % / mean 5.2 % (ε = 0.975: 17.8 %; ε ≤ 0.9: ≤ 5.2 %)",
    (1.0, "S"): "S max 3.2 % / mean 1.85 %",
    (1.0, "phi"): "attitude max 3.53° / mean 1.24°",
    (1.0, "k"): "k max 66.3 % / mean 27.2 % (ε ≤ 0.3, cross-coupled k_yx; "
    "self-contradicting at ε ≤ 0.1, [T368])",
    (1.0, "c"): "c max 9.7 % / mean 4.0 % (ε = 0.95)",
}


@pytest.mark.parametrize("ld", [0.5, 1.0])
@pytest.mark.parametrize("q", ["S", "phi", "k", "c"])
def test_someya_two_axial_groove(request, ld, q):
    if (ld, q) in MISSED:
        request.applymarker(pytest.mark.xfail(strict=True, reason=MISSED[(ld, q)]))
    e = errors(ld)[q]
    assert np.max(e) <= TARGET[q], (np.max(e), np.mean(e))


@pytest.mark.parametrize("ld", [0.5, 1.0])
def test_someya_targets_met_for_moderate_eccentricity(ld):
    """ε 0.5–0.9 (the usual operating range): S and c meet the issue's targets (3 %, 6 % of the
    largest c); measured max S 0.9 % / 2.2 %, c 4.5 % / 5.8 % at L/D 0.5 / 1. Attitude (0.9°,
    1.3°) and k (7.2 %, 11.3 %) do not meet theirs there either (see the xfails above)."""
    eps = np.array([float(r["eps"]) for r in _rows(ld)])
    sel = (eps >= 0.5) & (eps <= 0.9)
    e = errors(ld)
    assert np.max(e["S"][sel]) <= TARGET["S"]
    assert np.max(e["c"][sel]) <= TARGET["c"]


@pytest.mark.slow
def test_grooved_mesh_convergence():
    """Default mesh 180 × 16 against 720 × 64 (two halvings; the groove stays 9 → 36 cells):
    S within 0.5 %, attitude within 0.3°, k and c within 3 % of the largest coefficient
    (measured at L/D 1, ε 0.3 / 0.8 and L/D 0.5, ε 0.1: S 0.33 / 0.01 / 0.17 %, φ 0.13 / 0.09 /
    0.11°, k 1.1 / 0.34 / 1.3 %, c 1.2 / 0.62 / 1.3 %). The convergence is not monotone: groove edges and cavitation boundaries move by
    whole cells."""
    g = axial_grooves(2, 18.0)
    for ld, eps in ((1.0, 0.3), (1.0, 0.8), (0.5, 0.1)):
        a = coefficients(ld, eps, "reynolds", g)
        b = coefficients(ld, eps, "reynolds", g, (720, 64))
        assert abs(a["sommerfeld"] / b["sommerfeld"] - 1.0) <= 5e-3
        assert abs(math.degrees(a["attitude"] - b["attitude"])) <= 0.3
        for M in ("K", "C"):
            err = np.max(np.abs(a[M] - b[M])) / np.max(np.abs(b[M]))
            assert err <= 0.03, (ld, eps, M, err)


def _implied_attitude(kyx: float, kyy: float) -> float:
    """Attitude [deg] that the light-load identity cot φ = −k_yy/(2 k_yx) gives ([T368]; Someya's
    frame: x along the load, y across it in the direction of rotation)."""
    return math.degrees(math.atan2(-2.0 * kyx, kyy))


@pytest.mark.parametrize("condition", ["gumbel", "reynolds", "jfo"])
def test_light_load_attitude_identity(condition):
    """[T368]: as ε → 0 the attitude of a two-axial-groove bearing follows from two of its stiffnesses,
    cot φ = −k_yy/(2 k_yx) (1 + O(ε)), and ε k_xy → 1, whatever the film end and the groove width.
    Measured: |implied − solved| ≤ 0.005° at ε = 0.05 and ≤ 0.06° at ε = 0.1 over 10° and 30° grooves
    and L/D 0.5 and 1; ε k_xy = 1.010–1.012 at ε = 0.05."""
    for width in (10.0, 30.0):
        g = axial_grooves(2, width)
        for ld in (0.5, 1.0):
            for eps, tol in ((0.05, 0.02), (0.1, 0.1)):
                c = coefficients(ld, eps, condition, g)
                # Someya's frame from ours (load along −y, rotation from x to y): k_yx^S = −k_xy, k_yy^S = k_xx
                phi = math.degrees(c["attitude"])
                assert abs(_implied_attitude(-c["kxy"], c["kxx"]) - phi) <= tol, (width, ld, eps)
                if eps == 0.05:
                    assert abs(eps * -c["kyx"] - 1.0) <= 0.02, (width, ld)


def test_databook_breaks_the_light_load_identity():
    """[T368]: the transcribed databook rows at ε ≤ 0.1 imply attitudes 1.5–3.1° above the printed ones
    (L/D 0.5: 84.1° / 82.6°, 82.0° / 80.4°; L/D 1: 85.8° / 83.0°, 83.7° / 80.8°, 81.8° / 78.7°), more
    than 15 times the identity's remainder in any of our films at the same ε (test above), while its
    ε k_xy meets the second identity as ours does (1.005–1.03; ours 1.01–1.04 at the same ε). Its k_yx, about twice ours there, is the odd one out:
    the k target cannot be met by a solution of this bearing at those rows."""
    rows = [r for ld in (0.5, 1.0) for r in _rows(ld) if float(r["eps"]) <= 0.1]
    assert len(rows) == 5
    for r in rows:
        defect = _implied_attitude(float(r["kyx"]), float(r["kyy"])) - float(r["phi_deg"])
        assert 1.4 <= defect <= 3.2, (r["ld"], r["eps"], defect)
        assert abs(float(r["eps"]) * float(r["kxy"]) - 1.0) <= 0.05, (r["ld"], r["eps"])
