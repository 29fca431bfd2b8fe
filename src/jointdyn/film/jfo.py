"""Mass-conserving (JFO / Elrod–Adams) film on the finite-volume problem [T240–T243].

Unknowns per cell: pressure P ≥ 0 and fill fraction θ_f ≤ 1 (lubricant content / clearance
volume), complementary, P·(1 − θ_f) = 0. Cell balance (net outflow = 0), conservative, with the
Couette flux upwinded (Ω > 0: from cell i to i+1 through face i+1/2 carrying Ω·H_(i+1/2)·θ_f,i):

    (M P)_k + Ω·cv_j·(H_(i+1/2) θ_f,i − H_(i−1/2) θ_f,i−1) + 2ξ̇ cos(θ_i − phase)·area_k·θ_f,k = 0

(M the Poiseuille operator of [T71], Ω = B(2+ξ²)/ξ; θ_f ≡ 1 turns it into the Reynolds equation
of [T70] with the Couette source integrated exactly over the cell). Steady: the squeeze term
takes the content as frozen (∂θ_f/∂t = 0), so ξ̇ acts on the full film and on the content of the
cavitated cells alike [T242]. Solved by a primal–dual active-set iteration on the cavitated set C:
cells in C have P = 0 and unknown θ_f, the others θ_f = 1 and unknown P; one sparse LU of the
mixed (non-symmetric) system per iteration; a cell leaves the full set when P < 0, leaves C when
θ_f > 1; stop when C repeats. Convergence measure: the largest cell imbalance relative to the
largest Couette flux, and max |min(P, 1 − θ_f)| relative to max P [T243].
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:  # scipy.sparse (≈ 0.2 s to import with its linalg) only where a film is solved [T372]
    from scipy.sparse import csr_matrix


def transport(prob, A: float, B: float, omega=None) -> csr_matrix:
    """G with G θ_f = Couette + squeeze outflow of every cell (N×N) for the rates (A, B) [T241]
    (``omega``: the sliding speed Ω directly, for problems that are not a journal [T250])."""
    xi = prob.xi
    if omega is None:
        if not xi > 0.0:
            raise ValueError(f"eps = {xi!r} [-]: the jfo film needs eps > 0 (Ω = B(2+ξ²)/ξ)")
        omega = B * (2.0 + xi * xi) / xi
    nt, nz = prob.shape
    cv = prob.cv
    Hf = prob.Hface
    i = np.repeat(np.arange(nt), nz)
    j = np.tile(np.arange(nz), nt)
    k = i * nz + j
    if omega >= 0.0:  # face i+1/2 carries Ω H θ_f,i (outflow of i, inflow of i+1)
        up_out, up_in = k, ((i - 1) % nt) * nz + j
        c_out, c_in = omega * cv[j] * Hf[i], -omega * cv[j] * Hf[(i - 1) % nt]
    else:  # face i+1/2 carries Ω H θ_f,i+1 (inflow of i from i+1, negative outflow)
        up_out, up_in = ((i + 1) % nt) * nz + j, k
        c_out, c_in = omega * cv[j] * Hf[i], -omega * cv[j] * Hf[(i - 1) % nt]
    sq = 2.0 * A * np.cos(prob.theta[i] - prob.phase) * prob.area
    rows = np.concatenate([k, k, k])
    cols = np.concatenate([up_out, up_in, k])
    vals = np.concatenate([c_out, c_in, sq])
    from scipy.sparse import csr_matrix

    N = nt * nz
    return csr_matrix((vals, (rows, cols)), shape=(N, N))


def solve_jfo(prob, A: float, B: float, fixed, pfix=None, cavitated=None, max_iter: int = 200, omega=None):
    """Steady mass-conserving film [T241–T243]: returns (P ≥ 0, θ_f ∈ [0, 1], cavitated set,
    iterations, residual). ``fixed`` (N,) bool: supply cells (θ_f = 1, P = ``pfix`` or 0); at
    least one is needed (a film without a supply has no steady content). RuntimeError if the
    active set does not settle within ``max_iter`` iterations."""
    N = prob.bA.size
    if fixed is None or not np.any(fixed):
        raise ValueError(
            "cavitation = 'jfo': needs a lubricant supply (a feed line or grooves); "
            "the periodic (transient) jfo film is not available"
        )
    from scipy.sparse import csc_matrix, csr_matrix, diags
    from scipy.sparse.linalg import splu

    fx = np.asarray(fixed, bool)
    pf = np.zeros(N) if pfix is None else np.where(fx, np.asarray(pfix, float), 0.0)
    M = csr_matrix(prob.M)
    G = transport(prob, A, B, omega)
    Mc, Gc = csc_matrix(M), csc_matrix(G)
    rows = ~fx
    if cavitated is None:  # start: where the flooded (Reynolds-free) film is negative
        P0 = np.zeros(N)
        rhs = -(G @ np.ones(N)) - M @ pf
        P0[rows] = splu(csc_matrix(M[rows][:, rows])).solve(rhs[rows])
        cav = (P0 < 0.0) & rows
    else:
        cav = np.asarray(cavitated, bool) & rows
    ones = np.ones(N)
    for it in range(1, max_iter + 1):
        full = rows & ~cav
        fill_known = np.where(cav, 0.0, 1.0)
        rhs = -(Mc @ pf) - Gc @ fill_known
        # columns: P of the full cells, θ_f of the cavitated ones (a permutation of the free cells)
        S = (Mc @ diags(full.astype(float)) + Gc @ diags(cav.astype(float))).tocsr()[rows]
        free = np.flatnonzero(rows)
        x = splu(csc_matrix(S[:, free])).solve(rhs[rows])
        P = pf.copy()
        th = ones.copy()
        xf = np.zeros(N)
        xf[free] = x
        P[full] = xf[full]
        th[cav] = xf[cav]
        new = np.where(cav, ~(th > 1.0), P < 0.0) & rows
        if np.array_equal(new, cav):
            P[cav] = 0.0
            return P, th, cav, it, jfo_residual(prob, A, B, P, th, fx, omega)
        cav = new
    raise RuntimeError(f"jfo active set did not settle in {max_iter} iterations")


def cell_balance(prob, A: float, B: float, P: np.ndarray, fill: np.ndarray, omega=None) -> np.ndarray:
    """Net outflow of every cell (N,) [-] for the field (P, θ_f) [T241]: 0 at solved cells."""
    from scipy.sparse import csr_matrix

    return csr_matrix(prob.M) @ P + transport(prob, A, B, omega) @ fill


def jfo_residual(prob, A, B, P, fill, fixed, omega=None) -> float:
    """Convergence measure [T243]: max(cell imbalance / largest Couette flux,
    max|min(P, 1 − θ_f)| / max P) over the non-fixed cells [-]."""
    r = cell_balance(prob, A, B, P, fill, omega)[~fixed]
    scale = max(float(np.max(np.abs(transport(prob, A, B, omega).diagonal()))), 1e-300)
    comp = np.abs(np.minimum(P, 1.0 - fill))[~fixed]
    return float(max(np.max(np.abs(r)) / scale, np.max(comp) / max(float(np.max(P)), 1e-300)))


def flows(prob, A: float, B: float, P: np.ndarray, fill: np.ndarray, fixed: np.ndarray, labels=None) -> dict:
    """Discrete flows of a solved film over the full bearing (both halves) [T244], in units of
    the FV fluxes (physical Q = (R²c/2)·(rate scale)·value, e.g. ωR²c/2 for the steady film):
    ``supply`` net outflow of the supply cells (total and per label of ``labels``, an int array
    (N,) numbering the grooves, −1 elsewhere), ``side`` Poiseuille outflow through both ends,
    ``squeeze`` the content change rate Σ 2ξ̇cos·area·θ_f, ``content`` the film content
    Σ H θ_f·area (both halves) and ``imbalance`` = supply − side − squeeze (round-off)."""
    from scipy.sparse import csr_matrix

    out = 2.0 * cell_balance(prob, A, B, P, fill)
    nt, nz = prob.shape
    MP = csr_matrix(prob.M) @ P
    side = 2.0 * float(np.sum(MP))  # interior faces cancel; what is left leaves through the ends
    sq = 2.0 * float(np.sum(2.0 * A * np.cos(np.repeat(prob.theta, nz) - prob.phase) * prob.area * fill))
    H = 1.0 + prob.xi * np.cos(np.repeat(prob.theta, nz) - prob.phase)
    supply = float(np.sum(out[fixed]))
    res = {
        "supply": supply,
        "side": side,
        "squeeze": sq,
        "content": 2.0 * float(np.sum(H * fill * prob.area)),
        "imbalance": supply - side - sq,
    }
    if labels is not None:
        res["per_groove"] = [float(np.sum(out[labels == g])) for g in range(int(labels.max()) + 1)]
    return res


def omega_of(xi: float, B: float) -> float:
    """Ω = B(2+ξ²)/ξ [rate] (ξ > 0)."""
    return B * (2.0 + xi * xi) / xi if xi > 0 else math.nan
