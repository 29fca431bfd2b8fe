"""Rotational force elements (torsion spring, harmonic torque) against closed forms, and the Ueda
oscillator model file against an independent ODE integration and its published exponent."""

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import simpson, solve_ivp

from jointdyn.errors import ModelError
from jointdyn.forces.elements import NMEM, NOUT, eval_forces
from jointdyn.forces.torsion import HarmonicTorque, TorsionSpring
from jointdyn.io.modelfile import load_system
from jointdyn.multibody.model import Model
from jointdyn.simulation.simulate import SimConfig, simulate

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
# ∫₀¹ du/√(1 − u⁴) = ϖ/2, half the lemniscate constant (Abramowitz & Stegun 17.4.46 / OEIS A062539)
HALF_LEMNISCATE = 1.3110287771460599


def _rotor(*elements, angle=0.0, omega=0.0, inertia=2.0):
    """One rotor of inertia J [kg·m²] on a revolute joint to the ground at its centre."""
    from jointdyn.core.constraints import Revolute

    m = Model("rotor", gravity=(0.0, 0.0))
    m.add_ground_point("O", (0.0, 0.0))
    m.add_body(
        "r", 1.0, inertia, position=(0.0, 0.0), angle=angle, velocity=(0.0, 0.0, omega), points={"C": (0, 0)}
    )
    m.add("bearing", Revolute("ground", "O", "r", "C"))
    for k, e in enumerate(elements):
        m.add(f"e{k}", e)
    return m.compile()


def _outputs(system, t, q, qd):
    Q = np.zeros(system.n)
    out = np.zeros((len(system.elements), NOUT))
    eval_forces(
        t, q, qd, np.zeros((len(system.elements), NMEM)), system.fint, system.freal, system.tables, Q, out
    )
    return Q, out


def test_torsion_spring_moment_is_minus_the_gradient_of_its_energy():
    # M = −dV/dθ − c θ̇ with V = ½kθ² + ¼k₃θ⁴ [T132]: the energy output, differenced centrally
    # (h = 1e-6 rad, truncation ~ h²·V''' ~ 1e-10 relative), against the moment output
    e = TorsionSpring("ground", "r", stiffness=3.0, cubic_stiffness=-0.4, damping=0.7, free_angle=0.2)
    s = _rotor(e)
    rng = np.random.default_rng(3)
    for _ in range(20):
        th, w = rng.uniform(-2, 2), rng.uniform(-5, 5)
        q, qd = np.zeros(3), np.array([0.0, 0.0, w])
        q[2] = th + 0.2
        Q, out = _outputs(s, 0.0, q, qd)
        V = lambda x: 0.5 * 3.0 * x**2 + 0.25 * -0.4 * x**4
        assert out[0, 3] == pytest.approx(V(th), rel=1e-14, abs=1e-15)  # closed-form energy, round-off
        h = 1e-6
        dV = (V(th + h) - V(th - h)) / (2 * h)
        assert Q[2] == pytest.approx(-dV - 0.7 * w, rel=1e-8, abs=1e-9)
        assert out[0, 4] == pytest.approx(Q[2] * w, rel=1e-14, abs=1e-14)  # power = M θ̇


def test_cubic_spring_rotor_period_and_energy_conservation():
    # J θ'' + k₃ θ³ = 0 from θ = a, θ̇ = 0: period T = 4√2·(ϖ/2)/(a √(k₃/J)) exactly, and
    # ½Jθ̇² + ¼k₃θ⁴ is conserved. The energy drift is the integrator's global error: measured
    # max |ΔE|/E = 8.2e-8, 1.3e-8, 2.0e-9 at rtol 1e-10, 1e-11, 1e-12 (dopri5, 3 periods), so it
    # converges with the tolerance; bound 1e-8 at rtol 1e-12 (5× the measured value)
    J, k3, a = 2.0, 5.0, 0.8
    # with a harmonic torque of amplitude 0 (adds ±0 to the moment: the same numbers), the run
    # uses the kernel set of the Ueda model file, which the suite compiles anyway [T373]
    nothing = HarmonicTorque("r", amplitude=0.0, frequency=1.0)
    s = _rotor(TorsionSpring("ground", "r", cubic_stiffness=k3), nothing, angle=a, inertia=J)
    T = 4 * math.sqrt(2) * HALF_LEMNISCATE / (a * math.sqrt(k3 / J))
    res = simulate(s, SimConfig(t_end=3.2 * T, n_out=3201, solver="dopri5", rtol=1e-12, atol=1e-14))
    th = res.coordinate("r", "phi")
    w = res.qd[:, 2]
    E = 0.5 * J * w**2 + res.element("e0", "energy")
    assert np.abs(E - E[0]).max() <= 1e-8 * E[0]
    # period: the sample times of the three maxima of θ (θ = a at t = kT), refined by a parabola
    i = np.flatnonzero((th[1:-1] > th[:-2]) & (th[1:-1] >= th[2:])) + 1
    peaks = []
    for j in i:
        y0, y1, y2 = th[j - 1 : j + 2]
        dt = res.t[1] - res.t[0]
        peaks.append(res.t[j] + 0.5 * dt * (y0 - y2) / (y0 - 2 * y1 + y2))
    assert len(peaks) == 3
    # parabola through 3 samples (dt = T/1000): vertex error ~ dt²·θ'''/θ'' ~ 1e-7·T
    np.testing.assert_allclose(np.diff([0.0, *peaks]), T, rtol=2e-6)


def test_harmonic_torque_on_a_free_rotor_closed_form_and_work():
    # J ω̇ = A cos(Ωt + φ): ω = ω₀ + A/(JΩ)·(sin(Ωt+φ) − sin φ),
    # θ = θ₀ + (ω₀ − A sin φ/(JΩ)) t − A/(JΩ²)(cos(Ωt+φ) − cos φ) [T133]. The difference is the
    # integrator's global error: measured max |Δω| = 4.3e-6, 6.8e-7, 1.1e-7, 1.7e-8 rad/s at
    # rtol 1e-9 … 1e-12 (dopri5; rodas4 2.4e-9 … 2.6e-11), so it converges; bounds 1e-7 at
    # rtol 1e-12. The work ∫M θ̇ dt of the power output (Simpson, 4001 samples: quadrature error
    # ~ t·Δt⁴·max|P|/180 ~ 1e-10) equals the kinetic-energy change.
    J, A, Om, ph, w0 = 0.5, 3.0, 4.0, 0.3, 1.5
    # a torsion spring of zero stiffness and damping (adds ±0: the rotor stays free) makes the run
    # use the Ueda model file's kernel set, which the suite compiles anyway [T373]
    nothing = TorsionSpring("ground", "r")
    s = _rotor(HarmonicTorque("r", amplitude=A, frequency=Om, phase=ph), nothing, omega=w0, inertia=J)
    res = simulate(s, SimConfig(t_end=5.0, n_out=4001, solver="dopri5", rtol=1e-12, atol=1e-14))
    t = res.t
    th = res.coordinate("r", "phi")
    w = res.qd[:, 2]
    w_exact = w0 + A / (J * Om) * (np.sin(Om * t + ph) - math.sin(ph))
    th_exact = (w0 - A * math.sin(ph) / (J * Om)) * t - A / (J * Om**2) * (np.cos(Om * t + ph) - math.cos(ph))
    np.testing.assert_allclose(w, w_exact, rtol=0, atol=1e-7)
    np.testing.assert_allclose(th, th_exact, rtol=0, atol=1e-7)
    np.testing.assert_allclose(res.element("e0", "moment"), A * np.cos(Om * t + ph), rtol=1e-14, atol=1e-14)
    work = simpson(res.element("e0", "power"), x=t)
    # both sides carry the integrator's ω error (≤ 1.7e-8 of ω ≈ 2.5 rad/s): 1e-7 relative
    assert work == pytest.approx(0.5 * J * (w[-1] ** 2 - w0**2), rel=1e-7)


@pytest.mark.parametrize(
    "element, field",
    [
        (lambda: TorsionSpring("ground", "r", stiffness=-1.0), "stiffness"),
        (lambda: TorsionSpring("ground", "r", damping=float("nan")), "damping"),
        (lambda: HarmonicTorque("r", amplitude=1.0, frequency=-2.0), "frequency"),
    ],
)
def test_bad_values_name_the_parameter(element, field):
    with pytest.raises(ModelError, match=field):
        _rotor(element())


def test_ueda_model_file_follows_the_ode():
    # examples/ueda.toml is x'' + 0.05 x' + x³ = 7.5 cos t [T134]; against scipy DOP853 at
    # rtol = atol = 1e-12 over 2 forcing periods (before chaos amplifies the 1e-10 tolerances:
    # measured 4.8e-8 rad after 1 period, 9.2e-8 after 10; bound 1e-6 rad)
    _, system, cfg = load_system(EXAMPLES / "ueda.toml", ["simulation.t_end=12.566370614359172"])
    res = simulate(system, cfg)
    x = res.coordinate("rotor", "phi")
    ref = solve_ivp(
        lambda t, y: [y[1], -(y[0] ** 3) - 0.05 * y[1] + 7.5 * math.cos(t)],
        (0.0, res.t[-1]),
        [2.5, 0.0],
        t_eval=res.t,
        rtol=1e-12,
        atol=1e-12,
        method="DOP853",
    )
    assert np.abs(x - ref.y[0]).max() < 1e-6


@pytest.mark.slow
def test_ueda_model_file_reproduces_the_published_exponent():
    # Sprott (Chaos and Time-Series Analysis, 2003, p. 429): λ₁ = 0.0999 1/s for the Ueda
    # oscillator. Through the model file (rotor + torsion_spring + harmonic_torque) and the
    # mechanism path of the Benettin core, 1500 forcing periods after 100: measured
    # 0.0998 ± 0.0042 1/s (`jointdyn lyapunov examples/ueda.toml --tau 6.283185307179586
    # --segments 1500 --transient 628.3185307179586 --time-scale 1 --rtol 1e-10 --atol 1e-12`).
    # Bound: 3 standard errors of our batch means (plus Sprott's last digit, 5e-5)
    from jointdyn.studies.lyapunov import system_lyapunov

    _, system, _ = load_system(EXAMPLES / "ueda.toml", [])
    r = system_lyapunov(
        system, 2 * math.pi, 1500, transient=200 * math.pi, time_scale=1.0, rtol=1e-10, atol=1e-12
    )
    assert abs(r.exponent - 0.0999) < 3 * r.stderr + 5e-5
    assert r.stderr < 0.01  # the estimate resolves the value to 10 %, not just its sign
