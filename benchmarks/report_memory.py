"""Memory of ``jointdyn reproduce alshaer2005`` phase by phase, in one process (Linux).

Usage: ``python -m benchmarks.report_memory [--revs 4]``

Prints the resident set (VmRSS) and its peak so far (VmHWM) [MB] after the imports, after all
simulations of the reproduction, after the matplotlib figures (drawn in a process of their own,
[T220]: its peak is printed too) and after ``interactive.html`` (plotly.js data written
directly, [T173]); run it with a warm JIT cache, else the simulations' row includes LLVM's
compile-time memory. The dry ensemble (worker processes) is not run.
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path


def _status() -> tuple[float, float]:
    """(VmRSS, VmHWM) of this process [MB]."""
    got = {}
    for line in Path("/proc/self/status").read_text().splitlines():
        key, _, val = line.partition(":")
        if key in ("VmRSS", "VmHWM"):
            got[key] = int(val.split()[0]) / 1024
    return got["VmRSS"], got["VmHWM"]


def _child_peak(wait) -> float:
    """Call ``wait()`` while sampling the VmHWM of this process's children every 20 ms; the
    largest [MB] (read from /proc: the exit's ru_maxrss of a vforked child starts from the
    parent's peak)."""
    import os
    import threading
    import time

    peak, done = [0.0], threading.Event()

    def sample():
        kids = Path(f"/proc/{os.getpid()}/task/{os.getpid()}/children")
        while not done.is_set():
            for pid in kids.read_text().split():
                try:
                    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
                        if line.startswith("VmHWM:"):
                            peak[0] = max(peak[0], int(line.split()[1]) / 1024)
                except OSError:  # exited meanwhile
                    pass
            time.sleep(0.02)

    t = threading.Thread(target=sample)
    t.start()
    try:
        wait()
    finally:
        done.set()
        t.join()
    return peak[0]


def main(argv=None) -> list[tuple[str, float, float]]:
    ap = argparse.ArgumentParser(prog="python -m benchmarks.report_memory")
    ap.add_argument("--revs", type=float, default=4.0)
    a = ap.parse_args(argv)
    rows = []

    def mark(what: str) -> None:
        rows.append((what, *_status()))
        print(f"{what:<40} RSS {rows[-1][1]:6.0f} MB   peak {rows[-1][2]:6.0f} MB", flush=True)

    import jointdyn.studies.reproduce as rp

    mark("imports")
    runs = {}
    for case in rp.PAPER_CASES + rp.BEYOND_CASES:
        runs[case.name] = (*rp.run_case(case, a.revs), case)
    mark(f"{len(runs)} simulations")
    from jointdyn.viz.reproduce_data import figure_data
    from jointdyn.viz.reproduce_figures import drawing

    with drawing(figure_data(runs, a.revs), a.revs) as drawn:
        child = _child_peak(drawn)
    mark("matplotlib figures (other process)")
    print(f"{'  the drawing process':<40} peak {child:6.0f} MB", flush=True)
    try:
        from jointdyn.viz.iplots import reproduction_html

        with tempfile.TemporaryDirectory() as d:
            reproduction_html(runs, Path(d) / "interactive.html", a.revs)
        mark("interactive.html")
    except ImportError:
        print("interactive.html: needs the [interactive] extra (plotly)")
    return rows


if __name__ == "__main__":
    main()
