"""Mixed lubrication in the multibody journal element [T314–T316]: a journal driven at constant
speed under a dead load settles to the steady mixed operating point of ``jointdyn stribeck``
(``bearing.mixed.operating_point``, the same film with Reynolds cavitation and the same
Greenwood–Tripp surfaces, solved by a different path: finite volumes and root finding), and a
mechanism run down a speed ramp passes through the Stribeck minimum."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.optimize import fsolve

from jointdyn.bearing.mixed import Bearing, operating_point
from jointdyn.core.constraints import AngleDriver
from jointdyn.film.asperity import GreenwoodTripp, asperity_load
from jointdyn.film.models import Finite
from jointdyn.forces.elements import NOUT, eval_forces
from jointdyn.forces.journal import JournalBearing
from jointdyn.forces.mixed import GreenwoodTrippContact, asperity_loads
from jointdyn.multibody.model import Model
from jointdyn.simulation.simulate import SimConfig, simulate

R, L, C, MU, SIGMA, W = 0.025, 0.025, 25e-6, 0.02, 1.5e-6, 3000.0
G = 9.81


def _rig(omega, alpha=0.0):
    m = Model("stribeck_rig", gravity=(0.0, -G))
    m.add_ground_point("O", (0.0, 0.0))
    m.add_body("journal", W / G, 0.01, points={"O": (0.0, 0.0)})
    m.add("drive", AngleDriver("ground", "journal", omega=omega, alpha=alpha))
    asp = GreenwoodTrippContact(SIGMA)
    m.add(
        "bearing",
        JournalBearing("ground", "O", "journal", "O", R + C, R, L, MU, Finite("reynolds"), asperity=asp),
    )
    return m.compile(centre_imperfect=False)


def test_asperity_tables_equal_the_steady_resultant():
    asp = GreenwoodTrippContact(SIGMA)
    tr, tn = asp.tables(R, L, C)
    theta = np.linspace(0.0, 2 * math.pi, 4096, endpoint=False)
    w = np.full(4096, 2 * math.pi / 4096)
    for xi in (0.5, 0.8, 0.9, 0.93, 0.95, 0.97, 0.99, 0.998):
        ref = asperity_load(GreenwoodTripp(SIGMA), xi, R, L, C, theta, w)
        fr, wa = asperity_loads(xi, tr, tn)
        # measured: ≤ 5.7e-5 relative where the load exceeds 1 N (2.8e-5 N at ξ = 0.8) [T315]
        assert fr == pytest.approx(ref["F_r"], rel=1e-4, abs=1e-3)
        assert wa == pytest.approx(ref["normal"], rel=1e-4, abs=1e-3)


def _forces(rig, x, y, omega):
    Q, out = np.zeros(3), np.zeros((1, NOUT))
    q, qd = np.array([x, y, 0.0]), np.array([0.0, 0.0, omega])
    eval_forces(0.0, q, qd, rig.mem0.copy(), rig.fint, rig.freal, rig.tables, Q, out)
    return Q, dict(zip(JournalBearing.OUTPUTS, out[0]))


@pytest.mark.parametrize("speed", [1.0, 2.0, 4.0, 16.0])  # rev/s: asperity share 0.28 … 0
def test_quasi_static_point_equals_the_steady_mixed_operating_point(speed):
    b = Bearing(R, L, C, MU, GreenwoodTripp(SIGMA), flow=None)
    op = operating_point(b, W, speed)
    omega = 2 * math.pi * speed
    rig = _rig(omega)
    # the element's equilibrium under the dead load: film + asperities = W (Newton on its forces)
    e, att = op["eps"] * C, math.radians(op["attitude_deg"])  # φ ahead of the load [T271]
    x = fsolve(
        lambda z: _forces(rig, z[0] * C, z[1] * C, omega)[0][:2] + (0.0, -W),
        [e * math.sin(att) / C, -e * math.cos(att) / C],
        xtol=1e-12,
    )
    out = _forces(rig, x[0] * C, x[1] * C, omega)[1]
    assert out["xi"] == pytest.approx(op["eps"], abs=1e-3)  # measured ≤ 3e-4 [T316]
    assert -out["friction_torque"] == pytest.approx(op["friction_torque"], rel=0.01)  # measured ≤ 0.32 %
    # the dynamics stays there: 20 ms from that point
    y0 = rig.y0.copy()
    y0[0:2] = x * C
    res = simulate(rig, SimConfig(t_end=0.02, n_out=21), y0=y0)
    assert abs(res.element("bearing", "xi") - out["xi"]).max() < 1e-5
    with pytest.raises(KeyError, match="no memory slot 'oil_temperature'"):  # no thermal state here
        res.memory("bearing", "oil_temperature")
    assert "bearing.memory.heat_generated" not in res.to_xarray()


def test_a_mechanism_runs_through_the_stribeck_minimum():
    """The driven journal accelerated from 1 to 16 rev/s in 1 s, starting at its equilibrium: the
    friction torque falls from the mixed regime (2.15 N·m), passes a minimum near 7 rev/s
    (measured 0.202 N·m; quasi-static minimum 0.202 N·m at 8 rev/s [T316]) and rises to the
    hydrodynamic 0.317 N·m."""
    w0, w1 = 2 * math.pi, 32 * math.pi
    rig = _rig(w0, alpha=w1 - w0)
    x = fsolve(lambda z: _forces(rig, z[0] * C, z[1] * C, w0)[0][:2] + (0.0, -W), [0.3, -0.9], xtol=1e-12)
    y0 = rig.y0.copy()
    y0[0:2], y0[5] = x * C, w0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # ξ = 0.952 at the start: just beyond the finite table
        res = simulate(rig, SimConfig(t_end=1.0, n_out=151), y0=y0)
    torque = -res.element("bearing", "friction_torque")
    speed = (w0 + (w1 - w0) * res.t) / (2 * math.pi)
    k = int(np.argmin(torque))
    assert 5.0 < speed[k] < 10.0
    assert torque[0] > 10 * torque[k] and torque[-1] > 1.5 * torque[k]
    b = Bearing(R, L, C, MU, GreenwoodTripp(SIGMA), flow=None)
    assert torque[-1] == pytest.approx(operating_point(b, W, 16.0)["friction_torque"], rel=0.01)


@pytest.mark.parametrize(
    "kw, message",
    [
        (dict(sigma=0.0), r"GreenwoodTrippContact.sigma = 0.0 \[m\]"),
        (dict(sigma=1e-6, boundary_friction=1.5), r"boundary_friction = 1.5 \[-\]"),
        (dict(sigma=1e-6, slip_speed=-1.0), r"slip_speed = -1.0 \[m/s\]"),
    ],
)
def test_bad_asperity_input_names_the_parameter(kw, message):
    with pytest.raises(ValueError, match=message):
        JournalBearing("a", "A", "b", "B", R + C, R, L, MU, asperity=GreenwoodTrippContact(**kw)).validate()


def test_asperity_in_a_model_file_round_trips():
    from jointdyn.multibody.codec import decode_item, encode_value

    el = JournalBearing(
        "a", "A", "b", "B", R + C, R, L, MU, asperity=GreenwoodTrippContact(SIGMA, boundary_friction=0.12)
    )
    table = {
        "type": "journal_bearing",
        **{k: encode_value(v) for k, v in el.__dict__.items() if v is not None},
    }
    assert table["asperity"] == {
        "law": "greenwood_tripp",
        "sigma": SIGMA,
        "eta_beta_sigma": 0.04,
        "sigma_over_beta": 0.001,
        "modulus": 1.1e11,
        "boundary_friction": 0.12,
        "slip_speed": 0.001,
    }
    assert decode_item("elements", table) == el
