"""Solvers behind the cavitation conditions of :mod:`.cavitation` on the finite-volume system [T72].

* ``gumbel``: full-film solve M P = b (:func:`full_film`), negative pressures set to ambient afterwards.
* ``reynolds`` (Swift–Stieber): the linear complementarity problem
  P ≥ 0, w = M P − b ≥ 0, Pᵀw = 0, solved by the primal–dual active-set method (Hintermüller,
  Ito & Kunisch, SIAM J. Optim. 13 (2002) 865), finite termination for M-matrices. Convergence
  measure: the active set repeats and the complementarity residual
  r = max_k |min(P_k, w_k)| / max_k |b_k| is at rounding level (reported).
  Nodes in ``fixed`` (e.g. a supply line) are held at P = 0 (Dirichlet). A compiled projected
  SOR (:func:`psor`) solves the same problem by a different algorithm, as an independent check.
"""

from __future__ import annotations

import numpy as np
from numba import njit
from scipy.sparse import csr_matrix
from scipy.sparse.linalg import splu


def full_film(M: csr_matrix, b: np.ndarray, fixed=None) -> np.ndarray:
    """Solution of M P = b with P = 0 on the ``fixed`` nodes (boolean mask or None)."""
    P = np.zeros(b.size)
    free = np.ones(b.size, bool) if fixed is None else ~fixed
    P[free] = splu(M[free][:, free].tocsc()).solve(b[free])
    return P


def residual(M: csr_matrix, b: np.ndarray, P: np.ndarray, fixed=None) -> float:
    """Complementarity residual max|min(P, M P − b)| / max|b| over the non-fixed nodes [-]."""
    r = np.minimum(P, M @ P - b)
    if fixed is not None:
        r = r[~fixed]
    return float(np.max(np.abs(r)) / max(np.max(np.abs(b)), 1e-300))


def solve_lcp(M: csr_matrix, b: np.ndarray, fixed=None, cavitated=None, max_iter: int = 100):
    """Swift–Stieber LCP by the primal–dual active-set method [T72].

    Returns (P ≥ 0, cavitated mask, iterations). ``cavitated``: optional start guess (warm
    start); default the set where the full film is negative. Raises RuntimeError on no
    convergence (not observed: M is an M-matrix)."""
    n = b.size
    fx = np.zeros(n, bool) if fixed is None else np.asarray(fixed, bool)
    if cavitated is None:
        cav = full_film(M, b, fx) < 0.0
    else:
        cav = np.asarray(cavitated, bool).copy()
    cav |= fx
    for it in range(1, max_iter + 1):
        P = full_film(M, b, cav)
        w = M @ P - b
        # an active node stays active while its multiplier w ≥ 0; a free node leaves when P < 0
        new = np.where(cav, ~(w < 0.0), P < 0.0) | fx
        if np.array_equal(new, cav):
            return np.maximum(P, 0.0), cav, it
        cav = new
    raise RuntimeError(f"active-set LCP did not converge in {max_iter} iterations")


@njit(cache=True)
def _psor_csr(indptr, indices, data, b, P, fixed, omega, tol, max_sweeps):
    """Projected SOR sweeps in place; returns the sweep count, −1 if not converged."""
    n = b.size
    for sweep in range(max_sweeps):
        dmax = 0.0
        pmax = 0.0
        for i in range(n):
            if fixed[i]:
                continue
            s = b[i]
            d = 1.0
            for kk in range(indptr[i], indptr[i + 1]):
                j = indices[kk]
                if j == i:
                    d = data[kk]
                else:
                    s -= data[kk] * P[j]
            new = max(0.0, P[i] + omega * (s / d - P[i]))
            dmax = max(dmax, abs(new - P[i]))
            P[i] = new
            pmax = max(pmax, new)
        if dmax <= tol * pmax:
            return sweep + 1
    return -1


def psor(
    M: csr_matrix, b: np.ndarray, fixed=None, omega: float = 1.9, tol: float = 1e-14, max_sweeps: int = 200000
):
    """Projected SOR (Cryer, SIAM J. Control 9 (1971) 385) for the same LCP as :func:`solve_lcp`:
    an independent check [T72]. Stops when the largest update per sweep is ≤ tol·max P.
    Returns (P, sweeps); RuntimeError if not converged."""
    M = csr_matrix(M)
    fx = np.zeros(b.size, np.bool_) if fixed is None else np.asarray(fixed, np.bool_)
    P = np.zeros(b.size)
    n = _psor_csr(M.indptr, M.indices, M.data, np.asarray(b, float), P, fx, omega, tol, max_sweeps)
    if n < 0:
        raise RuntimeError(f"PSOR did not converge in {max_sweeps} sweeps")
    return P, n


@njit(cache=True)
def _masked_band_solve(band, zero, b, R, x):
    """x = solution of M x = b with x = 0 on ``zero`` (rows/columns replaced by the identity),
    M symmetric positive definite in upper band storage band[q, d] = M[q, q+d]: right-looking
    banded Cholesky M = RᵀR in the work array R (rank-1 updates of contiguous rows), then two
    triangular solves; O(N·u²) [T89]."""
    n, w = band.shape
    for j in range(n):
        for d in range(w):
            i = j + d
            if i >= n or ((zero[j] or zero[i]) and d > 0):
                R[j, d] = 0.0
            elif zero[j]:
                R[j, d] = 1.0
            else:
                R[j, d] = band[j, d]
    for j in range(n):
        r0 = np.sqrt(R[j, 0])
        R[j, 0] = r0
        m = min(w, n - j)
        for d in range(1, m):
            R[j, d] /= r0
        for d1 in range(1, m):
            f = R[j, d1]
            if f != 0.0:
                row = j + d1
                for d2 in range(d1, m):
                    R[row, d2 - d1] -= f * R[j, d2]
    for j in range(n):  # Rᵀ y = b, column-oriented
        x[j] = 0.0 if zero[j] else b[j]
    for j in range(n):
        x[j] /= R[j, 0]
        xj = x[j]
        for d in range(1, min(w, n - j)):
            x[j + d] -= R[j, d] * xj
    for j in range(n - 1, -1, -1):  # R x = y
        s = x[j]
        for d in range(1, min(w, n - j)):
            s -= R[j, d] * x[j + d]
        x[j] = s / R[j, 0]


@njit(cache=True)
def _band_matvec(band, x, y):
    """y = M x for symmetric M in upper band storage."""
    n, w = band.shape
    for i in range(n):
        y[i] = 0.0
    for i in range(n):
        y[i] += band[i, 0] * x[i]
        for d in range(1, min(w, n - i)):
            y[i] += band[i, d] * x[i + d]
            y[i + d] += band[i, d] * x[i]


@njit(cache=True)
def _active_set_banded(band, b, fixed, cav, max_iter):
    """The active-set iteration of :func:`solve_lcp` on the band form (permuted order); ``cav``
    is the start set (updated in place). Returns (P, iterations), iterations = −1 if not
    converged."""
    n, w = band.shape
    R = np.empty((n, w))
    P = np.empty(n)
    Mp = np.empty(n)
    for it in range(1, max_iter + 1):
        _masked_band_solve(band, cav, b, R, P)
        _band_matvec(band, P, Mp)
        same = True
        for k in range(n):
            new = fixed[k] or (not (Mp[k] - b[k] < 0.0) if cav[k] else P[k] < 0.0)
            if new != cav[k]:
                same = False
                cav[k] = new
        if same:
            for k in range(n):
                P[k] = max(P[k], 0.0)
            return P, it
    return P, -1


def solve_lcp_banded(prob, b: np.ndarray, fixed=None, cavitated=None, max_iter: int = 100):
    """:func:`solve_lcp` for an assembled problem (``prob`` from :func:`.fv.assemble`), compiled
    on the band form of M (:func:`.fv.band_form`): the same primal–dual active-set iteration and
    result (to rounding), 3–4× less CPU per iteration than a sparse LU of the reduced matrix
    [T72, T89]. Returns (P ≥ 0, cavitated mask, iterations); RuntimeError on no convergence."""
    n = b.size
    perm = prob.perm
    fx = np.zeros(n, np.bool_) if fixed is None else np.asarray(fixed, np.bool_)
    fxp = fx[perm]
    bp = np.ascontiguousarray(b[perm], dtype=float)
    if cavitated is None:  # start: where the full film is negative
        R = np.empty(prob.band.shape)
        P0 = np.empty(n)
        _masked_band_solve(prob.band, fxp.copy(), bp, R, P0)
        cav = (P0 < 0.0) | fxp
    else:
        cav = np.asarray(cavitated, np.bool_)[perm] | fxp
    Pp, it = _active_set_banded(prob.band, bp, fxp, cav, max_iter)
    if it < 0:
        raise RuntimeError(f"active-set LCP did not converge in {max_iter} iterations")
    P = np.empty(n)
    P[perm] = Pp
    mask = np.empty(n, np.bool_)
    mask[perm] = cav
    return P, mask, it
