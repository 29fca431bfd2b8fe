"""power_loss of the journal bearing is the film's dissipation, ≥ 0 by construction [T282];
the rest of the power of the loads the element applies is power_exchanged (non-zero only when
the film is evaluated at a capped eccentricity, ξ > ξ_cap with asperity contact, or without the
shear torques). Checked against the power of the applied generalized forces, −Q·q̇, computed
independently of the element's outputs."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from jointdyn.forces.contact_laws import LankaraniNikravesh
from jointdyn.forces.elements import NMEM, NOUT, eval_forces
from jointdyn.forces.journal import JournalBearing
from jointdyn.models.slider_crank import SPEED
from jointdyn.models.slider_crank_args import shipped_model
from jointdyn.multibody.model import Model
from jointdyn.simulation.simulate import SimConfig, simulate

MU, R, L, C = 0.4, 0.0100, 0.04, 5e-4


def _pair(film, shear=True, **kw):
    m = Model("pair", gravity=(0.0, 0.0))
    m.add_body("a", 1.0, 1e-3, points={"A": (0.0, 0.0)})
    m.add_body("b", 1.0, 1e-3, points={"B": (0.0, 0.0)})
    m.add("pin", JournalBearing("a", "A", "b", "B", R + C, R, L, MU, film=film, shear=shear, **kw))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # short at L/D = 2
        return m.compile(centre_imperfect=False)


def _forces(sysm, q, qd):
    Q = np.zeros(6)
    out = np.zeros((1, NOUT))
    eval_forces(0.0, q, qd, np.zeros((1, NMEM)), sysm.fint, sysm.freal, sysm.tables, Q, out)
    return Q, dict(zip(type(sysm.elements[0]).OUTPUTS, out[0]))


def _states(rng, xi_max):
    q = np.concatenate([rng.normal(size=2) * 0.1, rng.uniform(-3, 3, 1), [0, 0], rng.uniform(-3, 3, 1)])
    ang = rng.uniform(0, 2 * math.pi)
    q[3:5] = q[0:2] + rng.uniform(0, xi_max) * C * np.array([math.cos(ang), math.sin(ang)])
    qd = rng.normal(size=6) * np.array([0.2, 0.2, 300, 0.2, 0.2, 300])
    return q, qd


@pytest.mark.parametrize("film", ["ott", "alshaer2005", "short", "finite"])
@pytest.mark.parametrize("shear", [True, False])
def test_power_loss_is_nonnegative_and_the_rest_is_exchanged(film, shear):
    """300 random states per film model: power_loss ≥ 0; power_loss + power_exchanged = −Q·q̇
    (the power the applied loads take from the bodies); with the shear torques and ξ below the
    cap nothing is exchanged (round-off)."""
    sysm = _pair(film, shear)
    rng = np.random.default_rng(5)
    for _ in range(300):
        q, qd = _states(rng, 0.95)
        Q, out = _forces(sysm, q, qd)
        scale = np.abs(Q).max() * np.abs(qd).max() + 1e-300
        assert out["power_loss"] >= -1e-12 * scale
        assert out["power_loss"] + out["power_exchanged"] == pytest.approx(-(Q @ qd), abs=1e-11 * scale)
        if shear:
            assert abs(out["power_exchanged"]) <= 1e-11 * scale


def test_capped_film_with_asperity_contact():
    """ξ > ξ_cap = 1 − h_asp/c (= 0.7; asperity contact acts there): the film force is evaluated
    at ξ_cap while the journal sits further out; the dissipation stays ≥ 0 and the difference,
    c·F_t·(ξ − ξ_cap)·(ω_J + ω_B)/2, is exchanged with both signs."""
    sysm = _pair("alshaer2005", True, contact=LankaraniNikravesh(stiffness=1e10), asperity_height=0.3 * C)
    rng = np.random.default_rng(7)
    signs = set()
    for _ in range(300):
        q, qd = _states(rng, 0.0)
        ang = rng.uniform(0, 2 * math.pi)
        q[3:5] = q[0:2] + rng.uniform(0.701, 0.9) * C * np.array([math.cos(ang), math.sin(ang)])
        Q, out = _forces(sysm, q, qd)
        scale = abs(out["power_loss"]) + abs(out["power_exchanged"]) + 1e-300
        assert out["power_loss"] >= -1e-12 * scale
        signs.add(float(np.sign(out["power_exchanged"])))
    assert {-1.0, 1.0} <= signs


def test_replay_lubricated_run_with_asperity_contact():
    """The campaign's case (alshaer2005 + contact; asperity height 0.3 mm, c = 0.5 mm gave
    power_loss −0.27 W in 342 of 1441 samples over 2 revolutions; 0.3 mm is now above the c/2
    limit, 0.25 mm is the largest allowed): power_loss ≥ 0 everywhere, the negative part is in
    power_exchanged, and the two add up to −power wherever no contact force acts."""
    res = simulate(
        shipped_model("alshaer2005", {"contact": True, "asperity_height": 2.5e-4}).compile(),
        SimConfig(t_end=0.5 * 2 * math.pi / SPEED, n_out=181),
    )
    loss = res.element("piston_pin", "power_loss")
    exch = res.element("piston_pin", "power_exchanged")
    power = res.element("piston_pin", "power")
    free = res.element("piston_pin", "contact_force") == 0.0
    assert loss.min() >= 0.0 and exch.min() < 0.0
    np.testing.assert_allclose((loss + exch)[free], -power[free], rtol=1e-9, atol=1e-9 * np.abs(power).max())
