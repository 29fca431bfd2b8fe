"""2-D finite-volume Reynolds solver for a finite-length journal bearing, with Gümbel
(half-Sommerfeld) or Reynolds (Swift–Stieber) cavitation [T45–T46].

Equation (spec §1 conventions: θ from the maximum film, h = c(1 + ξ cos θ),
Ω = ω_J + ω_B − 2γ̇, z ∈ [−L/2, L/2])

    ∂/∂θ(h³ ∂p/∂θ)/R² + ∂/∂z(h³ ∂p/∂z) = 6μ[Ω ∂h/∂θ + 2cξ̇ cos θ],  p(θ, ±L/2) = 0, 2π-periodic.

Nondimensional form [T45]: ζ = z/R ∈ [−λ, λ] (λ = L/D), H = 1 + ξ cos θ,
p = (6μR²/c²)·P, A = ξ̇, B = ξΩ/(2+ξ²):

    ∂/∂θ(H³ ∂P/∂θ) + ∂/∂ζ(H³ ∂P/∂ζ) = A·2cos θ − B·(2+ξ²) sin θ.

Discretisation: cell-centred conservative finite volumes on a **mapped** periodic θ grid
θ = Θ_κ(s), s uniform, Θ_κ the inverse Sommerfeld map tan(s/2) = √((1−κ)/(1+κ))·tan(θ/2) with
κ = 0.85ξ (cells shrink by √((1−κ)/(1+κ)) at the minimum film θ = π); vertex-centred in ζ on
half the bearing ζ ∈ [0, λ] (symmetry ∂P/∂ζ = 0 at ζ = 0, P = 0 at ζ = λ) with
ζ = λ·tanh(βη)/tanh β, η uniform, β = 0.8·ln(1+λ) (finer cells toward the end, where the
long-bearing pressure drops to ambient). The matrix M (= −discrete operator) is a symmetric
M-matrix. Second order in both directions for the full film.

Cavitation [T46]:
* ``"gumbel"``: full-film solve M P = b (sparse LU), then p < 0 is set to 0 in the force
  integral (half-Sommerfeld, not mass conserving).
* ``"reynolds"``: Swift–Stieber as the linear complementarity problem
  P ≥ 0, w = M P − b ≥ 0, Pᵀw = 0 (the discrete obstacle problem), solved exactly by the
  primal–dual active-set method (Hintermüller, Ito & Kunisch, SIAM J. Optim. 13 (2002) 865):
  each iteration a sparse LU on the current pressurised set; finite convergence for M-matrices.
  A projected SOR (Cryer 1971) is provided as an independent check (``psor``).

Forces on the journal (spec §1: F_r along u = e/|e|, F_t along t = ẑ × u):
F = R²∫∫ p (cos θ, sin θ) dθ dζ over the full bearing, evaluated with the finite-volume weights.

Both conditions make the force positively homogeneous of degree 1 in (A, B): the linear
solve is linear, clipping and the LCP commute with scaling by s > 0 [T47].
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit
from scipy.sparse import csr_matrix
from scipy.sparse.linalg import splu

CAVITATION = ("gumbel", "reynolds")
#: default mesh: cells in θ (full circle), cells in ζ (half bearing) [-]
DEFAULT_MESH = (144, 16)


@dataclass(frozen=True)
class FDProblem:
    """Discretised Reynolds problem for one (ξ, λ, mesh): M P = A·bA + B·bB.

    theta  node angles θ_i (n_theta,) [rad]
    zeta   node axial coordinates ζ_j = z/R on the half bearing, incl. the end ζ = λ (n_zeta+1,) [-]
    M      symmetric M-matrix (N×N, CSR), N = n_theta·n_zeta, unknown k = i·n_zeta + j [-]
    bA     right-hand side for A = 1 (N,) [-]
    bB     right-hand side for B = 1 (N,) [-]
    wcos   force weights: ∫∫P cos θ dθ dζ over the full bearing = wcos·P (N,) [-]
    wsin   same for sin θ (N,) [-]
    """

    xi: float
    lam: float
    theta: np.ndarray
    zeta: np.ndarray
    M: csr_matrix
    bA: np.ndarray
    bB: np.ndarray
    wcos: np.ndarray
    wsin: np.ndarray


def theta_map(s, kappa):
    """Mapped angle θ = Θ_κ(s) ∈ [0, 2π) and dθ/ds = √(1−κ²)/(1 − κ cos s) [T45] [rad, -].

    s      uniform computational coordinate [rad]
    kappa  clustering parameter, 0 ≤ κ < 1 [-]
    """
    sk = math.sqrt((1.0 - kappa) * (1.0 + kappa))
    th = np.mod(np.arctan2(sk * np.sin(s), np.cos(s) - kappa), 2.0 * np.pi)
    return th, sk / (1.0 - kappa * np.cos(s))


def zeta_nodes(lam: float, n_zeta: int) -> np.ndarray:
    """Axial nodes ζ_j = λ·tanh(βη_j)/tanh β, η_j = j/n_zeta, β = 0.8·ln(1+λ) [T45] [-]."""
    eta = np.arange(n_zeta + 1) / n_zeta
    beta = 0.8 * math.log1p(lam)
    return lam * np.tanh(beta * eta) / math.tanh(beta)


def assemble(xi: float, lam: float, n_theta: int = DEFAULT_MESH[0], n_zeta: int = DEFAULT_MESH[1], kappa=None):
    """Finite-volume discretisation of the nondimensional Reynolds equation [T45].

    xi       eccentricity ratio, 0 ≤ ξ < 1 [-]
    lam      L/D > 0 [-]
    n_theta  cells around the circumference [-]
    n_zeta   cells on the half length [-]
    kappa    θ-clustering parameter (default 0.85ξ) [-]
    Returns an :class:`FDProblem`.
    """
    if not (0.0 <= xi < 1.0):
        raise ValueError(f"xi [-] must be in [0, 1); got {xi!r}")
    if not (math.isfinite(lam) and lam > 0.0):
        raise ValueError(f"L_over_D [-] must be finite and > 0; got {lam!r}")
    if kappa is None:
        kappa = 0.85 * xi
    nt, nz = int(n_theta), int(n_zeta)
    ds = 2.0 * np.pi / nt
    s = np.arange(nt) * ds
    th, dth = theta_map(s, kappa)
    thf, dthf = theta_map(s + 0.5 * ds, kappa)  # faces i+1/2
    H3 = (1.0 + xi * np.cos(th)) ** 3
    af = (1.0 + xi * np.cos(thf)) ** 3 / dthf  # H³/θ' at faces
    z = zeta_nodes(lam, nz)
    dzf = np.diff(z)  # ζ_{j+1} − ζ_j, j = 0..nz−1
    cv = np.empty(nz)  # control-volume widths in ζ
    cv[0] = 0.5 * dzf[0]
    cv[1:] = 0.5 * (dzf[1:] + dzf[:-1])
    I, J = np.meshgrid(np.arange(nt), np.arange(nz), indexing="ij")
    k = I * nz + J
    rows, cols, vals = [], [], []
    diag = np.zeros((nt, nz))
    # θ faces between i and i+1 (periodic): coefficient cv_j·a_{i+1/2}/Δs
    cth = cv[None, :] * af[:, None] / ds
    kp = ((I + 1) % nt) * nz + J
    rows += [k.ravel(), kp.ravel()]
    cols += [kp.ravel(), k.ravel()]
    vals += [-cth.ravel(), -cth.ravel()]
    diag += cth
    diag += np.roll(cth, 1, axis=0)
    # ζ faces between j and j+1: coefficient Δs·θ'_i·H³_i/(ζ_{j+1} − ζ_j); j+1 = nz is P = 0
    cz = ds * (dth * H3)[:, None] / dzf[None, :]  # (nt, nz)
    inner = J < nz - 1
    rows += [k[inner], k[inner] + 1]
    cols += [k[inner] + 1, k[inner]]
    vals += [-cz[inner], -cz[inner]]
    diag += cz
    diag[:, 1:] += cz[:, :-1]
    rows.append(k.ravel())
    cols.append(k.ravel())
    vals.append(diag.ravel())
    N = nt * nz
    M = csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(N, N))
    vol = (ds * dth)[:, None] * cv[None, :]  # cell areas in (θ, ζ)
    # M P = −(source·area): b = −S·vol
    bA = -(2.0 * np.cos(th))[:, None] * vol
    bB = ((2.0 + xi * xi) * np.sin(th))[:, None] * vol
    w = 2.0 * vol  # both halves of the bearing
    return FDProblem(
        xi,
        lam,
        th,
        z,
        M,
        bA.ravel(),
        bB.ravel(),
        (w * np.cos(th)[:, None]).ravel(),
        (w * np.sin(th)[:, None]).ravel(),
    )


def solve_lcp(M, b, cavitated=None, max_iter: int = 200):
    """Reynolds (Swift–Stieber) cavitation: P ≥ 0, w = M P − b ≥ 0, Pᵀw = 0 by the primal–dual
    active-set method [T46]. M: sparse M-matrix, b: right-hand side; ``cavitated`` an optional
    boolean start guess of the set where P = 0. Returns (P, cavitated, iterations)."""
    M = csr_matrix(M)
    n = b.size
    if cavitated is None:
        P = splu(M.tocsc()).solve(b)
        cav = P < 0.0
    else:
        cav = np.asarray(cavitated, dtype=bool).copy()
    for it in range(1, max_iter + 1):
        free = ~cav
        P = np.zeros(n)
        if free.any():
            Mf = M[free][:, free].tocsc()
            P[free] = splu(Mf).solve(b[free])
        w = M @ P - b
        new = np.where(cav, w > 0.0, P < 0.0)
        if np.array_equal(new, cav):
            return np.maximum(P, 0.0), cav, it
        cav = new
    raise RuntimeError(f"active-set LCP did not converge in {max_iter} iterations")


@njit(cache=True)
def _psor_csr(indptr, indices, data, b, P, omega, tol, max_sweeps):
    n = b.size
    for sweep in range(max_sweeps):
        dmax = 0.0
        pmax = 0.0
        for i in range(n):
            s = b[i]
            d = 0.0
            for kk in range(indptr[i], indptr[i + 1]):
                j = indices[kk]
                if j == i:
                    d = data[kk]
                else:
                    s -= data[kk] * P[j]
            new = max(0.0, P[i] + omega * (s / d - P[i]))
            dmax = max(dmax, abs(new - P[i]))
            P[i] = new
            pmax = max(pmax, abs(new))
        if dmax <= tol * pmax:
            return sweep + 1
    return -1


def psor(M, b, omega: float = 1.9, tol: float = 1e-13, max_sweeps: int = 200000, P0=None):
    """Projected SOR (Cryer 1971) for the same LCP as :func:`solve_lcp`: an independent check
    [T46]. Returns (P, sweeps); raises RuntimeError if not converged."""
    M = csr_matrix(M)
    P = np.zeros(b.size) if P0 is None else np.array(P0, dtype=float)
    n = _psor_csr(M.indptr, M.indices, M.data, b, P, omega, tol, max_sweeps)
    if n < 0:
        raise RuntimeError("PSOR did not converge")
    return P, n


def _check_cavitation(cavitation):
    if cavitation not in CAVITATION:
        raise ValueError(f"cavitation must be one of {CAVITATION}; got {cavitation!r}")


def unit_pressure(prob: FDProblem, A: float, B: float, cavitation: str = "gumbel", lu=None, cavitated=None):
    """Nondimensional film pressure P ≥ 0 (N,) for rates (A, B) = (ξ̇, ξΩ/(2+ξ²)) [1/s, 1/s]
    (any common scale) [T45–T46]. Returns (P, cavitated set or None)."""
    _check_cavitation(cavitation)
    b = A * prob.bA + B * prob.bB
    if cavitation == "gumbel":
        if lu is None:
            lu = splu(prob.M.tocsc())
        return np.maximum(lu.solve(b), 0.0), None
    P, cav, _ = solve_lcp(prob.M, b, cavitated)
    return P, cav


def unit_coefficients(
    xi: float,
    L_over_D: float,
    psi,
    cavitation: str = "gumbel",
    n_theta: int = DEFAULT_MESH[0],
    n_zeta: int = DEFAULT_MESH[1],
):
    """Dimensionless force coefficients f(ξ, ψ) (n_psi, 2) = (f_r, f_t) with
    F = k·ρ·f, k = μLR³/c², (A, B) = ρ(sin ψ, cos ψ) [T47].

    xi          eccentricity ratio, 0 ≤ ξ < 1 [-]
    L_over_D    L/D [-]
    psi         array of direction angles ψ = atan2(A, B) [rad]
    cavitation  "gumbel" or "reynolds"
    n_theta     cells around the circumference [-]
    n_zeta      cells on the half length [-]
    F = (6μR⁴/c²)∫∫P = (3k/λ)∫∫P for unit (A, B), so f = (3/λ)·(wcos·P, wsin·P).
    """
    _check_cavitation(cavitation)
    psi = np.atleast_1d(np.asarray(psi, dtype=float))
    prob = assemble(xi, L_over_D, n_theta, n_zeta)
    scale = 3.0 / L_over_D
    out = np.empty((psi.size, 2))
    if cavitation == "gumbel":
        lu = splu(prob.M.tocsc())
        PA, PB = lu.solve(prob.bA), lu.solve(prob.bB)
        P = np.maximum(np.sin(psi)[:, None] * PA[None, :] + np.cos(psi)[:, None] * PB[None, :], 0.0)
        out[:, 0] = scale * (P @ prob.wcos)
        out[:, 1] = scale * (P @ prob.wsin)
        return out
    # Reynolds: one LCP per ψ, warm-started from the previous ψ's cavitated set (ψ sorted)
    order = np.argsort(psi)
    cav = None
    for m in order:
        P, cav = unit_pressure(prob, math.sin(psi[m]), math.cos(psi[m]), "reynolds", cavitated=cav)
        out[m] = scale * (P @ prob.wcos), scale * (P @ prob.wsin)
    return out


def fd_force(
    xi: float,
    xi_dot: float,
    xi_Omega: float,
    mu: float,
    R: float,
    L: float,
    c: float,
    cavitation: str = "gumbel",
    n_theta: int = DEFAULT_MESH[0],
    n_zeta: int = DEFAULT_MESH[1],
):
    """Film force (F_r, F_t) on the journal from a direct 2-D Reynolds solve [T45–T46] [N].

    xi          eccentricity ratio ξ, 0 ≤ ξ < 1 [-]
    xi_dot      ξ̇ [1/s]
    xi_Omega    ξΩ, Ω = ω_J + ω_B − 2γ̇ [rad/s]
    mu          dynamic viscosity [Pa·s]
    R           journal radius [m]
    L           bearing length [m]
    c           radial clearance [m]
    cavitation  "gumbel" (half-Sommerfeld) or "reynolds" (Swift–Stieber)
    n_theta     cells around the circumference [-]
    n_zeta      cells on the half length [-]
    """
    _check_cavitation(cavitation)
    A = xi_dot
    B = xi_Omega / (2.0 + xi * xi)
    rho = math.hypot(A, B)
    if rho == 0.0:
        return 0.0, 0.0
    f = unit_coefficients(xi, L / (2.0 * R), [math.atan2(A, B)], cavitation, n_theta, n_zeta)[0]
    k = mu * L * R**3 / c**2
    return k * rho * f[0], k * rho * f[1]
