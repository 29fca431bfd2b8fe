"""1-D pocketed parallel slider with the mass-conserving condition: the analytic benchmark of
Fowell et al. (2007) for the ``jfo`` cell balance [T250].

Nondimensional (x over the length L, H = h/h₀, P = p h₀²/(6μUL)): flux q = θ_f H − H³ dP/dx,
dq/dx = 0; land H = 1 on [0, a) and (b, 1], pocket H = 1 + d on [a, b]; supply at both ends at
P_f > 0 (ambient above the cavitation pressure 0). The same active-set solver as the journal
(:func:`~jointdyn.film.jfo.solve_jfo`) on a 1-D problem with one ghost supply cell at each end.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.sparse import csr_matrix


@dataclass(frozen=True)
class Slider:
    """1-D cell-centred problem in the attributes :func:`~jointdyn.film.jfo.solve_jfo` reads;
    cells 0 and n+1 are the supply ghosts, 1..n cover [0, 1] uniformly."""

    x: np.ndarray  # cell centres (n+2,) [-]
    H: np.ndarray  # film thickness per cell (n+2,) [-]
    M: csr_matrix  # Poiseuille operator (net outflow of H³∇P), harmonic-mean face conductances
    Hface: np.ndarray  # Couette carrier of face i+1/2 = the upwind cell's H (n+2,) [-]
    cv: np.ndarray  # (1,) unit width
    area: np.ndarray  # cell lengths (n+2,)
    theta: np.ndarray  # unused angles (zeros) for the squeeze term (A = 0 here)
    bA: np.ndarray
    phase: float = 0.0
    xi: float = 0.0

    @property
    def shape(self) -> tuple[int, int]:
        return self.x.size, 1


def pocketed_slider(n: int, a: float, b: float, depth: float) -> Slider:
    """The slider on n cells (a·n and b·n integers put the pocket edges on faces) [T250]."""
    if not (0.0 < a < b < 1.0 and depth > -1.0):
        raise ValueError(f"pocket [{a}, {b}] depth {depth}: need 0 < a < b < 1 and depth > -1 [-]")
    dx = 1.0 / n
    x = (np.arange(n + 2) - 0.5) * dx
    H = np.where((x > a) & (x < b), 1.0 + depth, 1.0)
    g = np.empty(n + 1)  # face k+1/2 between cells k and k+1
    h3 = H**3
    g[:] = 2.0 * h3[:-1] * h3[1:] / (h3[:-1] + h3[1:]) / dx
    g[0] = h3[1] / (0.5 * dx)  # ghost 0 is the boundary value at x = 0
    g[-1] = h3[n] / (0.5 * dx)
    N = n + 2
    rows = np.concatenate([np.arange(N - 1), np.arange(1, N), np.arange(N)])
    cols = np.concatenate([np.arange(1, N), np.arange(N - 1), np.arange(N)])
    diag = np.zeros(N)
    diag[:-1] += g
    diag[1:] += g
    M = csr_matrix((np.concatenate([-g, -g, diag]), (rows, cols)), shape=(N, N))
    area = np.full(N, dx)
    return Slider(x, H, M, H.copy(), np.ones(1), area, np.zeros(N), np.zeros(N))


def solve_slider(prob: Slider, feed: float):
    """(P, θ_f, residual) with P = ``feed`` and θ_f = 1 in the ghosts, sliding speed Ω = 1 [T250]."""
    from jointdyn.film.jfo import solve_jfo

    N = prob.x.size
    fixed = np.zeros(N, bool)
    fixed[[0, -1]] = True
    P, fill, _, _, res = solve_jfo(prob, 0.0, 0.0, fixed, np.full(N, feed), omega=1.0)
    return P, fill, res


def slider_exact(a: float, b: float, depth: float, feed: float) -> dict:
    """Closed form [T250]: rupture at the pocket entry x = a (land 1 falls linearly from P_f to
    0), cavitated to x = c with content θ_f H = q, full film again from c to b (the content flux
    meets the Poiseuille flux: q = (1+d) − (1+d)³P'), land 2 back to P_f at x = 1.
    Valid while a ≤ c ≤ b. Returns q, c, P_b = P(b) (the peak), the load ∫P dx, the pocket's
    fill θ_cav, and the friction force on the moving wall [μUL/h₀]: its Couette part ∫θ_f/H dx
    and the total with 3∫H P' dx [T375]."""
    q = 1.0 + feed / a
    Hp = 1.0 + depth
    Pb = feed * (1.0 + (1.0 - b) / a)
    slope = (Hp - q) / Hp**3
    c = b - Pb / slope
    if not (a <= c <= b and slope > 0.0):
        raise ValueError(f"feed = {feed}: the closed form needs a <= c <= b (got c = {c:.6g})")
    load = 0.5 * feed * a + 0.5 * Pb * (b - c) + 0.5 * (Pb + feed) * (1.0 - b)
    # shear on the moving wall [T375]: ∫θ_f/H over the lands, the cavitated and the full pocket;
    # 3∫H P' = 3(−P_f + (1+d)P_b + P_f − P_b) = 3d·P_b
    couette = a + (1.0 - b) + (c - a) * (q / Hp) / Hp + (b - c) / Hp
    return {
        "q": q,
        "c": c,
        "P_b": Pb,
        "load": load,
        "theta_cav": q / Hp,
        "couette": couette,
        "friction": couette + 3.0 * depth * Pb,
    }


def slider_friction(prob: Slider, P: np.ndarray, fill: np.ndarray, feed: float) -> dict:
    """Friction force on the moving wall [μUL/h₀ per unit width] of a solved slider [T375]:
    ``couette`` Σ θ_f/H·dx (a partly filled cell shears only its lubricant's fraction θ_f of the
    width) and ``friction`` = couette + 3∫H dP/dx, the pressure-gradient part with face
    pressures weighted by the H³ conductances (P_f at the ends)."""
    n = prob.x.size - 2
    dx = 1.0 / n
    H = prob.H
    h3 = H**3
    Pf = (h3[:-1] * P[:-1] + h3[1:] * P[1:]) / (h3[:-1] + h3[1:])  # faces k+1/2, k = 0..n
    Pf[0] = Pf[-1] = feed
    couette = float(np.sum(fill[1:-1] / H[1:-1]) * dx)
    grad = float(np.sum(H[1:-1] * np.diff(Pf)))
    return {"couette": couette, "friction": couette + 3.0 * grad}


def slider_measured(prob: Slider, P: np.ndarray, fill: np.ndarray, feed: float) -> dict:
    """q (flux through the inlet face), c (start of the first full cell after the cavitated
    zone, linearly interpolated in θ_f), P_b (largest P), load (midpoint sum) [T250]."""
    n = prob.x.size - 2
    dx = 1.0 / n
    q = prob.H[0] * fill[0] - prob.H[1] ** 3 * (P[1] - feed) / (0.5 * dx)
    cav = np.flatnonzero(fill[1:-1] < 1.0 - 1e-12) + 1
    last = int(cav[-1])  # last partly filled cell: the film re-forms inside it
    # the content θ_f H·dx of a cell split as (c − x_l)·q + (x_r − c)·H  →  c
    xl = prob.x[last] - 0.5 * dx
    Hc = prob.H[last]
    frac = (1.0 - fill[last]) * Hc / (Hc - q) if Hc > q else 0.0
    c = xl + min(max(frac, 0.0), 1.0) * dx
    return {"q": float(q), "c": float(c), "P_b": float(np.max(P[1:-1])), "load": float(np.sum(P[1:-1]) * dx)}


def rupture_position(prob: Slider, fill: np.ndarray) -> float:
    """Left face of the first cavitated cell [-] (the rupture boundary) [T250]."""
    n = prob.x.size - 2
    first = int(np.flatnonzero(fill[1:-1] < 1.0 - 1e-12)[0]) + 1
    return float(prob.x[first] - 0.5 / n)
