"""Slow validation: the full Reynolds-condition table of the ``finite`` film (40 × 97 entries,
16 s of CPU time to build) against direct Swift–Stieber solves at random off-grid states [T80]."""

import math

import numpy as np
import pytest

from jointdyn.film import field as fm
from jointdyn.film.finite import build_table, finite_force

NO_PARAMS = np.zeros(1)  # the finite model's own parameter block (none)
MU, R, C, LD = 0.4, 0.01, 5e-4, 2.0


@pytest.mark.slow
def test_reynolds_table_interpolation_error():
    """Measured at L/D = 2 over 30 random states (ξ ∈ [0.05, 0.93], ψ uniform): max 2.1e-4,
    median 2.7e-5 relative to |F| against solves on the builder's mesh; bound 5e-4 (the
    Gümbel table's measured bicubic error is 1.4e-3, [T37])."""
    tab = build_table(LD, cavitation="reynolds")
    rng = np.random.default_rng(1)
    s = 6 * MU * R**4 / C**2
    errs = []
    for _ in range(30):
        xi, psi = rng.uniform(0.05, 0.93), rng.uniform(-math.pi, math.pi)
        A, B = math.sin(psi), math.cos(psi)
        F = np.array(finite_force(xi, A, B * (2 + xi * xi), MU, R, 2 * R * LD, C, NO_PARAMS, tab))
        d = s * np.array(fm.forces(fm.solve(xi, LD, A, B, "reynolds", False, (96, 12))))
        errs.append(np.linalg.norm(F - d) / np.linalg.norm(d))
    assert max(errs) < 5e-4, max(errs)
