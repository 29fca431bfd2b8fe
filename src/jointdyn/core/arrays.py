"""Element-wise copies for compiled code [T340].

``dst[:] = src`` between arrays in numba-compiled code links numba's shape-mismatch error (an
f-string of both shapes, with integer formatting and string joins) into the function: ≈ 2–3 s of
a first run's compiling for two lines of message that the shapes here never raise. These loops
copy the same values without it.
"""

from __future__ import annotations

from numba import njit


@njit(cache=True)
def copy_vector(dst, src) -> None:
    """dst[i] = src[i] for i < len(src) (dst at least as long)."""
    for i in range(src.shape[0]):
        dst[i] = src[i]


@njit(cache=True)
def copy_matrix(dst, src) -> None:
    """dst[i, j] = src[i, j] over src's shape (dst at least as large)."""
    for i in range(src.shape[0]):
        for j in range(src.shape[1]):
            dst[i, j] = src[i, j]
