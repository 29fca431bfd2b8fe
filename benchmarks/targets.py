"""The speed and memory targets of issue #27 ("fast from the first run"), measured side by side in
one run, as one table.

Usage: ``python -m benchmarks.targets [--repeat N] [--no-cold] [--write README.md]``;
``python -m benchmarks.targets --main-job [--repeat N] [--no-cold]`` measures the main job alone
(first run, N warm runs and the dry ensemble's share of a warm run; ≈ 2 min) and writes nothing.

Each row is measured by the benchmark module that owns it, in this one invocation (so every ratio
compares numbers taken minutes apart on the same machine). CPU seconds (user + sys of the command
and every process it waited for) are quoted beside wall seconds: they hold on a loaded machine.
"First" is a new user's first run: an empty home directory and no cache settings
(:func:`benchmarks.end_to_end.new_user_env`), so the kernel, film-table and matplotlib caches all
start empty (``--no-cold`` runs it in the current, warm environment instead).

* first runs: ``jointdyn run slider-crank --joint alshaer2005 --revs 1`` and the four-bar model
  file with its crank pin's film made a finite bearing with Reynolds' film end;
* the README's main job ``jointdyn reproduce alshaer2005``: first and warm CPU, peak RSS;
* ``jointdyn animate DIR --frames 120`` of the dry 4-revolution run;
* the floors kept from issue #15: perfect and dry against Exudyn (``benchmarks.peers``, needs the
  ``[peers]`` extra), π-film defaults against scipy's Radau (``benchmarks.end_to_end``).

A target is "met" only when the measured value satisfies it; nothing is rounded in its favour.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import tempfile
from pathlib import Path

from benchmarks import end_to_end

ROOT = Path(__file__).resolve().parents[1]
JD = [sys.executable, "-m", "jointdyn"]


def _finite_four_bar(d: str) -> str:
    """The shipped four-bar with its crank pin's film as a finite bearing with Reynolds' film end."""
    text = (ROOT / "examples" / "four_bar_lubricated.toml").read_text(encoding="utf-8")
    text = text.replace('film = "alshaer2005"', 'film = { law = "finite", cavitation = "reynolds" }')
    path = os.path.join(d, "four_bar_finite.toml")
    Path(path).write_text(text, encoding="utf-8")
    return path


def cli_rows(cold: bool) -> dict:
    """(wall [s], peak RSS [MB], CPU [s]) of the first and the warm runs of the commands above."""
    out: dict = {}
    with tempfile.TemporaryDirectory() as home, tempfile.TemporaryDirectory() as d:
        env = end_to_end.new_user_env(home) if cold else dict(os.environ)
        run = [*JD, "run", "slider-crank", "--joint", "alshaer2005", "--revs", "1"]
        for label in ("first", "warm"):
            out[f"alshaer2005_{label}"] = end_to_end.measure([*run, "--out", os.path.join(d, label)], env)
        model = _finite_four_bar(d)
        for label in ("first", "warm"):
            cmd = [*JD, "run", model, "--out", os.path.join(d, "fb" + label)]
            out[f"finite_file_{label}"] = end_to_end.measure(cmd, env)
    with tempfile.TemporaryDirectory() as home, tempfile.TemporaryDirectory() as d:
        env = end_to_end.new_user_env(home) if cold else dict(os.environ)
        for label in ("first", "warm"):
            cmd = [*JD, "reproduce", "alshaer2005", "--out", os.path.join(d, label)]
            out[f"reproduce_{label}"] = end_to_end.measure(cmd, env)
        dry = os.path.join(d, "dry")
        end_to_end.measure([*JD, "run", "slider-crank", "--joint", "dry", "--revs", "4", "--out", dry], env)
        cmd = [*JD, "animate", dry, "--out", os.path.join(d, "a.gif"), "--frames", "120"]
        out["animate"] = end_to_end.measure(cmd, env)
    return out


_ENSEMBLE = "from jointdyn.studies.reproduce_ensemble import dry_ensemble; dry_ensemble()"


def main_job(cold: bool, repeat: int) -> dict:
    """(wall [s], peak RSS [MB], CPU [s]) of ``jointdyn reproduce alshaer2005``: the first run
    (``first``, only if ``cold``), ``repeat`` warm runs (``warm``: all of them) and, in a fresh
    warm process, the dry ensemble the job runs (``ensemble``: its workers load the kernels
    from the cache themselves, so this slightly overstates its share of the job)."""
    out: dict = {"warm": []}
    with tempfile.TemporaryDirectory() as home, tempfile.TemporaryDirectory() as d:
        env = end_to_end.new_user_env(home) if cold else dict(os.environ)
        cmd = [*JD, "reproduce", "alshaer2005", "--overwrite", "--out", os.path.join(d, "r")]
        first = end_to_end.measure(cmd, env)
        if cold:
            out["first"] = first
        out["warm"] = [end_to_end.measure(cmd, env) for _ in range(repeat)]
        out["ensemble"] = end_to_end.measure([sys.executable, "-c", _ENSEMBLE], env)
    return out


def _main_job_text(m: dict) -> str:
    lines = [f"first run: {_cpu(m['first'])}, peak RSS {m['first'][1]:.0f} MB"] if "first" in m else []
    lines += [f"warm run {k + 1}: {_cpu(w)}, peak RSS {w[1]:.0f} MB" for k, w in enumerate(m["warm"])]
    best = min(w[2] for w in m["warm"])
    e = m["ensemble"]
    share = f"{100 * e[2] / best:.0f} % of the best warm CPU"
    lines.append(f"the dry ensemble alone (fresh warm process): {_cpu(e)}, {share}")
    return "\n".join(lines)


def _row(target: str, goal: str, measured: str, ok: bool | None) -> dict:
    return {
        "target": target,
        "goal": goal,
        "measured": measured,
        "met": "–" if ok is None else "✓" if ok else "✗",
    }


def _x(v: float) -> str:
    return f"{v:.1f}×" if math.isfinite(v) else "not reached"


def _versus(ours: dict, peer: dict) -> str:
    """'R× (ours vs peer ms; error e vs e, jointdyn SETTING)' of two peers rows."""
    return (
        f"{_x(peer['wall_s'] / ours['wall_s'])} "
        f"({ours['wall_s'] * 1e3:.1f} vs {peer['wall_s'] * 1e3:.0f} ms; "
        f"error {ours['error']:.1e} vs {peer['error']:.1e}, jointdyn {ours['setting']})"
    )


def _cpu(m: tuple) -> str:
    """'C s CPU (W s wall)' of a :func:`benchmarks.end_to_end.measure` triple."""
    return f"{m[2]:.1f} s CPU ({m[0]:.1f} s wall)"


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m benchmarks.targets")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--no-cold", action="store_true", help="first runs in the current (warm) environment")
    ap.add_argument(
        "--write", type=Path, default=None, help="also write FILE's <!-- generated:targets --> block"
    )
    ap.add_argument("--main-job", action="store_true", help="only the main job (first, warm, its ensemble)")
    a = ap.parse_args(argv)
    load_start = end_to_end.machine_load()
    if a.main_job:
        m = main_job(cold=not a.no_cold, repeat=a.repeat)
        print(
            _main_job_text(m)
            + f"\nMachine: {load_start} at the start, {end_to_end.machine_load()} at the end."
        )
        return m
    first = "first run" if not a.no_cold else "run (warm caches: --no-cold)"
    cli = cli_rows(cold=not a.no_cold)
    rows = [
        _row(
            f"{first}, `jointdyn run slider-crank --joint alshaer2005 --revs 1`",
            "≤ 15 s CPU",
            f"{_cpu(cli['alshaer2005_first'])}; warm {_cpu(cli['alshaer2005_warm'])}",
            cli["alshaer2005_first"][2] <= 15,
        ),
        _row(
            f"{first} of a four-bar model file with a finite (Reynolds) bearing,"
            " after the row above (same home)",
            "≤ 20 s CPU",
            f"{_cpu(cli['finite_file_first'])}; warm {_cpu(cli['finite_file_warm'])}",
            cli["finite_file_first"][2] <= 20,
        ),
        _row(
            f"README main job `jointdyn reproduce alshaer2005`, {first}",
            "≤ 45 s CPU",
            _cpu(cli["reproduce_first"]),
            cli["reproduce_first"][2] <= 45,
        ),
        _row(
            "README main job, warm",
            "≤ 6 s CPU",
            _cpu(cli["reproduce_warm"]),
            cli["reproduce_warm"][2] <= 6,
        ),
        _row(
            "README main job, peak RSS (first / warm)",
            "≤ 400 MB",
            f"{cli['reproduce_first'][1]:.0f} / {cli['reproduce_warm'][1]:.0f} MB",
            max(cli["reproduce_first"][1], cli["reproduce_warm"][1]) <= 400,
        ),
        _row(
            "`jointdyn animate DIR --frames 120` (dry, 4 revolutions)",
            "≤ 20 s",
            f"{cli['animate'][0]:.1f} s wall, {cli['animate'][2]:.1f} s CPU, {cli['animate'][1]:.0f} MB",
            cli["animate"][0] <= 20,
        ),
    ]
    try:
        from benchmarks import peers

        prow = peers.perfect_rows(a.repeat)
        drow, _ = peers.dry_rows(a.repeat)
    except ImportError:  # no Exudyn: the [peers] extra
        prow = drow = None
    if prow is not None:
        peer, best, _ = peers._ratio(prow, "h = 1e-05")
        rows.append(
            _row(
                "floor: perfect, 4 rev, end to end vs Exudyn h = 1e-5, at lower moment error",
                "≥ 12×",
                _versus(best, peer),
                peer["wall_s"] / best["wall_s"] >= 12,
            )
        )
    if drow is not None:
        peer, best, _ = peers._ratio(drow, "h = 1e-06")
        rows.append(
            _row(
                "floor: dry, 4 rev, end to end vs Exudyn h = 1e-6, at matched first-impact penetration",
                "≥ 40×",
                "no jointdyn tolerance as accurate" if best is None else _versus(best, peer),
                best is not None and peer["wall_s"] / best["wall_s"] >= 40,
            )
        )
    d = end_to_end.simulate_row("alshaer2005", 2 * a.repeat + 1)
    s = end_to_end.simulate_row("alshaer2005 scipy-radau 1e-7", a.repeat)
    ratio = s["simulate_s"] / d["simulate_s"]
    rows.append(
        _row(
            "floor: π-film defaults vs scipy-Radau rtol 1e-7 (compiled RHS), end to end, error ≤ 1e-4",
            "≥ 15×",
            f"{_x(ratio)} ({d['simulate_s'] * 1e3:.0f} vs {s['simulate_s'] * 1e3:.0f} ms;"
            f" error {d['error']:.1e} vs {s['error']:.1e})",
            ratio >= 15 and d["error"] <= 1e-4,
        )
    )
    text = end_to_end._table(rows, ["target", "goal", "measured", "met"])
    text += f"\n\nMachine: {load_start} at the start, {end_to_end.machine_load()} at the end."
    print("\n" + text)
    if a.write is not None:
        from jointdyn.cli.docs_gen import replace_blocks

        doc = a.write.read_text(encoding="utf-8")
        a.write.write_text(replace_blocks(doc, {"targets": text}), encoding="utf-8")
    return rows


if __name__ == "__main__":
    main()
