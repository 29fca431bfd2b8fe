"""Compile the kernels of models ahead of their first run, in parallel processes, into the cache
[T226].

A model's first run compiles the numerical kernels it needs (its element kinds, the method and
the Jacobian mode) and numba caches them on disk ([T170], [T225]); this runs each model for a
sliver of time, so that the next real run, and every worker process of a sweep or a test
session, loads instead of compiling. Models share the compiled loop of their method (the
element kernels of each combination of kinds are called by address, [T379]), so the warm-up
runs one target per loop first and the others after, when they only compile their element
kernels (every shipped joint from empty caches: 153.9 → 112.5 s CPU, 78.7 → 73.0 s wall on 2
cores). Warm-up is worth it when several processes would
otherwise each compile the same kernels (a sweep, the test suite), or for the wall time of a
first run on an idle multi-core machine.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path

#: the default shipped model's variants, as ``jointdyn run slider-crank --joint`` runs them (the README's
#: main job runs all but "short")
SHIPPED = ("perfect", "dry", "ott", "alshaer2005", "finite", "short")


def warm_one(target: str) -> dict:
    """Run ``target`` (a shipped joint name or a model-file path) for a sliver of time; returns
    ``{"target", "seconds" [s], "compilations"}`` (numba compilations it triggered)."""
    from numba.core import event

    n = [0]

    class _Count(event.Listener):
        def on_start(self, ev):
            n[0] += 1

        def on_end(self, ev):
            pass

    t0 = time.perf_counter()
    with event.install_listener("numba:compile", _Count()):
        if target in SHIPPED:
            from jointdyn.models.catalog import DEFAULT
            from jointdyn.studies.runs import run_shipped

            run_shipped(DEFAULT, target, revs=0.02, samples_per_rev=200)
        else:
            from jointdyn.io.modelfile import load_model
            from jointdyn.simulation.simulate import simulate

            model, cfg = load_model(Path(target))
            t_end = min(cfg.t_end, 1e-3)
            model, cfg = load_model(Path(target), [f"simulation.t_end={t_end!r}", "simulation.n_out=5"])
            simulate(model.compile(), cfg)
    return {"target": target, "seconds": time.perf_counter() - t0, "compilations": n[0]}


def warmup(
    targets: list[str] | None = None, processes: int | None = None, record: Callable | None = None
) -> list[dict]:
    """Warm the cache for ``targets`` (default: every shipped joint) on ``processes`` processes
    (None: all cores); ``record(result)`` is called as each finishes. Model files are checked
    before any process starts."""
    import os

    from jointdyn.io.pool import run_local

    targets = list(targets) if targets else list(SHIPPED)
    for t in targets:
        if t not in SHIPPED and not Path(t).is_file():
            raise ValueError(f"warmup {t!r}: neither a shipped joint ({', '.join(SHIPPED)}) nor a model file")
    results: list[dict] = []

    def done(key, result):
        results.append(result)
        if record is not None:
            record(result)

    # one target per compiled loop first, the others after: every model shares the loop of its
    # method (kernels called by address [T379]), so two processes would compile the same loop
    firsts: dict = {}
    for t in targets:
        firsts.setdefault(chain_of(t), t)
    for wave in (list(firsts.values()), [t for t in targets if t not in firsts.values()]):
        if wave:
            run_local(
                warm_one, [(t, (t,)) for t in wave], min(processes or os.cpu_count() or 1, len(wave)), done
            )
    return results


def chain_of(target: str) -> tuple:
    """(solver, Jacobian kind) a target's run uses: the compiled loop it shares with others."""
    from jointdyn.simulation.simulate import resolve_solver
    from jointdyn.studies.runs import model_system

    system, cfg = (
        model_system("slider-crank", {"joint": target}) if target in SHIPPED else model_system(target)
    )
    return resolve_solver(system, cfg.solver), cfg.jacobian
