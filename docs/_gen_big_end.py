"""Regenerate the figures and numbers of docs/user-guide/big-end.md (≈ 2 min CPU).

    python docs/_gen_big_end.py [--check]

A connecting-rod big-end bearing over two four-stroke cycles (the first washes out the flooded
start; the page shows the second): the massless-journal orbit of [T302] with the transient
mass-conserving film (jfo) and with Swift–Stieber at every instant (reynolds), the film content,
cavitated fraction and flows. Writes docs/figures/big_end_*.png and the block between
``<!-- generated:big-end -->`` and ``<!-- /generated -->`` of the page; ``--check`` recomputes
and exits 1 if the page's numbers differ.
"""

from __future__ import annotations

import argparse
import math
import re
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
PAGE = HERE / "user-guide" / "big-end.md"
FIG = HERE / "figures"

# engine and bearing (SI)
SPEED = 3000.0 * 2.0 * math.pi / 60.0  # crank speed [rad/s]
CRANK, ROD = 0.045, 0.15  # crank radius, rod length [m]
BORE, P_GAS = 0.08, 3.0e6  # bore [m], peak cylinder pressure (gauge) [Pa]
M_REC, M_ROT = 0.6, 0.4  # reciprocating mass, rotating big-end mass [kg]
R, L, C, MU = 0.03, 0.024, 30e-6, 0.012  # journal radius, length, radial clearance [m], viscosity [Pa·s]
FEED = 3.0e5  # groove supply pressure [Pa]
GROOVE_DEG, GROOVE_WIDTH_DEG = 90.0, 20.0  # groove centre from the rod axis, width [deg]
STEP_DEG = 4.0  # crank angle per time step [deg]


def kinematics(t):
    """Crank angle θ [rad], rod angle φ from the cylinder axis [rad], its rate φ̇ [rad/s] and the
    load on the crankpin (journal) in the rod (bearing) frame W [N] (gas + inertia)."""
    th = SPEED * t
    lam = CRANK / ROD
    sb = lam * math.sin(th)
    cb = math.sqrt(1.0 - sb * sb)
    beta_dot = lam * SPEED * math.cos(th) / cb
    cyc = math.degrees(th) % 720.0  # 0 = TDC of the intake stroke, 360 = firing TDC
    p = P_GAS * math.exp(-(((cyc - 370.0) / 25.0) ** 2))
    a = -CRANK * SPEED**2 * (math.cos(th) + lam * math.cos(2.0 * th))  # piston acceleration [m/s²]
    Fc = (p * math.pi * BORE**2 / 4.0 + M_REC * a) / cb  # rod compression [N]
    u = np.array([-cb, sb])  # rod axis, small end -> big end
    W = Fc * u + M_ROT * CRANK * SPEED**2 * np.array([math.cos(th), math.sin(th)])
    phi = math.atan2(u[1], u[0])
    rot = np.array([[math.cos(phi), math.sin(phi)], [-math.sin(phi), math.cos(phi)]])
    return th, phi, -beta_dot, rot @ W


def run(law: str, step_deg: float = STEP_DEG, mesh=(36, 8)) -> dict:
    from jointdyn.film.grooved import Grooves
    from jointdyn.film.jfo_transient import TransientFilm, orbit

    g = Grooves((math.radians(GROOVE_DEG),), math.radians(GROOVE_WIDTH_DEG), FEED * C**2 / (6.0 * MU * R**2))
    film = TransientFilm(L / (2.0 * R), g, mesh)
    n = int(round(1440.0 / step_deg))
    times = np.linspace(0.0, 4.0 * math.pi / SPEED * 2.0, n + 1)
    scale = C**2 / (MU * R**4)  # W̄ = W c²/(μR⁴) [1/s per N]
    out = orbit(
        film,
        lambda t: SPEED - kinematics(t)[2],
        lambda t: scale * kinematics(t)[3],
        times,
        (0.0, 0.0),
        law,
        mass=M_ROT * C**3 / (MU * R**4),
    )
    out["times"] = times
    out["crank_deg"] = np.degrees(SPEED * times)
    out["load"] = np.array([kinematics(t)[3] for t in times])
    return out


def numbers(jfo: dict, rey: dict, fine: dict) -> dict:
    from jointdyn.film.jfo_transient import balance_error

    second = jfo["crank_deg"] >= 720.0
    res = {}
    for name, r in (("jfo", jfo), ("reynolds", rey)):
        eps = np.hypot(r["e"][second, 0], r["e"][second, 1])
        k = int(np.argmax(eps))
        res[f"{name}_max_eps"] = float(eps[k])
        res[f"{name}_h_min_um"] = float(C * (1.0 - eps[k]) * 1e6)
        res[f"{name}_at_deg"] = float(r["crank_deg"][second][k] - 720.0)
    res["orbit_gap"] = float(np.max(np.hypot(*(jfo["e"][second] - rey["e"][second]).T)))
    ef = fine["e"][::2][second]
    res["step_gap"] = float(np.max(np.hypot(*(jfo["e"][second] - ef).T)))
    res["balance"] = balance_error(jfo)
    cav = jfo["cavitated"][second]
    res["cav_min"], res["cav_max"] = float(cav.min()), float(cav.max())
    V = R**2 * C * jfo["content"][second] * 1e9  # [mm³]
    res["content_min"], res["content_max"] = float(V.min()), float(V.max())
    Q = R**2 * C * jfo["inflow"][second] * 1e9  # [mm³/s]
    res["inflow_mean"] = float(np.mean(Q))
    res["side_mean"] = float(np.mean(R**2 * C * jfo["side"][second] * 1e9))
    res["peak_load_kN"] = float(np.max(np.hypot(*jfo["load"].T)) / 1e3)
    return res


def block(n: dict) -> str:
    g = lambda v, d=3: f"{v:#.{d}g}".rstrip(".")  # noqa: E731
    return (
        "| | jfo (transient, mass-conserving) | reynolds (Swift–Stieber, no history) |\n"
        "|---|---|---|\n"
        f"| largest ε over the cycle | {g(n['jfo_max_eps'], 4)} | {g(n['reynolds_max_eps'], 4)} |\n"
        f"| smallest film h_min [µm] | {g(n['jfo_h_min_um'])} | {g(n['reynolds_h_min_um'])} |\n"
        f"| at crank angle [deg] | {g(n['jfo_at_deg'])} | {g(n['reynolds_at_deg'])} |\n\n"
        f"Peak load {g(n['peak_load_kN'])} kN. Largest distance between the two orbits: "
        f"{g(n['orbit_gap'])} c. Time-step check: the jfo orbit at {STEP_DEG / 2:g}° steps differs "
        f"from the {STEP_DEG:g}° one by at most {g(n['step_gap'])} c (backward Euler, first order "
        f"[T303]). Cavitated fraction of the film over the cycle: {g(n['cav_min'])} to "
        f"{g(n['cav_max'])}; film content {g(n['content_min'])} to {g(n['content_max'])} mm³; mean "
        f"supply {g(n['inflow_mean'])} mm³/s, mean side outflow {g(n['side_mean'])} mm³/s. Lubricant "
        f"balance over both cycles (content change vs Σ Δt·(inflow − side outflow), relative to "
        f"the content): {n['balance']:.1e} [T301].\n"
    )


def figures(jfo: dict, rey: dict) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    second = jfo["crank_deg"] >= 720.0
    fig, (a0, a1) = plt.subplots(1, 2, figsize=(9, 4.4))
    W = jfo["load"][second] / 1e3
    a0.plot(W[:, 0], W[:, 1], "k-", lw=1)
    a0.set(
        xlabel="load along the rod axis [kN]", ylabel="across [kN]", title="load on the crankpin (rod frame)"
    )
    a0.set_aspect("equal", "datalim")
    t = np.linspace(0, 2 * math.pi, 200)
    a1.plot(np.cos(t), np.sin(t), color="0.6", lw=0.8)
    for r, lab, st in ((jfo, "jfo", "C0-"), (rey, "reynolds", "C3--")):
        a1.plot(r["e"][second, 0], r["e"][second, 1], st, lw=1.2, label=lab)
    a1.set(xlabel="e_x/c (rod axis)", ylabel="e_y/c", title="journal orbit in the bearing")
    a1.set_aspect("equal")
    a1.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(FIG / "big_end_orbit.png", dpi=110)
    plt.close(fig)
    ca = jfo["crank_deg"][second] - 720.0
    fig, ax = plt.subplots(3, 1, figsize=(8, 7), sharex=True)
    ax[0].plot(ca, np.hypot(*jfo["e"][second].T), "C0-", label="jfo")
    ax[0].plot(ca, np.hypot(*rey["e"][second].T), "C3--", label="reynolds")
    ax[0].set(ylabel="ε [-]")
    ax[0].legend(fontsize=8)
    ax[1].plot(ca, jfo["cavitated"][second], "C0-", label="jfo: cells at partial content")
    ax[1].plot(ca, rey["cavitated"][second], "C3--", label="reynolds: cells at P = 0")
    ax[1].set(ylabel="cavitated fraction [-]")
    ax[1].legend(fontsize=8)
    k = R**2 * C * 1e9
    ax[2].plot(ca, k * jfo["inflow"][second], "C2-", label="supply inflow [mm³/s]")
    ax[2].plot(ca, k * jfo["side"][second], "C1-", label="side outflow [mm³/s]")
    ax2 = ax[2].twinx()
    ax2.plot(ca, k * jfo["content"][second], "k:", label="film content [mm³]")
    ax2.set(ylabel="content [mm³]")
    ax[2].set(xlabel="crank angle [deg] (360 = firing TDC)", ylabel="flow [mm³/s]")
    ax[2].legend(fontsize=8, loc="upper left")
    ax2.legend(fontsize=8, loc="upper right")
    fig.tight_layout()
    fig.savefig(FIG / "big_end_cycle.png", dpi=110)
    plt.close(fig)


BLOCK = re.compile(r"(<!-- generated:big-end -->\n)(.*?)(<!-- /generated -->)", re.S)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="recompute, compare with the page, write nothing")
    a = ap.parse_args(argv)
    jfo, rey, fine = run("jfo"), run("reynolds"), run("jfo", STEP_DEG / 2.0)
    n = numbers(jfo, rey, fine)
    new = block(n)
    text = PAGE.read_text(encoding="utf-8")
    old = BLOCK.search(text).group(2)
    if a.check:
        if old != new:
            print(f"{PAGE.name}: generated block out of date; run python docs/_gen_big_end.py")
            return 1
        return 0
    PAGE.write_text(BLOCK.sub(lambda m: m.group(1) + new + m.group(3), text), encoding="utf-8")
    figures(jfo, rey)
    print(new)
    return 0


if __name__ == "__main__":
    sys.exit(main())
