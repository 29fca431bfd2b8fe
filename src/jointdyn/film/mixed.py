"""Steady mixed-lubrication film of the finite bearing: the average Reynolds film [T268], its
forces and its friction torque with the shear-stress factors [T269].

Units as :mod:`.field`: forces in μωR⁴/c², torques in μωR⁴/c (bearing fixed, journal speed
ω > 0, lubricant supplied at the maximum film θ = 0, as :func:`jointdyn.bearing.design.finite_steady`).
Friction torque on the journal (resisting), over the full bearing [T269]

    T̄ = ∫∫ (φ_f + V_r φ_fs)/H dθ dζ + ∫∫ 3 φ_fp H ∂P/∂θ dθ dζ,

the Couette part over the whole circumference (the Raimondi–Boyd treatment of [T75]); with
every factor 1 the second integral is ξF̄_t/2 by parts, which recovers [T75].
"""

from __future__ import annotations

import math

import numpy as np

from jointdyn.film.cavitation import condition
from jointdyn.film.fv import DEFAULT_MESH, assemble, check_ld, check_xi


def barus_pressure(q, barus: float):
    """Pressure P and viscosity ratio μ/μ₀ = e^{ᾱP} of the Barus film from the isoviscous reduced
    pressure q (P = −ln(1 − ᾱq)/ᾱ) [T317]; ValueError unless ᾱ·max q < 1."""
    q = np.asarray(q, dtype=float)
    m = barus * float(q.max(initial=0.0))
    if not m < 1.0:
        raise ValueError(
            f"pressure_viscosity: α·p_iso,max = {m:.3g} >= 1: the Barus film has no finite pressure "
            "here (Barus holds for moderate pressures only) [T317]"
        )
    r = 1.0 - barus * q
    return -np.log(r) / barus, 1.0 / r


def mixed_steady(
    eps: float,
    ld: float,
    flow=None,
    cavitation: str = "reynolds",
    mesh=DEFAULT_MESH,
    cavitated=None,
    barus: float = 0.0,
):
    """Nondimensional steady film at eccentricity ratio ε [T268–T269].

    eps         eccentricity ratio, 0 < ε < 1 [-]
    ld          L/D > 0 [-]
    flow        :class:`~jointdyn.film.flow_factors.AverageFlow` (average Reynolds film) or None
    cavitation  a registered condition (:mod:`.cavitation`)
    barus       ᾱ = α·6μ₀ωR²/c² ≥ 0 [-], Barus pressure–viscosity α [1/Pa] in the pressure unit of
                [T70] (0: isoviscous) [T317]
    Returns dict: Fr, Ft [μωR⁴/c²], torque T̄ [μωR⁴/c], couette (its Couette part), theta (nt,)
    [rad] and weights (nt,) [rad] (θ quadrature), cavitated (warm start), residual, iterations.
    """
    check_xi(eps)
    check_ld(ld)
    nt, nz = int(mesh[0]), int(mesh[1])
    prob = assemble(eps, ld, nt, nz, flow=flow)
    fixed = np.zeros(nt * nz, bool)
    fixed[:nz] = True  # supply line θ = 0
    s = condition(cavitation).solve(prob, 0.0, eps / (2.0 + eps * eps), fixed, cavitated)
    P = s.P.reshape(nt, nz)
    visc = None
    if barus > 0.0:  # reduced pressure → Barus pressure and viscosity ratio [T317]
        P, visc = barus_pressure(P, barus)
    th = prob.theta
    ds = 2.0 * math.pi / nt
    wt = ds * prob.dtheta  # θ weights
    rows = (2.0 * prob.area.reshape(nt, nz) * P).sum(axis=1)  # ∫P dθ dζ per θ node, full length
    Fr = 6.0 * float(np.sum(rows * np.cos(th)))
    Ft = 6.0 * float(np.sum(rows * np.sin(th)))
    H = 1.0 + eps * np.cos(th)
    if flow is None:
        fc, fp = np.ones(nt), np.ones(nt)
    else:
        fc, fp = flow.shear_factors(H)
    couette = float(np.sum(wt * fc / H) * 2.0 * ld)
    if visc is not None:  # the Couette shear with μ(p) where the film carries pressure [T317]
        couette += float(np.sum(2.0 * prob.area.reshape(nt, nz) * (fc / H)[:, None] * (visc - 1.0)))
    dPds = (np.roll(P, -1, axis=0) - np.roll(P, 1, axis=0)) / (2.0 * ds)  # periodic, P = 0 at θ = 0
    poiseuille = float(np.sum((3.0 * fp * H * ds)[:, None] * dPds * 2.0 * prob.cv[None, :]))
    return {
        "Fr": Fr,
        "Ft": Ft,
        "torque": couette + poiseuille,
        "couette": couette,
        "theta": th,
        "weights": wt,
        "cavitated": s.state,
        "residual": s.residual,
        "iterations": s.iterations,
    }
