"""Finite-length bearing: 2-D Reynolds equation with Gümbel (finite differences) or Reynolds
(Swift–Stieber, finite volumes + LCP, :mod:`jointdyn.bearing`) cavitation, tabulated for use
inside a simulation [T36–T38, T80].

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
from pathlib import Path

import numpy as np
from numba import njit

from jointdyn.core import atomic, interrupts

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


#: default cavitation condition of the ``finite`` film in dynamics: ``gumbel`` (see [T80])
DEFAULT_CAVITATION = "gumbel"


def _builder_hash(cavitation: str = DEFAULT_CAVITATION) -> str:
    """Hash of the table builder's sources (this file, the FV assembly, the LCP solvers, the
    cavitation registry and the module of the condition's class): any change of the builder
    invalidates the cached tables [T80, T88]."""
    from jointdyn.film import cavitation as cv
    from jointdyn.film import fv

    h = hashlib.sha1()
    lcp = Path(__file__).with_name("lcp.py")  # by name: importing it loads scipy.sparse [T372]
    files = [Path(__file__), Path(fv.__file__), lcp, Path(cv.__file__)]
    src = cv.source_file(cavitation)
    if src is not None and src.is_file() and src not in files:
        files.append(src)
    for mod in files:
        h.update(mod.read_bytes())
    return h.hexdigest()[:12]


def _fv_unit(xi: float, lam: float, psi: np.ndarray, cavitation: str, warm=None, mesh=(96, 12)):
    """Columns (f_r, f_t, P̂_max, θ_pmax, θ_rupture, side flow) per ψ for unit (A, B) =
    (sin ψ, cos ψ) with a registered cavitation condition on a periodic film (no supply line),
    and the condition's state per ψ. One solve per ψ on the FV mesh, warm-started from
    ``warm[k]`` (the same ψ at the previous ξ) if given, else from the neighbouring ψ
    (``reynolds``: the active set; 2.2 instead of 3.6 iterations per solve at L/D = 2)
    [T72, T80, T83, T88, T89]."""
    from jointdyn.film.cavitation import condition
    from jointdyn.film.field import end_flux, peak_of, rupture_of
    from jointdyn.film.fv import assemble

    cond = condition(cavitation)

    nt, nz = mesh
    prob = assemble(xi, lam, nt, nz)
    w = 2.0 * prob.area  # both halves of the bearing
    wc = w * np.repeat(np.cos(prob.theta), nz)
    ws = w * np.repeat(np.sin(prob.theta), nz)
    dth = 2.0 * np.pi / nt * prob.dtheta
    H = 1.0 + xi * np.cos(prob.theta)
    z = prob.zeta
    out = np.empty((psi.size, 6))
    cav = None
    states = []
    for k, ps in enumerate(psi):
        s = cond.solve(prob, math.sin(ps), math.cos(ps), None, cav if warm is None else warm[k])
        P, cav = s.P, s.state
        states.append(cav)
        P2 = P.reshape(nt, nz)
        pm, tp = peak_of(prob.theta, P2[:, 0])
        side = end_flux(dth, H, P2[:, -1], P2[:, -2], z[-1] - z[-2], z[-1] - z[-3])
        out[k] = (P @ wc, P @ ws, pm, tp, rupture_of(prob.theta, P2[:, 0], cavitation), side)
    return out, states


def _gumbel_outputs(xi: float, th, zeta, PA, PB, psi: np.ndarray) -> np.ndarray:
    """Columns (P̂_max, θ_pmax, θ_rupture, side flow) per ψ of the clipped FD film [T83]; the
    side flow is the end flux of the clipped field (Gümbel's film is not mass conserving)."""
    from jointdyn.film.field import end_flux, peak_of, rupture_of

    mid = zeta.size // 2  # ζ = 0
    H = 1.0 + xi * np.cos(th)
    dth = np.full(th.size, th[1] - th[0])
    dz = zeta[1] - zeta[0]
    out = np.empty((psi.size, 4))
    for k, ps in enumerate(psi):
        P = np.maximum(math.sin(ps) * PA + math.cos(ps) * PB, 0.0)
        pm, tp = peak_of(th, P[:, mid])
        side = end_flux(dth, H, P[:, -2], P[:, -3], dz, 2.0 * dz)
        out[k] = (pm, tp, rupture_of(th, P[:, mid], "gumbel"), side)
    return out


def build_table(
    L_over_D: float,
    n_xi: int = 40,
    n_psi: int = 97,
    n_theta: int = 180,
    n_zeta: int = 24,
    cache: bool = True,
    cavitation: str = DEFAULT_CAVITATION,
) -> np.ndarray:
    """Table for the ``finite`` kernels, shape (2 + 4·n_xi·n_psi, 2): row 0 = (n_xi, n_psi),
    row 1 = (ξ_max, number of blocks = 4), then four blocks of n_xi·n_psi rows, row-major in
    (ξ, ψ): (f_r, f_t)·(1−ξ²)^{3/2} [T37] (read by :func:`finite_force`), then for
    :func:`finite_outputs` [T83]: (P̂_max, side flow)·(1−ξ²)^{3/2}, (cos, sin) of θ_pmax and
    (cos, sin) of the mid-plane rupture angle. ``cavitation``:
    "gumbel" (FD full film clipped, n_theta × n_zeta cells [T36]) or any other registered
    condition of :mod:`jointdyn.film.cavitation`, e.g. "reynolds" (Swift–Stieber LCP), on the
    FV mesh 96 × 12 of the half bearing [T80, T88]. Cached on disk under
    ~/.cache/jointdyn/finite_tables, keyed by all arguments and a hash of the builder's sources."""
    if not (math.isfinite(L_over_D) and L_over_D > 0):
        raise ValueError(f"L_over_D = {L_over_D!r} [-]: must be > 0")
    from jointdyn.core.compiled import cache_base
    from jointdyn.film.cavitation import check_cavitation

    check_cavitation(cavitation)
    args = (2, L_over_D, n_xi, n_psi, n_theta, n_zeta, XI_MAX, cavitation, _builder_hash(cavitation))
    key = hashlib.sha1(repr(args).encode()).hexdigest()[:16]
    base = cache_base() / "finite_tables"
    f = base / f"{key}.npy"
    if cache and f.exists():
        return np.load(f)
    u = np.linspace(0.0, -math.log(1 - XI_MAX), n_xi)
    xis = 1 - np.exp(-u)
    psi = np.linspace(-np.pi, np.pi, n_psi)
    nb = n_xi * n_psi
    tab = np.zeros((2 + 4 * nb, 2))
    tab[0] = (n_xi, n_psi)
    tab[1] = (XI_MAX, 4.0)
    states = None
    for a, xi in enumerate(xis):
        interrupts.check()  # a CLI's Ctrl-C waited for the whole build (≈ 50 s with reynolds) [T336]
        if cavitation == "gumbel":
            th, zeta, PA, PB = solve_unit_pressures(xi, L_over_D, n_theta, n_zeta)
            fr, ft = unit_forces(th, zeta, PA, PB, psi)
            o = _gumbel_outputs(float(xi), th, zeta, PA, PB, psi)
        else:
            r, states = _fv_unit(float(xi), L_over_D, psi, cavitation, states)
            fr, ft, o = r[:, 0], r[:, 1], r[:, 2:]
        scale = (1 - xi * xi) ** 1.5
        rows = slice(2 + a * n_psi, 2 + (a + 1) * n_psi)
        tab[rows, 0] = fr * scale
        tab[rows, 1] = ft * scale
        rows = slice(2 + nb + a * n_psi, 2 + nb + (a + 1) * n_psi)
        tab[rows, 0] = o[:, 0] * scale
        tab[rows, 1] = o[:, 3] * scale
        for blk, col in ((2, 1), (3, 2)):
            rows = slice(2 + blk * nb + a * n_psi, 2 + blk * nb + (a + 1) * n_psi)
            tab[rows, 0] = np.cos(o[:, col])
            tab[rows, 1] = np.sin(o[:, col])
    if cache:
        try:
            base.mkdir(parents=True, exist_ok=True)
            with atomic.replacing(f) as tmp, open(tmp, "wb") as fh:
                np.save(fh, tab)
        except (OSError, ValueError):
            pass
    return tab


@njit(cache=True)
def _catmull_rom(p0, p1, p2, p3, w):
    """Cubic Catmull–Rom interpolation between p1 and p2 at w ∈ [0, 1] (C¹ across cells)."""
    return p1 + 0.5 * w * (
        p2 - p0 + w * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3 + w * (3.0 * (p1 - p2) + p3 - p0))
    )


@njit(cache=True)
def _psi_row(table, row0, n_psi, b, comp, wb):
    """Catmull–Rom in ψ along the table rows from ``row0`` (one ξ node), cell b, weight wb;
    ψ indices wrap with period n_psi − 1 (the grid holds both −π and π)."""
    m = n_psi - 1
    return _catmull_rom(
        table[row0 + (b - 1) % m, comp],
        table[row0 + b % m, comp],
        table[row0 + (b + 1) % m, comp],
        table[row0 + (b + 2) % m, comp],
        wb,
    )


@njit(cache=True)
def _interp(table, base, comp, n_xi, n_psi, a, wa, b, wb):
    """Bicubic value of column ``comp`` of the block from row ``base`` in cell (a, b) at weights
    (wa, wb) [T37]: Catmull–Rom in ψ on four ξ rows (clamped), linear ghost values beyond the ξ
    ends, then Catmull–Rom in ξ. Scalar temporaries only (no allocation in the RHS)."""
    c0 = _psi_row(table, base + min(max(a - 1, 0), n_xi - 1) * n_psi, n_psi, b, comp, wb)
    c1 = _psi_row(table, base + min(max(a, 0), n_xi - 1) * n_psi, n_psi, b, comp, wb)
    c2 = _psi_row(table, base + min(max(a + 1, 0), n_xi - 1) * n_psi, n_psi, b, comp, wb)
    c3 = _psi_row(table, base + min(max(a + 2, 0), n_xi - 1) * n_psi, n_psi, b, comp, wb)
    if a == 0:  # linear ghost values beyond the ξ ends instead of repeating the edge
        c0 = 2.0 * c1 - c2
    if a + 2 >= n_xi - 1:
        c3 = 2.0 * c2 - c1
    return _catmull_rom(c0, c1, c2, c3, wa)


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
    f0 = _interp(table, 2, 0, n_xi, n_psi, a, wa, b, wb)
    f1 = _interp(table, 2, 1, n_xi, n_psi, a, wa, b, wb)
    s = 6.0 * mu * R * R * R * R / (c * c) * rho / ((1.0 - xi) * (1.0 + xi)) ** 1.5
    return f0 * s, f1 * s


@njit(cache=True)
def _bicubic(table, base, comp, xi, psi):
    """Bicubic (Catmull–Rom) value of column ``comp`` of the block starting at row ``base``, at
    (u = −ln(1−min(ξ, ξ_max)), ψ): the interpolation of :func:`finite_force` [T37]."""
    n_xi = int(table[0, 0])
    n_psi = int(table[0, 1])
    xmax = table[1, 0]
    umax = -math.log(1.0 - xmax)
    u = -math.log(1.0 - min(xi, xmax))
    su = u / umax * (n_xi - 1)
    a = min(int(su), n_xi - 2)
    wa = su - a
    sp = (psi + math.pi) / (2.0 * math.pi) * (n_psi - 1)
    b = min(int(sp), n_psi - 2)
    wb = sp - b
    return _interp(table, base, comp, n_xi, n_psi, a, wa, b, wb)


@njit(cache=True)
def finite_outputs(xi, xi_dot, xi_Omega, mu, R, L, c, p, table):
    """Tabulated film outputs of the ``finite`` model [T83]: (p_max [Pa], θ_pmax [rad],
    θ_rupture [rad] at the mid-plane, θ from the maximum film in [0, 2π), side flow through both
    ends Q_s [m³/s]); p_max and Q_s are homogeneous of degree 1 in (A, B), the angles of degree 0
    (interpolated as (cos, sin)). Same arguments as :func:`finite_force`. (0, nan, nan, 0) at
    rest; all nan for a table without output blocks."""
    A = xi_dot
    B = xi_Omega / (2.0 + xi * xi)
    rho = math.sqrt(A * A + B * B)
    if table[1, 1] < 4.0:
        return math.nan, math.nan, math.nan, math.nan
    if rho == 0.0:
        return 0.0, math.nan, math.nan, 0.0
    nb = int(table[0, 0]) * int(table[0, 1])
    psi = math.atan2(A, B)
    s = rho / ((1.0 - xi) * (1.0 + xi)) ** 1.5
    pm = _bicubic(table, 2 + nb, 0, xi, psi) * s * 6.0 * mu * R * R / (c * c)
    qs = _bicubic(table, 2 + nb, 1, xi, psi) * s * 0.5 * c * R * R
    tp = math.atan2(_bicubic(table, 2 + 2 * nb, 1, xi, psi), _bicubic(table, 2 + 2 * nb, 0, xi, psi))
    tr = math.atan2(_bicubic(table, 2 + 3 * nb, 1, xi, psi), _bicubic(table, 2 + 3 * nb, 0, xi, psi))
    return pm, tp % (2.0 * math.pi), tr % (2.0 * math.pi), qs
