"""Does a stiff solver's crank-moment error follow its tolerance? One revolution, one process.

Usage: ``python -m benchmarks.rodas4_accuracy [--clearances 0.05,0.5]
[--solvers rodas4,rodas4:finite-differences,radau5,ros34pw2] [--rtols 1e-6,...,1e-11]
[--error-scale state|clearance] [--step-ends STRIDE]``

Per clearance (π-film pin of the benchmark slider-crank, 720 samples per revolution) and per
solver and rtol (atol = rtol·1e-3 with state scales, 1e-14 with clearance scales): the max and
median crank-moment error |ΔM|/peak over the samples against a converged run (radau5, rtol
1e-12, state scales; its difference to rodas4 at rtol 1e-11 is printed as the reference's own
error bar), the crank angle of the max, accepted / rejected steps. Runs the accuracy guard
[T111] rejects are kept (their samples are complete). ``--step-ends STRIDE``
also integrates to every STRIDE-th sample time as ``t_end`` (two samples: the error *at a step
end*) and prints its max and median next to the max of the normal run over the same samples
([T218]).
"""

from __future__ import annotations

import argparse
import math
import warnings

import numpy as np

from jointdyn import post
from jointdyn.errors import SimulationError
from jointdyn.models.slider_crank import SPEED, slider_crank
from jointdyn.simulation.simulate import SimConfig, simulate

N_OUT = 721
T_END = 2 * math.pi / SPEED


def _system(c_mm: float):
    kw = {"joint": "alshaer2005"} | ({} if c_mm == 0.5 else {"clearance": c_mm * 1e-3})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return slider_crank(**kw).compile()


def _run(system, spec: str, rtol: float, t_end: float = T_END, n_out: int = N_OUT, scale: str = "state"):
    solver, jac = ([*spec.split(":"), "exact"])[:2]
    atol = rtol * 1e-3 if scale == "state" else 1e-14
    cfg = SimConfig(
        t_end=t_end, n_out=n_out, solver=solver, rtol=rtol, atol=atol, jacobian=jac, error_scale=scale
    )
    try:
        return simulate(system, cfg)
    except SimulationError as err:  # the accuracy guard [T111]: the samples are complete
        if err.results is None or len(err.results.t) != n_out:
            raise
        return err.results


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m benchmarks.rodas4_accuracy")
    ap.add_argument("--clearances", default="0.05,0.5", help="radial clearances [mm]")
    ap.add_argument("--solvers", default="rodas4,rodas4:finite-differences,radau5,ros34pw2")
    ap.add_argument("--rtols", default="1e-6,1e-7,1e-8,1e-9,1e-10,1e-11")
    ap.add_argument("--error-scale", default="state", choices=("state", "clearance"))
    ap.add_argument("--step-ends", type=int, default=0, help="stride of the step-end runs (0: none)")
    ap.add_argument(
        "--write", default=None, help="also write FILE's <!-- generated:rodas4_accuracy --> block"
    )
    a = ap.parse_args(argv)
    rows = []
    for c in (float(x) for x in a.clearances.split(",")):
        system = _system(c)
        ref = _run(system, "radau5", 1e-12)
        Mr = post.driving_moment(ref)
        peak = float(np.abs(Mr).max())
        chk = float(np.abs(post.driving_moment(_run(system, "rodas4", 1e-11)) - Mr).max() / peak)
        print(f"\nc = {c:g} mm: reference radau5 rtol 1e-12; rodas4 rtol 1e-11 differs by {chk:.1e}")
        print(
            "| solver | rtol | max err | median err | crank angle of max [deg] "
            "| same samples, max | step-end max | step-end median | accepted | rejected |"
        )
        print("|---|---|---|---|---|---|---|---|---|---|")
        for spec in a.solvers.split(","):
            for rtol in (float(x) for x in a.rtols.split(",")):
                res = _run(system, spec, rtol, scale=a.error_scale)
                e = np.abs(post.driving_moment(res) - Mr) / peak
                k = int(e.argmax())
                se_max = se_med = sub_max = math.nan
                if a.step_ends > 0:
                    ks = range(a.step_ends, N_OUT, a.step_ends)
                    se = [
                        abs(
                            post.driving_moment(_run(system, spec, rtol, float(ref.t[i]), 2, a.error_scale))[
                                -1
                            ]
                            - Mr[i]
                        )
                        / peak
                        for i in ks
                    ]
                    se_max, se_med = float(np.max(se)), float(np.median(se))
                    sub_max = float(e[list(ks)].max())
                row = {
                    "c_mm": c,
                    "solver": spec,
                    "rtol": rtol,
                    "max": float(e.max()),
                    "median": float(np.median(e)),
                    "angle_deg": float(np.degrees(SPEED * res.t[k])),
                    "subset_max": sub_max,
                    "end_max": se_max,
                    "end_median": se_med,
                    "accepted": res.stats["accepted_steps"],
                    "rejected": res.stats["rejected_steps"],
                }
                rows.append(row)
                print(
                    f"| {spec} | {rtol:.0e} | {row['max']:.2e} | {row['median']:.1e} "
                    f"| {row['angle_deg']:.1f} | "
                    f"{sub_max:.2e} | {se_max:.2e} | {se_med:.1e} | {row['accepted']} | {row['rejected']} |",
                    flush=True,
                )
    body = summary(rows)
    print("\n" + body)
    if a.write:
        from pathlib import Path

        from jointdyn.cli.docs_gen import replace_blocks

        f = Path(a.write)
        f.write_text(
            replace_blocks(f.read_text(encoding="utf-8"), {"rodas4_accuracy": body}), encoding="utf-8"
        )
    return rows


def summary(rows) -> str:
    """One line per rtol: max |ΔM|/peak of every solver, one column group per clearance."""
    cs = list(dict.fromkeys(r["c_mm"] for r in rows))
    solvers = list(dict.fromkeys(r["solver"] for r in rows))
    rtols = sorted({r["rtol"] for r in rows}, reverse=True)
    err = {(r["c_mm"], r["solver"], r["rtol"]): r["max"] for r in rows}
    names = " / ".join(f"`{s}`" for s in solvers)
    out = [
        "| rtol | " + " | ".join(f"c = {c:g} mm: {names}" for c in cs) + " |",
        "|---" * (len(cs) + 1) + "|",
    ]
    for rt in rtols:
        cells = [" / ".join(f"{err.get((c, s, rt), math.nan):.1e}" for s in solvers) for c in cs]
        out.append(f"| {rt:.0e} | " + " | ".join(cells) + " |")
    return "\n".join(out)


if __name__ == "__main__":
    main()
