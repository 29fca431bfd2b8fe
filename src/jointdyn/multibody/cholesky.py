"""Dense Cholesky factorisation and substitution in place for the small symmetric positive
definite Schur complement (Φ_q M⁻¹ Φ_qᵀ) of the equations of motion [T10] (compiled; no
allocation)."""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def cholesky_factor(S):
    """In-place lower Cholesky factor of symmetric positive definite S; False if S is not
    positive definite to working precision (pivot ≤ 1e-13 of the largest diagonal entry)."""
    m = S.shape[0]
    scale = 0.0
    for i in range(m):
        scale = max(scale, abs(S[i, i]))
    for j in range(m):
        d = S[j, j]
        for k in range(j):
            d -= S[j, k] * S[j, k]
        if not d > 1e-13 * scale:
            return False
        d = np.sqrt(d)
        S[j, j] = d
        for i in range(j + 1, m):
            s = S[i, j]
            for k in range(j):
                s -= S[i, k] * S[j, k]
            S[i, j] = s / d
    return True


@njit(cache=True)
def cholesky_substitute(Lf, b):
    """Solve L Lᵀ x = b in place (b -> x) with the factor of :func:`cholesky_factor`."""
    m = Lf.shape[0]
    for i in range(m):
        s = b[i]
        for k in range(i):
            s -= Lf[i, k] * b[k]
        b[i] = s / Lf[i, i]
    for i in range(m - 1, -1, -1):
        s = b[i]
        for k in range(i + 1, m):
            s -= Lf[k, i] * b[k]
        b[i] = s / Lf[i, i]


@njit(cache=True)
def cholesky_solve(S, b):
    """Solve S x = b in place for symmetric positive definite S (destroys S, b -> x).

    Returns False if S is not positive definite to working precision."""
    if not cholesky_factor(S):
        return False
    cholesky_substitute(S, b)
    return True
