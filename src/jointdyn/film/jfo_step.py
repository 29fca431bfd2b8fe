"""Compiled backward-Euler step of the transient jfo film [T300, T304]: the same cell balance and
primal–dual active set as :meth:`~jointdyn.film.jfo_transient.TransientFilm.step`, with the
mixed (P | θ_f) system held in general band storage in the zig-zag order of
:func:`~jointdyn.film.fv.band_form` (θ neighbours, the periodic pair included, at most 2·nz
positions apart) and factorised by banded Gaussian elimination without pivoting. No pivoting is
needed: a column of a full cell is a column of M (a symmetric, weakly diagonally dominant
M-matrix), a column of a cavitated cell one of the upwind transport plus 2·area·H/Δt on the
diagonal (column sum 2·area·H/Δt > 0), so the mixed matrix is column diagonally dominant [T304].
O(N·(2·nz)²) per active-set iteration, no Python in the loop: the building block the multibody
right-hand side needs (it runs in the compiled loop).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from jointdyn.film.fv import assemble

#: the active set's dead band: a full cell cavitates at P < −P_TOL·(|ω| + 1 rad/s) [1/s], a
#: cavitated one fills at θ_f > 1 + FILL_TOL; values at round-off (the centred journal of an
#: unloaded film, P ≡ 0) otherwise flip the set forever [T306]
P_TOL = 1e-10
FILL_TOL = 1e-12


@dataclass(frozen=True)
class Geometry:
    """Per-cell data of a uniform bearing mesh in natural order k = i·nz + j: cos θ, sin θ of the
    cells (nt,) and of the faces i+1/2 (nt,), cv (nz,), axial face gaps dzf (nz,), area (N,),
    fixed (N,) bool, pfix (N,) [6μR²/c²·1/s], perm (N,) the zig-zag order, inv its inverse."""

    nt: int
    nz: int
    cn: np.ndarray
    sn: np.ndarray
    cf: np.ndarray
    sf: np.ndarray
    cv: np.ndarray
    dzf: np.ndarray
    area: np.ndarray
    fixed: np.ndarray
    pfix: np.ndarray
    perm: np.ndarray
    inv: np.ndarray

    def args(self) -> tuple:
        return (
            self.nt,
            self.nz,
            self.cn,
            self.sn,
            self.cf,
            self.sf,
            self.cv,
            self.dzf,
            self.area,
            self.fixed,
            self.pfix,
            self.perm,
            self.inv,
        )


def geometry(film) -> Geometry:
    """The :class:`Geometry` of a :class:`~jointdyn.film.jfo_transient.TransientFilm`."""
    nt, nz = film.mesh
    p0 = assemble(0.0, film.ld, nt, nz, kappa=0.0)
    ds = 2.0 * math.pi / nt
    th = np.arange(nt) * ds
    thf = th + 0.5 * ds
    inv = np.empty_like(p0.perm)
    inv[p0.perm] = np.arange(p0.perm.size)
    return Geometry(
        nt,
        nz,
        np.cos(th),
        np.sin(th),
        np.cos(thf),
        np.sin(thf),
        p0.cv.copy(),
        np.diff(p0.zeta),
        p0.area.copy(),
        np.asarray(film.fixed, np.bool_).copy(),
        np.asarray(film.pfix, float).copy(),
        np.asarray(p0.perm, np.int64),
        np.asarray(inv, np.int64),
    )


@njit(cache=True)
def _operators(ex, ey, omega, dt, nt, nz, cn, sn, cf, sf, cv, dzf, area, inv, Mb, Tb, H):
    """M (Poiseuille [T71]) and T (upwind transport + 2·area·H/Δt [T300]) in general band storage
    Xb[q, u + d] = X[perm q, perm(q + d)], u = 2·nz; H (N,) the cell films (natural order)."""
    u = 2 * nz
    Mb[:, :] = 0.0
    Tb[:, :] = 0.0
    ds = 2.0 * math.pi / nt
    for i in range(nt):
        hn = 1.0 - ex * cn[i] - ey * sn[i]
        hf = 1.0 - ex * cf[i] - ey * sf[i]
        hm = 1.0 - ex * cf[i - 1] - ey * sf[i - 1]  # face i−1/2 (i − 1 = −1 wraps)
        ip = (i + 1) % nt
        im = (i - 1) % nt
        for j in range(nz):
            k = i * nz + j
            q = inv[k]
            H[k] = hn
            cth = cv[j] * hf**3 / ds
            cthm = cv[j] * hm**3 / ds
            qp = inv[ip * nz + j]
            qm = inv[im * nz + j]
            Mb[q, u + qp - q] -= cth
            Mb[q, u + qm - q] -= cthm
            czj = ds * hn**3 / dzf[j]
            diag = cth + cthm + czj
            if j < nz - 1:
                Mb[q, u + inv[k + 1] - q] -= czj
            if j > 0:
                czm = ds * hn**3 / dzf[j - 1]
                diag += czm
                Mb[q, u + inv[k - 1] - q] -= czm
            Mb[q, u] += diag
            Tb[q, u] += 2.0 * area[k] * hn / dt
            if omega >= 0.0:
                Tb[q, u] += omega * cv[j] * hf
                Tb[q, u + qm - q] -= omega * cv[j] * hm
            else:
                Tb[q, u + qp - q] += omega * cv[j] * hf
                Tb[q, u] -= omega * cv[j] * hm


@njit(cache=True)
def _band_lu_solve(A, b, x):
    """Solve A x = b in place of A (general band, A[q, u + d], no pivoting)."""
    n, w = A.shape
    u = (w - 1) // 2
    for q in range(n):
        x[q] = b[q]
    row = np.empty(u)  # row j right of the diagonal, copied: the update loop then vectorises
    for j in range(n):
        piv = A[j, u]
        m = min(n, j + u + 1)
        L = m - j - 1
        for c in range(L):
            row[c] = A[j, u + 1 + c]
        xj = x[j]
        for i in range(j + 1, m):
            lij = A[i, u + j - i]
            if lij != 0.0:
                f = lij / piv
                A[i, u + j - i] = f
                Ai = A[i]
                base = u + j + 1 - i
                for c in range(L):
                    Ai[base + c] -= f * row[c]
                x[i] -= f * xj
    for j in range(n - 1, -1, -1):
        s = x[j]
        for c in range(j + 1, min(n, j + u + 1)):
            s -= A[j, u + c - j] * x[c]
        x[j] = s / A[j, u]


@njit(cache=True)
def _bmv(B, x, y):
    """y = B x for general band storage B[q, u + d]."""
    n, w = B.shape
    u = (w - 1) // 2
    for q in range(n):
        s = 0.0
        for d in range(-u, u + 1):
            c = q + d
            if 0 <= c < n:
                s += B[q, u + d] * x[c]
        y[q] = s


@njit(cache=True)
def jfo_step(
    ex, ey, omega, dt, content0, cav, nt, nz, cn, sn, cf, sf, cv, dzf, area, fixed, pfix, perm, inv, max_iter
):
    """Backward-Euler jfo step [T300, T304] to the journal position (ex, ey) = e/c [-] from the
    cell contents ``content0`` = H⁰θ_f⁰ (N,) [-] over dt > 0 [s] at relative rotation ω [rad/s];
    ``cav`` (N,) bool, natural order: the start cavitated set (warm start), updated in place.
    ``max_iter`` = 0 freezes the set: one solve with ``cav`` as given (full cells may then have
    P < 0, cavitated ones θ_f > 1), the film of the multibody stages [T348]. Returns (P (N,)
    [6μR²/c²·1/s], fill θ_f (N,), F_x, F_y [μR⁴/c²·1/s], inflow, side outflow [R²c/s], content
    [R²c], the net outflow of every supply cell (N,) [R²c/s] (0 elsewhere; its sum is the
    inflow) [T376], iterations (−1: no convergence)) as
    :meth:`~jointdyn.film.jfo_transient.TransientFilm.step`."""
    n = nt * nz
    u = 2 * nz
    Mb = np.empty((n, 2 * u + 1))
    Tb = np.empty((n, 2 * u + 1))
    A = np.empty((n, 2 * u + 1))
    H = np.empty(n)
    _operators(ex, ey, omega, dt, nt, nz, cn, sn, cf, sf, cv, dzf, area, inv, Mb, Tb, H)
    # permuted vectors
    b0 = np.empty(n)
    pf = np.empty(n)
    fx = np.empty(n, np.bool_)
    cp = np.empty(n, np.bool_)
    for q in range(n):
        k = perm[q]
        b0[q] = 2.0 * area[k] * content0[k] / dt
        pf[q] = pfix[k] if fixed[k] else 0.0
        fx[q] = fixed[k]
        cp[q] = cav[k] and not fixed[k]
    known = np.empty(n)
    r1 = np.empty(n)
    r2 = np.empty(n)
    rhs = np.empty(n)
    x = np.empty(n)
    P = np.empty(n)
    th = np.empty(n)
    its = -1
    p_tol = P_TOL * (abs(omega) + 1.0)  # round-off of P in a centred, unloaded film [T306]
    frozen = max_iter == 0
    for it in range(1, max(max_iter, 1) + 1):
        for q in range(n):
            known[q] = 0.0 if cp[q] else 1.0
        _bmv(Mb, pf, r1)
        _bmv(Tb, known, r2)
        for q in range(n):
            rhs[q] = 0.0 if fx[q] else b0[q] - r1[q] - r2[q]
            for d in range(-u, u + 1):
                c = q + d
                if c < 0 or c >= n or fx[c] or fx[q]:
                    A[q, u + d] = 0.0
                elif cp[c]:
                    A[q, u + d] = Tb[q, u + d]
                else:
                    A[q, u + d] = Mb[q, u + d]
            if fx[q]:
                A[q, u] = 1.0
        _band_lu_solve(A, rhs, x)
        same = True
        for q in range(n):
            if fx[q]:
                P[q] = pf[q]
                th[q] = 1.0
                continue
            if cp[q]:
                P[q] = 0.0
                th[q] = x[q]
                new = not (th[q] > 1.0 + FILL_TOL)
            else:
                P[q] = x[q]
                th[q] = 1.0
                new = P[q] < -p_tol
            if new != cp[q] and not frozen:
                same = False
                cp[q] = new
        if same:
            its = it
            break
    # outputs [T301]
    _bmv(Mb, P, r1)
    _bmv(Tb, th, r2)
    fxs = 0.0
    fys = 0.0
    inflow = 0.0
    side = 0.0
    content = 0.0
    Pn = np.empty(n)
    fn = np.empty(n)
    net = np.zeros(n)
    for q in range(n):
        k = perm[q]
        i = k // nz
        Pn[k] = P[q]
        fn[k] = th[q]
        cav[k] = cp[q]
        w = 2.0 * area[k] * P[q]
        fxs += w * cn[i]
        fys += w * sn[i]
        side += r1[q]
        if fx[q]:
            net[k] = r1[q] + r2[q] - b0[q]
            inflow += net[k]
        content += 2.0 * area[k] * H[k] * th[q]
    return Pn, fn, -6.0 * fxs, -6.0 * fys, inflow, side, content, net, its


@njit(cache=True)
def couette_gas(fill, H, area, cv, dzf):
    """Σ_k (1 − θ_f,k)·w_k/H_k [-] over the cells (natural order k = i·nz + j, nz = cv.size): the
    part of the Couette integral ∫∫dθ dζ/H over both halves that the gas of partly filled cells
    does not carry (striated flow: the lubricant spans the gap over the fraction θ_f of the
    width). w_k = 2·area_k, the last row's widened by the end half-cell 0.5·dzf[nz−1] beyond it,
    which takes its row's fill. 0 for a full film [T375]."""
    nz = cv.size
    end = 1.0 + 0.5 * dzf[nz - 1] / cv[nz - 1]
    s = 0.0
    for k in range(fill.size):
        g = 1.0 - fill[k]
        if g != 0.0:
            w = 2.0 * area[k] * (end if k % nz == nz - 1 else 1.0)
            s += g * w / H[k]
    return s


def step(geom: Geometry, e, omega: float, dt: float, content0, cav, max_iter: int = 200) -> tuple:
    """:func:`jfo_step` with its input checked (the compiled kernel itself checks nothing):
    ValueError naming the parameter for dt ≤ 0 [s], |e|/c ≥ 1 [-], a non-finite ω [rad/s] or
    arrays of the wrong size; RuntimeError if the active set does not settle in ``max_iter``."""
    n = geom.nt * geom.nz
    if not (math.isfinite(dt) and dt > 0.0):
        raise ValueError(f"dt = {dt!r} [s]: must be finite and > 0")
    ex, ey = (float(v) for v in e)
    if not math.hypot(ex, ey) < 1.0:
        raise ValueError(f"journal position |e|/c = {math.hypot(ex, ey)!r} [-]: must be < 1")
    if not math.isfinite(omega):
        raise ValueError(f"omega = {omega!r} [rad/s]: must be finite")
    c0 = np.ascontiguousarray(content0, dtype=float)
    if c0.shape != (n,) or not np.all(np.isfinite(c0)) or np.any(c0 < 0.0):
        raise ValueError(f"content0: needs {n} finite cell contents >= 0 [-] (H·θ_f of the mesh)")
    if not (isinstance(cav, np.ndarray) and cav.dtype == np.bool_ and cav.shape == (n,)):
        raise ValueError(f"cav: needs a bool array of {n} cells (updated in place)")
    out = jfo_step(ex, ey, float(omega), float(dt), c0, cav, *geom.args(), int(max_iter))
    if out[-1] < 0:
        raise RuntimeError(f"transient jfo active set did not settle in {max_iter} iterations")
    return out
