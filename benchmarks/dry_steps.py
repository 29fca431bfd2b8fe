"""Where the steps of the dry slider-crank go: free flight vs contact, rejections by cause.

Usage: ``python -m benchmarks.dry_steps [--rtol 1e-8,1e-5] [--revs 4] [--costs]``

Drives the compiled DOPRI5 loop one step attempt at a time (``driver.drive`` with a budget of 1,
which continues bit for bit, [T110]) and classifies every attempt: accepted in contact / in free
flight (the element's contact flag at the step's start), rejected by the error test or by the
onset test [T16] (the error norm of the rejected trial recomputed from its error vector). Counts
behind docs/theory.md [T201]; no timing (see ``benchmarks.peers`` and ``benchmarks.end_to_end``).

``--costs`` adds what one call of each piece of the step loop costs [T208–T210]: the right-hand
side, the projection and the contact hooks, each in a compiled loop on borrowed arrays as the
driver runs them (and the RHS once more on reference-counted arrays), at a state in contact and
one in free flight (best of 3 × 100,000 calls, wall time), and the whole compiled loop per step
attempt (CPU, median of 9 runs).
"""

from __future__ import annotations

import argparse
import math
import statistics
import time
import warnings

import numpy as np
from numba import njit

from jointdyn.core.borrowed import borrowed
from jointdyn.forces.contact_events import onset_limit, refine_peaks
from jointdyn.forces.elements import onset_fraction
from jointdyn.forces.journal import IN_CONTACT
from jointdyn.forces.kernel_set import call_memory, call_step_limit
from jointdyn.integrators.common import error_norm
from jointdyn.integrators.dopri5 import DOPRI5
from jointdyn.integrators.driver import RUNNING, T, drive, new_work, start
from jointdyn.models.slider_crank import PIN, SPEED, slider_crank
from jointdyn.multibody.dynamics import project, rhs


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


PIECES = ("rhs", "project", "step limits", "onset test", "peaks", "memory", "rhs (counted)")


def _piece_loop(piece: int):
    """A compiled loop of ``calls`` calls of one piece of the step loop (index into PIECES) on
    borrowed arrays, for the step (t, y) → (t + h, y₁); the last piece: the RHS on the caller's
    reference-counted arrays, as before [T208]. One compiled function per piece, so that no piece
    changes the code generated for another."""

    @njit
    def loop(P0, t, h, y0, y1_0, mem0, f0, calls):
        P, y, y1, mem, f = borrowed((P0, y0, y1_0, mem0, f0))
        n = y.shape[0] // 2
        acc = 0.0
        for _ in range(calls):
            if piece == 0:
                acc += rhs(t, y, mem, P, f)
            elif piece == 1:
                y[:] = y1  # the projection of the same unprojected state every call
                acc += project(t + h, y, P, 1e-12)
            elif piece == 2:
                acc += call_step_limit(P.kernels, (y[:n], y[n:], mem, P.fint, P.freal))
                acc += onset_limit(y[:n], y[n:], f[n:], mem, P.fint, P.freal)
            elif piece == 3:
                acc += onset_fraction(y[:n], y[n:], y1[:n], y1[n:], mem, P.fint, P.freal)
            elif piece == 4:
                refine_peaks(y[:n], y[n:], y1[:n], y1[n:], h, mem, P.fint, P.freal)
            elif piece == 5:
                acc += call_memory(P.kernels, (t + h, y1[:n], y1[n:], mem, P.fint, P.freal, P.tables))
            else:
                acc += rhs(t, y0, mem0, P0, f0)
        return acc

    return loop


def costs(rtol: float = 1e-5, calls: int = 100_000) -> dict:
    """ns per call of each piece of the step loop at a contact and a free-flight step of the
    dry run at ``rtol``, and µs per step attempt of the whole compiled loop (CPU) [T208–T210]."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        system = slider_crank(joint="dry").compile()
    k = system.element_names.index(PIN)
    P = system.packed(0.0)
    t_out = np.linspace(0.0, 4 * 2 * math.pi / SPEED, 2881)
    out: dict = {}
    cpu = []
    for _ in range(10):  # the first run loads the kernels
        w = new_work(DOPRI5, np.array(system.y0, float), np.array(system.mem0, float), 0.0, t_out, 0.0)
        c0 = time.process_time()
        drive(DOPRI5, P, t_out, rtol, 1e-2 * rtol, math.inf, 10**8, True, 2**62, w)
        cpu.append(time.process_time() - c0)
    attempts = int(w.stats[1] + w.stats[2])
    out["loop_us_per_attempt"] = 1e6 * statistics.median(cpu[1:]) / attempts
    out["rhs_per_attempt"] = w.stats[0] / attempts
    # one accepted step in contact and one in free flight: (y, mem) at its start, y₁ unprojected
    w = new_work(DOPRI5, np.array(system.y0, float), np.array(system.mem0, float), 0.0, t_out, 0.0)
    start(DOPRI5, P, True, w)
    found: dict = {}
    while len(found) < 2:
        t, y, mem, f, acc = w.ctl[T], w.y.copy(), w.mem.copy(), w.K[0].copy(), w.stats[1]
        label = "contact" if w.mem[k, IN_CONTACT] > 0.5 else "free"
        drive(DOPRI5, P, t_out, rtol, 1e-2 * rtol, math.inf, 10**8, True, 1, w)
        if w.stats[1] > acc and w.ctl[T] > 0.01 and label not in found:
            found[label] = (t, w.ctl[T] - t, y, w.y1.copy(), mem, f)
    for label, (t, h, y, y1, mem, f) in found.items():
        for i, piece in enumerate(PIECES):
            loop = _piece_loop(i)
            loop(P, t, h, y.copy(), y1, mem.copy(), f.copy(), 10)
            best = math.inf
            for _ in range(3):
                t0 = time.perf_counter()
                loop(P, t, h, y.copy(), y1, mem.copy(), f.copy(), calls)
                best = min(best, time.perf_counter() - t0)
            out[f"{label}: {piece}_ns"] = 1e9 * best / calls
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m benchmarks.dry_steps")
    ap.add_argument("--rtol", default="1e-8,1e-5")
    ap.add_argument("--revs", type=float, default=4.0)
    ap.add_argument("--costs", action="store_true", help="also time the pieces of the step loop")
    a = ap.parse_args(argv)
    if a.costs:
        for r in (float(x) for x in a.rtol.split(",")):
            print(f"rtol {r:g} costs: " + ", ".join(f"{k} {v:.3g}" for k, v in costs(r).items()))
    rows = {}
    for r in (float(x) for x in a.rtol.split(",")):
        rows[r] = trace(r, a.revs)
        print(f"rtol {r:g}: " + ", ".join(f"{k} {v:.4g}" for k, v in rows[r].items()))
    return rows


if __name__ == "__main__":
    main()
