"""Where the steps of the dry slider-crank go: free flight vs contact, rejections by cause.

Usage: ``python -m benchmarks.dry_steps [--rtol 1e-8,1e-5] [--revs 4]``

Drives the compiled DOPRI5 loop one step attempt at a time (``driver.drive`` with a budget of 1,
which continues bit for bit, [T110]) and classifies every attempt: accepted in contact / in free
flight (the element's contact flag at the step's start), rejected by the error test or by the
onset test [T16] (the error norm of the rejected trial recomputed from its error vector). Counts
behind docs/theory.md [T201]; no timing (see ``benchmarks.peers`` and ``benchmarks.end_to_end``).
"""

from __future__ import annotations

import argparse
import math
import warnings

import numpy as np

from jointdyn.forces.journal import IN_CONTACT
from jointdyn.integrators.common import error_norm
from jointdyn.integrators.driver import DOPRI5, RUNNING, T, drive, new_work, start
from jointdyn.models.slider_crank import PIN, SPEED, slider_crank


def trace(rtol: float, revs: float = 4.0) -> dict:
    """Step statistics of one dry run at (rtol, atol = 1e-2·rtol), 720 samples per revolution."""
    atol = 1e-2 * rtol
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        system = slider_crank(joint="dry").compile()
    k = system.element_names.index(PIN)
    P = system.packed(0.0)
    t_out = np.linspace(0.0, revs * 2 * math.pi / SPEED, int(revs * 720) + 1)
    w = new_work(DOPRI5, np.array(system.y0, float), np.array(system.mem0, float), 0.0, t_out, 0.0)
    start(DOPRI5, P, True, w)
    out = dict.fromkeys(("accepted_contact", "accepted_free", "rejected_error", "rejected_onset"), 0)
    out |= {"short_steps": 0, "time_in_contact": 0.0}
    while True:
        t, y, acc = w.ctl[T], w.y.copy(), w.stats[1]
        contact = w.mem[k, IN_CONTACT] > 0.5
        st = drive(DOPRI5, P, t_out, rtol, atol, math.inf, 10**8, True, 1, w)
        if w.stats[1] > acc:
            h = w.ctl[T] - t
            out["accepted_contact" if contact else "accepted_free"] += 1
            out["short_steps"] += h < 1e-6
            out["time_in_contact"] += h if contact else 0.0
        elif error_norm(w.err, y, w.y1, rtol, atol) > 1.0:
            out["rejected_error"] += 1
        else:
            out["rejected_onset"] += 1
        if st != RUNNING:
            break
    out["rhs"] = int(w.stats[0])
    out["impacts"] = int(w.mem[k, 2])
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m benchmarks.dry_steps")
    ap.add_argument("--rtol", default="1e-8,1e-5")
    ap.add_argument("--revs", type=float, default=4.0)
    a = ap.parse_args(argv)
    rows = {}
    for r in (float(x) for x in a.rtol.split(",")):
        rows[r] = trace(r, a.revs)
        print(f"rtol {r:g}: " + ", ".join(f"{k} {v:.4g}" for k, v in rows[r].items()))
    return rows


if __name__ == "__main__":
    main()
