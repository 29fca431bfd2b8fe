"""Tabulated external force, and the single-cylinder engine example's energy balance."""

import math
from pathlib import Path

import numpy as np
import pytest

from jointdyn.core.constraints import Translational
from jointdyn.forces.tabulated import TabulatedForce
from jointdyn.io.modelfile import load_model
from jointdyn.multibody.model import Model
from jointdyn.simulation.simulate import SimConfig, simulate

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def slider(force):
    m = Model("slider", gravity=(0.0, 0.0))
    m.add_ground_point("O", (0.0, 0.0))
    m.add_body("s", 2.0, 0.1, points={"c": (0.0, 0.0)})
    m.add("guide", Translational("ground", "O", "s", "c"))
    m.add("push", force)
    return m.compile()


def test_time_table_drives_a_free_slider_exactly():
    # F(t) = 100 t [N] for t ≤ 0.5 s, then 50 N: x = F/m integrated twice (closed form)
    f = TabulatedForce("s", "c", x=(0.0, 0.5), y=(0.0, 50.0), direction=(1.0, 0.0))
    res = simulate(slider(f), SimConfig(t_end=1.0, n_out=101, rtol=1e-10, atol=1e-12))
    t = res.t
    # a = 50 t (t ≤ 0.5), then 25 m/s²; v(0.5) = 6.25 m/s, x(0.5) = 50·0.125/6
    x_half, v_half = 50 * 0.5**3 / 6, 25 * 0.5**2
    x_ref = np.where(t <= 0.5, 50 * t**3 / 6, x_half + v_half * (t - 0.5) + 12.5 * (t - 0.5) ** 2)
    np.testing.assert_allclose(res.coordinate("s", "x"), x_ref, atol=1e-7)  # kink at 0.5 s: rtol-level


def test_angle_argument_wraps_with_the_period():
    f = TabulatedForce(
        "s", "c", x=(0.0, math.pi, 2 * math.pi), y=(0.0, 10.0, 0.0), argument="s", period=2 * math.pi
    )
    with pytest.raises(ValueError, match="strictly increasing"):
        TabulatedForce("s", "c", x=(0.0, 0.0), y=(1.0, 2.0)).validate()
    sysm = slider(f)  # the slider's angle is locked at 0: force = table(0) = 0
    res = simulate(sysm, SimConfig(t_end=0.1, n_out=3))
    assert np.all(res.coordinate("s", "x") == 0.0)


def test_engine_example_energy_balance():
    """Single-cylinder engine file with the gas force switched off: the work of the drive plus
    the (dissipative) work of both lubricated bearings equals the change of mechanical energy."""
    model, cfg = load_model(
        EXAMPLES / "engine_single_cylinder.toml",
        [
            "elements.gas.x=[0.0, 1.0]",
            "elements.gas.y=[0.0, 0.0]",
            "simulation.t_end=0.02",
            "simulation.n_out=4001",
        ],
    )
    sysm = model.compile()
    res = simulate(sysm, cfg)
    mass = 1.0 / sysm.minv
    E = 0.5 * (mass * res.qd**2).sum(1) - (res.q * sysm.q0_force).sum(1)
    w_drive = res.multipliers("drive")[:, 0] * res.qd[:, 3 * sysm.body_index("crank") + 2]
    p_el = sum(res.element(name, "power") for name in sysm.element_names)
    trap = lambda p: np.concatenate([[0.0], np.cumsum(0.5 * (p[1:] + p[:-1]) * np.diff(res.t))])
    balance = trap(w_drive) + trap(p_el) - (E - E[0])
    scale = trap(np.abs(w_drive))[-1]
    # trapezoidal quadrature of the powers on 4001 samples: ~1e-5 of the work turned over
    assert np.abs(balance).max() < 1e-4 * scale
    assert trap(p_el)[-1] < 0  # the films dissipate


#: the model files with a transient jfo film run in the slow tier: slider_crank_jfo's quarter
#: revolution takes ≈ 40 s CPU [T309], engine_big_end_jfo compiles a kernel set of its own (the
#: engine's kinds with the jfo film under radau5, 77 s CPU from an empty cache [T373]); the jfo
#: element runs end to end by default in tests/test_jfo_element.py, and both files load and build
#: below by default
SLOW_FILES = ("slider_crank_jfo", "engine_big_end_jfo")
ALL_FILES = [p for p in sorted(EXAMPLES.glob("*.toml")) if "[base]" not in p.read_text(encoding="utf-8")]
MODEL_FILES = [pytest.param(p, marks=pytest.mark.slow) if p.stem in SLOW_FILES else p for p in ALL_FILES]


@pytest.mark.parametrize("path", MODEL_FILES, ids=lambda p: p.stem)
def test_every_example_model_file_runs(path):
    model, cfg = load_model(path, ["simulation.t_end=0.003", "simulation.n_out=31"])
    res = simulate(model.compile(), cfg)
    assert np.all(np.isfinite(res.y)) and res.drift[:, 0].max() < 1e-10


@pytest.mark.parametrize("path", [p for p in ALL_FILES if p.stem in SLOW_FILES], ids=lambda p: p.stem)
def test_slow_tier_model_files_load_and_build(path):
    """The files whose run is in the slow tier parse, validate and build their system (initial
    state assembled on the constraints) by default; no kernel set of their own is compiled."""
    model, cfg = load_model(path, ["simulation.t_end=0.003", "simulation.n_out=31"])
    system = model.compile()
    assert cfg.t_end == 0.003 and np.all(np.isfinite(system.y0)) and system.y0.size > 0
