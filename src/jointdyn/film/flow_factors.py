"""Patir–Cheng flow factors and shear-stress factors of the average Reynolds equation [T264–T267].

Film parameter Λ = h/σ (h the nominal film, σ the composite RMS roughness), Peklenik surface
orientation γ (ratio of the x and z correlation lengths, the same on both surfaces), variance
ratio V_r = (σ₁² − σ₂²)/σ² (surface 1 the moving journal, 2 the bushing). Published fits:

* pressure flow (Patir & Cheng, ASME J. Lubr. Technol. 100 (1978) 12–17, Table 1) [T264]
  φ_x = 1 − C e^{−rΛ} (γ ≤ 1), φ_x = 1 + C Λ^{−r} (γ > 1); φ_z(Λ, γ) = φ_x(Λ, 1/γ);
* shear flow (ibid., Table 2) [T265] φ_s = V_r·Φ_s, Φ_s = A₁Λ^{α₁}e^{−α₂Λ + α₃Λ²} (Λ ≤ 5),
  A₂e^{−Λ/4} (Λ > 5);
* shear stress (Patir & Cheng, ASME J. Lubr. Technol. 101 (1979) 220–229) [T266]
  φ_f = E[h/h_T] for the truncated polynomial height density (35/32)(1 − x²)³ on ±3σ (closed
  form below, its power series in 1/z² for z = Λ/3 > 2), φ_fs = V_r·A₃Λ^{α₄}e^{−α₅Λ + α₆Λ²}
  (Λ < 7, 0 beyond), φ_fp = 1 − D e^{−sΛ}.

The fits hold for Λ ≥ 0.5 (φ_x for γ = 1/9, 1/6 from Λ = 1, γ = 1/3 from 0.75: there the fit
would turn negative); below they are evaluated at the end of their range (the mixed film there
carries a small share of the load, the asperities the rest [T262]); φ_fp (−0.006 at Λ = 0.5,
γ = 1) is floored at 0. The mean
gap is h̄_T = σ(ΛΦ(Λ) + ϕ(Λ)) for Gaussian heights (Φ, ϕ the normal distribution and density)
[T267]. Every factor → its smooth value (φ_x, φ_z, φ_f, φ_fp → 1; φ_s, φ_fs → 0) as Λ → ∞.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: surface orientations γ with published coefficients
GAMMAS = (1 / 9, 1 / 6, 1 / 3, 1.0, 3.0, 6.0, 9.0)
#: pressure flow factor (C, r) per γ [T264]
PRESSURE = ((1.48, 0.42), (1.38, 0.42), (1.18, 0.42), (0.90, 0.56), (0.225, 1.5), (0.520, 1.5), (0.870, 1.5))
#: shear flow factor (A₁, α₁, α₂, α₃, A₂) per γ [T265]
SHEAR = (
    (2.046, 1.12, 0.78, 0.03, 1.856),
    (1.962, 1.08, 0.77, 0.03, 1.754),
    (1.858, 1.01, 0.76, 0.03, 1.561),
    (1.899, 0.98, 0.92, 0.05, 1.126),
    (1.560, 0.85, 1.13, 0.08, 0.556),
    (1.290, 0.62, 1.09, 0.08, 0.388),
    (1.011, 0.54, 1.07, 0.08, 0.295),
)
#: shear stress factor φ_fs (A₃, α₄, α₅, α₆) per γ [T266]
STRESS_FS = (
    (14.1, 2.45, 2.30, 0.10),
    (13.4, 2.42, 2.30, 0.10),
    (12.3, 2.32, 2.30, 0.10),
    (11.1, 2.31, 2.38, 0.11),
    (9.8, 2.25, 2.80, 0.18),
    (10.1, 2.25, 2.90, 0.18),
    (8.7, 2.15, 2.97, 0.18),
)
#: shear stress factor φ_fp (D, s) per γ [T266]
STRESS_FP = ((1.51, 0.52), (1.51, 0.54), (1.47, 0.58), (1.40, 0.66), (0.98, 0.79), (0.97, 0.91), (0.73, 0.91))
#: smallest Λ at which the fits are evaluated [-]
LAMBDA_MIN = 0.5
#: smallest Λ of the published range of φ_x per γ (Patir & Cheng 1978, Table 1) [-]
PRESSURE_LAMBDA_MIN = (1.0, 1.0, 0.75, 0.5, 0.5, 0.5, 0.5)


def gamma_index(gamma: float) -> int:
    """Index of γ in ``GAMMAS`` (relative tolerance 1e-6), else ValueError naming the values."""
    for k, g in enumerate(GAMMAS):
        if math.isfinite(gamma) and abs(gamma - g) <= 1e-6 * g:
            return k
    raise ValueError(
        f"surface orientation gamma = {gamma!r} [-]: Patir–Cheng published 1/9, 1/6, 1/3, 1, 3, 6, 9"
    )


def _lam(L):
    return np.maximum(np.asarray(L, dtype=float), LAMBDA_MIN)


def phi_x(L, gamma: float = 1.0):
    """Pressure flow factor φ_x(Λ, γ) [-] along the sliding direction [T264]."""
    k = gamma_index(gamma)
    C, r = PRESSURE[k]
    L = np.maximum(np.asarray(L, dtype=float), PRESSURE_LAMBDA_MIN[k])
    return 1.0 - C * np.exp(-r * L) if gamma <= 1.0 else 1.0 + C * L ** (-r)


def phi_z(L, gamma: float = 1.0):
    """Pressure flow factor φ_z(Λ, γ) = φ_x(Λ, 1/γ) [-] across the sliding direction [T264]."""
    return phi_x(L, GAMMAS[len(GAMMAS) - 1 - gamma_index(gamma)])


def shear_flow(L, gamma: float = 1.0):
    """Φ_s(Λ, γ) [-] of one rough surface; φ_s = V_r·Φ_s [T265]."""
    A1, a1, a2, a3, A2 = SHEAR[gamma_index(gamma)]
    L = _lam(L)
    Lc = np.minimum(L, 5.0)
    return np.where(L <= 5.0, A1 * Lc**a1 * np.exp(-a2 * Lc + a3 * Lc * Lc), A2 * np.exp(-0.25 * L))


def _moments(n: int) -> np.ndarray:
    k = np.arange(n)
    return 35.0 / 16.0 * (1 / (2 * k + 1) - 3 / (2 * k + 3) + 3 / (2 * k + 5) - 1 / (2 * k + 7))


_M = _moments(40)


def phi_f(L):
    """Shear stress factor φ_f(Λ) [-] (Couette part, E[h/h_T], heights on ±3σ) [T266]: closed form
    for z = Λ/3 ≤ 2, the series Σ m_{2k} z^{−2k} (m the moments of (35/32)(1−x²)³) beyond."""
    z = np.atleast_1d(np.asarray(L, dtype=float) / 3.0)
    out = np.empty_like(z)
    a = z <= 1.0
    za = z[a]
    poly = -55.0 + za * (132.0 + za * (345.0 + za * (-160.0 + za * (-405.0 + za * (60.0 + 147.0 * za)))))
    out[a] = 35.0 / 32.0 * za * ((1.0 - za * za) ** 3 * np.log(300.0 * (za + 1.0)) + poly / 60.0)
    b = (z > 1.0) & (z <= 2.0)
    zb = z[b]
    out[b] = (
        35.0
        / 32.0
        * zb
        * (
            (1.0 - zb * zb) ** 3 * np.log((zb + 1.0) / (zb - 1.0))
            + zb / 15.0 * (66.0 + zb * zb * (30.0 * zb * zb - 80.0))
        )
    )
    c = z > 2.0
    inv = 1.0 / z[c] ** 2
    out[c] = np.polyval(_M[::-1], inv)
    return out if np.ndim(L) else float(out[0])


def stress_fs(L, gamma: float = 1.0):
    """Φ_fs(Λ, γ) [-] of one rough surface; φ_fs = V_r·Φ_fs (0 for Λ ≥ 7) [T266]."""
    A3, a4, a5, a6 = STRESS_FS[gamma_index(gamma)]
    L = _lam(L)
    Lc = np.minimum(L, 7.0)
    return np.where(L < 7.0, A3 * Lc**a4 * np.exp(-a5 * Lc + a6 * Lc * Lc), 0.0)


def phi_fp(L, gamma: float = 1.0):
    """Shear stress factor φ_fp(Λ, γ) = max(1 − D e^{−sΛ}, 0) [-] (Poiseuille part) [T266]."""
    D, s = STRESS_FP[gamma_index(gamma)]
    return np.maximum(1.0 - D * np.exp(-s * _lam(L)), 0.0)


def mean_gap(L):
    """h̄_T/σ = ΛΦ(Λ) + ϕ(Λ) [-], the mean local gap of Gaussian heights [T267]."""
    from scipy.special import ndtr

    L = np.asarray(L, dtype=float)
    return L * ndtr(L) + np.exp(-0.5 * L * L) / math.sqrt(2.0 * math.pi)


def mean_gap_slope(L):
    """d(h̄_T/σ)/dΛ = Φ(Λ) [-] [T267]."""
    from scipy.special import ndtr

    return ndtr(np.asarray(L, dtype=float))


@dataclass(frozen=True)
class AverageFlow:
    """The average Reynolds film of :func:`jointdyn.film.fv.assemble` in clearance units [T267].

    sigma_over_c  composite roughness over radial clearance σ/c > 0 [-]
    gamma         Peklenik surface orientation (one of ``GAMMAS``) [-]
    vr            variance ratio V_r = (σ₁² − σ₂²)/σ², −1 ≤ V_r ≤ 1 [-] (1: the journal alone rough)
    """

    sigma_over_c: float
    gamma: float = 1.0
    vr: float = 0.0

    def __post_init__(self):
        s = self.sigma_over_c
        if not (math.isfinite(s) and s > 0.0):
            raise ValueError(f"sigma/c = {s!r} [-]: the roughness must be > 0")
        gamma_index(self.gamma)
        if not (math.isfinite(self.vr) and -1.0 <= self.vr <= 1.0):
            raise ValueError(f"variance ratio vr = {self.vr!r} [-]: must be in [-1, 1]")

    @classmethod
    def of(cls, sigma1: float, sigma2: float, c: float, gamma: float = 1.0) -> AverageFlow:
        """From the RMS roughness of journal (σ₁) and bushing (σ₂) [m] and the clearance c [m]."""
        from jointdyn.film.asperity import composite_sigma

        s = composite_sigma(sigma1, sigma2)
        return cls(s / c, gamma, (sigma1 * sigma1 - sigma2 * sigma2) / (s * s))

    def lam(self, H):
        """Λ = h/σ = H/(σ/c) [-] of the nondimensional film H = h/c."""
        return np.asarray(H, dtype=float) / self.sigma_over_c

    def pressure_x(self, H):
        """φ_x(Λ)·H³ [-] (circumferential pressure flow coefficient)."""
        return phi_x(self.lam(H), self.gamma) * np.asarray(H, dtype=float) ** 3

    def pressure_z(self, H):
        """φ_z(Λ)·H³ [-] (axial pressure flow coefficient)."""
        return phi_z(self.lam(H), self.gamma) * np.asarray(H, dtype=float) ** 3

    def couette(self, H):
        """G = (h̄_T + σφ_s)/c [-], the transported gap: the source is ω ∂G/∂θ [T267]."""
        L = self.lam(H)
        return self.sigma_over_c * (mean_gap(L) + self.vr * shear_flow(L, self.gamma))

    def squeeze(self, H):
        """∂(h̄_T/c)/∂H = Φ(Λ) [-] (the squeeze source 2 ∂h̄_T/∂t per ∂H/∂t)."""
        return mean_gap_slope(self.lam(H))

    def shear_factors(self, H):
        """(φ_f + V_r φ_fs, φ_fp) [-] on the journal surface [T266]."""
        L = self.lam(H)
        return phi_f(L) + self.vr * stress_fs(L, self.gamma), phi_fp(L, self.gamma)
