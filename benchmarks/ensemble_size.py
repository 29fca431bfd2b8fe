"""What the reproduction's dry ensemble resolves, measured against a large one [T361].

    python -m benchmarks.ensemble_size                      # 16 replicas × 105 revolutions × 3 rtols
    python -m benchmarks.ensemble_size --replicas 8 --revs 60

Runs the dry slider-crank at rtol 1e-6, 1e-7 and 1e-8 (``replicas`` runs each, replica r > 0 from
the seeded 1e-9 velocity perturbation of :mod:`jointdyn.studies.ensemble`, all revolutions kept)
and prints: the CPU per revolution at each tolerance; the first revolution at which each replica
differs by > 1 % (peak moment) from replica 0; the lag-1 autocorrelation of the per-revolution
quantities; the median of each revolution index over all runs against the stationary pool
(revolutions ≥ 10) in standard errors (the transient); each tolerance's pooled distribution
against the 1e-7 + 1e-8 pool (shift as a fraction of the 5–95 % width); and, for the ensemble of
:data:`jointdyn.studies.reproduce_ensemble.ENSEMBLE`, the spread of the pooled median over disjoint
ensembles of that size cut from the large sample beside the mean bootstrap standard error such an
ensemble reports [T121]. CPU seconds; a loaded machine inflates them.
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

from jointdyn.studies.ensemble import _run_case, median_se
from jointdyn.studies.reproduce_ensemble import ENSEMBLE

Q = ("peak_moment", "rms_moment", "impacts", "max_contact_force", "max_penetration")
RTOLS = (1e-6, 1e-7, 1e-8)


def sample(replicas: int, revs: int) -> tuple[dict, dict]:
    """{rtol: {replica: {quantity: per-revolution array}}} and {rtol: CPU [s] per revolution}."""
    from jointdyn.multibody.system import shared_kinds
    from jointdyn.studies.runs import model_system

    data: dict = {}
    cpu: dict = {}
    joints = ("alshaer2005", "dry", "finite", "ott", "perfect")  # the kernel set of reproduce [T341]
    with shared_kinds(*(model_system("slider-crank", {"joint": j})[0] for j in joints)):
        _run_case("slider-crank", {"joint": "dry"}, 1, 0, 1e-7, 0, 720)  # loads the kernels
        for r in RTOLS:
            t0 = time.process_time()
            data[r] = {
                s: {
                    k: np.asarray(v)
                    for k, v in _run_case("slider-crank", {"joint": "dry"}, revs, 0, r, s, 720).items()
                }
                for s in range(replicas)
            }
            cpu[r] = (time.process_time() - t0) / (replicas * revs)
    return data, cpu


def _pool(data, rtols, k, start):
    return np.concatenate([run[k][start:] for r in rtols for run in data[r].values()])


def disjoint(data, rtols, replicas: int, recorded: int, start: int) -> dict:
    """{quantity: (sd of the pooled median over disjoint ensembles, mean bootstrap s.e., count)}
    of ensembles of ``replicas`` windows of ``recorded`` revolutions per tolerance."""
    n_runs, n_revs = len(data[rtols[0]]), len(next(iter(data[rtols[0]].values()))[Q[0]])
    wins = [(s, start + j * recorded) for s in range(n_runs) for j in range((n_revs - start) // recorded)]
    out = {}
    for k in Q:
        meds, ses = [], []
        for i in range(len(wins) // replicas):
            x = np.concatenate(
                [
                    data[r][s][k][a : a + recorded]
                    for r in rtols
                    for s, a in wins[i * replicas : (i + 1) * replicas]
                ]
            )
            meds.append(float(np.median(x)))
            ses.append(median_se(x))
        out[k] = (float(np.std(meds, ddof=1)), float(np.mean(ses)), float(np.median(meds)), len(meds))
    return out


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--replicas", type=int, default=16)
    ap.add_argument("--revs", type=int, default=105)
    a = ap.parse_args(argv)
    data, cpu = sample(a.replicas, a.revs)
    for r in RTOLS:
        print(f"rtol {r:g}: {1e3 * cpu[r]:.1f} ms CPU per revolution")
    for r in RTOLS:
        d0 = data[r][0]["peak_moment"]
        first = [
            int(np.argmax(np.abs(run["peak_moment"] - d0) > 0.01 * np.abs(d0)))
            for s, run in data[r].items()
            if s
        ]
        print(
            f"rtol {r:g}: first revolution with a replica's peak moment > 1 % off replica 0: {sorted(first)}"
        )
    print("lag-1 autocorrelation within runs (revolutions ≥ 5), mean over runs:")
    for k in Q:
        ac = [
            np.corrcoef(x[:-1], x[1:])[0, 1]
            for r in RTOLS
            for run in data[r].values()
            if (x := run[k][5:]).std() > 0
        ]
        print(f"  {k:18s} {np.mean(ac):+.3f}")
    print(
        "transient: median of revolution i over all runs minus that of revolutions ≥ 10, in standard errors:"
    )
    for k in Q:
        ref = _pool(data, RTOLS, k, 10)
        m, se = float(np.median(ref)), median_se(ref)
        z = []
        for i in range(6):
            x = np.array([run[k][i] for r in RTOLS for run in data[r].values()])
            z.append(f"{(np.median(x) - m) / math.hypot(se, median_se(x)):+.1f}")
        print(f"  {k:18s} i = 0…5: {' '.join(z)}")
    print(
        "tolerance (revolutions ≥ 5): median [5 %, 95 %] ± s.e., shift from the 1e-7 + 1e-8 pool / its width:"
    )
    for k in Q:
        ref = _pool(data, (1e-7, 1e-8), k, 5)
        width = float(np.subtract(*np.quantile(ref, [0.95, 0.05])))
        cells = []
        for r in RTOLS:
            x = _pool(data, (r,), k, 5)
            p5, med, p95 = np.quantile(x, [0.05, 0.5, 0.95])
            shift = 100 * (med - np.median(ref)) / width
            cells.append(f"{r:g}: {med:.4g} [{p5:.4g}, {p95:.4g}] ±{median_se(x):.2g} ({shift:+.0f} %)")
        print(f"  {k}: " + "; ".join(cells))
    e = ENSEMBLE
    rt, rec = tuple(e["rtols"]), e["revs"] - e["transient_revs"]
    print(
        f"the reproduce ensemble ({len(rt)} rtols × {e['replicas']} replicas × {rec} recorded revolutions): "
        "sd of the median over disjoint ensembles vs the mean bootstrap s.e. they report"
    )
    for k, (sd, se, med, n) in disjoint(data, rt, e["replicas"], rec, e["transient_revs"]).items():
        print(
            f"  {k:18s} {sd:.3g} ({100 * sd / med:.1f} %) vs {se:.3g} ({100 * se / med:.1f} %), {n} ensembles"
        )


if __name__ == "__main__":
    main()
