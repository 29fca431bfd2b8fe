"""Film solution of the finite-length bearing and the quantities a designer reads from it
[T70–T76]: forces, friction torques, inlet and side flow, peak pressure, rupture angle.

All quantities here are nondimensional; :mod:`.design` turns them into the Raimondi–Boyd
variables and SI numbers. Units of the nondimensional film (bearing fixed, journal speed ω > 0,
no squeeze unless (A, B) say otherwise): p = (6μR²/c²)·P, forces in μωR⁴/c², torques in μωR⁴/c.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from jointdyn.film.cavitation import condition
from jointdyn.film.fv import DEFAULT_MESH, FVProblem, assemble, check_ld, check_xi, theta_map
from jointdyn.film.jfo_step import couette_gas


@dataclass(frozen=True)
class Film:
    """A solved film on the mesh of ``prob``.

    prob      the discretised problem (:class:`FVProblem`)
    P         nondimensional pressure P ≥ 0 on the half bearing, shape (nt, nz) [-]
    fixed     nodes held at P = 0 by a supply line (None for a periodic film)
    residual  the condition's convergence measure (complementarity residual for ``reynolds``
              [T72], 0 for ``gumbel``) [-]
    iterations solver iterations [-]
    state     the condition's warm start for a neighbouring solve (``reynolds``: cavitated set)
    fill      fill fraction (nt, nz) of a mass-conserving condition, None otherwise [-]
    """

    prob: FVProblem
    P: np.ndarray
    fixed: np.ndarray | None
    residual: float
    iterations: int
    state: object = None
    fill: np.ndarray | None = None


def solve(
    xi: float,
    lam: float,
    A: float,
    B: float,
    cavitation: str = "reynolds",
    feed: bool = False,
    mesh: tuple[int, int] = DEFAULT_MESH,
    cavitated=None,
) -> Film:
    """Solve the film for the rates (A, B) = (ξ̇, ξΩ/(2+ξ²)) [1/s] (any common scale) [T70–T72].

    xi          eccentricity ratio, 0 ≤ ξ < 1 [-]
    lam         L/D > 0 [-]
    cavitation  a registered condition (:mod:`.cavitation`): "gumbel" (negative full-film
                pressure clipped), "reynolds" (Swift–Stieber LCP), ...
    feed        True: P = 0 on the line θ = 0 (lubricant supplied at the maximum film, the
                Raimondi–Boyd assumption for the steady 360° bearing) [T73]; False: periodic film
    mesh        (cells around, cells on the half length) [-]
    cavitated   optional warm start (a previous solution's ``state``)
    """
    check_xi(xi)
    check_ld(lam)
    cond = condition(cavitation)
    nt, nz = mesh
    prob = assemble(xi, lam, nt, nz)
    fixed = None
    if feed:
        fixed = np.zeros(nt * nz, bool)
        fixed[:nz] = True  # node row i = 0 is θ = 0
    s = cond.solve(prob, A, B, fixed, cavitated)
    fill = None if s.fill is None else s.fill.reshape(nt, nz)
    return Film(prob, s.P.reshape(nt, nz), fixed, s.residual, s.iterations, s.state, fill)


def _weights(f: Film):
    """Quadrature weights of the nodes over the full bearing (both halves) in (θ, ζ) [-]."""
    return 2.0 * f.prob.area.reshape(f.P.shape)


def forces(f: Film) -> tuple[float, float]:
    """(F_r, F_t) on the journal in units of (6μR⁴/c²)·(rate scale): R²∫∫P(cos θ, sin θ) [T74]."""
    w = _weights(f) * f.P
    th = f.prob.film_theta
    return float(np.sum(w.sum(axis=1) * np.cos(th))), float(np.sum(w.sum(axis=1) * np.sin(th)))


def couette_integral(f: Film) -> float:
    """∫∫ θ_f dθ dζ / H over the full bearing, the Couette shear integral [T75] [-]. Films that
    are not mass conserving are full over the whole circumference (the cavitated region carries
    the Couette shear, as in Raimondi–Boyd): exact value 4πλ/√(1−ξ²), here the periodic
    trapezoid rule on the mapped θ grid (spectrally accurate) times the full length 2λ. A
    mass-conserving film's partly filled cells carry θ_f of it: minus :func:`couette_gas` [T375]."""
    p = f.prob
    H = 1.0 + p.xi * np.cos(p.theta)
    ds = 2.0 * math.pi / p.theta.size
    width = 2.0 * p.lam  # Σ control volumes + end half-cells = λ on each half
    full = float(np.sum(ds * p.dtheta / H) * width)
    if f.fill is None:
        return full
    nz = p.cv.size
    return full - couette_gas(f.fill.ravel(), np.repeat(H, nz), p.area, p.cv, np.diff(p.zeta))


def side_flow(f: Film) -> float:
    """Side leakage through both ends, 2·∫ H³(−∂P/∂ζ)|_(ζ=λ) dθ [T76] [-]; with
    ∂p/∂z = (6μR/c²)∂P/∂ζ per unit rate, Q_s = (ωR²c/2)·side_flow for the steady film
    (P scaled to ω)."""
    p = f.prob
    z = p.zeta
    ds = 2.0 * math.pi / p.theta.size
    H = 1.0 + p.xi * np.cos(p.theta)
    return end_flux(ds * p.dtheta, H, f.P[:, -1], f.P[:, -2], z[-1] - z[-2], z[-1] - z[-3])


def inlet_flow(f: Film) -> float:
    """Circumferential flow into the film at the supply line θ = 0, ∫(H − H³ ∂P/∂θ) dζ over the
    full length, evaluated at the first θ face (finite-volume flux) [T76] [-]."""
    p = f.prob
    nt = p.theta.size
    ds = 2.0 * math.pi / nt
    thf, dthf = theta_map(np.array([0.5 * ds]), 0.85 * p.xi)
    Hf = 1.0 + p.xi * math.cos(float(thf[0]))
    flux = Hf**3 / float(dthf[0]) * (f.P[1, :] - f.P[0, :]) / ds
    dz_end = p.zeta[-1] - p.zeta[-2]
    return float(np.sum(2.0 * p.cv * (Hf - flux)) + dz_end * Hf)


def peak_of(theta: np.ndarray, row: np.ndarray) -> tuple[float, float]:
    """(P_max, θ at P_max) of a periodic row of pressures at the nodes θ [-, rad]: the largest
    node refined by the parabola through it and its neighbours (the peak is smooth) [T76]."""
    i = int(np.argmax(row))
    n = theta.size
    im, ip = (i - 1) % n, (i + 1) % n
    x0, x1, x2 = theta[im], theta[i], theta[ip]
    x0 = x0 - 2 * math.pi if x0 > x1 else x0
    x2 = x2 + 2 * math.pi if x2 < x1 else x2
    y0, y1, y2 = row[im], row[i], row[ip]
    d0, d2 = x0 - x1, x2 - x1
    a = ((y0 - y1) / d0 - (y2 - y1) / d2) / (d0 - d2)
    bq = (y0 - y1) / d0 - a * d0
    if a >= 0.0:
        return float(y1), float(x1)
    dx = -bq / (2 * a)
    return float(y1 + bq * dx + a * dx * dx), float(np.mod(x1 + dx, 2 * math.pi))


def peak(f: Film) -> tuple[float, float]:
    """(P_max, θ at P_max) [-, rad] at the mid-plane (:func:`peak_of`) [T76]."""
    return peak_of(f.prob.theta, f.P[:, 0])


def rupture_of(theta: np.ndarray, row: np.ndarray, cavitation: str = "reynolds") -> float:
    """Film rupture angle [rad] in (0, 2π) of a periodic row of pressures at the nodes θ: the
    end of the pressurised arc that contains the peak [T76]. Between the last pressurised node
    and the first ambient one, P is extrapolated to zero from the last two pressurised nodes —
    linearly in P^(1/k), k the condition's ``rupture_exponent`` (``reynolds``: k = 2, P ∝
    (θ_e − θ)² at a rupture with ∂P/∂θ = 0; ``gumbel``: k = 1). nan if the row has no ambient node."""
    k = int(np.argmax(row))
    th = np.unwrap(np.roll(theta, -k))
    r = np.roll(row, -k)
    zero = np.flatnonzero(r <= 0.0)
    if zero.size == 0 or zero[0] < 3:
        return float("nan")
    j = int(zero[0])
    k = condition(cavitation).rupture_exponent
    g = np.sqrt(r) if k == 2.0 else r ** (1.0 / k)
    x1, x2, y1, y2 = th[j - 2], th[j - 1], g[j - 2], g[j - 1]
    xe = x2 + y2 * (x2 - x1) / (y1 - y2) if y1 > y2 else th[j]
    return float(np.mod(min(xe, th[j]), 2.0 * np.pi))


def rupture_angle(f: Film, cavitation: str = "reynolds") -> float:
    """Mid-plane film rupture angle [rad] (θ from the maximum film) (:func:`rupture_of`) [T76]."""
    return rupture_of(f.prob.theta, f.P[:, 0], cavitation)


def end_flux(
    dtheta: np.ndarray, H: np.ndarray, P_last: np.ndarray, P_prev: np.ndarray, h1: float, h2: float
) -> float:
    """2·∫H³(−∂P/∂ζ)|_(ζ=λ) dθ [-]: the side flow through both ends, ∂P/∂ζ second order from the
    quadratic through (λ−h2, P_prev), (λ−h1, P_last), (λ, 0); dθ the θ quadrature weights [T76]."""
    dPdz = -(P_last * h2 * h2 - P_prev * h1 * h1) / (h1 * h2 * (h2 - h1))
    return float(2.0 * np.sum(dtheta * H**3 * (-dPdz)))


def pressure_field(
    xi: float,
    xi_dot: float,
    xi_Omega: float,
    mu: float,
    R: float,
    L: float,
    c: float,
    cavitation: str = "reynolds",
    mesh: tuple[int, int] = DEFAULT_MESH,
):
    """Film pressure p(θ, z) [Pa] at a bearing state (periodic film, no supply line) [T70–T72].

    xi        eccentricity ratio, 0 ≤ ξ < 1 [-]
    xi_dot    ξ̇ [1/s]
    xi_Omega  ξΩ, Ω = ω_J + ω_B − 2γ̇ [rad/s]
    mu        viscosity [Pa·s]; R, L, c journal radius, length, radial clearance [m]
    Returns θ (nt,) [rad] from the maximum film (bearing frame: global angle α = θ + γ + π),
    z (2nz+1,) [m] over the full length, p (nt, 2nz+1) [Pa].
    """
    for name, v in (("mu", mu), ("R", R), ("L", L), ("c", c)):
        if not (math.isfinite(v) and v > 0.0):
            raise ValueError(f"{name} = {v!r}: must be finite and > 0 (SI units)")
    f = solve(xi, L / (2.0 * R), xi_dot, xi_Omega / (2.0 + xi * xi), cavitation, False, mesh)
    half = np.concatenate([f.P, np.zeros((f.P.shape[0], 1))], axis=1)
    full = np.concatenate([half[:, :0:-1], half], axis=1)
    zeta = f.prob.zeta
    z = R * np.concatenate([-zeta[:0:-1], zeta])
    return f.prob.theta.copy(), z, 6.0 * mu * R * R / (c * c) * full


def film_outputs(
    xi: float,
    xi_dot: float,
    xi_Omega: float,
    mu: float,
    R: float,
    L: float,
    c: float,
    cavitation: str = "reynolds",
    mesh: tuple[int, int] = DEFAULT_MESH,
) -> dict:
    """Film outputs at a bearing state [T76] (arguments as :func:`pressure_field`): peak
    pressure p_max [Pa], its angle theta_pmax [rad] and the mid-plane rupture angle
    theta_rupture [rad] (θ from the maximum film, bearing frame), side flow through both ends
    side_flow [m³/s] (Q_s = (cR²/2)·∫H³(−∂P/∂ζ)dθ), and F_r, F_t [N] of the same solve."""
    f = solve(xi, L / (2.0 * R), xi_dot, xi_Omega / (2.0 + xi * xi), cavitation, False, mesh)
    pm, tp = peak(f)
    s = 6.0 * mu * R * R / (c * c)
    fr, ft = forces(f)
    return {
        "p_max": s * pm,
        "theta_pmax": tp,
        "theta_rupture": rupture_angle(f, cavitation),
        "side_flow": 0.5 * c * R * R * side_flow(f),
        "F_r": s * R * R * fr,
        "F_t": s * R * R * ft,
    }
