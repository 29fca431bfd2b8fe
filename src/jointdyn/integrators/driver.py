"""The one compiled step-control loop shared by the compiled integrators [T110].

Each method contributes a compiled ``attempt`` (one trial step from the state in ``Work``) and a
dense-output writer; this module owns everything around them: step-size limits (``hmax``,
contact ``step_limit``, landing on ``t_end`` or on output times), rejection and retry (error
norm, failed right-hand side, singular iteration matrix, unresolved contact onset), the
accepted-step hooks (projection, element memory), the step-size controller and the Jacobian
reuse counter.

All loop state lives in the arrays of :class:`Work` (``ctl``: floats, ``ictl``: integers), so
:func:`drive` can return after ``budget`` step attempts and be called again to continue *bit for
bit* as if it had never stopped (``simulate`` uses this to stay responsive to signals).

The loop is compiled once per (method, Jacobian kind), with the method as a compile-time
constant, so that a run compiles only the method it uses [T170]; :func:`start` and
:func:`drive` pick the compiled entry point.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from jointdyn.core.borrowed import borrowed
from jointdyn.forces.contact_events import onset_limit, refine_peaks
from jointdyn.forces.elements import onset_fraction, step_limit
from jointdyn.integrators.common import MAX_STEPS, OK, RHS_FAILED, STEP_TOO_SMALL, accept_hooks, write_dense
from jointdyn.integrators.dopri5 import attempt_dopri5, dopri5_accepted, dopri5_rejected, fsal_reusable
from jointdyn.integrators.radau5 import (
    HHFAC,
    attempt_radau5,
    radau5_accepted,
    radau5_rejected,
    store_polynomial,
    tolerances,
    write_dense_radau5,
)
from jointdyn.integrators.rodas4 import attempt_rodas4, jacobian, write_dense_rodas
from jointdyn.integrators.ros34pw2 import attempt_ros34pw2
from jointdyn.multibody.dynamics import rhs
from jointdyn.multibody.jacobian import jacobian_work_size, system_jacobian_into

# method codes
DOPRI5, RODAS4, ROS34PW2, RADAU5 = 0, 1, 2, 3
METHODS = {"dopri5": DOPRI5, "rodas4": RODAS4, "ros34pw2": ROS34PW2, "radau5": RADAU5}
# accepted steps a Jacobian is kept (0: none needed; radau5 decides itself from the Newton rate)
REUSE = np.array([0, 1, 10, 1 << 60])  # accepted steps a Jacobian is kept (0: none needed)
# with the exact Jacobian ros34pw2 takes a fresh one every step: measured 2× less wall time at
# equal accuracy than reusing it for 10 steps (python -m benchmarks.work_precision, [T117])
REUSE_EXACT = np.array([0, 1, 1, 1 << 60])
RUNNING = -1  # drive() returned because its step budget was used up; call it again

# attempt() results
ATTEMPT_OK, ATTEMPT_SINGULAR, ATTEMPT_BAD, ATTEMPT_DIVERGED = 0, 1, 2, 3

# slots of Work.ctl (floats) and Work.ictl (integers)
T, H, H_PROP, E_PREV, H_LU = range(5)  # slots 4–11: radau5 (see radau5.py)
IOUT, FAIL, AGE, STARTED = range(4)  # slots 4–5: radau5
EXACT_JAC = 6  # 1: analytic jacobian.system_jacobian_into, 0: forward differences


class Work(NamedTuple):
    """Everything a compiled integration carries between steps and between calls."""

    y: np.ndarray  # state [q, q̇] at ctl[T]
    mem: np.ndarray  # element memory
    f0: np.ndarray  # f(t, y)
    ctl: np.ndarray  # float loop state (slots T, H, H_PROP, E_PREV, …)
    ictl: np.ndarray  # integer loop state (slots IOUT, FAIL, AGE, …)
    stats: np.ndarray  # [RHS evaluations, accepted, rejected, Jacobians, LU pairs, Newton its, Newton fails]
    Y: np.ndarray  # output states (n_out, nn)
    MEM: np.ndarray  # output memory (n_out, nf, NMEM)
    K: np.ndarray  # stage vectors (10, nn)
    Jm: np.ndarray  # ∂f/∂y
    W: np.ndarray  # iteration matrix (real, LU)
    piv: np.ndarray
    W1: np.ndarray  # radau5: the real iteration matrix, reduced to (nn/2, nn/2) (LU) [T181]
    W2: np.ndarray  # radau5: the complex iteration matrix (nn/2, nn/2), complex128 (LU)
    piv2: np.ndarray
    cz: np.ndarray  # radau5: complex stage right-hand side (nn)
    ft: np.ndarray  # ∂f/∂t
    yt: np.ndarray
    y1: np.ndarray
    fw: np.ndarray
    work: np.ndarray
    err: np.ndarray
    gk: np.ndarray
    jw: np.ndarray  # scratch of the exact Jacobian (jacobian.system_jacobian_into)
    ysc: np.ndarray  # stiff methods: fixed error scales (> 0) replacing |y_i| (0: |y_i|) [T186]


def new_work(
    method: int, y0, mem0, t0: float, t_out, h0: float, exact_jacobian: bool = False, ysc=None
) -> Work:
    """Work arrays for integrating from (t0, y0, mem0); outputs at or before t0 are filled.
    ``exact_jacobian``: the stiff methods use :func:`jointdyn.multibody.jacobian.system_jacobian` (one
    force evaluation, counted as one RHS evaluation) instead of forward differences. ``ysc``
    (nn,): fixed error scales of the stiff methods (``weights.clearance_scale``; None: |y_i|)."""
    nn = y0.shape[0]
    nout = t_out.shape[0]
    Y = np.zeros((nout, nn))
    MEM = np.zeros((nout,) + mem0.shape)
    iout = 0
    while iout < nout and t_out[iout] <= t0:  # samples at or before t0: the initial state
        iout += 1
    Y[:iout] = y0
    MEM[:iout] = mem0
    n2 = nn // 2 if method == RADAU5 else 1
    ctl = np.zeros(12)
    ctl[T] = t0
    ctl[H] = h0 if h0 > 0 else 1e-6 * max(1.0, abs(t_out[-1] - t0))
    ctl[H_PROP] = ctl[H]
    ctl[E_PREV] = 1.0
    ctl[H_LU] = -1.0
    ctl[5:8] = (1.0, 1.0, 1.0)  # radau5: θ, Newton factor, previous h
    ictl = np.zeros(7, dtype=np.int64)
    ictl[EXACT_JAC] = int(bool(exact_jacobian))
    ictl[IOUT] = iout
    ictl[AGE] = REUSE[method]  # forces a Jacobian on the first step
    return Work(
        y=y0.astype(float).copy(),
        mem=mem0.astype(float).copy(),
        f0=np.zeros(nn),
        ctl=ctl,
        ictl=ictl,
        stats=np.zeros(7, dtype=np.int64),
        Y=Y,
        MEM=MEM,
        K=np.zeros((10, nn)),
        Jm=np.zeros((nn, nn)),
        W=np.zeros((nn, nn)),
        piv=np.zeros(nn, dtype=np.int64),
        W1=np.zeros((n2, n2)),
        W2=np.zeros((n2, n2), dtype=np.complex128),
        piv2=np.zeros(n2, dtype=np.int64),
        cz=np.zeros(2 * n2, dtype=np.complex128),
        ft=np.zeros(nn),
        yt=np.zeros(nn),
        y1=np.zeros(nn),
        fw=np.zeros(nn),
        work=np.zeros(nn),
        err=np.zeros(nn),
        gk=np.zeros(nn),
        # m ≤ n constraint rows for a non-singular system (a longer scratch is made if needed)
        jw=np.zeros(jacobian_work_size(nn // 2, nn // 2, mem0.shape[0]) if exact_jacobian else 1),
        ysc=np.zeros(nn) if ysc is None or method == DOPRI5 else np.asarray(ysc, dtype=float).copy(),
    )


# The step loop is compiled once per (method, Jacobian) by :func:`_entry`: the method code and
# the Jacobian flag are closure constants, so numba's dead-branch pruning removes the other
# methods before typing and a dopri5 run never compiles the stiff methods or a Jacobian. The
# constants are the closure's only cells (integers), so the on-disk cache key of every entry
# point is the same in every process.


@njit(cache=True)
def _reject_factor(method, en):
    """Step-size factor after an error-test failure (en > 1); DOPRI5: ``dopri5_rejected``."""
    if method == RODAS4:
        return max(0.2, 0.9 * en**-0.25)
    return max(0.2, 0.8 * en ** (-1.0 / 3.0))


def _entry(METHOD: int, EXACT: int):
    """The compiled driver of one method (``EXACT``: 1 analytic Jacobian, 0 forward
    differences)."""

    @njit(cache=True)
    def drive_method(P, t_out, rtol, atol, hmax, max_steps, do_project, budget, w):
        """Start (once), then integrate towards t_out[-1] for at most ``budget`` step attempts
        (``budget < 0``: start only). Returns OK, RUNNING or an error status."""
        # the caller owns every array for the whole call and nothing below keeps one: no
        # reference counting in the loop (its atomic updates cost ≈ 45 % of a dry RHS) [T208]
        P, t_out, w = borrowed(P), borrowed(t_out), borrowed(w)
        # start: hooks and f(t0, y0) at the initial state (written here, not as a compiled
        # function of its own, which would link and optimise the right-hand side once more)
        if w.ictl[STARTED] == 0:
            t = w.ctl[T]
            st = accept_hooks(t, w.y, w.mem, P, do_project, 0.0, 0.0)  # = the defaults: no gap test
            if st != OK:
                return st
            if rhs(t, w.y, w.mem, P, w.f0) != 0:
                return RHS_FAILED
            w.stats[0] += 1
            if METHOD == DOPRI5:
                w.K[0, :] = w.f0
            w.ictl[STARTED] = 1
        if budget < 0:
            return OK
        nn = w.y.shape[0]
        n = nn // 2
        nout = t_out.shape[0]
        y, mem, stats, ctl, ictl = w.y, w.mem, w.stats, w.ctl, w.ictl
        y1 = w.y1
        t = ctl[T]
        h = ctl[H]
        h_prop = ctl[H_PROP]
        iout = ictl[IOUT]
        fail_status = ictl[FAIL]
        t_end = t_out[-1]
        hmin = 1e-14 * max(1.0, abs(t_end))
        reuse = REUSE_EXACT[METHOD] if EXACT == 1 else REUSE[METHOD]
        jw_need = jacobian_work_size(n, P.n_rows, P.fint.shape[0])  # radau5: q̈ read from w.jw
        attempts = 0
        status = OK
        while t < t_end:
            if attempts >= budget:
                status = RUNNING
                break
            attempts += 1
            if stats[1] + stats[2] >= max_steps:
                status = MAX_STEPS
                break
            if METHOD != DOPRI5 and ictl[AGE] >= reuse:  # (dopri5: REUSE = 0, no Jacobian)
                if EXACT == 1:
                    bad = system_jacobian_into(t, y, mem, P, w.Jm, w.ft, w.jw)
                    stats[0] += 1
                else:
                    bad = jacobian(t, y, w.f0, mem, P, w.Jm, w.ft, w.work, w.fw)
                    stats[0] += nn + 1
                if bad != 0:
                    status = RHS_FAILED
                    break
                stats[3] += 1
                ictl[AGE] = 0
                ctl[H_LU] = -1.0  # radau5: refactor with the new Jacobian
            h = min(h, hmax, step_limit(y[:n], y[n:], mem, P.fint, P.freal, P.kinds))
            h = min(h, onset_limit(y[:n], y[n:], w.f0[n:], mem, P.fint, P.freal, P.kinds))  # onset [T201]
            h_prop = h
            if METHOD == ROS34PW2:  # no dense output: land on the next output time
                if iout < nout and t + h >= t_out[iout] - 1e-14 * abs(t_out[iout]):
                    h = t_out[iout] - t
            elif t + h >= t_end - 1e-14 * abs(t_end):
                h = t_end - t
            if h < hmin:
                status = STEP_TOO_SMALL if fail_status == OK else fail_status
                break
            if METHOD == DOPRI5:
                res, en = attempt_dopri5(t, h, P, w, rtol, atol)
            elif METHOD == RODAS4:
                res, en = attempt_rodas4(t, h, P, w, rtol, atol)
            elif METHOD == ROS34PW2:
                res, en = attempt_ros34pw2(t, h, P, w, rtol, atol)
            else:
                res, en = attempt_radau5(t, h, P, w, rtol, atol)
            if res == ATTEMPT_SINGULAR:  # iteration matrix not invertible
                stats[2] += 1
                h *= 0.5
                if METHOD == ROS34PW2:
                    ictl[AGE] = reuse
                continue
            if res == ATTEMPT_DIVERGED:  # radau5: Newton failed; renew a Jacobian that is not fresh
                stats[2] += 1
                stats[6] += 1
                h *= ctl[HHFAC]
                ictl[4] = 1  # radau5.REJECTED
                if ictl[AGE] > 0:
                    ictl[AGE] = reuse
                continue
            if res == ATTEMPT_BAD or not np.isfinite(en):
                stats[2] += 1
                fail_status = RHS_FAILED
                h *= 0.25
                if METHOD == ROS34PW2 or (METHOD == RADAU5 and ictl[AGE] > 0):
                    ictl[AGE] = reuse
                continue
            if en > 1.0:
                stats[2] += 1
                if METHOD == RADAU5:
                    h = radau5_rejected(h, en, w)
                    if ictl[AGE] > 0:
                        ictl[AGE] = reuse
                    continue
                if METHOD == DOPRI5:
                    h = dopri5_rejected(h, en)
                    ictl[4] = 1  # (radau5's REJECTED slot) no growth on the next accepted step
                    continue
                h *= _reject_factor(METHOD, en)
                if METHOD == ROS34PW2 and ictl[AGE] > 0:  # a stale Jacobian may be the cause
                    ictl[AGE] = reuse
                continue
            frac = onset_fraction(y[:n], y[n:], y1[:n], y1[n:], mem, P.fint, P.freal, P.kinds)
            if frac < 1.0:
                stats[2] += 1
                h *= max(frac, 0.01)
                continue
            # accepted
            fail_status = OK
            t_new = t + h
            # outputs in (t, t_new] from the continuous extension (before the accepted-step hooks)
            if METHOD == DOPRI5:
                iout = write_dense(t, y, w.K[0], t_new, y1, w.K[6], mem, t_out, iout, w.Y, w.MEM)
            elif METHOD == RODAS4:
                iout = write_dense_rodas(t, y, t_new, y1, w.K, mem, t_out, iout, w.Y, w.MEM)
            elif METHOD == RADAU5:
                store_polynomial(t_new - t, w)
                iout = write_dense_radau5(t, t_new, y1, w.K, mem, t_out, iout, w.Y, w.MEM)
            refine_peaks(y[:n], y[n:], y1[:n], y1[n:], h, mem, P.fint, P.freal, P.kinds)  # [T202]
            y[:] = y1
            t = t_new
            stats[1] += 1
            ictl[AGE] += 1
            st = accept_hooks(t, y, mem, P, do_project, rtol, atol, w.ysc)
            if st != OK:
                status = st
                break
            if METHOD == ROS34PW2:
                while iout < nout and t_out[iout] <= t + 1e-14 * abs(t):
                    w.Y[iout] = y
                    w.MEM[iout] = mem
                    iout += 1
            if METHOD == DOPRI5 and fsal_reusable(y, y1, w.err, rtol, atol, do_project and P.n_rows > 0):
                w.K[0, :] = w.K[6]  # first-same-as-last [T203]
                w.f0[:] = w.K[6]
            elif not (METHOD == RADAU5 and EXACT == 1):  # (radau5, exact: f0 after its controller)
                if rhs(t, y, mem, P, w.f0) != 0:
                    status = RHS_FAILED
                    break
                stats[0] += 1
                if METHOD == DOPRI5:
                    w.K[0, :] = w.f0
            e_now = max(en, 1e-10)
            if METHOD == DOPRI5:
                h, ctl[E_PREV] = dopri5_accepted(h, en, ctl[E_PREV], ictl[4] == 1)
                ictl[4] = 0
            elif METHOD == RODAS4:
                h *= min(6.0, max(0.2, 0.9 * e_now**-0.25))
            elif METHOD == RADAU5:
                h = radau5_accepted(h, hmax, en, w, reuse)
            else:
                # PI controller (Gustafsson; Hairer & Wanner II §IV.8): exponents 0.7/k, 0.4/k, k = 3
                fac = 0.9 * e_now ** (-0.7 / 3.0) * ctl[E_PREV] ** (0.4 / 3.0)
                ctl[E_PREV] = e_now
                h = max(h, h_prop) * min(3.0, max(0.2, fac))
            if METHOD == RADAU5 and EXACT == 1:
                # a Jacobian due at the next step is taken now: its accelerations are f(t, y), so
                # f0 costs no evaluation of its own (same arithmetic as rhs) [T185]
                if ictl[AGE] >= reuse and t < t_end and w.jw.shape[0] >= jw_need:
                    if system_jacobian_into(t, y, mem, P, w.Jm, w.ft, w.jw) != 0:
                        status = RHS_FAILED
                        break
                    for i in range(n):
                        w.f0[i] = y[n + i]
                        w.f0[n + i] = w.jw[2 * n + i]  # q̈ of the Jacobian's accelerations
                    stats[0] += 1
                    stats[3] += 1
                    ictl[AGE] = 0
                    ctl[H_LU] = -1.0
                else:
                    if rhs(t, y, mem, P, w.f0) != 0:
                        status = RHS_FAILED
                        break
                    stats[0] += 1
        if status == OK and iout == nout:
            w.Y[nout - 1] = y
            w.MEM[nout - 1] = mem
        ctl[T] = t
        ctl[H] = h
        ctl[H_PROP] = h_prop
        ictl[IOUT] = iout
        ictl[FAIL] = fail_status
        return status

    return drive_method


# One entry point per (method, Jacobian); a run compiles (or loads) exactly one of them.
_ENTRIES = {(mth, exact): _entry(mth, exact) for mth in (RODAS4, ROS34PW2, RADAU5) for exact in (0, 1)}
_ENTRIES[DOPRI5, 0] = _entry(DOPRI5, 0)


def _entry_of(method: int, w: Work):
    return _ENTRIES[method, 0 if method == DOPRI5 else int(w.ictl[EXACT_JAC])]


_NO_TIMES = np.zeros(1)


def start(method, P, do_project, w):
    """Accepted-step hooks and f(t0, y0) at the initial state; returns a status code."""
    return _entry_of(method, w)(P, _NO_TIMES, 0.0, 0.0, 0.0, 0, bool(do_project), -1, w)


def drive(method, P, t_out, rtol, atol, hmax, max_steps, do_project, budget, w):
    """Integrate towards t_out[-1] for at most ``budget`` step attempts.

    Returns OK (t_out[-1] reached), RUNNING (budget used up; call again to continue) or an
    error status (common.py). Outputs go to w.Y/w.MEM up to index w.ictl[IOUT]. Starts the
    integration first (:func:`start`) if that has not been done."""
    return _entry_of(method, w)(
        P, t_out, float(rtol), float(atol), float(hmax), int(max_steps), bool(do_project), int(budget), w
    )


def method_tolerances(method: int, rtol: float, atol: float) -> tuple[float, float]:
    """The tolerances the method's error test uses for the user's (rtol, atol)."""
    return tolerances(rtol, atol) if method == RADAU5 else (rtol, atol)


def run(
    method: int, P, y0, mem0, t0, t_out, rtol, atol, h0, hmax, max_steps, do_project, exact_jacobian=False
):
    """Integrate from t0 to t_out[-1] in one call; returns (Y, MEM, n_written, stats, status,
    t_reached, h_next, y_final, mem_final), the historical return of the compiled solvers."""
    w = new_work(method, y0, mem0, t0, t_out, h0, exact_jacobian)
    st = start(method, P, do_project, w)
    rtol, atol = method_tolerances(method, rtol, atol)
    if st == OK:
        st = drive(method, P, t_out, rtol, atol, hmax, max_steps, do_project, 2**62, w)
    h = w.ctl[H_PROP] if st == OK else w.ctl[H]
    return w.Y, w.MEM, int(w.ictl[IOUT]), w.stats, st, float(w.ctl[T]), h, w.y, w.mem
