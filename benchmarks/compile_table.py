"""Every numba compilation of one first run (empty cache): function, signature, compile time.

    python -m benchmarks.compile_table                       # run slider-crank --joint alshaer2005 --revs 1
    python -m benchmarks.compile_table --top 30 -- run slider-crank --joint dry --revs 1
    python -m benchmarks.compile_table --before OLD/src      # both trees, side by side
    python -m benchmarks.compile_table --before OLD/src --together   # both at once (shared load)
    python -m benchmarks.compile_table --cli "reproduce alshaer2005"   # any CLI command (--out D added)

Runs the CLI command in a fresh process with a new, empty cache (``NUMBA_CACHE_DIR``,
``XDG_CACHE_HOME``) and records numba's ``numba:compile`` events (``benchmarks.coldstart``'s child:
one event per compiled signature, cache loads send none). Prints per tree the CPU time (user +
sys), the number of compilations, the summed compile time and the peak RSS; for this tree the
top compilations by *self* time (own typing, lowering and LLVM work, nested compiles of callees
excluded) with their argument types, and every function compiled with more than one signature,
showing only the argument positions where the signatures differ (int32 against int64,
readonly against writable arrays, literal against plain, …).
"""

from __future__ import annotations

import argparse
import shlex
import tempfile
from collections import defaultdict
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from benchmarks.coldstart import SRC, _run


def _short(s: str, n: int) -> str:
    return s if len(s) <= n else s[: n - 1] + "…"


def _split_sig(sig: str) -> list[str]:
    """Top-level comma split of a signature string (nested brackets kept whole)."""
    out, depth, cur = [], 0, []
    for ch in sig:
        if ch in "([{<":
            depth += 1
        elif ch in ")]}>":
            depth -= 1
        if ch == "," and depth == 0:
            out.append("".join(cur).strip())
            cur = []
        else:
            cur.append(ch)
    if cur:
        out.append("".join(cur).strip())
    return out


def _measure(src: Path, argv: list[str]) -> dict:
    with tempfile.TemporaryDirectory() as cache, tempfile.TemporaryDirectory() as out:
        return _run(src, cache, [*argv, "--out", out])


def _tables(r: dict, top: int) -> None:
    comp = r["compiles"]
    print(f"\ntop {top} compilations by self time [s] (top: a compile started from Python, callees included)")
    print(f"{'self':>6} {'top':>6} {'dep':>3}  function  (argument types)")
    for name, inc, exc, depth, sig in sorted(comp, key=lambda c: -c[2])[:top]:
        name = name.replace("jointdyn.", "")
        top_s = f"{inc:6.2f}" if depth == 0 else "     -"
        print(f"{exc:6.2f} {top_s} {depth:3d}  {name}  ({_short(sig, 110)})")
    sigs: dict[str, list[tuple[str, float]]] = defaultdict(list)
    for name, _inc, exc, _depth, sig in comp:
        sigs[name].append((sig, exc))
    dup = {k: v for k, v in sigs.items() if len(v) > 1}
    n_extra = sum(len(v) - 1 for v in dup.values())
    t_extra = sum(sum(sorted(e for _, e in v)[:-1]) for v in dup.values())
    print(
        f"\nfunctions compiled with more than one signature: {len(dup)} "
        f"({n_extra} extra compilations, {t_extra:.2f} s self time beyond the dearest of each)"
    )
    for name, v in sorted(dup.items(), key=lambda kv: -sum(e for _, e in kv[1])):
        parts = [_split_sig(s) for s, _ in v]
        width = max(len(p) for p in parts)
        diff = [i for i in range(width) if len({p[i] if i < len(p) else "" for p in parts}) > 1]
        print(f"{sum(e for _, e in v):6.2f} s {len(v):3d}x  {name.replace('jointdyn.', '')}")
        for (_, e), p in zip(v, parts, strict=True):
            shown = "; ".join(f"#{i}: {_short(p[i], 60)}" for i in diff if i < len(p)) or "(same types)"
            print(f"{'':14}{e:6.2f} s  {_short(shown, 150)}")


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(prog="python -m benchmarks.compile_table")
    ap.add_argument("--before", default=None, help="another src/ tree to measure first")
    ap.add_argument("--top", type=int, default=30)
    ap.add_argument(
        "--together",
        action="store_true",
        help="run both trees at the same time (a loaded machine then loads both alike) [T357]",
    )
    ap.add_argument("--cli", default=None, help="the CLI command as one string (default: the argv after --)")
    ap.add_argument("rest", nargs="*")
    a = ap.parse_args(argv)
    cli = shlex.split(a.cli) if a.cli else (a.rest or "run slider-crank --joint alshaer2005 --revs 1".split())
    trees = ([("before", Path(a.before))] if a.before else []) + [("this", SRC)]
    if a.together:
        with ThreadPoolExecutor(len(trees)) as pool:
            futures = {label: pool.submit(_measure, src, cli) for label, src in trees}
            res = {label: f.result() for label, f in futures.items()}
    else:
        res = {label: _measure(src, cli) for label, src in trees}
    print(f"jointdyn {' '.join(cli)} --out D   (fresh process, empty cache)")
    head = f"{'tree':<7} {'wall [s]':>8} {'CPU [s]':>8} {'compiles':>8} {'compile self [s]':>16}"
    print(f"{head} {'peak RSS':>9}")
    for label, r in res.items():
        total = sum(c[2] for c in r["compiles"])
        print(
            f"{label:<7} {r['process']:8.1f} {r['cpu']:8.1f} {len(r['compiles']):8d} {total:16.1f} "
            f"{r['peak_rss_mb']:7.0f}MB"
        )
    _tables(res["this"], a.top)


if __name__ == "__main__":
    main()
