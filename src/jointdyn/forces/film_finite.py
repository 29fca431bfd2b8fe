"""Finite-length bearing: 2-D Reynolds equation by finite differences, Gümbel cavitation,
tabulated for use inside a simulation [T36–T38].

Nondimensional form (θ from the maximum film, ζ = z/R ∈ [−λ, λ], λ = L/D, H = 1 + ξ cos θ):
∂/∂θ(H³ ∂P/∂θ) + ∂/∂ζ(H³ ∂P/∂ζ) = S(θ), P = 0 at ζ = ±λ, periodic in θ. The pressure is
p = (6μR²/c²)(A·P_A + B·P_B) with A = ξ̇, B = ξΩ/(2+ξ²), S_A = 2 cos θ, S_B = −(2+ξ²) sin θ
([T20] with the axial term). Gümbel (half-Sommerfeld) cavitation clips p < 0, so the force is
positively homogeneous of degree 1 in (A, B): **F = (6μR⁴/c²)·ρ·f(ξ, ψ)**, ρ = √(A²+B²),
ψ = atan2(A, B), f = ∫∫ max(sin ψ P_A + cos ψ P_B, 0)(cos θ, sin θ) dθ dζ [T36]. The table holds
f·(1−ξ²)^{3/2} on a grid uniform in u = −ln(1−ξ) and ψ, interpolated bicubically [T37].
"""

from __future__ import annotations

import hashlib
import math
import os
from pathlib import Path

import numpy as np
from numba import njit

XI_MAX = 0.95  # table range; beyond it the force is extrapolated with the (1−ξ²)^{-3/2} scaling


def solve_unit_pressures(xi: float, lam: float, n_theta: int = 180, n_zeta: int = 24):
    """Full-film unit pressures P_A, P_B on the (θ, ζ) grid by conservative finite differences
    (sparse LU) [T36]. Returns θ (n_theta,), ζ (n_zeta+1,), P_A, P_B (n_theta, n_zeta+1)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.linalg import splu

    th = (np.arange(n_theta) + 0.0) * 2 * np.pi / n_theta
    dth = 2 * np.pi / n_theta
    zeta = np.linspace(-lam, lam, n_zeta + 1)
    dz = zeta[1] - zeta[0]
    H = 1 + xi * np.cos(th)
    Hp = (1 + xi * np.cos(th + dth / 2)) ** 3  # H³ at i+1/2
    Hm = (1 + xi * np.cos(th - dth / 2)) ** 3
    nz = n_zeta - 1  # interior ζ nodes
    idx = lambda i, j: (i % n_theta) * nz + j  # noqa: E731
    rows, cols, vals = [], [], []
    for i in range(n_theta):
        for j in range(nz):
            k = idx(i, j)
            diag = -(Hp[i] + Hm[i]) / dth**2 - 2 * H[i] ** 3 / dz**2
            rows += [k, k, k]
            cols += [k, idx(i + 1, j), idx(i - 1, j)]
            vals += [diag, Hp[i] / dth**2, Hm[i] / dth**2]
            for jj in (j - 1, j + 1):
                if 0 <= jj < nz:
                    rows.append(k)
                    cols.append(idx(i, jj))
                    vals.append(H[i] ** 3 / dz**2)
    n = n_theta * nz
    M = coo_matrix((vals, (rows, cols)), shape=(n, n)).tocsc()
    lu = splu(M)
    out = []
    for S in (2 * np.cos(th), -(2 + xi * xi) * np.sin(th)):
        rhs = np.repeat(S, nz)
        P = np.zeros((n_theta, n_zeta + 1))
        P[:, 1:-1] = lu.solve(rhs).reshape(n_theta, nz)
        out.append(P)
    return th, zeta, out[0], out[1]


def unit_forces(th, zeta, PA, PB, psi):
    """f(ξ, ψ) = ∫∫ max(sinψ P_A + cosψ P_B, 0)(cos θ, sin θ) dθ dζ (trapezoid in ζ) [T36]."""
    dth = th[1] - th[0]
    wz = np.full(zeta.size, zeta[1] - zeta[0])
    wz[[0, -1]] *= 0.5
    p = np.maximum(np.sin(psi)[:, None, None] * PA + np.cos(psi)[:, None, None] * PB, 0.0)
    sp = (p * wz).sum(axis=2) * dth  # (n_psi, n_theta)
    return sp @ np.cos(th), sp @ np.sin(th)


def build_table(
    L_over_D: float, n_xi: int = 40, n_psi: int = 97, n_theta: int = 180, n_zeta: int = 24, cache: bool = True
) -> np.ndarray:
    """Table for the ``finite`` kernel, shape (2 + n_xi·n_psi, 2): row 0 = (n_xi, n_psi),
    row 1 = (ξ_max, 0), then (f_r, f_t)·(1−ξ²)^{3/2} row-major in (ξ, ψ) [T37]. Cached on disk
    under ~/.cache/jointdyn (keyed by all arguments)."""
    if not (math.isfinite(L_over_D) and L_over_D > 0):
        raise ValueError(f"L_over_D = {L_over_D!r} [-]: must be > 0")
    key = hashlib.sha1(repr((1, L_over_D, n_xi, n_psi, n_theta, n_zeta, XI_MAX)).encode()).hexdigest()[:16]
    base = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "jointdyn" / "finite_tables"
    f = base / f"{key}.npy"
    if cache and f.exists():
        return np.load(f)
    u = np.linspace(0.0, -math.log(1 - XI_MAX), n_xi)
    xis = 1 - np.exp(-u)
    psi = np.linspace(-np.pi, np.pi, n_psi)
    tab = np.zeros((2 + n_xi * n_psi, 2))
    tab[0] = (n_xi, n_psi)
    tab[1] = (XI_MAX, 0.0)
    for a, xi in enumerate(xis):
        th, zeta, PA, PB = solve_unit_pressures(xi, L_over_D, n_theta, n_zeta)
        fr, ft = unit_forces(th, zeta, PA, PB, psi)
        scale = (1 - xi * xi) ** 1.5
        tab[2 + a * n_psi : 2 + (a + 1) * n_psi, 0] = fr * scale
        tab[2 + a * n_psi : 2 + (a + 1) * n_psi, 1] = ft * scale
    if cache:
        try:
            base.mkdir(parents=True, exist_ok=True)
            tmp = base / f"{key}.{os.getpid()}.npy"
            np.save(tmp, tab)
            os.replace(tmp, f)
        except OSError:
            pass
    return tab


@njit(cache=True)
def _catmull_rom(p0, p1, p2, p3, w):
    """Cubic Catmull–Rom interpolation between p1 and p2 at w ∈ [0, 1] (C¹ across cells)."""
    return p1 + 0.5 * w * (
        p2 - p0 + w * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3 + w * (3.0 * (p1 - p2) + p3 - p0))
    )


@njit(cache=True)
def finite_force(xi, xi_dot, xi_Omega, mu, R, L, c, p, table):
    """Tabulated finite-length film force [T37]: F = (6μR⁴/c²)·ρ·f(ξ, ψ), bicubic (Catmull–Rom,
    C¹; periodic in ψ, end-clamped in u) in (u = −ln(1−ξ), ψ) on f·(1−ξ²)^{3/2}; for ξ > ξ_max
    the table edge is used with the (1−ξ²)^{-3/2} scaling (an extrapolation, see docs/theory.md)."""
    A = xi_dot
    B = xi_Omega / (2.0 + xi * xi)
    rho = math.sqrt(A * A + B * B)
    if rho == 0.0:
        return 0.0, 0.0
    n_xi = int(table[0, 0])
    n_psi = int(table[0, 1])
    xmax = table[1, 0]
    umax = -math.log(1.0 - xmax)
    u = -math.log(1.0 - min(xi, xmax))
    su = u / umax * (n_xi - 1)
    a = min(int(su), n_xi - 2)
    wa = su - a
    psi = math.atan2(A, B)
    sp = (psi + math.pi) / (2.0 * math.pi) * (n_psi - 1)
    b = min(int(sp), n_psi - 2)
    wb = sp - b
    out = np.zeros(2)
    for comp in range(2):
        col = np.zeros(4)
        for i in range(4):
            ai = min(max(a - 1 + i, 0), n_xi - 1)
            v = np.zeros(4)
            for j in range(4):
                # ψ grid includes both −π and π (same value): period n_psi − 1
                bj = (b - 1 + j) % (n_psi - 1)
                v[j] = table[2 + ai * n_psi + bj, comp]
            col[i] = _catmull_rom(v[0], v[1], v[2], v[3], wb)
        if a == 0:  # linear ghost values beyond the ξ ends instead of repeating the edge
            col[0] = 2.0 * col[1] - col[2]
        if a + 2 >= n_xi - 1:
            col[3] = 2.0 * col[2] - col[1]
        out[comp] = _catmull_rom(col[0], col[1], col[2], col[3], wa)
    s = 6.0 * mu * R * R * R * R / (c * c) * rho / ((1.0 - xi) * (1.0 + xi)) ** 1.5
    return out[0] * s, out[1] * s
