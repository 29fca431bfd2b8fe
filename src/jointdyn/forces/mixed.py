"""Mixed lubrication in the multibody journal element: Greenwood–Tripp asperity contact in parallel
with the film, and boundary friction [T314–T316].

The asperity resultant of the aligned bearing [T262] depends on ξ only (for given R, L, c and
surfaces): it is tabulated once per element on a uniform grid in u = −ln(1 − ξ) (ξ ≤ 0.999,
``N_U`` points, log of the values interpolated linearly) from the exact F_{5/2} [T261] by the
periodic trapezoid rule on ``N_THETA`` nodes, and interpolated in the kernel. It acts on the
journal centre along −u (toward the centre) like the film's radial force, in parallel with the
un-capped film [T263]; boundary friction is the couple T_b = R_J·f_b·tanh((ω_J − ω_B)R_J/v_s)·W_a
[T270] on journal (−) and bushing (+), W_a = ∫p_a dA.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from numba import njit

from jointdyn.core.layout import check_finite

GREENWOOD_TRIPP = 1
N_U = 800  # grid points of the tables in u = −ln(1 − ξ)
U_MAX = math.log(1000.0)  # ξ ≤ 0.999 (beyond: the value at 0.999)
N_THETA = 2048  # θ nodes of the resultant (periodic trapezoid rule)
WIDTH = 2  # parameter block: f_b, v_s
FB, VS = range(WIDTH)


@dataclass(frozen=True)
class GreenwoodTrippContact:
    """Greenwood–Tripp asperity contact in parallel with the film, with boundary friction [T314]."""

    sigma: float
    """composite RMS roughness σ = √(σ₁² + σ₂²) [m], > 0"""
    eta_beta_sigma: float = 0.04
    """roughness parameter ηβσ [-], > 0 (typically 0.03–0.07)"""
    sigma_over_beta: float = 0.001
    """σ/β [-], > 0 (typically 1e-4–1e-2)"""
    modulus: float = 1.1e11
    """composite modulus E' [Pa], > 0"""
    boundary_friction: float = 0.1
    """boundary friction coefficient f_b [-], in [0, 1]"""
    slip_speed: float = 1e-3
    """regularisation speed v_s of the boundary friction [m/s], > 0"""
    code: ClassVar[int] = GREENWOOD_TRIPP
    PARAMS: ClassVar[tuple[str, ...]] = ("boundary_friction", "slip_speed")

    def validate(self) -> None:
        o = type(self).__name__
        for name, unit in (
            ("sigma", "m"),
            ("eta_beta_sigma", "-"),
            ("sigma_over_beta", "-"),
            ("modulus", "Pa"),
        ):
            check_finite(o, name, getattr(self, name), unit, "> 0", lambda v: v > 0)
        check_finite(o, "boundary_friction", self.boundary_friction, "-", "in [0, 1]", lambda v: 0 <= v <= 1)
        check_finite(o, "slip_speed", self.slip_speed, "m/s", "> 0", lambda v: v > 0)

    def surfaces(self):
        """The steady model's contact (:class:`jointdyn.film.asperity.GreenwoodTripp`)."""
        from jointdyn.film.asperity import GreenwoodTripp

        return GreenwoodTripp(self.sigma, self.eta_beta_sigma, self.sigma_over_beta, self.modulus)

    def tables(self, R: float, L: float, c: float) -> tuple[np.ndarray, np.ndarray]:
        """(u, ln(−F_r)) and (u, ln W_a) on the uniform u grid [T315]: F_r [N] the radial
        resultant (≤ 0, toward the centre), W_a = ∫p_a dA [N]."""
        from jointdyn.film.asperity import asperity_load

        gt = self.surfaces()
        u = np.linspace(0.0, U_MAX, N_U)
        theta = np.linspace(0.0, 2.0 * math.pi, N_THETA, endpoint=False)
        w = np.full(N_THETA, 2.0 * math.pi / N_THETA)
        fr, wa = np.empty(N_U), np.empty(N_U)
        for i, ui in enumerate(u):
            a = asperity_load(gt, 1.0 - math.exp(-ui), R, L, c, theta, w)
            fr[i], wa[i] = -a["F_r"], a["normal"]
        tiny = 1e-300
        return (
            np.column_stack([u, np.log(np.maximum(fr, tiny))]),
            np.column_stack([u, np.log(np.maximum(wa, tiny))]),
        )


ASPERITY_MODELS = {"greenwood_tripp": GreenwoodTrippContact}


@njit(cache=True)
def asperity_loads(xi, tab_r, tab_n):
    """(F_r [N] ≤ 0 along the line of centres, W_a [N]) at ξ from the element's tables [T315]."""
    u = -math.log(1.0 - xi) if xi < 0.999 else U_MAX
    s = u / U_MAX * (N_U - 1)
    i = min(int(s), N_U - 2)
    f = s - i
    lr = (1.0 - f) * tab_r[i, 1] + f * tab_r[i + 1, 1]
    ln = (1.0 - f) * tab_n[i, 1] + f * tab_n[i + 1, 1]
    return -math.exp(lr), math.exp(ln)
