"""Regenerate the multibody results of docs/user-guide/big-end.md (the engine's big end).

    python docs/_gen_big_end_multibody.py [--check]

Runs ``examples/engine_single_cylinder.toml`` (3000 rpm, rodas4) with the big end as a finite
bearing with the ``gumbel``, ``reynolds`` and ``jfo`` films (same bearing, small end as in the
example) over a warm-up cycle and one recorded 720° cycle, and writes the block between
``<!-- generated:big-end-multibody -->`` and ``<!-- /generated -->`` of the page and
docs/figures/big_end_mb_*.png; the CPU cost goes into the ``big-end-multibody-cost`` block
(not compared). ``--check`` recomputes and exits 1 if the page's numbers differ.
"""

from __future__ import annotations

import argparse
import math
import re
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
PAGE = HERE / "user-guide" / "big-end.md"
FIG = HERE / "figures"
EXAMPLE = ROOT / "examples" / "engine_single_cylinder.toml"
ELEMENT = "big_end"
LAWS = ("gumbel", "reynolds", "jfo")
CYCLE = 0.04  # one four-stroke cycle at 3000 rpm: 720° [s]
N_OUT = 2 * 360 + 1  # 2° of crank angle per sample over warm-up + recorded cycle
# solver, rtol, atol: the example's for the table films; the jfo film runs radau5 at rtol 1e-9 (at
# 1e-7 the check of [T111] found its force unresolved; rodas4 at 1e-7 now runs it in a sixth of the
# CPU, its orbit within 0.0041 c of this one: docs/theory.md [T377])
TABLE_RUN = ("rodas4", 1e-7, 1e-11)
SOLVER = {"gumbel": TABLE_RUN, "reynolds": TABLE_RUN, "jfo": ("radau5", 1e-9, 1e-12)}
# jfo film of the big end: one axial supply groove in the rod eye at 90° from the rod axis, fed at
# 2 bar; mesh 24 × 4 cells (coarse: the run must stay a few minutes of CPU)
SUPPLY = {"supply_angle": 90.0, "supply_width": 20.0, "supply_pressure": 2.0e5}
MESH = {"cells_around": 24, "cells_half_length": 4}


def film_key(law: str) -> str:
    extra = {**SUPPLY, **MESH} if law == "jfo" else {}
    items = "".join(f", {k} = {v!r}" for k, v in extra.items())
    return f'{{ law = "finite", cavitation = "{law}"{items} }}'


def run(law: str):
    """One run of the engine with the big end's film ``law``: (Results, CPU seconds)."""
    from jointdyn.io.modelfile.load import load_system
    from jointdyn.simulation.simulate import simulate

    keys = [
        f"elements.{ELEMENT}.film={film_key(law)}",
        f"simulation.t_end={2.0 * CYCLE!r}",
        f"simulation.n_out={N_OUT}",
        f"simulation.solver={SOLVER[law][0]}",
        f"simulation.rtol={SOLVER[law][1]!r}",
        f"simulation.atol={SOLVER[law][2]!r}",
    ]
    t0 = time.process_time()
    _, system, cfg = load_system(EXAMPLE, keys)
    res = simulate(system, cfg)
    return res, time.process_time() - t0


def jfo_peak_pressure(res) -> np.ndarray:
    """Peak film pressure [Pa] of the big end's jfo film at every sample: the film the element's
    force evaluates at the sample's state [T345] (the committed fill of the sample's memory row
    frozen at the journal position e_b, squeezed from ė_b over the shortest step), its largest
    cell pressure P·6μR²/c². The film force of that same solve is checked against the element's
    output force (Fx, Fy): a different element formula stops the generator instead of publishing
    pressures of another film."""
    from jointdyn.core.layout import BODY_I, BODY_J
    from jointdyn.film.jfo_step import jfo_step
    from jointdyn.forces.jfo_film import CELLS, DT_MIN_TURN, FILM_TIME, _capped, _films, _unpack
    from jointdyn.forces.journal import CLR, CONTACT, H_ASP, JFO, MU, NO_CONTACT, R_J, XI_GUARD
    from jointdyn.forces.journal_geometry import journal_kinematics
    from jointdyn.forces.journal_pieces import bushing_frame

    s = res.system
    k = s.element_names.index(ELEMENT)
    ip, r, slot = s.fint[k], s.freal[k], int(s.fint[k, JFO])
    bi, bj, c, mu, R = ip[BODY_I], ip[BODY_J], r[CLR], r[MU], r[R_J]
    cap = min((c - r[H_ASP]) / c if ip[CONTACT] != NO_CONTACT else XI_GUARD, XI_GUARD)
    g = _unpack(s.tables, slot)
    nt, nz, cn, sn = g[:4]
    n = nt * nz
    fx_out, fy_out = res.element(ELEMENT, "Fx"), res.element(ELEMENT, "Fy")
    out = np.empty(len(res.t))
    for i in range(len(res.t)):
        q, qd, mem = res.y[i, : s.n], res.y[i, s.n :], res.mem[i, k]
        ex, ey, edx, edy, _, _, _, _, wi, wj = journal_kinematics(q, qd, bi, bj, r)
        co, si, ebx, eby, vbx, vby = bushing_frame(q, bi, ex, ey, edx, edy, wi, c)
        omega = wj - wi
        ebx, eby = _capped(ebx, eby, cap)
        content0 = _films(ebx, eby, nt, nz, cn, sn)
        cav = np.zeros(n, bool)
        if mem[FILM_TIME] == mem[FILM_TIME]:  # committed fill θ_f = Hθ_f/H(e_n), frozen at e_b
            fill = np.asarray(mem[CELLS : CELLS + n]) / _films(
                mem[CELLS + n], mem[CELLS + n + 1], nt, nz, cn, sn
            )
            content0 *= fill
            cav = (fill < 1.0) & ~g[9]  # the committed active set, frozen [T348]
        dt = DT_MIN_TURN / max(abs(omega), 1.0)
        ex1, ey1 = _capped(ebx + vbx * dt, eby + vby * dt, cap)
        P, _, fbx, fby, *_, its = jfo_step(ex1, ey1, omega, dt, content0, cav, *g, 0)
        scale = mu * R**4 / (c * c)
        fx, fy = (co * fbx - si * fby) * scale, (si * fbx + co * fby) * scale
        if its < 0 or math.hypot(fx - fx_out[i], fy - fy_out[i]) > 1e-9 * max(math.hypot(fx, fy), 1.0):
            raise RuntimeError(f"sample {i}: the recomputed jfo film is not the element's ({fx}, {fy} N)")
        out[i] = np.max(P) * 6.0 * mu * R * R / (c * c)
    return out


def jfo_cavitated(res) -> np.ndarray:
    """Fraction [-] of the big end's jfo cells (supply cells excluded) that the committed film of
    each sample fills only partly: fill θ_f = Hθ_f/H(e_n) < 1 [T345]."""
    from jointdyn.forces.jfo_film import CELLS, FILM_TIME, _films, _unpack
    from jointdyn.forces.journal import JFO

    s = res.system
    k = s.element_names.index(ELEMENT)
    g = _unpack(s.tables, int(s.fint[k, JFO]))
    nt, nz, cn, sn, fixed = g[0], g[1], g[2], g[3], g[9]
    n = nt * nz
    out = np.empty(len(res.t))
    for i in range(len(res.t)):
        mem = res.mem[i, k]
        if not mem[FILM_TIME] == mem[FILM_TIME]:  # before the first commit: the full film
            out[i] = 0.0
            continue
        fill = np.asarray(mem[CELLS : CELLS + n]) / _films(mem[CELLS + n], mem[CELLS + n + 1], nt, nz, cn, sn)
        out[i] = np.mean(fill[~fixed] < 1.0 - 1e-9)
    return out


def cycle_of(res) -> dict:
    """The recorded (second) cycle of a run: crank angle [deg] from 0 and the big end's
    outputs there (orbit in the bushing = rod frame [T290])."""
    from jointdyn import post

    sel = res.t >= CYCLE * (1.0 - 1e-9)
    crank = np.degrees(res.crank_angle()[sel] - res.crank_angle()[sel][0])
    ex, ey = res.orbit(ELEMENT)
    t = res.t[sel]
    out = {
        "t": t,
        "crank": crank,
        "ex": ex[sel],
        "ey": ey[sel],
        "h_min": res.element(ELEMENT, "h_min")[sel],
        "loss": res.element(ELEMENT, "power_loss")[sel],
        "force": np.hypot(res.element(ELEMENT, "Fx")[sel], res.element(ELEMENT, "Fy")[sel]),
    }
    el = res.system.elements[res.system.element_names.index(ELEMENT)]
    if el.film.cavitation == "jfo":  # the committed film's accumulated volumes [T307]
        for k in ("film_time", "film_content", "inflow_volume", "side_volume"):
            out[k] = res.memory(ELEMENT, k)[sel]
        out["p_max"] = jfo_peak_pressure(res)[sel]
        out["cavitated"] = jfo_cavitated(res)[sel]
    else:
        fo = post.film_outputs(res, ELEMENT)
        out["p_max"], out["side_flow"] = fo["p_max"][sel], fo["side_flow"][sel]
    return out


def mean(t, x) -> float:
    """Time average over the samples (trapezoidal) [unit of x]."""
    return float(np.trapezoid(x, t) / (t[-1] - t[0]))


def numbers(cyc: dict) -> dict:
    n = {}
    for law, c in cyc.items():
        k = int(np.argmin(c["h_min"]))
        n[f"{law}_h_min_um"] = float(c["h_min"][k] * 1e6)
        n[f"{law}_at_deg"] = float(c["crank"][k])
        n[f"{law}_max_eps"] = float(np.max(np.hypot(c["ex"], c["ey"])))
        n[f"{law}_loss_W"] = mean(c["t"], c["loss"])
        n[f"{law}_peak_force_N"] = float(np.max(c["force"]))
        k = int(np.argmax(c["p_max"]))
        n[f"{law}_p_max_MPa"] = float(c["p_max"][k] / 1e6)
        n[f"{law}_p_at_deg"] = float(c["crank"][k])
        if law == "jfo":  # from the committed volumes over the cycle's commits [T307]
            span = float(c["film_time"][-1] - c["film_time"][0])
            v_in = float(c["inflow_volume"][-1] - c["inflow_volume"][0])
            v_side = float(c["side_volume"][-1] - c["side_volume"][0])
            V = c["film_content"]
            n["jfo_inflow_mm3s"] = v_in / span * 1e9
            n["jfo_side_mm3s"] = v_side / span * 1e9
            n["jfo_content_min_mm3"], n["jfo_content_max_mm3"] = float(V.min() * 1e9), float(V.max() * 1e9)
            # content balance over the cycle [T301]: ΔV against inflow volume − side volume
            n["jfo_balance"] = abs(float(V[-1] - V[0]) - (v_in - v_side)) / float(np.mean(V))
        else:
            n[f"{law}_side_mm3s"] = mean(c["t"], c["side_flow"]) * 1e9
    for a in (law for law in cyc if law != "reynolds"):
        ca, cb = cyc[a], cyc["reynolds"]
        gap = np.hypot(ca["ex"] - cb["ex"], ca["ey"] - cb["ey"])
        if a == "jfo":  # the state where the orbits part most
            i = int(np.argmax(gap))
            n["jfo_force_at_gap_N"] = float(ca["force"][i])
            n["jfo_cav_at_gap"] = float(ca["cavitated"][i])
            n["jfo_cav_min"], n["jfo_cav_max"] = float(ca["cavitated"].min()), float(ca["cavitated"].max())
        n[f"gap_{a}_reynolds"] = float(np.max(gap))
        n[f"gap_{a}_at_deg"] = float(cb["crank"][int(np.argmax(gap))])
        n[f"gap_{a}_median"] = float(np.median(gap))
        n[f"gap_{a}_over_02"] = float(np.mean(gap > 0.2))
    return n


def block(n: dict) -> str:
    g = lambda v, d=3: f"{v:#.{d}g}".rstrip(".")  # noqa: E731
    cell = lambda key, d: g(n[key], d) if key in n else "—"  # noqa: E731
    row = lambda label, key, d=3: (  # noqa: E731
        f"| {label} | " + " | ".join(cell(f"{law}_{key}", d) for law in LAWS) + " |\n"
    )
    return (
        "| recorded cycle (720°, after one warm-up cycle) | " + " | ".join(LAWS) + " |\n"
        "|---|"
        + "---|" * len(LAWS)
        + "\n"
        + row("smallest film thickness h_min [µm]", "h_min_um")
        + row("at crank angle [deg] (360 = firing TDC)", "at_deg")
        + row("largest eccentricity ratio ε [-]", "max_eps", 4)
        + row("peak film pressure [MPa]", "p_max_MPa")
        + row("at crank angle [deg]", "p_at_deg")
        + row("peak film force [N]", "peak_force_N")
        + row("friction power, cycle mean [W]", "loss_W")
        + row("side flow, cycle mean [mm³/s]", "side_mm3s")
        + row("supply inflow, cycle mean [mm³/s]", "inflow_mm3s")
        + ("\n" + _jfo_text(n) if "jfo_balance" in n else "")
        + "\n"
        + _cross_text(n)
    )


def _jfo_text(n: dict) -> str:
    g = lambda v, d=3: f"{v:#.{d}g}".rstrip(".")  # noqa: E731
    return (
        f"jfo film: mean supply inflow {g(n['jfo_inflow_mm3s'])} mm³/s, mean side outflow "
        f"{g(n['jfo_side_mm3s'])} mm³/s (the accumulated volumes over the cycle's commits), film "
        f"content {g(n['jfo_content_min_mm3'])} to {g(n['jfo_content_max_mm3'])} mm³; lubricant "
        f"balance over the cycle (|ΔV − (inflow volume − side volume)| relative to the mean content, "
        f"[T307]): {n['jfo_balance']:.1e}; cavitated (partly filled) cells {g(n['jfo_cav_min'], 2)} to "
        f"{g(n['jfo_cav_max'], 2)} of the film. Where the jfo and reynolds orbits part most (below), the "
        f"jfo film force is {g(n['jfo_force_at_gap_N'])} N and {g(n['jfo_cav_at_gap'], 2)} of its cells "
        "are cavitated.\n"
    )


def _cross_text(n: dict) -> str:
    """The comparisons of each film with reynolds (the classical design tables) [-, µm, c]."""
    g = lambda v, d=3: f"{v:#.{d}g}".rstrip(".")  # noqa: E731
    parts = [
        f"{law} − reynolds: h_min {g(n[f'{law}_h_min_um'] - n['reynolds_h_min_um'])} µm, peak pressure "
        f"ratio {g(n[f'{law}_p_max_MPa'] / n['reynolds_p_max_MPa'])}, friction power ratio "
        f"{g(n[f'{law}_loss_W'] / n['reynolds_loss_W'])}, distance between the orbits at the same sample: "
        f"largest {g(n[f'gap_{law}_reynolds'])} c (at {g(n[f'gap_{law}_at_deg'])}°), median "
        f"{g(n[f'gap_{law}_median'])} c, over 0.2 c at {100 * n[f'gap_{law}_over_02']:.1f} % of the samples"
        for law in LAWS
        if law != "reynolds"
    ]
    return "Cross-checks (computed from the runs above): " + "; ".join(parts) + ".\n"


def cost_block(cpu: dict, steps: dict) -> str:
    parts = ", ".join(f"{law} {cpu[law]:.1f} s ({steps[law]} steps)" for law in LAWS)
    mesh = f"{MESH['cells_around']} × {MESH['cells_half_length']}"
    return (
        f"CPU time of the last generation (model build and two cycles each, warm numba cache): {parts}; "
        f"the jfo film on {mesh} cells, {SOLVER['jfo'][0]} at rtol {SOLVER['jfo'][1]:g}.\n"
    )


def figures(cyc: dict) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from jointdyn.viz.orbit import journal_orbit

    style = {"gumbel": "C2", "reynolds": "C3", "jfo": "C0"}
    fig, ax = plt.subplots(figsize=(5.2, 5.2))
    for law in LAWS:
        c = cyc[law]
        journal_orbit(c["ex"], c["ey"], ax=ax, label=law, frame="bushing (rod)", zoom=False, color=style[law])
    ax.legend(fontsize=7, loc="lower left")
    ax.set_title("big-end orbit, recorded cycle", fontsize=9)
    fig.tight_layout()
    fig.savefig(FIG / "big_end_mb_orbit.png", dpi=90)
    plt.close(fig)
    fig, axs = plt.subplots(4, 1, figsize=(7, 8.2), sharex=True)
    ref = cyc["reynolds"]
    for law in LAWS:
        c = cyc[law]
        axs[0].plot(c["crank"], c["h_min"] * 1e6, color=style[law], lw=1, label=law)
        axs[1].plot(c["crank"], c["force"], color=style[law], lw=1, label=law)
        axs[2].plot(c["crank"], c["loss"], color=style[law], lw=1, label=law)
        if law != "reynolds":
            gap = np.hypot(c["ex"] - ref["ex"], c["ey"] - ref["ey"])
            axs[3].plot(c["crank"], gap, color=style[law], lw=1, label=f"{law} − reynolds")
    axs[0].set(ylabel="h_min [µm]")
    axs[1].set(ylabel="film force [N]")
    axs[2].set(ylabel="friction power [W]")
    axs[3].set(ylabel="orbit distance [c]", xlabel="crank angle [deg] (360 = firing TDC)")
    axs[3].legend(fontsize=7)
    axs[0].legend(fontsize=7)
    for a in axs:
        a.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(FIG / "big_end_mb_cycle.png", dpi=90)
    plt.close(fig)


def _block_re(name: str):
    return re.compile(rf"(<!-- generated:{name} -->\n)(.*?)(<!-- /generated -->)", re.S)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="recompute, compare with the page, write nothing")
    a = ap.parse_args(argv)
    cyc, cpu, steps = {}, {}, {}
    for law in LAWS:
        res, cpu[law] = run(law)
        cyc[law] = cycle_of(res)
        steps[law] = res.stats["accepted_steps"]
        print(f"{law}: {cpu[law]:.1f} s CPU, {res.stats}", file=sys.stderr)
    new = block(numbers(cyc))
    text = PAGE.read_text(encoding="utf-8")
    main_re = _block_re("big-end-multibody")
    old = main_re.search(text).group(2)
    if a.check:
        if old != new:
            print(f"{PAGE.name}: generated block out of date; run python docs/_gen_big_end_multibody.py")
            return 1
        return 0
    text = main_re.sub(lambda m: m.group(1) + new + m.group(3), text)
    text = _block_re("big-end-multibody-cost").sub(
        lambda m: m.group(1) + cost_block(cpu, steps) + m.group(3), text
    )
    PAGE.write_text(text, encoding="utf-8")
    figures(cyc)
    print(new)
    return 0


if __name__ == "__main__":
    sys.exit(main())
