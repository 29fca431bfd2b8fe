"""The transient jfo film under the compiled stiff methods [T377]: `examples/slider_crank_jfo.toml`
(one crank revolution by default) with ``auto`` (radau5 with the clearance error scale), ``rodas4``
and ``ros34pw2`` at each ``--rtols``, against ``--reference-method`` at ``--reference``.

Usage: ``python -m benchmarks.jfo_methods [--revolutions 1] [--rtols 1e-8,1e-9,1e-10] [--reference 1e-12]
[--reference-method auto] [--big-end]``

Prints per run: CPU seconds (``time.process_time``, warm: each method first runs 1e-5 s), accepted
steps, right-hand sides, Jacobians, the lubricant balance max|Δcontent − (inflow volume − side
volume)| / content [T307] and the film force's distance to the reference run,
max|F − F_ref| / max|F_ref| over the samples (0.5° of crank, as the example).

``--big-end``: instead, the engine's big end with the jfo film (`examples/engine_big_end_jfo.toml`,
two 720° cycles as docs/user-guide/big-end.md) with radau5 at rtol 1e-9 (the page's), rodas4 at
1e-7 (the table films' on the page) and 1e-9, ros34pw2 at 1e-9; per run CPU, steps, and over the
recorded (second) cycle the smallest film, the mean friction power and the distance of the orbit
(bushing frame, [c]) to the radau5 run's at the same sample.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import time
import warnings
from pathlib import Path

import numpy as np

from jointdyn.io.modelfile.load import load_system
from jointdyn.simulation.simulate import simulate

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "slider_crank_jfo.toml"
BIG_END = EXAMPLE.with_name("engine_big_end_jfo.toml")
CYCLE = 0.04  # the engine's 720° at 3000 rpm [s]
OMEGA = 523.5987755982989  # the example's crank speed [rad/s]
METHODS = ("auto", "rodas4", "ros34pw2")


def run(method: str, rtol: float, t_end: float):
    """(results, CPU [s]) of the example with ``method`` at ``rtol`` over ``t_end`` [s]."""
    _, system, cfg = load_system(EXAMPLE, [f"simulation.solver={method}", f"simulation.rtol={rtol!r}"])
    n_out = max(int(round(t_end * OMEGA * 180.0 / math.pi * 2.0)), 1) + 1  # 0.5° of crank, as the example
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t0 = time.process_time()
        res = simulate(system, dataclasses.replace(cfg, t_end=t_end, n_out=n_out))
    return res, time.process_time() - t0


def force(res) -> np.ndarray:
    return np.hypot(res.element("piston_pin", "Fx"), res.element("piston_pin", "Fy"))


def balance(res) -> float:
    """max|content − content₀ − (inflow volume − side volume)| / content₀ over the samples [T307]."""
    content = res.memory("piston_pin", "film_content")
    v_in, v_side = res.memory("piston_pin", "inflow_volume"), res.memory("piston_pin", "side_volume")
    i0 = int(np.argmax(np.isfinite(res.memory("piston_pin", "film_time"))))
    c0 = content[i0] - (v_in[i0] - v_side[i0])
    return float(np.abs(content[i0:] - c0 - (v_in[i0:] - v_side[i0:])).max() / c0)


def big_end() -> None:
    rows = (
        ("radau5", 1e-9, 1e-12),
        ("rodas4", 1e-7, 1e-11),
        ("rodas4", 1e-9, 1e-12),
        ("ros34pw2", 1e-9, 1e-12),
    )
    print("| method | rtol | CPU [s] | steps | h_min [µm] | friction [W] | orbit to radau5 max, median [c] |")
    print("|---|---|---|---|---|---|---|")
    ref = None
    for m, rtol, atol in rows:
        keys = [f"simulation.solver={m}", f"simulation.rtol={rtol!r}", f"simulation.atol={atol!r}"]
        _, system, cfg = load_system(BIG_END, keys)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            simulate(system, dataclasses.replace(cfg, t_end=1e-5, n_out=2))  # compile
            t0 = time.process_time()
            res = simulate(system, dataclasses.replace(cfg, t_end=2.0 * CYCLE, n_out=721))
            cpu = time.process_time() - t0
        sel = res.t >= CYCLE * (1.0 - 1e-9)
        ex, ey = (v[sel] for v in res.orbit("big_end"))
        t, loss = res.t[sel], res.element("big_end", "power_loss")[sel]
        ref = (ex, ey) if ref is None else ref
        d = np.hypot(ex - ref[0], ey - ref[1])
        print(
            f"| {m} | {rtol:g} | {cpu:.1f} | {res.stats['accepted_steps']} | "
            f"{res.element('big_end', 'h_min')[sel].min() * 1e6:.4f} | "
            f"{np.trapezoid(loss, t) / (t[-1] - t[0]):.3f} | {d.max():.2g} / {np.median(d):.2g} |"
        )


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--revolutions", type=float, default=1.0)
    ap.add_argument("--rtols", default="1e-8,1e-9,1e-10")
    ap.add_argument("--reference", type=float, default=1e-12)
    ap.add_argument("--reference-method", default="auto", choices=METHODS)
    ap.add_argument("--big-end", action="store_true")
    a = ap.parse_args(argv)
    if a.big_end:
        big_end()
        return
    t_end = a.revolutions * 2.0 * math.pi / OMEGA
    for m in METHODS:
        run(m, 1e-8, 1e-5)  # compile
    ref, cpu = run(a.reference_method, a.reference, t_end)
    F_ref = force(ref)
    print(
        f"reference {a.reference_method} rtol {a.reference:g}: {cpu:.2f} s CPU, "
        f"{ref.stats['accepted_steps']} steps"
    )
    print("| method | rtol | CPU [s] | steps | RHS | Jacobians | balance | max|F − F_ref| / max|F_ref| |")
    print("|---|---|---|---|---|---|---|---|")
    for m in METHODS:
        for rtol in (float(x) for x in a.rtols.split(",")):
            res, cpu = run(m, rtol, t_end)
            s = res.stats
            err = float(np.abs(force(res) - F_ref).max() / np.abs(F_ref).max())
            print(
                f"| {m} | {rtol:g} | {cpu:.2f} | {s['accepted_steps']} | {s['rhs_evaluations']} | "
                f"{s['jacobians']} | {balance(res):.1e} | {err:.4f} |"
            )


if __name__ == "__main__":
    main()
