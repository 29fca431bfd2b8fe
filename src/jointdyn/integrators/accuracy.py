"""Accuracy guard: is each element's force determined by the state to the accuracy the error
control delivers? [T111]

The error test accepts a step when the state error is of the order of the tolerance
s_j = atol + rtol·|y_j| in every component. The force of an element is then known only to

    δF_k = Σ_j |F_k(y + s_j e_j) − F_k(y)|        (secant over the tolerance, all components)

A very stiff element (film of huge viscosity, tiny clearance) can have δF_k larger than the
force itself: the state is "accurate" but the force computed from it — and every multiplier
that carries it, e.g. a crank moment — is noise. :func:`force_resolution` evaluates δF_k;
``jointdyn.simulate`` checks it at a set of output samples and stops with a
:class:`~jointdyn.errors.SimulationError` naming the element instead of returning noise.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from jointdyn.core.layout import TYPE
from jointdyn.core.precompiled import call
from jointdyn.forces.elements import NOUT, film_gap_rows
from jointdyn.forces.journal import JOURNAL
from jointdyn.forces.kernel_set import call_forces

FX, FY = 4, 5  # element output columns of the force on body j (forces.elements.OUT_COLUMNS)


@njit(cache=True)
def force_resolution(t, y, mem, P, rtol, atol, dF, ysc=None):
    """δF_k [N] of every element at (t, y) into dF (nf,) [T111]; ``ysc``: the error test's
    fixed scales (None or 0: |y_j|) [T186]."""
    fint, freal, tables = P.fint, P.freal, P.tables
    nn = y.shape[0]
    n = nn // 2
    nf = fint.shape[0]
    Q = np.zeros(n)
    out0 = np.zeros((nf, NOUT))
    out1 = np.zeros((nf, NOUT))
    call_forces(P.kernels, (t, y[:n], y[n:], mem, fint, freal, tables, Q, out0))
    yp = y.copy()
    dF[:] = 0.0
    for j in range(nn):
        s = abs(y[j])
        if ysc is not None:
            if ysc[j] > 0.0:
                s = ysc[j]
        yp[j] = y[j] + (atol + rtol * s)
        Q[:] = 0.0
        call_forces(P.kernels, (t, yp[:n], yp[n:], mem, fint, freal, tables, Q, out1))
        for k in range(nf):
            dF[k] += np.hypot(out1[k, FX] - out0[k, FX], out1[k, FY] - out0[k, FY])
        yp[j] = y[j]


@njit(cache=True)
def film_gap_unresolved(q, qd, P, rtol, atol, qsc):
    """0, or FILM_BREAKDOWN + k for the first journal bearing without a contact law whose minimum
    film thickness h_min = c − |e| [m] is not larger than the change of |e| a state error at the
    tolerances can make, Σ_j |δ(q + s_j e_j) − δ(q)| with s_j = atol + rtol·|q_j| [T115] (or
    rtol·qsc_j where the error test's fixed scale qsc_j > 0, [T186]; qsc may be empty): the
    integration then cannot tell the film from ξ ≥ 1 (breakdown). rtol = 0: no check."""
    if rtol <= 0.0:
        return 0
    return film_gap_rows(q, qd, P.fint, P.freal, rtol, atol, qsc)  # 0 without journals [T383]


@njit(cache=True)
def worst_resolution(ts, ys, mems, P, rtol, atol, idx, ysc):
    """Over the samples ``idx``: (largest δF_k [N], sample index where it occurs) per element."""
    nf = P.fint.shape[0]
    worst = np.zeros(nf)
    where = np.zeros(nf, dtype=np.int64)
    dF = np.zeros(nf)
    for i in idx:
        force_resolution(ts[i], ys[i], mems[i], P, rtol, atol, dF, ysc)
        for k in range(nf):
            if dF[k] > worst[k]:
                worst[k] = dF[k]
                where[k] = i
    return worst, where


def check_force_resolution(ts, ys, mems, eout, P, rtol, atol, n_check: int = 64, ysc=None):
    """(element index, δF [N], peak |F| [N], time [s]) of the journal element (film, clearance
    contact) whose force is least resolved relative to its peak, checked at ``n_check`` evenly
    spaced samples and at each element's largest-force sample; None if there is no journal
    element or no sample. ``ysc``: the error test's fixed scales (None: |y_j|) [T186]."""
    nt, nf = eout.shape[0], eout.shape[1]
    if nt == 0 or nf == 0:
        return None
    journal = P.fint[:, TYPE] == JOURNAL  # the stiff elements (film, contact) the guard is for
    if not journal.any():
        return None
    F = np.hypot(eout[:, :, FX], eout[:, :, FY])
    idx = np.unique(np.concatenate([np.linspace(0, nt - 1, min(n_check, nt)).astype(np.int64), F.argmax(0)]))
    scale = np.zeros(ys.shape[1]) if ysc is None else ysc  # 0: |y_j|
    worst, where = call(worst_resolution, ts, ys, mems, P, float(rtol), float(atol), idx, scale)  # [T382]
    peak = F.max(0)
    ratio = np.where(peak > 0, worst / np.where(peak > 0, peak, 1.0), 0.0)  # unloaded: nothing to resolve
    ratio = np.where(journal, ratio, -1.0)
    k = int(ratio.argmax())
    return k, float(worst[k]), float(peak[k]), float(ts[where[k]])
