"""Single impacts through the full clearance-joint element: a free pin (no gravity) launched
from the centre of a fixed hole hits the wall once; restitution = rebound/approach normal speed."""

import math

import numpy as np
import pytest

from jointdyn.forces.contact_laws import Flores, Hertz, HuntCrossley, LankaraniNikravesh
from jointdyn.forces.journal import ClearanceJoint
from jointdyn.multibody.model import Model
from jointdyn.simulation.simulate import SimConfig, simulate

RB, RJ = 0.0105, 0.0100
K = 6.9e10  # benchmark journal-in-bearing stiffness [T160, T56] [N/m^1.5]


def impact(law, v0=1.0, mass=0.14, solver="dopri5", rtol=1e-9):
    m = Model("impact", gravity=(0.0, 0.0))
    m.add_ground_point("O", (0.0, 0.0))
    m.add_body(
        "pin", mass, 1e-4, position=(0.0, 0.0), velocity=(v0 * 0.6, v0 * 0.8, 0.0), points={"c": (0.0, 0.0)}
    )
    m.add("joint", ClearanceJoint("ground", "O", "pin", "c", RB, RJ, contact=law))
    sysm = m.compile(centre_imperfect=False)
    c = RB - RJ
    t_end = 2 * c / v0 * 1.5  # out to the wall and most of the way back
    res = simulate(sysm, SimConfig(t_end=t_end, n_out=3, solver=solver, rtol=rtol, atol=1e-13))
    vx, vy = res.qd[-1, 0], res.qd[-1, 1]
    assert res.mem[-1, 0, 2] == 1  # exactly one impact recorded
    # radial rebound speed (the pin moves back along the line of centres: frictionless, central)
    return -(vx * 0.6 + vy * 0.8) / v0, math.hypot(-vx * 0.8 + vy * 0.6, 0.0)


def one_dof_restitution(law, v0=1.0, mass=0.14):
    """Independent reference: m δ̈ = −F(δ, δ̇, v0) from δ = 0, δ̇ = v0 until δ returns to 0
    (scipy Radau, tight tolerances); the law written out here, not taken from the library."""
    from scipy.integrate import solve_ivp

    Kl, n, cr = law.stiffness, law.exponent, law.restitution
    chi = {
        "LankaraniNikravesh": 0.75 * (1 - cr**2),
        "HuntCrossley": 1.5 * (1 - cr),
        "Flores": 8 * (1 - cr) / (5 * cr),
        "Hertz": 0.0,
    }[type(law).__name__]

    def f(t, y):
        d = max(y[0], 0.0)
        return [y[1], -max(Kl * d**n * (1 + chi * y[1] / v0), 0.0) / mass]

    ev = lambda t, y: y[0] + 1e-15 if t > 0 else 1.0
    ev.terminal, ev.direction = True, -1
    sol = solve_ivp(f, (0, 1e-2), [0.0, v0], method="Radau", rtol=1e-11, atol=1e-16, events=ev)
    return -sol.y_events[0][0][1] / v0


LAWS = [
    (LankaraniNikravesh, 0.9),
    (LankaraniNikravesh, 0.7),
    (HuntCrossley, 0.9),
    (HuntCrossley, 0.7),
    (Flores, 0.9),
    (Flores, 0.7),
    (Flores, 0.5),
]


def _tier(solver, law, cr):
    """Every law under dopri5 and Lankarani–Nikravesh (the dry slider-crank's law, whose kernels
    the suite compiles anyway) under the stiff methods run in the default tier; the other laws
    under the stiff methods are ``slow``: each (law, stiff method) pair compiles a kernel set of
    its own, ≈ 40 s of CPU from a cold cache, and what they add — the law's Jacobian inside the
    stiff step — is covered by every law's Jacobian against finite differences
    (tests/test_jacobians_laws.py) and by Lankarani–Nikravesh here."""
    marks = () if solver == "dopri5" or law is LankaraniNikravesh else pytest.mark.slow
    return pytest.param(solver, law, cr, marks=marks, id=f"{solver}-{law.__name__}-{cr}")


@pytest.mark.parametrize(
    "solver,law,cr", [_tier(s, law, cr) for s in ("dopri5", "rodas4", "ros34pw2") for law, cr in LAWS]
)
def test_element_restitution_equals_the_law(law, cr, solver):
    lw = law(stiffness=K, exponent=1.5, restitution=cr)
    e, vt = impact(lw, solver=solver)
    # the element (onset δ̇⁻ captured at ≤ 1e-8 m penetration, 2-D journal kinematics) reproduces
    # the law's own 1-DOF restitution; 1e-4 covers the onset resolution and rtol = 1e-9
    assert e == pytest.approx(one_dof_restitution(lw), rel=1e-4)
    assert vt < 1e-9  # central impact: no tangential velocity created


@pytest.mark.parametrize(
    "law,cr,tol",
    [(LankaraniNikravesh, 0.9, 0.02), (HuntCrossley, 0.9, 0.05), (Flores, 0.9, 0.05), (Flores, 0.7, 0.05)],
)
def test_restitution_matches_the_laws_intent_in_their_validity_range(law, cr, tol):
    """Issue 4 tolerances: LN 2 %, Hunt–Crossley/Flores 5 %. LN and Hunt–Crossley are derived
    for c_r close to 1; at c_r = 0.7 the laws themselves give 0.796 and 0.768 (see the 1-DOF
    reference above), so no integrator can meet 2 % there: Flores et al. (2011) is the law
    for low restitution."""
    e, _ = impact(law(stiffness=K, exponent=1.5, restitution=cr))
    assert e == pytest.approx(cr, rel=tol)


def test_hertz_conserves_energy():
    e, _ = impact(Hertz(stiffness=K, exponent=1.5))
    # elastic law: rebound speed = approach speed to integrator tolerance (rtol 1e-9)
    assert e == pytest.approx(1.0, abs=1e-6)


def test_dry_slider_crank_compiled_and_scipy_event_paths_agree():
    """First revolution (before chaos sets in, [T162]): the compiled onset handling
    and scipy's event location give the same impacts, the same first-impact depth and RMS."""
    from jointdyn import post
    from jointdyn.models.slider_crank import slider_crank

    sysm = slider_crank("dry").compile()
    out = {}
    for solver in ("dopri5", "scipy-radau"):
        r = simulate(sysm, SimConfig(t_end=0.012, n_out=721, solver=solver, rtol=1e-7, atol=1e-11))
        out[solver] = (r.mem[-1, 0, 2], r.eout[:, 0, 2].max(), np.sqrt(np.mean(post.driving_moment(r) ** 2)))
    (ia, xa, ra), (ib, xb, rb) = out["dopri5"], out["scipy-radau"]
    # measured 29–30 over solvers, rtol 1e-6 … 1e-9 and chunking (a grazing re-contact comes and goes)
    assert abs(ia - ib) <= 1 and 29 <= ia <= 30
    assert xa == pytest.approx(xb, abs=1e-6)  # largest sampled ξ = first impact, converged
    # RMS over the revolution: measured 130.0–135.6 N·m across solvers/step sequences (chaotic
    # after the first impacts); 6 % bounds that spread
    assert ra == pytest.approx(rb, rel=0.06)
