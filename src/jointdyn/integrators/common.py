"""Pieces shared by the compiled integrators: error norm, dense output, accepted-step hooks, the
forward-difference Jacobian."""

from __future__ import annotations

import numpy as np
from numba import njit

from jointdyn.core.arrays import copy_matrix, copy_vector
from jointdyn.forces.kernel_set import call_memory
from jointdyn.integrators.accuracy import film_gap_unresolved
from jointdyn.multibody.dynamics import project, rhs

# status codes of the compiled integrators (messages in jointdyn.simulate)
OK = 0
STEP_TOO_SMALL = 1
MAX_STEPS = 2
RHS_FAILED = 3
MEMORY_FAILED = 4
PROJECTION_FAILED = 5
INTERRUPTED = 6  # SIGINT/SIGTERM (set by jointdyn.simulate, never by compiled code)
FORCE_UNRESOLVED = 7  # an element force is noise at the tolerances (set by jointdyn.simulate)


@njit(cache=True)
def error_norm(err, y0, y1, rtol, atol):
    """RMS of err_i / (atol + rtol·max(|y0_i|, |y1_i|)) (Hairer–Wanner)."""
    s = 0.0
    n = err.shape[0]
    for i in range(n):
        sc = atol + rtol * max(abs(y0[i]), abs(y1[i]))
        e = err[i] / sc
        s += e * e
    return np.sqrt(s / n)


@njit(cache=True)
def error_norm_scaled(err, y0, y1, rtol, atol, ysc):
    """:func:`error_norm` with a fixed scale ysc_i > 0 [SI of component i] in place of
    max(|y0_i|, |y1_i|) where given (ysc_i = 0: that max, the same arithmetic) [T186]."""
    s = 0.0
    n = err.shape[0]
    for i in range(n):
        sc = atol + rtol * (ysc[i] if ysc[i] > 0.0 else max(abs(y0[i]), abs(y1[i])))
        e = err[i] / sc
        s += e * e
    return np.sqrt(s / n)


@njit(cache=True)
def hermite(y0, f0, y1, f1, h, th, out):
    """Cubic Hermite interpolation on [t, t+h] at fraction th (4th-order accurate state)."""
    h00 = (1.0 + 2.0 * th) * (1.0 - th) ** 2
    h10 = th * (1.0 - th) ** 2
    h01 = th * th * (3.0 - 2.0 * th)
    h11 = th * th * (th - 1.0)
    for i in range(y0.shape[0]):
        out[i] = h00 * y0[i] + h10 * h * f0[i] + h01 * y1[i] + h11 * h * f1[i]


FSAL_PROJECTION = 0.01  # largest projection correction (error-norm units) for which f(y₁) is reused


@njit(cache=True)
def fsal_reusable(y, y1, scratch, rtol, atol, projected):
    """True if f(t+h, y₁) (the last stage of a first-same-as-last method) can serve as f(t, y) at
    the accepted state y [T203]: always without projection; after the projection y₁ → y when the
    correction is at most ``FSAL_PROJECTION`` in the error norm. For DOPRI5, reusing k₇ then
    perturbs the next step by ≈ h·b₁·J·(y − y₁), below 0.1·h‖J‖·0.01 ≤ 3.3e-3 of the tolerance on
    its stability region (h‖J‖ ≤ 3.3). ``scratch`` (len(y)) is overwritten."""
    if not projected:
        return True
    for i in range(y.shape[0]):
        scratch[i] = y[i] - y1[i]
    return error_norm(scratch, y1, y, rtol, atol) <= FSAL_PROJECTION


@njit(cache=True)
def accept_hooks(t, y, mem, P, do_project, rtol=0.0, atol=0.0, ysc=None):
    """After an accepted step: project on the constraints, then update element memory; with
    the error test's (rtol, atol) and its fixed scales ``ysc`` (None or 0: |y_i|, [T186]), also
    stop on a film gap the tolerances do not resolve [T115]."""
    if do_project and P.n_rows > 0:
        if project(t, y, P, 1e-12) < 0.0:
            return PROJECTION_FAILED
    n = y.shape[0] // 2
    # non-zero codes from the elements (≥ 10, e.g. FILM_BREAKDOWN + element) pass through
    st = call_memory(P.kernels, (t, y[:n], y[n:], mem, P.fint, P.freal, P.tables))
    if st != OK:
        return st
    if ysc is None:
        return film_gap_unresolved(y[:n], y[n:], P, rtol, atol, y[:0])
    return film_gap_unresolved(y[:n], y[n:], P, rtol, atol, ysc[:n])


@njit(cache=True)
def start_outputs(y0, mem0, t0, t_out):
    """Output buffers (Y, MEM) with every sample at or before t0 filled with the initial state;
    returns (Y, MEM, index of the next sample)."""
    nout = t_out.shape[0]
    Y = np.zeros((nout, y0.shape[0]))
    MEM = np.zeros((nout, mem0.shape[0], mem0.shape[1]))
    iout = 0
    while iout < nout and t_out[iout] <= t0:
        copy_vector(Y[iout], y0)
        copy_matrix(MEM[iout], mem0)
        iout += 1
    return Y, MEM, iout


@njit(cache=True)
def fd_jacobian(t, y, f0, mem, P, Jm, ft, work, fw):
    """Forward-difference ∂f/∂y (columns) and ∂f/∂t at (t, y) with f0 = f(t, y) (2n + 1
    evaluations of the right-hand side). Returns a status (0 = ok)."""
    nn = y.shape[0]
    n = nn // 2
    eps = 1.4901161193847656e-08
    bad = 0
    for j in range(nn):
        scale = abs(y[j])
        if j >= n:
            scale = max(scale, 1e-3)
        else:
            scale = max(scale, 1e-5)
        d = eps * scale
        copy_vector(work, y)
        work[j] += d
        bad |= rhs(t, work, mem, P, fw)
        for i in range(nn):
            Jm[i, j] = (fw[i] - f0[i]) / d
    dt = eps * max(abs(t), 1e-3)
    bad |= rhs(t + dt, y, mem, P, fw)
    for i in range(nn):
        ft[i] = (fw[i] - f0[i]) / dt
    return bad
