"""docs/how-to-add-a-model.md, run literally: one test per extension kind. Each takes the kind's
code block from the page, saves it as a module, registers it in a fresh process (a plugin from
user code: no package file edited) and runs it end to end in a small mechanism, against an
independent reference — a law equal to a built-in reproduces the built-in's trajectory (bit for
bit where the same floating-point operations run; to the tolerance where only the Jacobian
differs), a closed form, or a conservation law."""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

HOW_TO = Path(__file__).resolve().parents[1] / "docs" / "how-to-add-a-model.md"

# a journal (1 kg, centred, spinning at ω₀) in a bushing fixed to the ground, gravity as the load
PRELUDE = textwrap.dedent(
    """
    import json, sys, warnings
    sys.path.insert(0, sys.argv[1])
    import numpy as np
    from jointdyn.multibody.model import Model
    from jointdyn.simulation.simulate import SimConfig, simulate


    def journal(element, omega):
        m = Model("journal", gravity=(0.0, -9.81))
        m.add_ground_point("O", (0.0, 0.0))
        m.add_body("journal", 1.0, 1e-4, velocity=(0.0, 0.0, omega), points={"C": (0.0, 0.0)})
        m.add("pin", element)
        return m.compile(centre_imperfect=False)


    def run(system, solver, t_end=0.05):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            res = simulate(system, SimConfig(t_end=t_end, n_out=51, solver=solver, rtol=1e-8))
        assert res.status == 0, res.status  # 0: reached t_end
        notes = [str(w.message) for w in caught if "differenced" in str(w.message)]
        return {"y": res.y.tolist(), "fx": res.element("pin", "Fx").tolist(), "notes": notes}
    """
)


def _block(heading: str) -> str:
    """The first ```python block of the section ``## <heading>…`` after its "**From user
    code**" (if it says so; the first block otherwise)."""
    text = HOW_TO.read_text(encoding="utf-8")
    section = text[text.index(f"## {heading}") :]
    section = section[max(section.find("**From user code**"), 0) :]
    start = section.index("```python\n") + 10
    return section[start : section.index("\n```\n", start)]


def _run(tmp_path, heading: str, module: str, body: str, *args: str):
    (tmp_path / f"{module}.py").write_text(_block(heading), encoding="utf-8")
    script = PRELUDE + textwrap.dedent(body)
    p = subprocess.run(
        [sys.executable, "-c", script, str(tmp_path), *args], capture_output=True, text=True, check=False
    )
    assert p.returncode == 0, p.stderr[-3000:]
    return json.loads(p.stdout.strip().splitlines()[-1])


@pytest.mark.parametrize("solver", ["dopri5", pytest.param("radau5", marks=pytest.mark.slow)])
def test_how_to_film_model(solver, tmp_path):
    """``ScaledPiFilm(scale=2)`` at μ/2 equals ``alshaer2005`` at μ in every operation (×2 and
    ×½ are exact in binary): the same forces and, under dopri5, the same trajectory bit for bit.
    Under radau5 (slow tier: it compiles the stiff method and the Jacobians for the plugin) the
    plugin (no ``jacobian``) is differenced [T229] — named in a warning — and the trajectory
    agrees to the tolerance."""
    out = _run(
        tmp_path,
        "A film model",
        "plugin_film",
        """
        from plugin_film import ScaledPiFilm
        from jointdyn.film.models import film_forces
        from jointdyn.forces.journal import JournalBearing

        def bearing(film, mu):
            return JournalBearing("ground", "O", "journal", "C", 0.0105, 0.0100, 0.04, mu, film=film, shear=False)

        rng = np.random.default_rng(2)
        st = dict(xi=rng.uniform(0, 0.95, 50), xi_dot=rng.normal(size=50) * 50, gamma=rng.uniform(-3, 3, 50),
                  gamma_dot=rng.normal(size=50) * 50, omega_journal=100.0, omega_bearing=0.0,
                  viscosity=0.4, length=0.04, radius=0.01, clearance=5e-4)
        a = film_forces("alshaer2005", **st)
        b = film_forces(ScaledPiFilm(scale=2.5), **st)
        forces = bool(np.array_equal(b["Fr"], 2.5 * a["Fr"]) and np.array_equal(b["Ft"], 2.5 * a["Ft"]))
        print(json.dumps({"forces": forces, **{
            f"{name}_{solver}": run(journal(bearing(film, mu), 100.0), solver)
            for name, film, mu in (("ref", "alshaer2005", 0.4), ("plugin", ScaledPiFilm(scale=2.0), 0.2))
            for solver in (sys.argv[2],)}}))
        """,
        solver,
    )
    assert out["forces"]
    if solver == "dopri5":
        ref, plug = out["ref_dopri5"], out["plugin_dopri5"]
        np.testing.assert_array_equal(plug["y"], ref["y"])
        y = np.array(ref["y"])
        assert np.hypot(y[-1, 0], y[-1, 1]) > 0.1 * 5e-4  # the journal moved off centre: a real test
        return
    assert out["plugin_radau5"]["notes"] and "scaled_pi" in out["plugin_radau5"]["notes"][0]
    assert not out["ref_radau5"]["notes"]
    ya, yb = np.array(out["ref_radau5"]["y"]), np.array(out["plugin_radau5"]["y"])
    # same model, Jacobians exact vs differenced: the step sequences differ, the solutions agree
    # to the tolerance (rtol 1e-8 of the state; 1e-5 of the clearance bounds the accumulated error)
    assert np.abs(ya[:, :2] - yb[:, :2]).max() <= 1e-5 * 5e-4


@pytest.mark.parametrize("solver", ["dopri5", pytest.param("radau5", marks=pytest.mark.slow)])
def test_how_to_contact_law(solver, tmp_path):
    """A dry journal dropped in its bushing (impacts from ≈ 10 ms on): ``PowerLaw`` runs the
    operations of ``Hertz`` — dopri5 trajectories bit for bit; under radau5 it is differenced
    (named) and agrees to the tolerance."""
    out = _run(
        tmp_path,
        "A contact law",
        "plugin_contact",
        """
        from plugin_contact import PowerLaw
        from jointdyn.forces.contact_laws import Hertz
        from jointdyn.forces.journal import ClearanceJoint

        def joint(law):
            return ClearanceJoint("ground", "O", "journal", "C", 0.0105, 0.0100, contact=law)

        print(json.dumps({f"{name}_{solver}": run(journal(joint(law), 0.0), solver)
            for name, law in (("ref", Hertz(stiffness=6.9e10)), ("plugin", PowerLaw(stiffness=6.9e10)))
            for solver in (sys.argv[2],)}))
        """,
        solver,
    )
    if solver == "dopri5":
        ref, plug = out["ref_dopri5"], out["plugin_dopri5"]
        np.testing.assert_array_equal(plug["y"], ref["y"])
        assert np.diff(np.array(ref["y"])[:, 1]).max() > 0.0  # it rose again: it bounced off the bushing
        return
    assert out["plugin_radau5"]["notes"] and "PowerLaw" in out["plugin_radau5"]["notes"][0]
    ya, yb = np.array(out["ref_radau5"]["y"]), np.array(out["plugin_radau5"]["y"])
    assert np.abs(ya[:, :2] - yb[:, :2]).max() <= 1e-5 * 5e-4


@pytest.mark.parametrize("solver", ["dopri5", pytest.param("radau5", marks=pytest.mark.slow)])
def test_how_to_friction_law(solver, tmp_path):
    """A dry spinning journal dropped in its bushing: ``TanhFriction`` (with its ``jacobian``)
    runs the operations of ``Coulomb`` — radau5 and dopri5 trajectories bit for bit, no warning."""
    out = _run(
        tmp_path,
        "A friction law",
        "plugin_friction",
        """
        from plugin_friction import TanhFriction
        from jointdyn.forces.contact_laws import Hertz
        from jointdyn.forces.friction_laws import Coulomb
        from jointdyn.forces.journal import ClearanceJoint

        def joint(friction):
            return ClearanceJoint("ground", "O", "journal", "C", 0.0105, 0.0100,
                                  contact=Hertz(stiffness=6.9e10), friction=friction)

        print(json.dumps({f"{name}_{solver}": run(journal(joint(law), 50.0), solver)
            for name, law in (("ref", Coulomb(0.1)), ("plugin", TanhFriction(0.1)))
            for solver in (sys.argv[2],)}))
        """,
        solver,
    )
    ref, plug = out[f"ref_{solver}"], out[f"plugin_{solver}"]
    np.testing.assert_array_equal(plug["y"], ref["y"])
    assert not plug["notes"]
    w = np.array(ref["y"])[:, 5]
    assert w[-1] < 50.0 - 1.0  # friction acted: the spin slowed down


HOW_TO_TORQUE = """
from plugin_torque import ConstantTorque  # the how-to's code block, literally, as a module
m = Model("free body", gravity=(0.0, 0.0))
m.add_body("b", 2.0, 0.5, position=(0.0, 0.0))
m.add("motor", ConstantTorque("b", moment=3.0))
res = simulate(m.compile(), SimConfig(t_end=2.0, n_out=5, solver=sys.argv[2], rtol=1e-10, atol=1e-12))
print(json.dumps([res.t.tolist(), res.y[:, 2].tolist(), res.eout[:, 0, :2].tolist()]))
"""


@pytest.mark.parametrize("solver", ["dopri5", pytest.param("radau5", marks=pytest.mark.slow)])
def test_how_to_force_element(solver, tmp_path):
    """The how-to's new element type, registered in a fresh process exactly as written there,
    runs in a model: a free body (J = 0.5 kg·m²) under M = 3 N·m turns by φ = M t²/(2J). radau5
    differentiates it by the finite-difference fallback (no exact Jacobian registered)."""
    t, phi, out = (
        np.array(v) for v in _run(tmp_path, "A force element type", "plugin_torque", HOW_TO_TORQUE, solver)
    )
    # both methods integrate a quadratic in t exactly up to rounding and the step-size control:
    # 1e-9 relative is 10× the rtol of the run (1e-10)
    np.testing.assert_allclose(phi, 3.0 * t**2 / (2 * 0.5), rtol=1e-9, atol=1e-12)
    np.testing.assert_array_equal(out[:, 0], 3.0)  # output column "moment"
    np.testing.assert_allclose(out[:, 1], 3.0 * 3.0 * t / 0.5, rtol=1e-9)  # power M·ω, ω = M t / J


def test_how_to_output(tmp_path):
    """A rotary damper's declared outputs reach the results and ``timeseries.csv`` with their
    units, and its ``power`` the metric ``energy_dissipated``: a free body (J = 0.5 kg·m²,
    ω₀ = 10 rad/s, c = 0.2 N·m·s/rad) spins down as ω = ω₀e^{−ct/J}, and the energy dissipated is
    the kinetic energy lost, ½J(ω₀² − ω²)."""
    out = _run(
        tmp_path,
        "An output or a metric",
        "plugin_output",
        """
        import csv
        from plugin_output import RotaryDamper
        from jointdyn.studies.metrics import metrics
        from jointdyn.studies.outputs import system_columns, write_csv

        m = Model("spin-down", gravity=(0.0, 0.0))
        m.add_body("b", 2.0, 0.5, velocity=(0.0, 0.0, 10.0))
        m.add("damper", RotaryDamper("b", damping=0.2))
        res = simulate(m.compile(), SimConfig(t_end=2.0, n_out=2001, solver="dopri5", rtol=1e-10, atol=1e-12))
        path = sys.argv[1] + "/timeseries.csv"
        write_csv(path, system_columns(res))
        with open(path, encoding="utf-8") as f:
            rows = list(csv.reader(f))
        col = rows[0].index("damper.omega [rad/s]")
        print(json.dumps({"t": res.t.tolist(), "omega": res.element("damper", "omega").tolist(),
            "moment": res.element("damper", "moment").tolist(), "header": rows[0],
            "csv_omega": [float(r[col]) for r in rows[1:]],
            "energy": metrics(res)["damper.energy_dissipated"]}))
        """,
    )
    t, w = np.array(out["t"]), np.array(out["omega"])
    exact = 10.0 * np.exp(-0.2 * t / 0.5)
    np.testing.assert_allclose(w, exact, rtol=1e-8)  # rtol 1e-10 run; 100× for accumulation
    np.testing.assert_allclose(out["moment"], -0.2 * w, rtol=1e-15)
    assert {"damper.moment [N·m]", "damper.omega [rad/s]", "damper.power [W]"} <= set(out["header"])
    np.testing.assert_array_equal(out["csv_omega"], w)  # %.17g: the float round-trips
    lost = 0.5 * 0.5 * (10.0**2 - exact[-1] ** 2)
    # trapezoidal rule on 2001 samples of an exponential: error ≈ h²·(2c/J)²/12 ≈ 5e-8 relative
    assert abs(out["energy"] - lost) <= 1e-6 * lost


CAVITATION_RUN = """
import plugin_cavitation  # registers "reynolds-delegated"
from jointdyn.bearing.design import bearing_table
from jointdyn.film.finite import build_table
from jointdyn.film.models import Finite
from jointdyn.forces.journal import JournalBearing

a = bearing_table("finite", "reynolds", 0.5, [0.3, 0.8], mesh=(48, 6))
b = bearing_table("finite", "reynolds-delegated", 0.5, [0.3, 0.8], mesh=(48, 6))
cols = ("sommerfeld", "attitude_deg", "friction_variable", "flow_variable", "theta_end_deg")
kw = {"n_xi": 3, "n_psi": 5, "cache": False}
ta = build_table(1.0, cavitation="reynolds", **kw)
tb = build_table(1.0, cavitation="reynolds-delegated", **kw)
out = {"design": all(np.array_equal(a[c], b[c]) for c in cols), "table": bool(np.array_equal(ta, tb))}
if sys.argv[2] == "dynamic":
    for cav in ("reynolds", "reynolds-delegated"):
        el = JournalBearing("ground", "O", "journal", "C", 0.0105, 0.0100, 0.02, 0.4, film=Finite(cavitation=cav))
        out[cav] = run(journal(el, 100.0), "dopri5")
print(json.dumps(out))
"""


@pytest.mark.parametrize("mode", ["tables", pytest.param("dynamic", marks=pytest.mark.slow)])
def test_how_to_cavitation_condition(mode, tmp_path):
    """A condition that delegates to Swift–Stieber reproduces ``reynolds`` bit for bit through the
    registry: the design table, the dynamic ``finite`` table and (slow tier: two full tables are
    built) the trajectory of a journal under a constant load."""
    out = _run(tmp_path, "A cavitation condition", "plugin_cavitation", CAVITATION_RUN, mode)
    assert out["design"] and out["table"]
    if mode == "dynamic":
        np.testing.assert_array_equal(out["reynolds-delegated"]["y"], out["reynolds"]["y"])
