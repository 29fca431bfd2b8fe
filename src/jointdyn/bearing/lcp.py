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
