"""What the user waits for: ``simulate()`` and the CLI end to end, side by side in one run.

Usage: ``python -m benchmarks.end_to_end [--quick] [--no-cli] [--cases perfect,dry,...]``
(``--cases`` also takes the rows of ``CLEARANCE_CASES``: ``SimConfig.error_scale = "clearance"``)

Per case (the benchmark slider-crank, 4 crank revolutions, the README's sampling of 720 samples
per revolution = 2881 samples, the library defaults unless a solver is named):

* ``simulate`` — wall time of the ``simulate(system, config)`` call, median of N warm runs
  (kernels compiled and loaded), split into the integrator's own time (``Results.wall_time``) and
  the rest (output samples: accelerations, multipliers, element outputs, drift);
* ``save`` — writing ``results.nc`` (netCDF) and the CSV time series of the run;
* ``error`` — max |ΔM|/peak of the crank moment against a converged run of the same model
  (rtol 1e-11, same sampling);
* ``cli warm`` / ``cli cold`` — ``jointdyn run slider-crank --joint J --revs 4`` in a fresh
  process (warm: JIT cache filled; cold: empty JIT and table caches), with each run's own peak RSS.

Every ratio in the README's speed section is computed from rows of one invocation of this
command, on one machine, in one process (``simulate`` rows) or back to back (CLI rows).
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

from jointdyn import post
from jointdyn.models.slider_crank import SPEED, slider_crank
from jointdyn.simulation.simulate import SimConfig, simulate

REVS = 4
N_OUT = REVS * 720 + 1
T_END = REVS * 2 * math.pi / SPEED
ROOT = Path(__file__).resolve().parents[1]

# case: (slider_crank kwargs, solver or None for the default, rtol or None for the default)
CASES = {
    "perfect": ({"joint": "perfect"}, None, None),
    "dry": ({"joint": "dry"}, None, None),
    "alshaer2005": ({"joint": "alshaer2005"}, None, None),
    "alshaer2005 scipy-radau 1e-7": ({"joint": "alshaer2005"}, "scipy-radau", 1e-7),
    "alshaer2005 c=0.05mm": ({"joint": "alshaer2005", "clearance": 0.05e-3}, None, None),
    "finite": ({"joint": "finite"}, None, None),
}
# not in the default list: SimConfig.error_scale = "clearance" at rtol 3e-6 of the clearance
# (atol 1e-10, the library default) [T186]
CLEARANCE_CASES = {
    "alshaer2005 clearance 3e-6": ({"joint": "alshaer2005"}, None, 3e-6),
    "alshaer2005 clearance 3e-5": ({"joint": "alshaer2005"}, None, 3e-5),
    "alshaer2005 c=0.05mm clearance 3e-6": ({"joint": "alshaer2005", "clearance": 0.05e-3}, None, 3e-6),
}
CLI_JOINTS = ("perfect", "dry", "alshaer2005")


def _config(solver, rtol, error_scale=None) -> SimConfig:
    """The library defaults except the named solver, rtol (atol = rtol·1e-3, or 1e-10 with
    clearance scales) and error scale."""
    kw = {} if solver is None else {"solver": solver}
    if rtol is not None:
        kw |= {"rtol": rtol, "atol": rtol * 1e-3 if error_scale is None else 1e-10}
    if error_scale is not None:
        kw |= {"error_scale": error_scale}
    return SimConfig(t_end=T_END, n_out=N_OUT, **kw)


def _save(res, d: Path) -> float:
    t0 = time.perf_counter()
    res.save(d / "results.nc")
    M = post.driving_moment(res)
    np.savetxt(d / "timeseries.csv", np.column_stack([res.t, M]), delimiter=",", header="t,crank_moment")
    return time.perf_counter() - t0


def simulate_row(name, repeat):
    kw, solver, rtol = CASES[name] if name in CASES else CLEARANCE_CASES[name]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        system = slider_crank(**kw).compile()
    cfg = _config(solver, rtol, None if name in CASES else "clearance")
    ref = simulate(system, SimConfig(t_end=T_END, n_out=N_OUT, solver=cfg.solver, rtol=1e-11, atol=1e-14))
    simulate(system, cfg)  # JIT warm-up
    totals, integ, res = [], [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        res = simulate(system, cfg)
        totals.append(time.perf_counter() - t0)
        integ.append(res.wall_time)
    with tempfile.TemporaryDirectory() as d:
        save = _save(res, Path(d))
    M, Mr = post.driving_moment(res), post.driving_moment(ref)
    return {
        "case": name,
        "solver": res.config["solver"],
        "rtol": cfg.rtol,
        "simulate_s": statistics.median(totals),
        "integrate_s": statistics.median(integ),
        "outputs_s": statistics.median(totals) - statistics.median(integ),
        "save_s": save,
        "rhs": res.stats["rhs_evaluations"],
        "error": float(np.abs(M - Mr).max() / np.abs(Mr).max()),
    }


# runs one command in a child and prints its wall time [s], peak RSS [kB] and CPU time (user +
# sys) [s]: a fresh parent per measurement, so RUSAGE_CHILDREN holds exactly that command (not
# the cold run before it) and every process the command started and waited for
_MEASURE = (
    "import resource, subprocess, sys, time; t0 = time.perf_counter(); "
    "subprocess.run(sys.argv[1:], check=True, capture_output=True); "
    "r = resource.getrusage(resource.RUSAGE_CHILDREN); "
    "print(time.perf_counter() - t0, r.ru_maxrss, r.ru_utime + r.ru_stime)"
)


def measure(cmd: list[str], env: dict) -> tuple[float, float, float]:
    """(wall time [s], peak RSS [MB], CPU time user + sys [s]) of ``cmd`` in a fresh process."""
    r = subprocess.run(
        [sys.executable, "-c", _MEASURE, *cmd], check=True, env=env, cwd=ROOT, capture_output=True, text=True
    )
    wall, rss, cpu = r.stdout.split()
    return float(wall), float(rss) / 1024, float(cpu)


def new_user_env(home: str) -> dict:
    """The environment of a new user: an empty ``home`` and no cache settings (jointdyn's kernel
    and table caches, matplotlib's font cache, all start empty), as the README's first command."""
    drop = ("XDG_CACHE_HOME", "NUMBA_CACHE_DIR", "NUMBA_OPT", "MPLCONFIGDIR")
    return {**{k: v for k, v in os.environ.items() if k not in drop}, "HOME": home}


def machine_load() -> str:
    """The 1-minute load average and the core count, to print beside timings (a shared machine)."""
    return f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores"


def cli_row(joint):
    """Wall and CPU times [s] and peak RSS [MB] of the CLI run, each in a fresh process: cold as a
    new user starts (empty home, :func:`new_user_env`), then warm twice in that home."""
    exe = [sys.executable, "-m", "jointdyn", "run", "slider-crank", "--joint", joint, "--revs", str(REVS)]
    out = {}
    with tempfile.TemporaryDirectory() as home:
        env = new_user_env(home)
        for label in ("cold", "warm", "warm2"):
            with tempfile.TemporaryDirectory() as d:
                out[label] = measure([*exe, "--out", os.path.join(d, "o")], env)
    warm = min(out["warm"], out["warm2"])
    return {
        "case": f"cli {joint}",
        "cli_warm_s": warm[0],
        "cli_warm_cpu_s": min(out["warm"][2], out["warm2"][2]),
        "cli_cold_s": out["cold"][0],
        "cli_cold_cpu_s": out["cold"][2],
        "cold/warm": out["cold"][0] / warm[0],
        "rss_cold_MB": out["cold"][1],
        "rss_warm_MB": max(out["warm"][1], out["warm2"][1]),
    }


def _table(rows, cols):
    lines = ["| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    for r in rows:
        cells = [f"{r[c]:.4g}" if isinstance(r.get(c), float) else str(r.get(c, "–")) for c in cols]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m benchmarks.end_to_end")
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--quick", action="store_true", help="1 repeat, perfect and alshaer2005 only, no CLI")
    ap.add_argument("--no-cli", action="store_true")
    ap.add_argument(
        "--write",
        type=Path,
        default=None,
        help="also write the result into FILE's <!-- generated:speed --> block",
    )
    a = ap.parse_args(argv)
    load_start = machine_load()
    names = ["perfect", "alshaer2005"] if a.quick else a.cases.split(",")
    rows = [simulate_row(n, 1 if a.quick else a.repeat) for n in names]
    cols = ["case", "solver", "rtol", "simulate_s", "integrate_s", "outputs_s", "save_s", "rhs", "error"]
    lines = [_table(rows, cols), ""]
    by = {r["case"]: r for r in rows}
    if "alshaer2005" in by and "alshaer2005 scipy-radau 1e-7" in by:
        d, s = by["alshaer2005"], by["alshaer2005 scipy-radau 1e-7"]
        lines.append(
            f"π-film, library defaults vs the scipy-Radau reference path (compiled RHS, rtol 1e-7), "
            f"same process: the defaults are {s['simulate_s'] / d['simulate_s']:.1f}× faster end to end "
            f"at a max crank-moment error of {d['error']:.2g} vs {s['error']:.2g} of the peak."
        )
    if "perfect" in by:
        p = by["perfect"]
        lines.append(
            f"Perfect joint: output samples cost {p['outputs_s'] / N_OUT * 1e6:.2f} µs each "
            f"({p['outputs_s'] / p['simulate_s']:.0%} of `simulate`); results.nc + CSV {p['save_s']:.3f} s."
        )
    if not (a.quick or a.no_cli):
        cli = [cli_row(j) for j in CLI_JOINTS]
        cols = [
            "case",
            "cli_warm_s",
            "cli_warm_cpu_s",
            "cli_cold_s",
            "cli_cold_cpu_s",
            "cold/warm",
            "rss_cold_MB",
            "rss_warm_MB",
        ]
        lines += ["", _table(cli, cols)]
    lines += [
        "",
        f"Machine: {load_start} at the start, {machine_load()} at the end (CPU seconds hold under load).",
    ]
    text = "\n".join(lines)
    print(text)
    if a.write is not None:
        from jointdyn.cli.docs_gen import replace_blocks

        doc = a.write.read_text(encoding="utf-8")
        a.write.write_text(replace_blocks(doc, {"speed": text}), encoding="utf-8")
    return rows


if __name__ == "__main__":
    main()
