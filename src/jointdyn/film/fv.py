"""2-D finite-volume Reynolds problem of a finite-length journal bearing [T70–T72].

Nondimensional equation (θ from the maximum film, H = 1 + ξ cos θ, ζ = z/R ∈ [−λ, λ], λ = L/D):

    ∂/∂θ(H³ ∂P/∂θ) + ∂/∂ζ(H³ ∂P/∂ζ) = A·2cos θ − B·(2+ξ²) sin θ,   P(θ, ±λ) = 0,

p = (6μR²/c²)·P with A = ξ̇, B = ξΩ/(2+ξ²), Ω = ω_J + ω_B − 2γ̇ [T70]. Cell-centred conservative
finite volumes on a periodic θ grid clustered toward the minimum film by the inverse Sommerfeld
map tan(θ/2) = √((1−κ)/(1+κ))·tan(s/2), κ = 0.85ξ, s uniform [T71]; vertex-centred in ζ on the
half bearing ζ ∈ [0, λ] (symmetry at ζ = 0, P = 0 at ζ = λ), ζ = λ·tanh(βη)/tanh β, η uniform,
β = 0.8·ln(1+λ) (finer toward the ends). The matrix M (minus the discrete operator) is a
symmetric M-matrix, so the complementarity problems of :mod:`.lcp` have a unique solution.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:  # scipy.sparse (≈ 0.1 s to import) only where a film is assembled [T372]
    from scipy.sparse import csr_matrix

#: default mesh: cells around the circumference, cells on the half length [-]
DEFAULT_MESH = (144, 16)


@dataclass(frozen=True)
class FVProblem:
    """Discretised Reynolds problem for one (ξ, λ, mesh): M P = A·bA + B·bB.

    xi, lam  eccentricity ratio [-], L/D [-]
    theta    node angles θ_i (nt,) [rad], node 0 at θ = 0 (maximum film)
    dtheta   dθ/ds at the nodes (nt,) [-]; ds = 2π/nt
    zeta     ζ_j = z/R on the half bearing incl. the end ζ = λ (nz+1,) [-]
    cv       ζ widths of the control volumes (nz,) [-]
    M        symmetric M-matrix (N×N CSR), N = nt·nz, unknown k = i·nz + j [-]
    bA, bB   right-hand sides for A = 1 and B = 1 (N,) [-]
    area     control-volume areas in (θ, ζ) (N,) [-]
    band     M in symmetric upper band storage in the zig-zag θ order (N, u+1), u = 2·nz:
             band[q, d] = M[perm[q], perm[q+d]] (for :func:`~jointdyn.film.lcp.solve_lcp_banded`)
    perm     unknown order of ``band``: position q holds unknown perm[q] (N,) [-]
    phase    angle of the maximum film on the mesh [rad]: H = 1 + ξ cos(θ − phase) (0: the mesh
             angles are the film angles; a mesh fixed in the bearing has phase = γ + π) [T240]
    Hface    film thickness at the θ faces i+1/2 (nt,) [-] (the Couette fluxes of [T241])
    flow     the average-film model (:class:`~jointdyn.film.flow_factors.AverageFlow`) or None
    """

    xi: float
    lam: float
    theta: np.ndarray
    dtheta: np.ndarray
    zeta: np.ndarray
    cv: np.ndarray
    M: csr_matrix
    bA: np.ndarray
    bB: np.ndarray
    area: np.ndarray
    band: np.ndarray
    perm: np.ndarray
    phase: float = 0.0
    Hface: np.ndarray | None = None
    flow: object = None

    @property
    def film_theta(self) -> np.ndarray:
        """Node angles from the maximum film, θ_i − phase in [0, 2π) (nt,) [rad]."""
        return np.mod(self.theta - self.phase, 2.0 * np.pi)

    @property
    def shape(self) -> tuple[int, int]:
        return self.theta.size, self.cv.size


def theta_map(s, kappa: float):
    """θ = Θ_κ(s) ∈ [0, 2π) and dθ/ds = √(1−κ²)/(1 − κ cos s) [T71] [rad, -] (s [rad], 0 ≤ κ < 1)."""
    sk = math.sqrt((1.0 - kappa) * (1.0 + kappa))
    th = np.mod(np.arctan2(sk * np.sin(s), np.cos(s) - kappa), 2.0 * np.pi)
    return th, sk / (1.0 - kappa * np.cos(s))


def zeta_nodes(lam: float, nz: int) -> np.ndarray:
    """Axial nodes ζ_j = λ·tanh(βη_j)/tanh β, η_j = j/nz, β = 0.8·ln(1+λ) [T71] [-]."""
    eta = np.arange(nz + 1) / nz
    beta = 0.8 * math.log1p(lam)
    return lam * np.tanh(beta * eta) / math.tanh(beta)


def check_xi(xi: float) -> None:
    if not (math.isfinite(xi) and 0.0 <= xi < 1.0):
        raise ValueError(f"eccentricity ratio eps = {xi!r} [-]: must be in [0, 1)")


def check_ld(lam: float) -> None:
    if not (math.isfinite(lam) and lam > 0.0):
        raise ValueError(f"ld = L/D = {lam!r} [-]: must be finite and > 0")


def assemble(
    xi: float,
    lam: float,
    nt: int = DEFAULT_MESH[0],
    nz: int = DEFAULT_MESH[1],
    kappa=None,
    phase: float = 0.0,
    theta0: float = 0.0,
    flow=None,
) -> FVProblem:
    """Finite-volume discretisation [T71] of the nondimensional Reynolds equation [T70], or with
    ``flow`` of Patir–Cheng's average Reynolds equation [T268]: H³ → φ_x H³ on the θ faces and
    φ_z H³ on the ζ faces, the wedge source ω∂H/∂θ → ω∂G/∂θ (G = (h̄_T + σφ_s)/c, integrated
    exactly over each control volume as the difference of G at its θ faces), the squeeze source
    scaled by ∂h̄_T/∂h.

    xi     eccentricity ratio, 0 ≤ ξ < 1 [-]
    lam    L/D > 0 [-]
    nt     cells around the circumference [-]
    nz     cells on the half length [-]
    kappa  θ-clustering parameter (default 0.85ξ; 0 = uniform) [-]
    phase  mesh angle of the maximum film [rad]: H = 1 + ξ cos(θ − phase) [T240]
    theta0 mesh angle of node 0 [rad] (uniform meshes fixed in the bearing) [T240]
    flow   None (smooth film) or an :class:`~jointdyn.film.flow_factors.AverageFlow`
    """
    check_xi(xi)
    check_ld(lam)
    if kappa is None:
        kappa = 0.85 * xi
    nt, nz = int(nt), int(nz)
    ds = 2.0 * np.pi / nt
    s = np.arange(nt) * ds
    th, dth = theta_map(s, kappa)
    thf, dthf = theta_map(s + 0.5 * ds, kappa)  # faces i+1/2
    th = np.mod(th + theta0, 2.0 * np.pi)
    thf = thf + theta0
    Hn = 1.0 + xi * np.cos(th - phase)
    Hf = 1.0 + xi * np.cos(thf - phase)
    if flow is None:
        H3 = Hn**3
        af = Hf**3 / dthf  # H³/θ' at the faces
    else:
        H3 = flow.pressure_z(Hn)
        af = flow.pressure_x(Hf) / dthf
    z = zeta_nodes(lam, nz)
    dzf = np.diff(z)
    cv = np.empty(nz)
    cv[0] = 0.5 * dzf[0]
    cv[1:] = 0.5 * (dzf[1:] + dzf[:-1])
    Ig, Jg = np.meshgrid(np.arange(nt), np.arange(nz), indexing="ij")
    k = Ig * nz + Jg
    rows, cols, vals = [], [], []
    diag = np.zeros((nt, nz))
    cth = cv[None, :] * af[:, None] / ds  # θ faces i+1/2 (periodic)
    kp = ((Ig + 1) % nt) * nz + Jg
    rows += [k.ravel(), kp.ravel()]
    cols += [kp.ravel(), k.ravel()]
    vals += [-cth.ravel(), -cth.ravel()]
    diag += cth + np.roll(cth, 1, axis=0)
    cz = ds * (dth * H3)[:, None] / dzf[None, :]  # ζ faces j+1/2; j+1 = nz is P = 0
    inner = Jg < nz - 1
    rows += [k[inner], k[inner] + 1]
    cols += [k[inner] + 1, k[inner]]
    vals += [-cz[inner], -cz[inner]]
    diag += cz
    diag[:, 1:] += cz[:, :-1]
    rows.append(k.ravel())
    cols.append(k.ravel())
    vals.append(diag.ravel())
    from scipy.sparse import csr_matrix

    N = nt * nz
    M = csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(N, N))
    area = (ds * dth)[:, None] * cv[None, :]
    bA = -(2.0 * np.cos(th - phase))[:, None] * area  # M P = −∫source
    if flow is None:
        bB = ((2.0 + xi * xi) * np.sin(th - phase))[:, None] * area
    else:  # B(2+ξ²)/ξ = Ω: M P = −Ω ∫∂G/∂θ = −Ω (G(θ_{i+1/2}) − G(θ_{i−1/2}))·cv [T268]
        bA = bA * flow.squeeze(Hn)[:, None]
        G = flow.couette(Hf)
        dG = G - np.roll(G, 1)
        scale = 0.0 if xi == 0.0 else -(2.0 + xi * xi) / xi
        bB = (scale * dG)[:, None] * cv[None, :]
    band, perm = band_form(M, nt, nz)
    return FVProblem(
        xi, lam, th, dth, z, cv, M, bA.ravel(), bB.ravel(), area.ravel(), band, perm, float(phase), Hf, flow
    )


def band_form(M: csr_matrix, nt: int, nz: int) -> tuple[np.ndarray, np.ndarray]:
    """M (unknown k = i·nz + j, periodic in i) in symmetric upper band storage after ordering θ
    zig-zag, i = 0, nt−1, 1, nt−2, …: θ neighbours, including the periodic pair (0, nt−1), are
    then at most 2 positions apart, so the half bandwidth is u = 2·nz instead of (nt−1)·nz
    [T89]. Returns (band (N, u+1) with band[q, d] = M[perm[q], perm[q+d]], perm (N,))."""
    zig = np.empty(nt, np.int64)
    zig[0::2] = np.arange((nt + 1) // 2)
    zig[1::2] = nt - 1 - np.arange(nt // 2)
    perm = (zig[:, None] * nz + np.arange(nz)[None, :]).ravel()
    inv = np.empty_like(perm)
    inv[perm] = np.arange(perm.size)
    C = M.tocoo()
    qi, qj = inv[C.row], inv[C.col]
    up = qi <= qj
    u = 2 * nz
    band = np.zeros((perm.size, u + 1))
    band[qi[up], qj[up] - qi[up]] = C.data[up]
    return band, perm
