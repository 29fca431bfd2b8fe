"""Feed holes and a circumferential groove as supply features [T366]: against closed forms (axial
Poiseuille flow of the grooved concentric bearing), an exact identity (a circumferential groove at
ambient pressure splits the film into two plain bearings of the land length), the mass balance of
the mass-conserving film, linearity in the feed pressure, the CLI columns and refusals, and the
transient jfo element fed through them in the multibody loop."""

from __future__ import annotations

import dataclasses
import math
import re
import warnings
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from jointdyn.cli import app
from jointdyn.film.grooved import CircumferentialGroove, FeedHoles, feed_holes, film_at
from jointdyn.film.jfo import flows
from jointdyn.film.models import Finite
from jointdyn.io.modelfile.load import load_model
from jointdyn.simulation.simulate import simulate

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "slider_crank_jfo.toml"


def _flows(lam, e, cav, supply, mesh):
    F, s, prob, fixed, lab = film_at(lam, e, (0.0, 0.0), cav, supply, mesh)
    xi = math.hypot(*e)
    fill = np.ones(s.P.size) if s.fill is None else s.fill
    return F, flows(prob, 0.0, xi / (2.0 + xi * xi), s.P, fill, fixed, lab), prob, lab


@pytest.mark.parametrize("lam, mesh", [(0.5, (36, 8)), (1.0, (72, 16))])
def test_concentric_circumferential_groove_is_axial_poiseuille_flow(lam, mesh):
    """ε = 0: no wedge, the lands carry p linear from p_f to 0; Q = 2·2πR·c³p_f/(12μℓ) with the
    land ℓ = R(λ − ζ_g) from the groove's last node ζ_g, i.e. Q̄ = 4πP_f/(λ − ζ_g) in ωR²c/2 —
    linear pressure is exact on any finite-volume mesh."""
    feed = 0.02
    _, fl, prob, lab = _flows(lam, (1e-14, 0.0), "reynolds", CircumferentialGroove(0.3, feed), mesh)
    nz = mesh[1]
    zg = prob.zeta[:-1][lab[:nz] >= 0].max()
    exact = 4.0 * math.pi * feed / (lam - zg)
    assert fl["supply"] == pytest.approx(exact, rel=1e-12)
    assert fl["side"] == pytest.approx(exact, rel=1e-12)


@pytest.mark.parametrize("cavitation", ["gumbel", "reynolds"])
def test_circumferential_groove_splits_the_film_into_two_plain_bearings(cavitation):
    """At ambient supply pressure each land is a plain bearing of length ℓ = R(λ − ζ_g) with both
    ends at p = 0, i.e. a plain bearing of L/D = (λ − ζ_g)/2: F(λ, groove) = 2 F_plain. The two
    meshes differ, so the identity holds to the mesh's order: measured 5.2e-3 and 1.4e-3 of |F| on
    (90, 16) and (180, 32) (order 1.9)."""
    lam, e = 1.0, (0.6 * math.cos(0.7), 0.6 * math.sin(0.7))
    errs = []
    for mesh in ((90, 16), (180, 32)):
        F, _, prob, lab = _flows(lam, e, cavitation, CircumferentialGroove(0.4), mesh)
        zg = prob.zeta[:-1][lab[: mesh[1]] >= 0].max()
        Fp = film_at((lam - zg) / 2.0, e, (0.0, 0.0), cavitation, None, mesh)[0]
        errs.append(np.abs(F - 2.0 * Fp).max() / np.abs(F).max())
    assert errs[1] < 2e-3 and errs[0] / errs[1] > 3.4


def test_feed_holes_conserve_oil_and_flow_is_linear_in_the_feed():
    """jfo: what the holes supply leaves at the ends (steady, mass conserving), per hole flows add
    to the supply; concentric, the film is Laplace's problem and the flow is exactly linear in P_f."""
    lam, mesh = 0.5, (180, 16)
    e = (0.6 * math.cos(0.7), 0.6 * math.sin(0.7))
    F, fl, _, lab = _flows(lam, e, "jfo", feed_holes(2, 0.3, 0.05), mesh)
    assert fl["supply"] > 0.0 and fl["side"] == pytest.approx(fl["supply"], rel=1e-12)
    assert sum(fl["per_groove"]) == pytest.approx(fl["supply"], rel=1e-12)
    assert len(fl["per_groove"]) == 2 and min(fl["per_groove"]) > 0.0
    assert np.hypot(*F) > 0.1
    # a hole holds the nodes within d/2 on the unrolled surface: (Δθ)² + ζ² ≤ (d/2R)²
    assert 0 < np.count_nonzero(lab == 0) < 0.25**2 * math.pi / ((2 * math.pi / 180) * (lam / 16)) * 1.5
    q = [
        _flows(lam, (1e-14, 0.0), "reynolds", FeedHoles((1.0,), 0.3, f), mesh)[1]["supply"]
        for f in (0.01, 0.02)
    ]
    assert q[1] == pytest.approx(2.0 * q[0], rel=1e-12) and q[0] > 0.0


def test_supply_refusals_name_the_parameter():
    with pytest.raises(ValueError, match=r"feed hole diameter/R = 0.001 \[-\]: narrower than one mesh cell"):
        film_at(0.5, (0.3, 0.0), (0.0, 0.0), "reynolds", FeedHoles((1.0,), 0.001), (180, 16))
    with pytest.raises(ValueError, match=r"feed hole diameter/R = 1.5 \[-\]: must be < L/R = 1"):
        film_at(0.5, (0.3, 0.0), (0.0, 0.0), "reynolds", FeedHoles((1.0,), 1.5), (36, 8))
    with pytest.raises(ValueError, match=r"holes at 90 and 270 \[deg\] overlap|hole diameter"):
        FeedHoles((0.5 * math.pi, 1.5 * math.pi), 3.5)
    with pytest.raises(ValueError, match=r"circumferential groove width/R = -1.0 \[-\]"):
        CircumferentialGroove(-1.0)
    with pytest.raises(ValueError, match=r"circumferential groove width/R = 2 \[-\]: must be < L/R = 1"):
        film_at(0.5, (0.3, 0.0), (0.0, 0.0), "reynolds", CircumferentialGroove(2.0), (36, 8))
    with pytest.raises(ValueError, match=r"Finite.supply = 'hole': unknown"):
        Finite(cavitation="jfo", supply="hole")
    with pytest.raises(ValueError, match=r"Finite.supply_diameter = 0.0 \[m\]: feed_holes need"):
        Finite(cavitation="jfo", supply="feed_holes")
    with pytest.raises(ValueError, match=r"Finite.supply_count = 9 \[-\]"):
        Finite(cavitation="jfo", supply_count=9)


@pytest.mark.parametrize(
    "args, match",
    [
        (["--grooves", "2", "--feed-holes", "1", "--hole-diameter", "0.1"], "give one supply feature"),
        (["--feed-holes", "1"], "--feed-holes needs --hole-diameter"),
        (["--hole-diameter", "0.2"], "--hole-diameter needs --feed-holes"),
        (["--circumferential-groove", "1.5"], r"--circumferential-groove 1.5 \[-, fraction of the bearing"),
        (["--circumferential-groove", "0.1", "--cavitation", "jfo"], "the jfo film carries no load"),
    ],
)
def test_bearing_table_supply_refusals_are_one_line(args, match):
    r = CliRunner().invoke(app, ["bearing-table", "--ld", "0.5", "--eps", "0.5", *args])
    assert r.exit_code == 2, r.output
    assert len(r.output.strip().splitlines()) == 1
    assert re.search(match, r.output)


def test_bearing_table_prints_a_flow_per_feed_hole():
    r = CliRunner().invoke(
        app,
        ["bearing-table", "--ld", "0.5", "--eps", "0.6", "--feed-holes", "2", "--hole-diameter", "0.25"]
        + ["--cavitation", "jfo"],
    )
    assert r.exit_code == 0, r.output
    lines = [s for s in r.output.splitlines() if s and not s.startswith("warning")]
    head, row = lines[0].split(","), [float(x) for x in lines[1].split(",")]
    d = dict(zip(head, row, strict=True))
    assert d["hole_flow_1"] + d["hole_flow_2"] == pytest.approx(d["flow_variable"], rel=1e-5)
    assert d["side_flow_ratio"] == pytest.approx(1.0, rel=1e-6)  # mass conserving
    assert 0.0 < d["fill_min"] < 1.0 and d["sommerfeld"] > 0.0


@pytest.mark.parametrize(
    "film",
    [
        'supply = "feed_holes", supply_diameter = 0.004',
        'supply = "circumferential_groove", supply_diameter = 0.004, supply_pressure = 2e5',
    ],
)
def test_jfo_element_fed_through_holes_or_a_circumferential_groove_balances(tmp_path, film):
    """The example's pin fed through a feed hole, or a pressurised circumferential groove: the
    lubricant balance of the run closes to round-off of the content [T307]; the feature's flow
    output is the inflow [T376]."""
    text = EXAMPLE.read_text(encoding="utf-8").replace("supply_angle = 90.0 }", film + " }")
    assert film in text
    path = tmp_path / "m.toml"
    path.write_text(text, encoding="utf-8")
    model, cfg = load_model(path)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = simulate(model.compile(), dataclasses.replace(cfg, t_end=3e-4, n_out=11))
    content = run.memory("piston_pin", "film_content")
    v_in = run.memory("piston_pin", "inflow_volume")
    v_side = run.memory("piston_pin", "side_volume")
    i0 = int(np.argmax(np.isfinite(run.memory("piston_pin", "film_time"))))
    c0 = content[i0] - (v_in[i0] - v_side[i0])
    assert np.abs(content[i0:] - c0 - (v_in[i0:] - v_side[i0:])).max() <= 1e-10 * c0
    assert v_side[-1] > 1e-3 * c0 and abs(v_in[-1]) > 1e-3 * c0
    # the one feature's flow output is the inflow [T376]
    feature = run.element("piston_pin", "hole_flow_1" if "holes" in film else "circumferential_flow_1")
    inflow = run.element("piston_pin", "inflow")
    assert np.abs(feature - inflow).max() <= 1e-12 * np.abs(inflow).max()


def _short_arc_force(eps, phi, arc):
    """Ocvirk's short-bearing film (Gümbel) restricted to a partial arc centred on the load line:
    p ∝ ε sin θ/(1 + ε cos θ)³ on 0 < θ < π (film angles from the maximum film), θ = α − φ − π in
    the load frame; in the short limit the pressure is local, so the arc only cuts the integral."""
    from scipy.integrate import quad

    def comp(lo, hi):
        g = lambda t, f: eps * math.sin(t) / (1 + eps * math.cos(t)) ** 3 * f(t + phi + math.pi)  # noqa: E731
        return -np.array([quad(g, lo, hi, args=(math.cos,))[0], quad(g, lo, hi, args=(math.sin,))[0]])

    a = 0.5 * math.radians(arc)
    lo = (-a - phi - math.pi) % (2.0 * math.pi)
    parts = [(max(lo + s, 0.0), min(lo + s + 2 * a, math.pi)) for s in (0.0, 2 * math.pi, -2 * math.pi)]
    cut = sum((comp(x, y) for x, y in parts if y > x), np.zeros(2))
    return cut / np.linalg.norm(comp(0.0, math.pi))


@pytest.mark.parametrize("arc, order", [(150.0, 2), (90.0, 1)])
def test_partial_arc_tends_to_the_short_bearing_arc(arc, order):
    """As L/D → 0 the partial arc's film force (over the full bearing's) tends to the short-bearing
    pressure cut to the arc, at second order in L/D where the arc ends lie in low pressure and at
    first order where an end cuts the pressure hill (an end layer of width ∝ L). Measured (ε = 0.6,
    φ = 1.3 rad, mesh (360, 16)): 150°: 4.4e-3, 1.2e-3; 90°: 5.5e-2, 3.0e-2 at L/D = 1/8, 1/16."""
    from jointdyn.film.grooved import partial_arc

    eps, phi = 0.6, 1.3
    e = (eps * math.cos(phi), eps * math.sin(phi))
    errs = []
    for lam in (0.125, 0.0625):
        Fa = film_at(lam, e, (0.0, 0.0), "gumbel", partial_arc(arc), (360, 16))[0]
        Ff = film_at(lam, e, (0.0, 0.0), "gumbel", None, (360, 16))[0]
        errs.append(np.abs(Fa / np.linalg.norm(Ff) - _short_arc_force(eps, phi, arc)).max())
    assert errs[0] / errs[1] > (3.4 if order == 2 else 1.7)
    assert errs[1] < (2e-3 if order == 2 else 3.5e-2)


def test_partial_arc_table_has_the_arc_friction_and_open_flow():
    """The Couette shear acts on the arc only: friction·W − εF_t/2 = 2λ∫_arc dθ/H, which is about
    arc/360° of the full bearing's at small ε; the open part's flow is a column."""
    from jointdyn.bearing.grooved_table import grooved_table
    from jointdyn.film.grooved import partial_arc

    tab = grooved_table("reynolds", 1.0, [0.05], partial_arc(120.0), coefficients=False)
    assert "open_flow_1" in tab and tab["open_flow_1"][0] == pytest.approx(tab["flow_variable"][0])
    full = grooved_table("reynolds", 1.0, [0.05], feed_holes(1, 0.3), coefficients=False)
    # friction force ratio (friction variable × W, W = 2λ/(πS)): measured 0.33357; the pressure
    # term ε·F_t/2 and the arc's 1/H are O(ε) at ε = 0.05
    ratio = (
        tab["friction_variable"][0]
        / full["friction_variable"][0]
        * full["sommerfeld"][0]
        / tab["sommerfeld"][0]
    )
    assert ratio == pytest.approx(120.0 / 360.0, abs=0.005)
