"""Lumped oil temperature of a journal bearing in the dynamics [T310–T313]: a flywheel on an ideal
axle runs down in a bearing whose film heats the oil; checked against the flywheel's kinetic
energy (mechanics, independent of the thermal memory), against an independent ODE of the same
two physical laws solved by scipy, and for the closure of its own energy balance."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from jointdyn.core.constraints import Revolute
from jointdyn.errors import PhysicsWarning, SimulationError
from jointdyn.film.models import film_forces
from jointdyn.film.viscosity import oil_by_name
from jointdyn.forces.journal import JournalBearing
from jointdyn.forces.thermal import LumpedOil
from jointdyn.io.modelfile import load_model
from jointdyn.multibody.codec import decode_item, encode_value
from jointdyn.multibody.model import Model
from jointdyn.post import film_outputs, film_states, film_viscosity
from jointdyn.simulation.simulate import SimConfig, simulate

R, L, C = 0.01, 0.02, 20e-6  # journal radius, length, clearance [m]
INERTIA, W0 = 0.05, 300.0  # flywheel [kg·m²], initial speed [rad/s]


def _flywheel(thermal):
    m = Model("flywheel", gravity=(0.0, 0.0))
    m.add_ground_point("O", (0.0, 0.0))
    m.add_body("w", 1.0, INERTIA, points={"O": (0.0, 0.0)})
    m.add("axle", Revolute("ground", "O", "w", "O"))  # ξ = 0: the film carries no load
    m.add(
        "bearing",
        JournalBearing(
            "ground",
            "O",
            "w",
            "O",
            R + C,
            R,
            L,
            0.04 if thermal is None else None,
            film="short",
            thermal=thermal,
        ),
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # short film at L/D = 1
        return m.compile(centre_imperfect=False)


def _run(thermal, t_end):
    s = _flywheel(thermal)
    y0 = s.y0.copy()
    y0[len(y0) // 2 + 2] = W0
    return simulate(s, SimConfig(t_end=t_end, n_out=201), y0=y0)


def test_oil_heats_up_and_the_viscosity_follows():
    th = LumpedOil("ISO_VG46", inlet_temp=40.0, heat_capacity=20.0, h_A=0.5, ambient_temp=20.0)
    res = _run(th, 20.0)
    T = res.memory("bearing", "oil_temperature")
    gen = res.memory("bearing", "heat_generated")
    rem = res.memory("bearing", "heat_removed")
    w = res.y[:, len(res.y[0]) // 2 + 2]
    # energy balance of the thermal state over the run [T312] (measured: 2e-11 J of 348 J)
    assert abs(th.heat_capacity * (T[-1] - T[0]) - (gen[-1] - rem[-1])) <= 1e-6 * gen[-1]
    # the heat generated is the flywheel's lost kinetic energy (measured: 1.2e-8 relative)
    assert gen[-1] == pytest.approx(0.5 * INERTIA * (W0**2 - w[-1] ** 2), rel=1e-6)
    # independent reference: I dω/dt = −kμ(T)ω, C dT/dt = kμ(T)ω² − hA(T − T_amb) with the Python
    # viscosity law, k = 2πR³L/c (Petroff at ξ = 0) [T75, T310]
    oil, k = oil_by_name("ISO_VG46"), 2 * math.pi * R**3 * L / C

    def f(t, z):
        mu = oil.viscosity(z[1])
        return [
            -k * mu * z[0] / INERTIA,
            (k * mu * z[0] ** 2 - th.h_A * (z[1] - th.ambient_temp)) / th.heat_capacity,
        ]

    ref = solve_ivp(f, (0.0, 20.0), [W0, 40.0], t_eval=res.t, method="DOP853", rtol=1e-11, atol=1e-11)
    assert T[-1] - T[0] > 5.0  # it heats up (5.6 K) …
    mu = res.memory("bearing", "viscosity")
    assert mu[-1] < 0.8 * mu[0]  # … and the viscosity follows
    np.testing.assert_allclose(mu, [oil.viscosity(t - 273.15) for t in T], rtol=1e-12)
    # lock-step error, DT_STEP = 0.01 K per step [T312] (measured: 0.009 K, 1.4e-5)
    np.testing.assert_allclose(T - 273.15, ref.y[1], atol=0.02)
    np.testing.assert_allclose(w, ref.y[0], rtol=5e-5)


def test_oil_out_of_its_law_stops_the_run_naming_the_bearing():
    th = LumpedOil("ISO_VG46", inlet_temp=140.0, heat_capacity=0.01)  # adiabatic, tiny capacity
    with pytest.raises(SimulationError, match="'bearing': the oil temperature left the viscosity law"):
        _run(th, 1.0)


@pytest.mark.parametrize(
    "kw, message",
    [
        (dict(oil="ISO_VG47"), "oil = 'ISO_VG47': unknown grade"),
        (dict(heat_capacity=0.0), r"heat_capacity = 0.0 \[J/K\]"),
        (dict(inlet_temp=200.0), r"inlet_temp = 200.0 \[°C\]"),
        (dict(mass_flow=-1.0), r"mass_flow = -1.0 \[kg/s\]"),
    ],
)
def test_bad_thermal_input_names_the_parameter(kw, message):
    args = dict(oil="ISO_VG46", inlet_temp=40.0, heat_capacity=20.0) | kw
    with pytest.raises(ValueError, match=message):
        JournalBearing("a", "A", "b", "B", R + C, R, L, 0.04, thermal=LumpedOil(**args)).validate()


def test_thermal_in_a_model_file(tmp_path):
    text = f"""
[model]
name = "flywheel"
gravity = [0.0, 0.0]
[ground.points]
O = [0.0, 0.0]
[bodies.w]
mass = 1.0
inertia = {INERTIA}
points = {{ O = [0.0, 0.0] }}
[joints.axle]
type = "revolute"
body_i = "ground"
point_i = "O"
body_j = "w"
point_j = "O"
[elements.bearing]
type = "journal_bearing"
body_i = "ground"
point_i = "O"
body_j = "w"
point_j = "O"
bearing_radius = {R + C}
journal_radius = {R}
length = {L}
film = "short"
thermal = {{ law = "lumped", oil = "ISO_VG46", inlet_temp = 40.0, heat_capacity = 20.0, h_A = 0.5 }}
[simulation]
t_end = 1.0
"""
    p = tmp_path / "m.toml"
    p.write_text(text)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model, _ = load_model(p, assemble=False)
    el = model.items["bearing"]
    assert el.thermal == LumpedOil("ISO_VG46", inlet_temp=40.0, heat_capacity=20.0, h_A=0.5)
    table = {
        "type": "journal_bearing",
        **{k: encode_value(v) for k, v in el.__dict__.items() if v is not None},
    }
    assert decode_item("elements", table) == el  # codec round trip
    p.write_text(text.replace("heat_capacity = 20.0", "heat_capacity = -1.0"))
    with pytest.raises(Exception, match="heat_capacity"):
        load_model(p, assemble=False)


def test_the_viscosity_is_the_oils_everywhere():
    """With ``thermal`` the bearing takes no ``viscosity`` (one given anyway is unused and said
    so; none without thermal is refused), and what is computed after the run from the film (peak
    pressure) uses μ(T) of the run's memory, not a constant [T311]."""
    th = LumpedOil("ISO_VG46", inlet_temp=40.0, heat_capacity=2.0, h_A=0.05)
    with pytest.warns(PhysicsWarning, match=r"viscosity = 0.04 \[Pa·s\] is unused"):
        JournalBearing("a", "A", "b", "B", R + C, R, L, 0.04, film="alshaer2005", thermal=th).validate()
    with pytest.raises(ValueError, match=r"viscosity \[Pa·s\]: required \(> 0\) unless thermal is set"):
        JournalBearing("a", "A", "b", "B", R + C, R, L, film="short").validate()
    # a free journal carrying its weight (ξ > 0: a pressure field), spinning down while the oil heats
    m = Model("free journal", gravity=(0.0, -9.81))
    m.add_ground_point("O", (0.0, 0.0))
    m.add_body("w", 1.0, INERTIA, points={"O": (0.0, 0.0)})
    m.add("bearing", JournalBearing("ground", "O", "w", "O", R + C, R, L, film="short", thermal=th))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # short film at L/D = 1
        s = m.compile(centre_imperfect=False)
    y0 = s.y0.copy()
    y0[len(y0) // 2 + 2] = W0
    res = simulate(s, SimConfig(t_end=2.0, n_out=41), y0=y0)
    T = res.memory("bearing", "oil_temperature") - 273.15
    mu = film_viscosity(res, "bearing")
    oil = oil_by_name("ISO_VG46")
    np.testing.assert_allclose(mu, [oil.viscosity(t) for t in T], rtol=1e-12)  # the oil's law at T
    assert mu[-1] < 0.9 * mu[0]  # the oil heated: a constant μ would be ≥ 10 % off
    # the film force the kernel recorded (with μ of its memory) against the film model's Python
    # API at the same states with film_viscosity: equal; with μ(T_in) it would be ≥ 10 % off
    st = {k: v[1:] for k, v in film_states(res, "bearing").items()}  # sample 0: centred, ξ = 0
    wj = res.y[1:, len(res.y[0]) // 2 + 2]
    gdot = 0.5 * (wj - st["xi_Omega"] / st["xi"])  # ξΩ = ξ(ω_J + ω_B − 2γ̇), ω_B = 0 [T14]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # short film at L/D = 1
        f = film_forces("short", st["xi"], st["xi_dot"], st["gamma"], gdot, wj, 0.0, mu[1:], L, R, C)
    fx, fy = res.element("bearing", "Fx")[1:], res.element("bearing", "Fy")[1:]
    scale = np.max(np.hypot(fx, fy))
    np.testing.assert_allclose(f["Fx"], fx, rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(f["Fy"], fy, rtol=0, atol=1e-9 * scale)
    assert np.all(film_outputs(res, "bearing")["p_max"][1:] > 0.0)  # a loaded film everywhere
