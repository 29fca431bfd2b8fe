"""Contact events in the step loop [T200–T204]: onset prediction, Hermite peak penetration,
FSAL after projection, against closed forms and finite differences."""

import math
import warnings

import numpy as np
import pytest

from jointdyn.forces.contact_events import first_root, hermite_peak, penetration_rates
from jointdyn.forces.contact_laws import Hertz
from jointdyn.forces.journal import ClearanceJoint, penetration
from jointdyn.models.slider_crank import PIN, slider_crank
from jointdyn.multibody.dynamics import rhs
from jointdyn.multibody.model import Model
from jointdyn.simulation.simulate import SimConfig, simulate

RB, RJ = 0.0105, 0.0100


def test_first_root_against_numpy():
    rng = np.random.default_rng(1)
    for _ in range(200):
        a, b = rng.normal(size=2)
        c = -abs(rng.normal())
        roots = np.roots([a, b, c])
        pos = [r.real for r in roots if abs(r.imag) < 1e-12 and r.real > 0]
        expect = min(pos) if pos else math.inf
        assert first_root(a, b, c) == pytest.approx(expect, rel=1e-12)  # round-off of two formulas
    assert first_root(0.0, 2.0, -1.0) == 0.5
    assert first_root(0.0, -2.0, -1.0) == math.inf


def test_penetration_rates_against_finite_differences():
    """δ̇, δ̈ of the benchmark pin at an off-centre state against central differences of δ along
    q(s) = q + q̇s + ½q̈s², which matches the motion to second order at s = 0."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        system = slider_crank(joint="dry").compile()
    P = system.packed(0.0)
    y = np.array(system.y0, float)
    n = y.shape[0] // 2
    y[6] += 0.3e-3  # slider 0.3 mm off the rod eye along x
    y[6 + n], y[7 + n] = 0.3, 0.4  # and moving away and sideways [m/s]
    f = np.zeros(2 * n)
    assert rhs(0.0, y, system.mem0.copy(), P, f) == 0
    q, qd, qdd = y[:n], y[n:], f[n:]
    k = system.element_names.index(PIN)
    bi, bj, r = P.fint[k, 1], P.fint[k, 2], P.freal[k]
    d, dd, ddd = penetration_rates(q, qd, qdd, bi, bj, r)
    d_ref, dd_ref = penetration(q, qd, bi, bj, r)
    assert d == d_ref and dd == dd_ref
    eps = 1e-6  # [s]; truncation O(eps²·δ''''), round-off O(1e-16·|q|/eps²)
    dm = penetration(q - qd * eps + 0.5 * qdd * eps**2, qd, bi, bj, r)[0]
    dp = penetration(q + qd * eps + 0.5 * qdd * eps**2, qd, bi, bj, r)[0]
    assert (dp - dm) / (2 * eps) == pytest.approx(dd, rel=1e-6)
    assert (dp - 2 * d + dm) / eps**2 == pytest.approx(ddd, rel=1e-4)  # ≈ 1e-16·0.17 m/eps² / |δ̈|


def test_hermite_peak_is_exact_for_cubics_and_fourth_order():
    p = np.polynomial.Polynomial([-1e-6, 3e-2, 50.0, -4e4])  # δ(t) [m], a max inside [0, h]
    h = 1.5e-3
    dp = p.deriv()
    crit = [r.real for r in dp.roots() if 0 < r.real < h]
    assert hermite_peak(p(0), dp(0), p(h), dp(h), h) == pytest.approx(max(p(c) for c in crit), rel=1e-12)
    # δ = A sin(ωt) on [t0, t0 + h] around its peak: the interpolation error falls as h⁴
    A, w = 2e-5, 7e4
    errs = []
    for h in (2e-5, 1e-5):
        t0 = math.pi / (2 * w) - 0.3 * h
        v = hermite_peak(
            A * math.sin(w * t0),
            A * w * math.cos(w * t0),
            A * math.sin(w * (t0 + h)),
            A * w * math.cos(w * (t0 + h)),
            h,
        )
        errs.append(abs(v - A) / A)
    assert 12 < errs[0] / errs[1] < 20  # 2⁴ = 16


def _hertz_impact(rtol, v0=1.0, mass=0.14, K=6.9e10):
    m = Model("impact", gravity=(0.0, 0.0))
    m.add_ground_point("O", (0.0, 0.0))
    m.add_body(
        "pin", mass, 1e-4, position=(0.0, 0.0), velocity=(v0 * 0.6, v0 * 0.8, 0.0), points={"c": (0.0, 0.0)}
    )
    m.add("joint", ClearanceJoint("ground", "O", "pin", "c", RB, RJ, contact=Hertz(stiffness=K)))
    res = simulate(
        m.compile(centre_imperfect=False),
        SimConfig(t_end=3 * (RB - RJ) / v0, n_out=3, solver="dopri5", rtol=rtol, atol=rtol * 1e-4),
    )
    exact = (5 * mass * v0**2 / (4 * K)) ** 0.4  # ½mv₀² = (2/5)Kδ_max^2.5 (Hertz, no loss)
    return abs(res.mem[-1, 0, 3] - exact) / exact


def test_peak_penetration_converges_to_the_hertz_energy_balance():
    """max_penetration is the peak of δ(t), not of the step ends: its error against the closed
    form falls with the tolerance (measured 6.4e-5, 1.6e-6, 1.7e-7 at rtol 1e-5, 1e-7, 1e-8;
    the step ends alone gave 2.9e-3, 3.1e-4, 7.9e-7)."""
    e5, e7, e8 = (_hertz_impact(r) for r in (1e-5, 1e-7, 1e-8))
    assert e5 < 2e-4 and e7 < 5e-6 and e8 < 6e-7  # ≈ 3× the measured errors
    assert e5 > e7 > e8


def test_onset_is_landed_and_fsal_survives_projection():
    """Dry slider-crank up to just after the first impact (t ≈ 2.2729e-4 s): free-flight steps
    land on the onset instead of growing into the wall and being rejected; the projection's
    corrections are negligible, so every accepted step reuses k₇ and the RHS count is 6 per
    attempt + 1 (start)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        system = slider_crank(joint="dry").compile()
    res = simulate(system, SimConfig(t_end=2.3e-4, n_out=3, solver="dopri5", rtol=1e-7, atol=1e-9))
    st = res.stats
    assert st["rhs_evaluations"] == 6 * (st["accepted_steps"] + st["rejected_steps"]) + 1
    assert res.memory(PIN, "impacts")[-1] == 1
    # measured: 0 rejections, 97 RHS; before [T201, T203]: 19 rejections, 332 RHS
    assert st["rejected_steps"] <= 2 and st["rhs_evaluations"] < 150


def test_dry_steps_benchmark_classifies_every_attempt():
    """benchmarks.dry_steps up to just after the first impact (0.02 rev ≈ 0.24 ms): every attempt
    is classified once (6 RHS each with FSAL, + 1 at the start). No timing."""
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from benchmarks.dry_steps import trace

    r = trace(1e-7, revs=0.02)
    attempts = r["accepted_contact"] + r["accepted_free"] + r["rejected_error"] + r["rejected_onset"]
    assert r["rhs"] == 6 * attempts + 1
    assert r["impacts"] == 1 and r["accepted_contact"] > 0 and r["time_in_contact"] > 0


def test_dry_steps_costs_time_every_piece():
    """benchmarks.dry_steps --costs: every piece of the step loop timed at a contact and a
    free-flight step, and the loop per attempt (no timing assertions: values only finite)."""
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from benchmarks.dry_steps import PIECES, costs

    c = costs(1e-5, calls=100)
    for label in ("contact", "free"):
        assert all(np.isfinite(c[f"{label}: {p}_ns"]) and c[f"{label}: {p}_ns"] > 0 for p in PIECES)
    assert c["loop_us_per_attempt"] > 0
    # 6 per attempt with FSAL [T203], + 1 at the start and 1 after each projection too large for
    # FSAL: measured 14,888 RHS / 2,481 attempts = 6.0008
    assert 6.0 <= c["rhs_per_attempt"] < 6.1
