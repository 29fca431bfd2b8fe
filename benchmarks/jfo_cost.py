"""Cost of the transient jfo film against the ``finite`` table in the multibody loop: the numbers
that decide whether the compiled jfo step [T304] fits the speed target of the transient jfo
bearing (one slider-crank revolution ≤ 20× the ``finite`` table run) [T305].

Usage: ``python -m benchmarks.jfo_cost [--mesh 36x8] [--reference 72x16] [--steps 200] [--end-to-end]``

Prints, in CPU seconds (``time.process_time``, warm: kernels compiled, table cached):

* the ``finite`` run: one revolution of ``slider_crank("finite")`` with the library defaults, its
  CPU and its counts of right-hand sides and Jacobians;
* the compiled jfo step (:func:`~jointdyn.film.jfo_step.jfo_step`) at ``--mesh``: median CPU per
  step over ``--steps`` steps of a journal on a Lissajous path (|e|/c up to 0.9, Δt = 1e-5 s at
  ω = 524 rad/s, the slider-crank's crank speed; warm-started from the previous step's
  cavitated set, as the multibody loop would);
* the projected ratio (finite CPU + film solves × step CPU) / finite CPU with one film solve per
  right-hand side and two more per Jacobian (the film force depends on e(t) only, not on ė, in
  the backward-Euler form, so its column block is two differences) — a lower bound: the coupling
  itself and any extra steps the content limit forces are not in it;
* the mesh error: max over the path of |F(mesh) − F(reference)| / |F(reference)|.

``--end-to-end`` measures instead the built element [T306, T345–T349, T351]: one revolution of the
same slider-crank with ``film = Finite(cavitation="jfo")`` (``examples/slider_crank_jfo.toml``,
same configuration as the ``finite`` run; ``--mesh`` defaults to the film's default mesh) in CPU
seconds, its ratio to the ``finite`` run, its counts, and the error of its film force against the
same run on a refined mesh over ``--window`` revolutions (default the whole revolution; max
|F(mesh) − F(refined)| / max |F(refined)| at the samples; the 72 × 16 run costs ≈ 15 s CPU).
"""

from __future__ import annotations

import argparse
import math
import statistics
import time
import warnings

import numpy as np

from jointdyn import slider_crank
from jointdyn.film.grooved import Grooves
from jointdyn.film.jfo_step import geometry, jfo_step
from jointdyn.film.jfo_transient import TransientFilm
from jointdyn.film.models import Finite
from jointdyn.simulation.simulate import SimConfig, simulate

OMEGA = 523.5987755982989  # the slider-crank's crank speed [rad/s]
DT = 1e-5  # [s]


def finite_run() -> tuple[float, dict]:
    """CPU [s] and stats of one warm revolution of the finite-table slider-crank."""
    system = slider_crank("finite").compile()
    cfg = SimConfig(2.0 * math.pi / OMEGA, n_out=201)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        simulate(system, cfg)
        t0 = time.process_time()
        r = simulate(system, cfg)
    return time.process_time() - t0, r.stats


def path(n: int) -> np.ndarray:
    t = np.arange(1, n + 1) * DT * OMEGA / 20.0
    return np.stack([0.9 * np.cos(3.0 * t), 0.8 * np.sin(2.0 * t)], axis=1)


def step_cost(mesh, n: int) -> tuple[float, np.ndarray]:
    """Median CPU per compiled step [s] and the forces (n, 2) along the path."""
    f = TransientFilm(0.5, Grooves((0.5 * math.pi,), 0.3, 0.0), mesh)
    g = geometry(f)
    es = path(n)
    content = f.flooded(es[0])
    cav = np.zeros(content.size, np.bool_)
    jfo_step(es[0, 0], es[0, 1], OMEGA, DT, content, cav.copy(), *g.args(), 200)  # compile
    cpu, F = [], np.empty((n, 2))
    for k, e in enumerate(es):
        t0 = time.process_time()
        P, fill, fx, fy, _, _, _, _, it = jfo_step(e[0], e[1], OMEGA, DT, content, cav, *g.args(), 200)
        cpu.append(time.process_time() - t0)
        if it < 0:
            raise SystemExit(f"step {k}: the active set did not settle")
        F[k] = fx, fy
        H = 1.0 - e[0] * np.repeat(g.cn, g.nz) - e[1] * np.repeat(g.sn, g.nz)
        content = H * fill
    return statistics.median(cpu), F


def jfo_run(mesh, revolutions: float) -> tuple[float, object, str]:
    """CPU [s], results and status of the example's jfo slider-crank on ``mesh`` over
    ``revolutions`` (warm: a first run of 1e-5 s compiles)."""
    import dataclasses
    from pathlib import Path

    from jointdyn.io.modelfile.load import load_model

    model, _ = load_model(Path(__file__).resolve().parents[1] / "examples" / "slider_crank_jfo.toml")
    el = model.items["piston_pin"]
    film = dataclasses.replace(el.film, cells_around=mesh[0], cells_half_length=mesh[1])
    model.items["piston_pin"] = dataclasses.replace(el, film=film)
    system = model.compile()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        simulate(system, SimConfig(1e-5, n_out=2))
        cfg = SimConfig(revolutions * 2.0 * math.pi / OMEGA, n_out=max(int(200 * revolutions), 2) + 1)
        t0 = time.process_time()
        try:
            r, status = simulate(system, cfg), "complete"
        except Exception as err:  # e.g. the force-resolution check [T111]: the results are kept
            r, status = err.results, str(err).split(";")[0]
    return time.process_time() - t0, r, status


def end_to_end(mesh, ref, window: float) -> None:
    cpu_f, stats_f = finite_run()
    cpu_j, r, status = jfo_run(mesh, 1.0)
    print(
        f"finite run, one revolution: {cpu_f:.4f} s CPU, {stats_f['rhs_evaluations']} RHS, "
        f"{stats_f['jacobians']} Jacobians"
    )
    print(
        f"jfo run {mesh[0]}x{mesh[1]}, one revolution: {cpu_j:.2f} s CPU, {r.stats['rhs_evaluations']} RHS, "
        f"{r.stats['jacobians']} Jacobians, {r.stats['accepted_steps']} steps ({status})"
    )
    print(f"ratio jfo/finite: {cpu_j / cpu_f:.0f}x")
    a = r if window == 1.0 else jfo_run(mesh, window)[1]
    _, b, _ = jfo_run(ref, window)
    n = min(len(a.t), len(b.t))
    Fa = np.stack([a.element("piston_pin", k)[:n] for k in ("Fx", "Fy")], axis=1)
    Fb = np.stack([b.element("piston_pin", k)[:n] for k in ("Fx", "Fy")], axis=1)
    err = float(np.max(np.hypot(*(Fa - Fb).T)) / np.max(np.hypot(*Fb.T)))
    print(f"film force error of {mesh[0]}x{mesh[1]} against {ref[0]}x{ref[1]} over {window} rev: {err:.3g}")


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    default = Finite()
    ap.add_argument("--mesh", default=f"{default.cells_around}x{default.cells_half_length}")
    ap.add_argument("--reference", default="72x16")
    ap.add_argument("--steps", type=int, default=200)
    ap.add_argument("--end-to-end", action="store_true")
    ap.add_argument("--window", type=float, default=1.0, help="revolutions of the mesh comparison")
    a = ap.parse_args(argv)
    mesh = tuple(int(x) for x in a.mesh.split("x"))
    ref = tuple(int(x) for x in a.reference.split("x"))
    if a.end_to_end:
        end_to_end(mesh, ref, a.window)
        return
    cpu_f, stats = finite_run()
    per, F = step_cost(mesh, a.steps)
    _, Fr = step_cost(ref, a.steps)
    solves = stats["rhs_evaluations"] + 2 * stats["jacobians"]
    ratio = (cpu_f + solves * per) / cpu_f
    err = float(np.max(np.hypot(*(F - Fr).T) / np.hypot(*Fr.T)))
    print(
        f"finite run, one revolution: {cpu_f * 1e3:.2f} ms CPU, {stats['rhs_evaluations']} RHS, "
        f"{stats['jacobians']} Jacobians"
    )
    print(f"compiled jfo step, mesh {a.mesh}: {per * 1e6:.1f} µs CPU (median of {a.steps})")
    print(f"projected jfo/finite ratio (lower bound, {solves} film solves): {ratio:.1f}×")
    print(f"force error of {a.mesh} against {a.reference} over the path: {err:.3g}")


if __name__ == "__main__":
    main()
