"""The one compiled step-control loop shared by the compiled integrators [T110], built from a
:class:`Stepper` record per method [T230].

A method is a :class:`Stepper`: a few declarations (order, stiff, Jacobian reuse, its own control
slots, tolerance transform, extra statistics) and compiled hooks — ``attempt`` (one trial step
from the state in :class:`Work`), ``rejected`` and ``accepted`` (its step-size control),
``dense`` (its continuous extension; None: land on the output times); ``fsal`` names the stage
that is f(t + h, y₁), reused as the next f(t, y). This module owns everything around them: the
step-size limits (``hmax``, contact ``step_limit``, landing on ``t_end`` or on output times),
rejection and retry (error norm, failed right-hand side, singular iteration matrix, unresolved
contact onset), the accepted-step hooks (projection, element memory), the Jacobian and its age.

All loop state lives in the arrays of :class:`Work` (``ctl``: floats, ``ictl``: integers; the
driver's slots first, then the method's own, declared by its record), so :func:`drive` can return
after ``budget`` step attempts and be called again to continue *bit for bit* as if it had never
stopped (``simulate`` uses this to stay responsive to signals).

The loop is compiled once per (stepper, Jacobian kind), only when a run uses it [T170], and for
all models: the element kernels are called by address (``forces.kernel_set``, [T379]).
"""

from __future__ import annotations

import hashlib
import types
from collections.abc import Callable
from typing import NamedTuple

import numpy as np
from numba import njit

from jointdyn.core.arrays import copy_matrix, copy_vector
from jointdyn.core.borrowed import borrowed
from jointdyn.core.precompiled import call
from jointdyn.forces import kernel_set as ks
from jointdyn.forces.contact_events import onset_limit, refine_peaks
from jointdyn.forces.elements import onset_fraction
from jointdyn.integrators.common import (
    MAX_STEPS,
    OK,
    RHS_FAILED,
    STEP_TOO_SMALL,
    accept_hooks,
    fd_jacobian,
    fsal_reusable,
)
from jointdyn.multibody.dynamics import rhs
from jointdyn.multibody.jacobian import jacobian_work_size, system_jacobian_into

RUNNING = -1  # drive() returned because its step budget was used up; call it again

# attempt() results; a rejected() hook gets ATTEMPT_OK for a failed error test (en > 1)
ATTEMPT_OK, ATTEMPT_SINGULAR, ATTEMPT_BAD, ATTEMPT_DIVERGED = 0, 1, 2, 3

# the driver's slots of Work.ctl (floats) and Work.ictl (integers); a method's own follow from
# CTL0 and ICTL0 (declared by its Stepper record, never shared with another method)
T, H, H_PROP = range(3)
IOUT, FAIL, AGE, STARTED, EXACT_JAC = range(5)  # EXACT_JAC 1: analytic Jacobian, 0: differences
CTL0, ICTL0 = 3, 5


class Stepper(NamedTuple):
    """One compiled integration method: what the shared step loop needs to know about it [T230].

    Hooks (numba-compiled; ``w`` is the :class:`Work`):

    * ``attempt(t, h, P, w, rtol, atol) -> (ATTEMPT_*, error norm)``: one trial step from
      (t, w.y), f(t, y) in w.f0, to w.y1;
    * ``rejected(res, h, en, ctl, ictl, stats, reuse) -> h`` (``w.ctl``, ``w.ictl``, ``w.stats``):
      after a rejection (``res`` the attempt's result, ATTEMPT_OK: the error test failed). The
      loop has already counted it and halved h (singular) or quartered it (failed right-hand
      side); the hook may renew a Jacobian by setting ``ictl[AGE] = reuse``;
    * ``accepted(h, h_prop, hmax, en, ctl, ictl, stats, reuse) -> h``: the next h after an
      accepted step (h_prop: the step proposed before the clip to an output time);
    * ``dense(t, t_new, y, f0, y1, K, mem, ctl, ictl, t_out, iout, Y, MEM) -> iout`` (None: every
      step lands on the next output time; the arguments are ``w``'s arrays): write the outputs in
      (t, t_new] into Y, MEM before the accepted-step hooks. (A hook taking ``w`` itself is passed
      its 25 arrays by value: ≈ 4 % of a dry run when called once per step [T230].)
    """

    name: str
    order: int  # of the solution (its error estimate is of lower order)
    attempt: Callable
    rejected: Callable
    accepted: Callable
    dense: Callable | None = None
    fsal: int | None = None  # row of w.K that is f(t + h, y₁): first-same-as-last [T203]
    stiff: bool = False  # implicit: takes the clearance error scales w.ysc [T186]
    reuse: tuple[int, int] | None = None  # accepted steps a Jacobian is kept (differences, exact); None: none
    jacobian_at_accept: bool = False  # exact: a due Jacobian right after an accepted step gives f0 [T185]
    ctl: tuple[float, ...] = ()  # initial values of its own float slots Work.ctl[CTL0:]
    ictl: tuple[int, ...] = ()  # initial values of its own integer slots Work.ictl[ICTL0:]
    tolerances: Callable | None = None  # (rtol, atol) -> those of its error test; None: as given
    stats: tuple[str, ...] = ()  # names of its counters Work.stats[4:] for Results.stats

    def __call__(
        self, P, y0, mem0, t0, t_out, rtol, atol, h0, hmax, max_steps, do_project, exact_jacobian=False
    ):
        """The historical solver signature: :func:`run`."""
        return run(self, P, y0, mem0, t0, t_out, rtol, atol, h0, hmax, max_steps, do_project, exact_jacobian)


class Work(NamedTuple):
    """Everything a compiled integration carries between steps and between calls."""

    y: np.ndarray  # state [q, q̇] at ctl[T]
    mem: np.ndarray  # element memory
    f0: np.ndarray  # f(t, y)
    ctl: np.ndarray  # float loop state (slots T, H, H_PROP, then the method's)
    ictl: np.ndarray  # integer loop state (slots IOUT, FAIL, AGE, STARTED, EXACT_JAC, then the method's)
    stats: np.ndarray  # [RHS evaluations, accepted, rejected, Jacobians, then the method's counters]
    Y: np.ndarray  # output states (n_out, nn)
    MEM: np.ndarray  # output memory (n_out, nf, NMEM)
    K: np.ndarray  # stage vectors (10, nn)
    Jm: np.ndarray  # ∂f/∂y
    W: np.ndarray  # iteration matrix (real, LU)
    piv: np.ndarray
    W1: np.ndarray  # reduced real iteration matrix (nn/2, nn/2) (radau5 [T181])
    W2: np.ndarray  # reduced complex iteration matrix (nn/2, nn/2), complex128
    piv2: np.ndarray
    cz: np.ndarray  # complex stage right-hand side (nn)
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
    stepper: Stepper, y0, mem0, t0: float, t_out, h0: float, exact_jacobian: bool = False, ysc=None
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
    n2 = nn // 2
    ctl = np.zeros(CTL0 + len(stepper.ctl))
    ctl[T] = t0
    ctl[H] = h0 if h0 > 0 else 1e-6 * max(1.0, abs(t_out[-1] - t0))
    ctl[H_PROP] = ctl[H]
    ctl[CTL0:] = stepper.ctl
    ictl = np.zeros(ICTL0 + len(stepper.ictl), dtype=np.int64)
    ictl[EXACT_JAC] = int(bool(exact_jacobian))
    ictl[IOUT] = iout
    ictl[AGE] = stepper.reuse[0] if stepper.reuse else 0  # forces a Jacobian on the first step
    ictl[ICTL0:] = stepper.ictl
    return Work(
        y=y0.astype(float).copy(),
        mem=mem0.astype(float).copy(),
        f0=np.zeros(nn),
        ctl=ctl,
        ictl=ictl,
        stats=np.zeros(4 + len(stepper.stats), dtype=np.int64),
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
        jw=np.zeros(call(jacobian_work_size, nn // 2, nn // 2, mem0.shape[0]) if exact_jacobian else 1),
        ysc=np.zeros(nn) if ysc is None or not stepper.stiff else np.asarray(ysc, dtype=float).copy(),
    )


@njit(cache=True)
def _no_dense(t, t_new, w, t_out, iout):
    """``dense`` of a method that lands on the output times (never called)."""
    return iout


# the names of the hooks in the step loop: loop() binds them to a stepper's (globals of its copy)
_attempt = _rejected = _accepted = _dense = None


def _template(LAND, FSAL, JAC, EXACT, AT_ACCEPT, REUSE):
    """The step loop; :func:`loop` rebinds its globals ``_attempt``, ``_rejected``, ``_accepted``
    and ``_dense`` to a stepper's hooks. The flags are closure constants (integers), so
    numba's dead-branch pruning removes what a stepper does not use before typing (a method
    without a Jacobian never compiles one)."""

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
            st = accept_hooks(t, w.y, w.mem, P, do_project, 0.0, 0.0, w.ysc)  # rtol 0: no gap test [T340]
            if st != OK:
                return st
            if rhs(t, w.y, w.mem, P, w.f0) != 0:
                return RHS_FAILED
            w.stats[0] += 1
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
        reuse = REUSE
        jw_need = jacobian_work_size(n, P.n_rows, P.fint.shape[0])  # AT_ACCEPT: q̈ read from w.jw
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
            if JAC == 1 and ictl[AGE] >= reuse:
                if EXACT == 1:
                    bad = system_jacobian_into(t, y, mem, P, w.Jm, w.ft, w.jw)
                    stats[0] += 1
                else:
                    bad = fd_jacobian(t, y, w.f0, mem, P, w.Jm, w.ft, w.work, w.fw)
                    stats[0] += nn + 1
                if bad != 0:
                    status = RHS_FAILED
                    break
                stats[3] += 1
                ictl[AGE] = 0
            q, qd, fint, freal = y[:n], y[n:], P.fint, P.freal
            h = min(h, hmax, ks.call_step_limit(P.kernels, (q, qd, mem, fint, freal)))
            h = min(h, onset_limit(q, qd, w.f0[n:], mem, fint, freal))  # onset [T201]
            h_prop = h
            if LAND == 1:  # no dense output: land on the next output time
                if iout < nout and t + h >= t_out[iout] - 1e-14 * abs(t_out[iout]):
                    h = t_out[iout] - t
            elif t + h >= t_end - 1e-14 * abs(t_end):
                h = t_end - t
            if h < hmin:
                status = STEP_TOO_SMALL if fail_status == OK else fail_status
                break
            res, en = _attempt(t, h, P, w, rtol, atol)
            if res == ATTEMPT_OK and not np.isfinite(en):
                res = ATTEMPT_BAD
            if res != ATTEMPT_OK or en > 1.0:
                stats[2] += 1
                if res == ATTEMPT_SINGULAR:  # iteration matrix not invertible
                    h *= 0.5
                elif res == ATTEMPT_BAD:
                    fail_status = RHS_FAILED
                    h *= 0.25
                h = _rejected(res, h, en, ctl, ictl, stats, reuse)
                continue
            frac = onset_fraction(q, qd, y1[:n], y1[n:], mem, fint, freal)
            if frac < 1.0:
                stats[2] += 1
                h *= max(frac, 0.01)
                continue
            # accepted
            fail_status = OK
            t_new = t + h
            # outputs in (t, t_new] from the continuous extension (before the accepted-step hooks)
            if LAND == 0:
                iout = _dense(t, t_new, y, w.f0, y1, w.K, mem, ctl, ictl, t_out, iout, w.Y, w.MEM)
            refine_peaks(q, qd, y1[:n], y1[n:], h, mem, fint, freal)  # [T202]
            copy_vector(y, y1)
            t = t_new
            stats[1] += 1
            ictl[AGE] += 1
            st = accept_hooks(t, y, mem, P, do_project, rtol, atol, w.ysc)
            if st != OK:
                status = st
                break
            if LAND == 1:
                while iout < nout and t_out[iout] <= t + 1e-14 * abs(t):
                    copy_vector(w.Y[iout], y)
                    copy_matrix(w.MEM[iout], mem)
                    iout += 1
            if FSAL >= 0 and fsal_reusable(y, y1, w.err, rtol, atol, do_project and P.n_rows > 0):
                copy_vector(w.f0, w.K[FSAL])  # first-same-as-last [T203]
            elif AT_ACCEPT == 0:  # (AT_ACCEPT: f0 after the controller)
                if rhs(t, y, mem, P, w.f0) != 0:
                    status = RHS_FAILED
                    break
                stats[0] += 1
            h = _accepted(h, h_prop, hmax, en, ctl, ictl, stats, reuse)
            if AT_ACCEPT == 1:
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
                else:
                    if rhs(t, y, mem, P, w.f0) != 0:
                        status = RHS_FAILED
                        break
                    stats[0] += 1
        if status == OK and iout == nout:
            copy_vector(w.Y[nout - 1], y)
            copy_matrix(w.MEM[nout - 1], mem)
        ctl[T] = t
        ctl[H] = h
        ctl[H_PROP] = h_prop
        ictl[IOUT] = iout
        ictl[FAIL] = fail_status
        return status

    return drive_method


def _code_digest(code, digest) -> None:
    digest.update(code.co_code)
    digest.update(repr((code.co_names, code.co_varnames)).encode())
    for c in code.co_consts:
        if isinstance(c, types.CodeType):
            _code_digest(c, digest)
        else:  # (a frozenset's repr follows the string hashes of the process: sorted)
            digest.update(repr(sorted(map(repr, c)) if isinstance(c, frozenset) else c).encode())


def _fingerprint(hooks) -> str:
    """A digest of the hooks' Python code: part of the loop's on-disk cache name, so that an
    edited hook of a stepper defined outside the package is not served a stale loop (the
    package's own sources key the whole cache directory)."""
    digest = hashlib.sha256()
    for f in hooks:
        py = getattr(f, "py_func", f)
        digest.update(f"{py.__module__}.{py.__qualname__}".encode())
        _code_digest(py.__code__, digest)
    return digest.hexdigest()[:12]


_LOOPS: dict = {}


def loop(stepper: Stepper, exact: int):
    """The compiled driver of ``stepper`` (``exact``: 1 analytic Jacobian, 0 forward differences),
    built on first use [T170, T230].

    The hooks become *globals* of the loop's function (a copy of this module's namespace) rather
    than closure cells: numba keys its on-disk cache by a pickle of the closure cells, in which a
    compiled function carries a per-process identifier, so a loop closing over the hooks would
    be compiled again in every process. The cells are the stepper's integer flags; the function's
    name carries the stepper's name and :func:`_fingerprint`, so each stepper has its own cache
    entries and the key is the same in every process."""
    jac = stepper.reuse is not None
    exact = int(exact) if jac else 0
    key = (stepper, exact)
    if key not in _LOOPS:
        land = stepper.dense is None
        hooks = {
            "_attempt": stepper.attempt,
            "_rejected": stepper.rejected,
            "_accepted": stepper.accepted,
            "_dense": _no_dense if land else stepper.dense,
        }
        reuse = stepper.reuse[exact] if stepper.reuse else 0
        at_accept = int(stepper.jacobian_at_accept and exact == 1)
        fsal = -1 if stepper.fsal is None else stepper.fsal
        tmpl = _template(int(land), fsal, int(jac), exact, at_accept, reuse)
        fn = types.FunctionType(tmpl.__code__, globals() | hooks, tmpl.__name__, None, tmpl.__closure__)
        fn.__qualname__ = f"drive_{stepper.name}_{_fingerprint(hooks.values())}"
        fn.__doc__ = tmpl.__doc__
        _LOOPS[key] = njit(cache=True)(fn)
    return _LOOPS[key]


_NO_TIMES = np.zeros(1)


def _loop_for(stepper: Stepper, P, w):
    exact = int(w.ictl[EXACT_JAC]) if stepper.reuse is not None else 0
    if exact:  # a method that uses the exact Jacobian
        ks.require_jacobian(P.kernels)
    return loop(stepper, exact)


def start(stepper: Stepper, P, do_project, w):
    """Accepted-step hooks and f(t0, y0) at the initial state; returns a status code."""
    return call(_loop_for(stepper, P, w), P, _NO_TIMES, 0.0, 0.0, 0.0, 0, bool(do_project), -1, w)


def drive(stepper: Stepper, P, t_out, rtol, atol, hmax, max_steps, do_project, budget, w):
    """Integrate towards t_out[-1] for at most ``budget`` step attempts.

    Returns OK (t_out[-1] reached), RUNNING (budget used up; call again to continue) or an
    error status (common.py). Outputs go to w.Y/w.MEM up to index w.ictl[IOUT]. Starts the
    integration first (:func:`start`) if that has not been done."""
    args = (P, t_out, float(rtol), float(atol), float(hmax), int(max_steps), bool(do_project), int(budget), w)
    return call(_loop_for(stepper, P, w), *args)  # compiled at install where built [T382]


def method_tolerances(stepper: Stepper, rtol: float, atol: float) -> tuple[float, float]:
    """The tolerances the method's error test uses for the user's (rtol, atol)."""
    return (rtol, atol) if stepper.tolerances is None else stepper.tolerances(rtol, atol)


def run(
    stepper: Stepper, P, y0, mem0, t0, t_out, rtol, atol, h0, hmax, max_steps, do_project, exact_jacobian=0
):
    """Integrate from t0 to t_out[-1] in one call; returns (Y, MEM, n_written, stats, status,
    t_reached, h_next, y_final, mem_final), the historical return of the compiled solvers."""
    w = new_work(stepper, y0, mem0, t0, t_out, h0, exact_jacobian)
    st = start(stepper, P, do_project, w)
    rtol, atol = method_tolerances(stepper, rtol, atol)
    if st == OK:
        st = drive(stepper, P, t_out, rtol, atol, hmax, max_steps, do_project, 2**62, w)
    h = w.ctl[H_PROP] if st == OK else w.ctl[H]
    return w.Y, w.MEM, int(w.ictl[IOUT]), w.stats, st, float(w.ctl[T]), h, w.y, w.mem
