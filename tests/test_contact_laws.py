"""Contact and friction laws [T50–T63]: the compiled kernels the simulator runs, tested against
independent references — single 1-DOF impacts integrated here with scipy, the laws' stated
restitution, closed forms (exact energy balance [T57], linear dashpot [T58], Hertz contact
time), and the benchmark stiffness (spec/benchmark.md).

Print the measured restitution table: ``python tests/test_contact_laws.py``.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq
from scipy.special import beta as beta_fn

from jointdyn.errors import PhysicsWarning
from jointdyn.forces import contact_laws as cl
from jointdyn.forces import friction_laws as fl
from jointdyn.forces.contact_laws import (
    CONTACT_LAWS,
    Flores,
    Hertz,
    HuntCrossley,
    KelvinVoigt,
    LankaraniNikravesh,
    contact_force,
    journal_bearing_stiffness,
    kelvin_voigt_restitution,
    law_from_name,
)
from jointdyn.forces.friction_laws import (
    FRICTION_LAWS,
    Ambrosio,
    Coulomb,
    NoFriction,
    friction_coefficient,
    friction_law_from_name,
)

# spec/benchmark.md dry case: steel journal (R_j = 10.0 mm) in a steel bearing (R_i = 10.5 mm)
K_BENCH = journal_bearing_stiffness(10.5e-3, 10.0e-3, 207e9, 0.3, 207e9, 0.3)  # [N/m^1.5]

#: impact magnitudes (K [N/m^n], n [-], m [kg], v0 [m/s]): two from the benchmark (the slider's
#: 0.14 kg at 1 m/s, the crank's 0.3 kg at 0.1 m/s) and a soft, heavy, slow, linear-exponent one
MAGNITUDES = {
    "bench_0.14kg_1mps": (K_BENCH, 1.5, 0.14, 1.0),
    "bench_0.3kg_0.1mps": (K_BENCH, 1.5, 0.30, 0.1),
    "soft_n1_2kg_5cmps": (1.0e5, 1.0, 2.0, 0.05),
}
DAMPED = {"lankarani_nikravesh": LankaraniNikravesh, "hunt_crossley": HuntCrossley, "flores": Flores}
#: damping factor χ of F = Kδⁿ[1 + χδ̇/δ̇⁻], written out from the papers (not read from the library)
CHI = {
    "lankarani_nikravesh": lambda c: 3 * (1 - c**2) / 4,  # Lankarani & Nikravesh 1990, eq. (16)
    "hunt_crossley": lambda c: 3 * (1 - c) / 2,  # Hunt & Crossley 1975
    "flores": lambda c: 8 * (1 - c) / (5 * c),  # Flores et al. 2011, eq. (30)
}


def make(law_cls, **kw):
    """Construct a law, silencing the validity warning (tested on its own below)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PhysicsWarning)
        return law_cls(**kw)


def impact(law, mass, v0, clamp=True):
    """Single impact of a mass on a fixed wall: m δ̈ = −F(δ, δ̇, δ̇⁻ = v0) from δ = 0, δ̇ = v0
    until δ returns to 0 (event). Returns (restitution, max penetration [m], contact time [s]).

    Integrated in scaled variables x = δ/δ_H, u = δ̇/v0, τ = t v0/δ_H (δ_H the Hertz-type
    penetration scale) with DOP853 at rtol 1e-12 so the tolerances mean the same at every
    magnitude. ``clamp=False`` replaces the kernel by the unclamped Kelvin–Voigt force (test
    reference only)."""
    p = np.array(law.params(), dtype=np.float64)
    K, n = p[0], p[1]
    dH = ((n + 1) * mass * v0**2 / (2 * K)) ** (1 / (n + 1))  # Hertz max penetration (energy)
    code = law.code

    def rhs(tau, y):
        d, dd = y[0] * dH, y[1] * v0
        if clamp:
            f = contact_force(code, d, dd, v0, p)
        else:
            f = K * d + p[2] * dd if d > 0 else 0.0
        return [y[1], -f / mass * dH / v0**2]

    sep = lambda tau, y: y[0]
    sep.terminal, sep.direction = True, -1
    sol = solve_ivp(
        rhs, (0, 50), [0.0, 1.0], method="DOP853", rtol=1e-12, atol=1e-14, events=sep, dense_output=True
    )
    assert sol.status == 1, "no separation"
    tau_s = sol.t_events[0][0]
    tt = np.linspace(0, tau_s, 4001)
    return -sol.y_events[0][0][1], sol.sol(tt)[0].max() * dH, tau_s * dH / v0


def exact_restitution(chi):
    """Root e of χ − ln(1 + χ) = −χe − ln(1 − χe) [T57] (brentq; independent of the library)."""
    lhs = chi - math.log1p(chi)
    return brentq(
        lambda e: -chi * e - math.log1p(-chi * e) - lhs,
        0.0,
        min(1.0, (1 - 1e-15) / chi),
        xtol=1e-15,
        rtol=1e-15,
    )


# -- single impacts --------------------------------------------------------------------------------
@pytest.mark.parametrize("mag", sorted(MAGNITUDES))
@pytest.mark.parametrize("name", sorted(DAMPED))
@pytest.mark.parametrize("cr", [0.9, 0.7, 0.5])
def test_impact_restitution_equals_the_exact_energy_balance(name, cr, mag):
    K, n, m, v0 = MAGNITUDES[mag]
    law = make(DAMPED[name], stiffness=K, exponent=n, restitution=cr)
    e, _, _ = impact(law, m, v0)
    ref = exact_restitution(CHI[name](cr))
    # DOP853 at rtol 1e-12 in scaled variables: measured agreement ≤ 1e-10; 1e-8 leaves margin.
    # The same e at every magnitude and exponent: the balance [T57] holds for any K, n, m, v0.
    assert e == pytest.approx(ref, rel=1e-8)
    # the library's closed form [T57] (bisection) agrees with this brentq root to rounding
    assert law.effective_restitution() == pytest.approx(ref, rel=1e-12)


# the laws' intent (issue tolerances: LN 2 %, Hunt–Crossley and Flores 5 %), inside their ranges
IN_RANGE = [
    ("lankarani_nikravesh", 0.9, 0.02),
    ("hunt_crossley", 0.9, 0.05),
    ("flores", 0.9, 0.05),
    ("flores", 0.7, 0.05),
]
# outside them the law itself misses its c_r (not the integrator: see the exact balance above)
OUT_OF_RANGE = [
    ("lankarani_nikravesh", 0.7, 0.02),  # e = 0.796 (+13.7 %)
    ("lankarani_nikravesh", 0.5, 0.02),  # e = 0.725 (+45 %)
    ("hunt_crossley", 0.7, 0.05),  # e = 0.768 (+9.7 %)
    ("hunt_crossley", 0.5, 0.05),  # e = 0.663 (+33 %)
    ("flores", 0.5, 0.05),  # e = 0.470 (−5.9 %)
]


@pytest.mark.parametrize("mag", ["bench_0.14kg_1mps", "soft_n1_2kg_5cmps"])
@pytest.mark.parametrize("name,cr,tol", IN_RANGE)
def test_impact_restitution_matches_the_laws_intent(name, cr, tol, mag):
    K, n, m, v0 = MAGNITUDES[mag]
    with warnings.catch_warnings():
        warnings.simplefilter("error", PhysicsWarning)  # inside the validity range: no warning
        law = DAMPED[name](stiffness=K, exponent=n, restitution=cr)
    e, _, _ = impact(law, m, v0)
    assert e == pytest.approx(cr, rel=tol)


@pytest.mark.parametrize("name,cr,tol", OUT_OF_RANGE)
def test_outside_the_validity_range_the_law_warns_and_misses_its_restitution(name, cr, tol):
    K, n, m, v0 = MAGNITUDES["bench_0.14kg_1mps"]
    with pytest.warns(PhysicsWarning, match="outside the law's validity range"):
        law = DAMPED[name](stiffness=K, exponent=n, restitution=cr)
    e, _, _ = impact(law, m, v0)
    assert abs(e - cr) > tol * cr  # documents the limit (docs: T52–T54)


@pytest.mark.parametrize("mag", sorted(MAGNITUDES))
def test_hertz_impact_conserves_energy_and_matches_hertz_closed_forms(mag):
    K, n, m, v0 = MAGNITUDES[mag]
    e, dmax, tc = impact(Hertz(stiffness=K, exponent=n), m, v0)
    # elastic: rebound = approach speed; DOP853 at rtol 1e-12 gives ≤ 1e-11, bound 1e-9 (issue: ~1e-8)
    assert e == pytest.approx(1.0, abs=1e-9)
    # energy: ½mv0² = Kδ_max^(n+1)/(n+1); sampled maximum (4001 samples) → 1e-6
    assert dmax == pytest.approx(((n + 1) * m * v0**2 / (2 * K)) ** (1 / (n + 1)), rel=1e-6)
    # contact time t_c = 2(δ_max/v0)∫₀¹(1 − x^(n+1))^(−½)dx = 2(δ_max/v0)B(1/(n+1), ½)/(n+1)
    # (quadrature of the energy integral; 2.9432 δ_max/v0 for n = 1.5); event location → 1e-9
    a = n + 1
    assert tc == pytest.approx(2 * dmax / v0 * beta_fn(1 / a, 0.5) / a, rel=1e-6)


@pytest.mark.parametrize("zeta", [0.05, 0.3, 0.7071, 1.0, 2.0])
def test_kelvin_voigt_restitution_is_the_linear_oscillator_one(zeta):
    m, v0, K = 0.14, 1.0, 1.0e8  # [kg], [m/s], [N/m]
    D = 2 * zeta * math.sqrt(K * m)
    law = KelvinVoigt(stiffness=K, damping=D)
    e, _, _ = impact(law, m, v0)
    # the clamped dashpot separates where F = 0 (δ > 0): closed form [T58] (Schwager & Pöschel
    # 2007), all three damping regimes; integration at rtol 1e-12 → 1e-8
    assert e == pytest.approx(kelvin_voigt_restitution(K, D, m), rel=1e-8)
    assert e == pytest.approx(law.restitution(m), rel=1e-8)
    if zeta < 1:
        # the textbook e = exp(−πζ/√(1−ζ²)) holds for the *unclamped* (adhesive) dashpot, which
        # returns to δ = 0 after half a damped period — checked here for the harness itself —
        # and the clamp makes the true rebound faster than that
        classic = math.exp(-math.pi * zeta / math.sqrt(1 - zeta**2))
        e_pull, _, _ = impact(law, m, v0, clamp=False)
        assert e_pull == pytest.approx(classic, rel=1e-8)
        assert e > classic


@pytest.mark.parametrize("cr", [0.95, 0.7, 0.3])
def test_kelvin_voigt_from_restitution_round_trip(cr):
    m, v0, K = 0.3, 0.1, 5.0e7  # [kg], [m/s], [N/m]
    law = KelvinVoigt.from_restitution(K, cr, m)
    e, _, _ = impact(law, m, v0)
    assert e == pytest.approx(cr, rel=1e-8)  # integration at rtol 1e-12 (see above)


# -- kernel properties ----------------------------------------------------------------------------
def all_laws():
    return [
        Hertz(stiffness=K_BENCH),
        LankaraniNikravesh(stiffness=K_BENCH, restitution=0.9),
        HuntCrossley(stiffness=K_BENCH, restitution=0.9),
        Flores(stiffness=K_BENCH, restitution=0.6),
        KelvinVoigt(stiffness=1e8, damping=2e3),
    ]


@pytest.mark.parametrize("law", all_laws(), ids=lambda l: type(l).__name__)
def test_zero_force_out_of_contact_and_never_negative(law):
    p = np.array(law.params())
    for d in (0.0, -1e-12, -1e-6, -1.0):
        for dd in (-10.0, 0.0, 10.0):
            assert contact_force(law.code, d, dd, 1.0, p) == 0.0
    rng = np.random.default_rng(1)
    d = rng.uniform(0, 1e-4, 2000)
    dd = rng.uniform(-5, 5, 2000)
    f = np.array([contact_force(law.code, a, b, 0.5, p) for a, b in zip(d, dd)])
    assert np.all(f >= 0.0) and np.all(np.isfinite(f))
    # strongly separating: the damping term dominates, the clamp holds F at 0 (no adhesion)
    if law.code != cl.HERTZ:
        assert contact_force(law.code, 1e-6, -1e3, 1e-3, p) == 0.0


@pytest.mark.parametrize("law", all_laws()[:4], ids=lambda l: type(l).__name__)
def test_power_law_force_is_continuous_at_contact(law):
    p = np.array(law.params())
    for dd in (-1.0, 0.0, 1.0):
        # |F(ε)| ≤ Kεⁿ(1 + χ|δ̇|/δ̇⁻) → 0 with ε: at ε = 1e-15 m, F < 1e-10 N
        f = contact_force(law.code, 1e-15, dd, 1.0, p)
        assert 0.0 <= f < K_BENCH * 1e-15**1.5 * 10 < 1e-10


def test_kelvin_voigt_jumps_by_the_damping_force_at_contact():
    """The documented drawback of the linear dashpot [T55]: F(0⁺) = Dδ̇, not 0."""
    law = KelvinVoigt(stiffness=1e8, damping=2e3)
    p = np.array(law.params())
    assert contact_force(law.code, 1e-15, 0.5, 0.5, p) == pytest.approx(1e3, rel=1e-6)  # D·δ̇ = 2e3·0.5
    assert contact_force(law.code, 1e-15, 0.0, 0.5, p) == pytest.approx(1e-7)  # Kε: continuous at rest


def test_kernel_values_by_hand():
    d, dd, v0 = 2e-5, 0.3, 0.8  # [m], [m/s], [m/s]
    K, n, c = 6.9e10, 1.5, 0.85
    base = K * d**n
    expect = {
        Hertz(stiffness=K, exponent=n): base,
        LankaraniNikravesh(stiffness=K, exponent=n, restitution=c): base * (1 + 0.75 * (1 - c * c) * dd / v0),
        HuntCrossley(stiffness=K, exponent=n, restitution=c): base * (1 + 1.5 * (1 - c) * dd / v0),
        Flores(stiffness=K, exponent=n, restitution=c): base * (1 + 1.6 * (1 - c) / c * dd / v0),
        KelvinVoigt(stiffness=1e8, damping=50.0): 1e8 * d + 50.0 * dd,
    }
    for law, ref in expect.items():
        assert contact_force(law.code, d, dd, v0, np.array(law.params())) == pytest.approx(ref, rel=1e-14)
    assert math.isnan(contact_force(99, d, dd, v0, np.zeros(4)))  # unknown code is visible


def test_registry_codes_tags_and_params():
    assert list(CONTACT_LAWS) == ["hertz", "lankarani_nikravesh", "hunt_crossley", "flores", "kelvin_voigt"]
    assert len({c.code for c in CONTACT_LAWS.values()}) == len(CONTACT_LAWS)
    assert [c.theory for c in CONTACT_LAWS.values()] == ["T51", "T52", "T53", "T54", "T55"]
    for law in all_laws():
        p = law.params()
        assert len(p) == 4 and all(type(v) is float for v in p)
    assert list(FRICTION_LAWS) == ["none", "coulomb", "ambrosio"]
    assert [c.code for c in FRICTION_LAWS.values()] == [fl.NONE, fl.COULOMB, fl.AMBROSIO] == [0, 1, 2]
    assert [c.theory for c in FRICTION_LAWS.values()] == ["T63", "T61", "T62"]
    # registry names unique across both families (Model.to_dict maps classes back to names)
    assert not set(CONTACT_LAWS) & set(FRICTION_LAWS)


def test_law_from_name():
    assert law_from_name("flores", stiffness=1e9, restitution=0.8) == Flores(1e9, 1.5, 0.8)
    with pytest.raises(ValueError, match="'hertzian' is unknown; valid: flores, hertz, hunt_crossley"):
        law_from_name("hertzian", stiffness=1e9)
    assert friction_law_from_name("coulomb", coefficient=0.1) == Coulomb(0.1)
    with pytest.raises(ValueError, match="'stribeck' is unknown; valid: ambrosio, coulomb, none"):
        friction_law_from_name("stribeck")


# -- validation ------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "cls,kw,fragment",
    [
        (Hertz, dict(stiffness=0.0), r"Hertz.stiffness = 0.0 \[N/m\^n\]: must be > 0"),
        (Hertz, dict(stiffness=-1e9), r"Hertz.stiffness = -1000000000.0 \[N/m\^n\]: must be > 0"),
        (Hertz, dict(stiffness=math.inf), r"Hertz.stiffness = inf \[N/m\^n\].*finite"),
        (Hertz, dict(stiffness=1e9, exponent=0.0), r"Hertz.exponent = 0.0 \[-\]: must be > 0"),
        (LankaraniNikravesh, dict(stiffness=math.nan), r"LankaraniNikravesh.stiffness = nan \[N/m\^n\]"),
        (
            LankaraniNikravesh,
            dict(stiffness=1e9, restitution=1.5),
            r"restitution = 1.5 \[-\]: must be in \(0, 1\]",
        ),
        (
            HuntCrossley,
            dict(stiffness=1e9, restitution=-0.1),
            r"HuntCrossley.restitution = -0.1 \[-\]: must be in \(0, 1\]",
        ),
        (
            Flores,
            dict(stiffness=1e9, restitution=0.0),
            r"Flores.restitution = 0.0 \[-\]: must be in \(0, 1\]",
        ),
        (Flores, dict(stiffness=1e9, exponent=-1.5), r"Flores.exponent = -1.5 \[-\]"),
        (KelvinVoigt, dict(stiffness=-1.0), r"KelvinVoigt.stiffness = -1.0 \[N/m\]: must be > 0"),
        (
            KelvinVoigt,
            dict(stiffness=1.0, damping=-2.0),
            r"KelvinVoigt.damping = -2.0 \[N·s/m\]: must be ≥ 0",
        ),
        (Coulomb, dict(coefficient=-0.1), r"Coulomb.coefficient = -0.1 \[-\]: must be ≥ 0"),
        (
            Coulomb,
            dict(coefficient=0.1, regularization_velocity=0.0),
            r"regularization_velocity = 0.0 \[m/s\]: must be > 0",
        ),
        (Ambrosio, dict(coefficient=0.1, v0=-1e-4), r"Ambrosio.v0 = -0.0001 \[m/s\]: must be ≥ 0"),
        (
            Ambrosio,
            dict(coefficient=0.1, v0=1e-3, v1=1e-3),
            r"Ambrosio.v1 = 0.001 \[m/s\]: must be > v0 = 0.001",
        ),
        (
            Ambrosio,
            dict(coefficient=0.1, v0=2e-3, v1=1e-3),
            r"Ambrosio.v1 = 0.001 \[m/s\]: must be > v0 = 0.002",
        ),
        (Ambrosio, dict(coefficient=math.nan), r"Ambrosio.coefficient = nan \[-\]"),
    ],
)
def test_bad_parameters_name_the_parameter_unit_and_range(cls, kw, fragment):
    with pytest.raises(ValueError, match=fragment):
        cls(**kw)


@pytest.mark.parametrize(
    "kw,fragment",
    [
        (dict(nu_bearing=0.5), r"nu_bearing = 0.5 \[-\]: must be in \(-1, 0.5\)"),
        (dict(nu_journal=-1.0), r"nu_journal = -1.0 \[-\]: must be in \(-1, 0.5\)"),
        (dict(E_bearing=0.0), r"E_bearing = 0.0 \[Pa\]: must be > 0"),
        (dict(E_journal=-2e11), r"E_journal = -200000000000.0 \[Pa\]: must be > 0"),
        (dict(R_journal=10.5e-3), r"R_journal = 0.0105 \[m\]: must be in \(0, R_bearing = 0.0105\)"),
        (dict(R_journal=11e-3), r"R_journal = 0.011 \[m\]"),
        (dict(R_bearing=math.nan), r"R_bearing = nan \[m\]"),
    ],
)
def test_stiffness_helper_bad_inputs(kw, fragment):
    args = dict(
        R_bearing=10.5e-3, R_journal=10.0e-3, E_bearing=207e9, nu_bearing=0.3, E_journal=207e9, nu_journal=0.3
    )
    args.update(kw)
    with pytest.raises(ValueError, match=fragment):
        journal_bearing_stiffness(**args)


def test_journal_bearing_stiffness_benchmark_value():
    # spec/benchmark.md quotes K ≈ 6.9e10 N/m^1.5 (two digits: ±0.05e10 → 1 %)
    assert K_BENCH == pytest.approx(6.9e10, rel=0.01)
    # by hand: σ = (1 − 0.3²)/207e9 for both, √(R_i R_j/(R_i − R_j)) = √(0.21 m) (T56)
    sigma = 0.91 / 207e9
    assert K_BENCH == pytest.approx(4 / 3 / (2 * sigma) * math.sqrt(0.21), rel=1e-13)
    # the value the shipped model files carry (examples/slider_crank_dry.toml)
    assert K_BENCH == pytest.approx(69494005044.38522, rel=1e-15)
    # symmetric in the two materials; softer material, lower K (aluminium bearing, E = 70 GPa)
    K_al = journal_bearing_stiffness(10.5e-3, 10.0e-3, 70e9, 0.33, 207e9, 0.3)
    assert K_al == pytest.approx(
        journal_bearing_stiffness(10.5e-3, 10.0e-3, 207e9, 0.3, 70e9, 0.33), rel=1e-15
    )
    assert K_al < K_BENCH


def test_effective_restitution_limits():
    # χ → 0: e = 1 − 2χ/3 + 4χ²/9 + O(χ³) (series of [T57]); the library keeps full precision there
    for chi in (1e-12, 1e-8, 1e-4):
        assert cl.effective_restitution(chi) == pytest.approx(1 - 2 * chi / 3 + 4 * chi**2 / 9, rel=1e-12)
    assert cl.effective_restitution(0.0) == 1.0
    with pytest.raises(ValueError, match=r"chi = -1.0 \[-\]"):
        cl.effective_restitution(-1.0)


# -- friction --------------------------------------------------------------------------------------
def mu_eff(law, v):
    return friction_coefficient(law.code, v, np.array(law.params()))


FRICTION = [NoFriction(), Coulomb(0.15, 1e-4), Ambrosio(0.15, 1e-4, 1e-3)]


@pytest.mark.parametrize("law", FRICTION, ids=lambda l: type(l).__name__)
def test_friction_sign_zero_slip_and_odd_symmetry(law):
    mu = getattr(law, "coefficient", 0.0)
    assert mu_eff(law, 0.0) == 0.0
    for v in (1e-2, 0.1, 3.0):  # ≥ 10 v_reg and ≥ v1: full friction
        # tanh(100) = 1 in double precision; at 10 v_reg, 1 − tanh 10 = 4.1e-9
        assert mu_eff(law, v) == pytest.approx(mu, rel=5e-9)
        assert mu_eff(law, -v) == pytest.approx(-mu, rel=5e-9)
        # the tangential force −μ_eff F_n opposes the slip
        assert -mu_eff(law, v) * 100.0 <= 0.0 <= -mu_eff(law, -v) * 100.0
    for v in np.linspace(-2e-3, 2e-3, 401):
        assert mu_eff(law, -v) == -mu_eff(law, v)
        assert abs(mu_eff(law, v)) <= mu


@pytest.mark.parametrize("law", FRICTION[1:], ids=lambda l: type(l).__name__)
def test_friction_is_continuous_and_monotone(law):
    # fine grid through 0, v0, v1: the largest jump is bounded by the largest slope × step
    # (Coulomb μ/v_reg; Ambrósio 1.5 μ/(v1 − v0)); no jump at v = 0
    v = np.linspace(-2e-3, 2e-3, 400001)
    m = np.array([mu_eff(law, x) for x in v])
    slope = 0.15 / 1e-4 if isinstance(law, Coulomb) else 1.5 * 0.15 / 9e-4
    assert np.max(np.abs(np.diff(m))) <= slope * (v[1] - v[0]) * (1 + 1e-9)
    assert np.all(np.diff(m) >= 0)


def test_coulomb_regularisation_value():
    assert mu_eff(Coulomb(0.2, 1e-3), 1e-3) == pytest.approx(0.2 * math.tanh(1.0), rel=1e-15)


def test_ambrosio_ramp_values():
    law = Ambrosio(0.2, v0=1e-4, v1=1e-3)
    for v, cd in [
        (0.0, 0.0),
        (5e-5, 0.0),  # below v0: no friction
        (1e-4, 0.0),  # at v0
        (1e-4 + 0.25 * 9e-4, 0.15625),  # x = 1/4: x²(3 − 2x) = 5/32
        (5.5e-4, 0.5),  # mid-ramp: 1/2 (also the linear ramp's value)
        (1e-4 + 0.75 * 9e-4, 0.84375),  # x = 3/4: 27/32
        (1e-3, 1.0),  # at v1
        (0.5, 1.0),
    ]:
        assert mu_eff(law, v) == pytest.approx(0.2 * cd, abs=1e-15)
        assert mu_eff(law, -v) == pytest.approx(-0.2 * cd, abs=1e-15)
    # v0 = 0: the ramp starts at zero slip
    assert mu_eff(Ambrosio(0.2, v0=0.0, v1=1e-3), 5e-4) == pytest.approx(0.1, rel=1e-14)


def test_friction_unknown_code_is_nan():
    assert math.isnan(friction_coefficient(99, 1.0, np.zeros(4)))


if __name__ == "__main__":  # the measured restitution table of the report
    print(f"K_bench = {K_BENCH:.6e} N/m^1.5")
    print(f"{'law':22s} {'c_r':>5s} " + " ".join(f"{k:>20s}" for k in MAGNITUDES) + f" {'exact [T57]':>12s}")
    for name, cls in DAMPED.items():
        for cr in (0.9, 0.7, 0.5):
            row = []
            for K, n, m, v0 in MAGNITUDES.values():
                row.append(impact(make(cls, stiffness=K, exponent=n, restitution=cr), m, v0)[0])
            ref = exact_restitution(CHI[name](cr))
            print(
                f"{name:22s} {cr:5.2f} "
                + " ".join(f"{e:20.10f}" for e in row)
                + f" {ref:12.6f} ({(ref - cr) / cr:+.2%})"
            )
    for K, n, m, v0 in MAGNITUDES.values():
        print(f"hertz K={K:.3g} n={n} m={m} v0={v0}: e - 1 = {impact(Hertz(K, n), m, v0)[0] - 1:+.2e}")
    for zeta in (0.05, 0.3, 1.0, 2.0):
        K, m = 1e8, 0.14
        D = 2 * zeta * math.sqrt(K * m)
        e = impact(KelvinVoigt(K, D), m, 1.0)[0]
        print(
            f"kelvin_voigt zeta={zeta}: e = {e:.10f}, closed form [T58] {kelvin_voigt_restitution(K, D, m):.10f}"
        )
