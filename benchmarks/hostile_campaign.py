"""A hostile-user replay: runs each case as the console script would and classifies the outcome.

    PYTHONPATH=$PWD/src python -m benchmarks.hostile_campaign [--timeout 120]

Outcomes: ``clear`` (refused: exit ≠ 0 and one stderr line), ``fine`` (exit 0 where success is
right), ``unclear`` (refused with several lines), ``traceback`` (a Python traceback or "internal
error"), ``hang`` (no end within the timeout), ``wrong-exit`` (exit 0 where a refusal is right).
Silent wrong numbers cannot be told apart here: the tests named in docs/validation.md check them.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DRY = ROOT / "examples" / "slider_crank_dry.toml"
SWEEP = '[base]\nfile = "{model}"\nrevs = 0.05\n[grid]\n{grid}\n'
FRICTION = '{{ law = "coulomb", coefficient = {mu}, regularization_velocity = 1e-4 }}'


def _files(d: Path) -> dict[str, list[str]]:
    """Write the inputs of the cases into ``d``; returns {case: argv} with 'ok:' for success."""
    slash = d / "slash.toml"
    slash.write_text(DRY.read_text().replace("[elements.piston_pin]", '[elements."pin/x"]'))
    inline = '"elements.piston_pin.friction" = [' + ", ".join(FRICTION.format(mu=m) for m in (0.1, 0.2)) + "]"
    sweeps = {
        "inline": SWEEP.format(model=DRY, grid=inline),
        "slash": SWEEP.format(model=slash, grid='"simulation.rtol" = [1e-7, 1e-8]'),
        "nan": SWEEP.format(model=DRY, grid='"simulation.rtol" = [1e-7, nan]'),
        "repeat": SWEEP.format(model=DRY, grid='"simulation.rtol" = [1e-7, 1e-7]'),
    }
    for k, text in sweeps.items():
        (d / f"sweep_{k}.toml").write_text(text)
    os.mkfifo(d / "fifo.toml")
    sc = ["run", "slider-crank", "--revs", "0.05"]

    def o(name: str) -> list[str]:
        return ["--out", str(d / name)]

    return {
        "sweeps: inline-table grid value": ["ok", "sweep", str(d / "sweep_inline.toml"), *o("s1")],
        "sweeps: element named pin/x": ["sweep", str(d / "sweep_slash.toml"), *o("s2")],
        "sweeps: nan grid value": ["sweep", str(d / "sweep_nan.toml"), *o("s3")],
        "sweeps: repeated grid value": ["sweep", str(d / "sweep_repeat.toml"), *o("s4")],
        "model files: FIFO as model file": ["run", str(d / "fifo.toml"), *o("r1")],
        "model files: first_step = -1": ["run", str(DRY), "--set", "simulation.first_step=-1", *o("r2")],
        "model files: rtol = 1e-300": ["run", str(DRY), "--set", "simulation.rtol=1e-300", *o("r3")],
        "bearing: c > R": ["bearing-table", "--ld", "1", "--load", "100", "--speed", "10", "--radius", "0.01",
                           "--clearance", "0.02", "--viscosity", "0.01"],
        "bearing: 10⁶ eccentricities": ["bearing-table", "--ld", "1", "--eps", "0.1:0.9:1000000"],
        "bearing: asperity height 0.000499": [*sc, "--joint", "alshaer2005", "--contact",
                                              "--asperity-height", "0.000499", *o("r4")],
        "resources: animate --frames 1e8": ["animate", str(d / "none"), "--frames", "100000000"],
        "resources: samples-per-rev 5e6": [*sc, "--samples-per-rev", "5000000", "--revs", "100",
                                           *o("r5")],
        "files: bearing-table --out missing dir": ["bearing-table", "--ld", "1", *o("no/t.csv")],
        "files: bearing-table --out /dev/null": ["ok", "bearing-table", "--ld", "1", "--eps", "0.5",
                                                 "--out", "/dev/null"],
        "chaos: ensemble --rtols 1e-7,1e-7": ["ensemble", "slider-crank", "--rtols", "1e-7,1e-7",
                                             *o("e1")],
        "chaos: Lyapunov of the zero-DOF slider-crank": ["lyapunov", "slider-crank", "--joint", "perfect",
                                                        *o("l1")],
    }  # fmt: skip


def classify(argv: list[str], timeout: float) -> tuple[str, str]:
    want_ok = argv[0] == "ok"
    argv = argv[1:] if want_ok else argv
    cmd = [sys.executable, "-c", "import jointdyn_entry as e; e.main()", *argv]
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired:
        return "hang", f"no end within {timeout:g} s"
    lines = [ln for ln in p.stderr.splitlines() if ln.strip() and not ln.startswith("warning:")]
    if "Traceback" in p.stderr or "internal error" in p.stderr:
        return "traceback", (lines or [""])[-1]
    if p.returncode == 0:
        return ("fine" if want_ok else "wrong-exit"), "exit 0"
    if want_ok:
        return "unclear", (lines or [""])[0]
    return ("clear" if len(lines) == 1 else "unclear"), (lines or [""])[0][:140]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--timeout", type=float, default=120.0)
    args = ap.parse_args(argv)
    counts: Counter = Counter()
    with tempfile.TemporaryDirectory() as tmp:
        for case, cmd in _files(Path(tmp)).items():
            outcome, detail = classify(cmd, args.timeout)
            counts[outcome] += 1
            print(f"{outcome:10s} {case}: {detail}", flush=True)
    print("counts: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())))
    return 0 if set(counts) <= {"clear", "fine"} else 1


if __name__ == "__main__":
    raise SystemExit(main())
