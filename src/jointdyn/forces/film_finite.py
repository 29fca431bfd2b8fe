"""Finite-length journal bearing for use inside a simulation: a table of dimensionless force
coefficients from the 2-D Reynolds solver (``jointdyn.reynolds_fd``), interpolated by a compiled
kernel [T47–T49].

Homogeneity [T47]: for Gümbel and for Reynolds (Swift–Stieber) cavitation the film force is
positively homogeneous of degree 1 in (A, B) = (ξ̇, ξΩ/(2+ξ²)), so with ρ = √(A²+B²) and
ψ = atan2(A, B)

    F = k·ρ·f(ξ, ψ),   k = μLR³/c²,   f = (f_r, f_t) dimensionless, per L/D and cavitation.

Table [T48]: f̃ = (1−ξ²)^{3/2}·f on n_xi values of ξ uniform in u = −ln(1−ξ) from 0 to
ξ_max = 0.98 (clustered toward the wall) × n_psi values of ψ uniform on [−π, π) (periodic).
(1−ξ²)^{-3/2} is the order of the film force as ξ → 1 for any finite L/D (the pressure zone,
of width ~R√(1−ξ), becomes long compared with nothing but L: locally a long-bearing squeeze
film, spec §5), so f̃ stays bounded and varies like e^{±u}, which a cubic in u follows closely.
Kernel [T49]: bicubic Catmull–Rom (C¹) in (u, ψ), periodic in ψ, linear ghost values at the
u ends; above ξ_max the edge value of f̃ is used with the (1−ξ²)^{-3/2} law (extrapolation).

Array layout (the kernel receives only the array): shape (1 + n_xi, n_psi, 2), float64,
C-contiguous. Row 0 is a header, flat[0..8] = (MAGIC, n_xi, n_psi, ξ_max, L/D, cavitation code
(0 gumbel, 1 reynolds), n_theta, n_zeta, FORMAT); rows 1.. hold f̃[a, b, (r, t)]. The kernel reads
the flat buffer, so ``table.reshape(-1, 2)`` (the (rows, 2) slices the simulator stacks) works
unchanged.
"""

from __future__ import annotations

import hashlib
import math
import os
import time
from pathlib import Path

import numpy as np
from numba import njit

from ..reynolds_fd import DEFAULT_MESH, unit_coefficients

XI_MAX = 0.98  #: largest tabulated ξ [-]
MAGIC = 7391.0  #: header tag of a finite-bearing table [-]
FORMAT = 2.0  #: table format version [-]
CAVITATION_CODES = {"gumbel": 0, "reynolds": 1}
DEFAULT_TABLE = {"gumbel": dict(n_xi=48, n_psi=128), "reynolds": dict(n_xi=32, n_psi=96)}


def cache_dir() -> Path:
    """Cache directory of the tables: $JOINTDYN_CACHE, else $XDG_CACHE_HOME/jointdyn/finite_tables,
    else ~/.cache/jointdyn/finite_tables."""
    env = os.environ.get("JOINTDYN_CACHE")
    if env:
        return Path(env)
    return Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "jointdyn" / "finite_tables"


def table_grid(table: np.ndarray):
    """(ξ grid (n_xi,), ψ grid (n_psi,), header dict) of a table [-, rad]."""
    flat = np.asarray(table).reshape(-1)
    if flat[0] != MAGIC:
        raise ValueError("not a finite-bearing table (bad header)")
    n_xi, n_psi = int(flat[1]), int(flat[2])
    xmax = float(flat[3])
    u = np.linspace(0.0, -math.log1p(-xmax), n_xi)
    psi = -np.pi + 2.0 * np.pi * np.arange(n_psi) / n_psi
    cav = {v: k for k, v in CAVITATION_CODES.items()}[int(flat[5])]
    meta = dict(n_xi=n_xi, n_psi=n_psi, xi_max=xmax, L_over_D=float(flat[4]), cavitation=cav,
                n_theta=int(flat[6]), n_zeta=int(flat[7]), format=float(flat[8]))
    return -np.expm1(-u), psi, meta


def _row(args):
    xi, lod, psi, cavitation, n_theta, n_zeta = args
    f = unit_coefficients(xi, lod, psi, cavitation, n_theta, n_zeta)
    return f * ((1.0 - xi) * (1.0 + xi)) ** 1.5


def build_finite_table(
    L_over_D: float,
    cavitation: str = "gumbel",
    n_xi=None,
    n_psi=None,
    mesh=DEFAULT_MESH,
    cache: bool = True,
    workers=None,
) -> np.ndarray:
    """Force-coefficient table for :func:`finite_force` [T48] (layout: module docstring).

    L_over_D    bearing length over journal diameter L/D > 0 [-]
    cavitation  "gumbel" (half-Sommerfeld) or "reynolds" (Swift–Stieber)
    n_xi        ξ values, uniform in −ln(1−ξ) on [0, 0.98] (≥ 4; default 48 gumbel, 32 reynolds) [-]
    n_psi       ψ values, uniform on [−π, π) (≥ 8; default 128 gumbel, 96 reynolds) [-]
    mesh        (n_theta, n_zeta) of the Reynolds solver [-]
    cache       load/save under :func:`cache_dir` (np.save, keyed by all arguments)
    workers     processes for the Reynolds build (default: min(2, CPUs)) [-]

    Build time (2 cores, default sizes, measured): gumbel ≈ 1 s, reynolds ≈ 30 s (see [T48]).
    """
    if not (isinstance(L_over_D, (int, float)) and math.isfinite(L_over_D) and L_over_D > 0):
        raise ValueError(f"L_over_D = {L_over_D!r} [-]: must be > 0")
    if cavitation not in CAVITATION_CODES:
        raise ValueError(f"cavitation must be one of {tuple(CAVITATION_CODES)}; got {cavitation!r}")
    n_xi = int(DEFAULT_TABLE[cavitation]["n_xi"] if n_xi is None else n_xi)
    n_psi = int(DEFAULT_TABLE[cavitation]["n_psi"] if n_psi is None else n_psi)
    if n_xi < 4 or n_psi < 8:
        raise ValueError(f"table needs n_xi >= 4 and n_psi >= 8; got {n_xi}, {n_psi}")
    n_theta, n_zeta = (int(m) for m in mesh)
    key_tuple = (FORMAT, float(L_over_D), cavitation, n_xi, n_psi, n_theta, n_zeta, XI_MAX)
    key = hashlib.sha1(repr(key_tuple).encode()).hexdigest()[:16]
    path = cache_dir() / f"finite_{cavitation}_{key}.npy"
    if cache and path.exists():
        try:
            tab = np.load(path)
            if tab.shape == (1 + n_xi, n_psi, 2) and tab.reshape(-1)[0] == MAGIC:
                return tab
        except (OSError, ValueError):
            pass
    t0 = time.perf_counter()
    u = np.linspace(0.0, -math.log1p(-XI_MAX), n_xi)
    xis = -np.expm1(-u)
    psi = -np.pi + 2.0 * np.pi * np.arange(n_psi) / n_psi
    jobs = [(float(x), float(L_over_D), psi, cavitation, n_theta, n_zeta) for x in xis]
    if workers is None:
        workers = min(2, os.cpu_count() or 1) if cavitation == "reynolds" else 1
    if workers > 1:
        from concurrent.futures import ProcessPoolExecutor

        with ProcessPoolExecutor(max_workers=workers) as ex:
            rows = list(ex.map(_row, jobs))
    else:
        rows = [_row(j) for j in jobs]
    tab = np.zeros((1 + n_xi, n_psi, 2))
    head = tab[0].reshape(-1)
    head[:9] = (MAGIC, n_xi, n_psi, XI_MAX, L_over_D, CAVITATION_CODES[cavitation], n_theta, n_zeta, FORMAT)
    tab[1:] = np.array(rows)
    build_finite_table.last_build_seconds = time.perf_counter() - t0
    if cache:
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            tmp = path.with_name(f"{path.stem}.{os.getpid()}.npy")
            np.save(tmp, tab)
            os.replace(tmp, path)
        except OSError:
            pass
    return tab


build_finite_table.last_build_seconds = float("nan")


@njit(cache=True)
def _catmull_rom(p0, p1, p2, p3, w):
    """Cubic Catmull–Rom interpolation between p1 and p2 at w ∈ [0, 1] (C¹ across cells) [T49]."""
    return p1 + 0.5 * w * (p2 - p0 + w * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3 + w * (3.0 * (p1 - p2) + p3 - p0)))


@njit(cache=True)
def _col(flat, off, ai, n_psi, b, wb, comp):
    """Catmull–Rom value in ψ of row ai of the table [T49]."""
    base = off + ai * n_psi * 2 + comp
    return _catmull_rom(
        flat[base + ((b - 1) % n_psi) * 2],
        flat[base + (b % n_psi) * 2],
        flat[base + ((b + 1) % n_psi) * 2],
        flat[base + ((b + 2) % n_psi) * 2],
        wb,
    )


@njit(cache=True)
def _interp(flat, off, n_xi, n_psi, a, wa, b, wb, comp):
    """Bicubic Catmull–Rom value of component ``comp`` in cell (a, b) at weights (wa, wb) [T49]."""
    c1 = _col(flat, off, a, n_psi, b, wb, comp)
    c2 = _col(flat, off, a + 1, n_psi, b, wb, comp)
    if a > 0:
        c0 = _col(flat, off, a - 1, n_psi, b, wb, comp)
    else:  # quadratic ghost value beyond the ξ = 0 end (exact for quadratics in u)
        c0 = 3.0 * c1 - 3.0 * c2 + _col(flat, off, 2, n_psi, b, wb, comp)
    if a + 2 <= n_xi - 1:
        c3 = _col(flat, off, a + 2, n_psi, b, wb, comp)
    else:  # same at the ξ_max end
        c3 = 3.0 * c2 - 3.0 * c1 + _col(flat, off, n_xi - 3, n_psi, b, wb, comp)
    return _catmull_rom(c0, c1, c2, c3, wa)


@njit(cache=True)
def finite_force(xi, xi_dot, xi_Omega, mu, R, L, c, table):
    """Tabulated finite-length film force on the journal [T47–T49].

    xi        eccentricity ratio ξ, 0 ≤ ξ < 1 [-]
    xi_dot    ξ̇ [1/s]
    xi_Omega  ξΩ, Ω = ω_J + ω_B − 2γ̇ [rad/s]
    mu        dynamic viscosity [Pa·s]
    R         journal radius [m]
    L         bearing length [m]
    c         radial clearance [m]
    table     array from :func:`build_finite_table` (any shape with the same flat buffer) [-]

    A = ξ̇, B = ξΩ/(2+ξ²), ρ = √(A²+B²), ψ = atan2(A, B), u = −ln(1−ξ)          [T47]
    F = (μLR³/c²)·ρ·f̃(u, ψ)/(1−ξ²)^{3/2}, f̃ bicubic Catmull–Rom (periodic in ψ)  [T49]
    Returns (F_r, F_t) [N]; (0, 0) at ξ̇ = ξΩ = 0; (nan, nan) if ``table`` is not a table.
    The table's L/D is not checked against L/(2R) here (the builder keys it).
    """
    A = xi_dot
    B = xi_Omega / (2.0 + xi * xi)
    rho = math.hypot(A, B)
    if rho == 0.0:
        return 0.0, 0.0
    flat = table.reshape(table.size)
    if flat.size < 9 or flat[0] != MAGIC:
        return math.nan, math.nan
    n_xi = int(flat[1])
    n_psi = int(flat[2])
    xmax = flat[3]
    off = 2 * n_psi
    umax = -math.log1p(-xmax)
    u = -math.log1p(-min(xi, xmax))
    su = u / umax * (n_xi - 1)
    a = min(int(su), n_xi - 2)
    wa = su - a
    psi = math.atan2(A, B)
    sp = (psi + math.pi) / (2.0 * math.pi) * n_psi
    b = int(math.floor(sp))
    wb = sp - b
    res0 = _interp(flat, off, n_xi, n_psi, a, wa, b, wb, 0)
    res1 = _interp(flat, off, n_xi, n_psi, a, wa, b, wb, 1)
    w = (1.0 - xi) * (1.0 + xi)
    s = mu * L * R * R * R / (c * c) * rho / (w * math.sqrt(w))
    return res0 * s, res1 * s


# ---------------------------------------------------------------------------------------------
# Compatibility layer for the previous API (used by film_models.Finite.table and
# tests/test_film_finite.py until the lead rewires them): ``build_table`` returns the new table
# in the (rows, 2) form the simulator stacks; ``solve_unit_pressures``/``unit_forces`` are the
# previous uniform-mesh Gümbel solver, unchanged.


def build_table(L_over_D: float, cavitation: str = "gumbel", cache: bool = True, **kw) -> np.ndarray:
    """:func:`build_finite_table` reshaped to (rows, 2) (same flat buffer; ``finite_force``
    accepts both forms). Extra keywords are passed on (n_xi, n_psi, mesh)."""
    kw = {k: v for k, v in kw.items() if k in ("n_xi", "n_psi", "mesh", "workers")}
    return build_finite_table(L_over_D, cavitation, cache=cache, **kw).reshape(-1, 2)




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



