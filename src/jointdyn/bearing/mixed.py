"""Steady operating point of a journal bearing in mixed lubrication and its Stribeck curve
[T268–T272].

At a constant load W and journal speed N the journal settles where the film force (average
Reynolds film with Patir–Cheng factors [T268]) plus the Greenwood–Tripp asperity force [T262]
balance the load: |F_film(ε) + F_asp(ε)| = W, solved for ε in u = −ln(1 − ε); the attitude is
the angle of the total force from the line of centres [T271]. Friction torque on the journal =
hydrodynamic shear with the shear-stress factors [T269] + boundary friction of the asperity load,
T_b = R·f_b·tanh(ωR/v_s)·∫p_a dA (regularised Coulomb, v_s the regularisation speed) [T270].
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from jointdyn.bearing.design import EPS_MAX
from jointdyn.core import interrupts
from jointdyn.film.asperity import GreenwoodTripp, asperity_load
from jointdyn.film.fv import DEFAULT_MESH
from jointdyn.film.mixed import mixed_steady

#: CSV columns of :func:`stribeck`, in order
STRIBECK_COLUMNS = (
    "speed_rpm",
    "friction_torque",
    "friction_coefficient",
    "h_min",
    "eps",
    "asperity_load_fraction",
    "hersey",
)


@dataclass(frozen=True)
class Bearing:
    """Geometry, lubricant and surfaces of the mixed bearing.

    radius, length, clearance  R, L, c > 0 [m]
    viscosity                  μ > 0 [Pa·s]
    contact                    Greenwood–Tripp asperity contact (:class:`GreenwoodTripp`)
    flow                       :class:`~jointdyn.film.flow_factors.AverageFlow` or None (smooth film)
    boundary_friction          f_b ≥ 0 [-]
    slip_speed                 v_s > 0 [m/s], regularisation speed of the boundary friction
    pressure_viscosity         Barus α ≥ 0 [1/Pa], μ = μ₀e^{αp} (0: isoviscous) [T317]
    """

    radius: float
    length: float
    clearance: float
    viscosity: float
    contact: GreenwoodTripp
    flow: object = None
    boundary_friction: float = 0.1
    slip_speed: float = 1e-3
    pressure_viscosity: float = 0.0

    def __post_init__(self):
        for name, v, unit in (
            ("radius", self.radius, "m"),
            ("length", self.length, "m"),
            ("clearance", self.clearance, "m"),
            ("viscosity", self.viscosity, "Pa·s"),
            ("slip_speed", self.slip_speed, "m/s"),
        ):
            if not (math.isfinite(v) and v > 0.0):
                raise ValueError(f"{name} = {v!r} [{unit}]: must be finite and > 0")
        f = self.boundary_friction
        if not (math.isfinite(f) and 0.0 <= f <= 1.0):
            raise ValueError(f"boundary_friction = {f!r} [-]: must be in [0, 1]")
        a = self.pressure_viscosity
        if not (math.isfinite(a) and 0.0 <= a <= 1e-7):
            raise ValueError(f"pressure_viscosity = {a!r} [1/Pa]: must be in [0, 1e-7] (oils: 1e-8 … 3e-8)")


def _state(b: Bearing, eps: float, omega: float, mesh, warm):
    """Dimensional forces [N] and torque parts at ε (journal speed ω [rad/s])."""
    R, L, c = b.radius, b.length, b.clearance
    barus = b.pressure_viscosity * 6.0 * b.viscosity * omega * R**2 / c**2  # [T70, T317]
    d = mixed_steady(eps, L / (2.0 * R), b.flow, "reynolds", mesh, warm, barus)
    fs = b.viscosity * omega * R**4 / c**2
    a = asperity_load(b.contact, eps, R, L, c, d["theta"], d["weights"])
    Fr, Ft = fs * d["Fr"] + a["F_r"], fs * d["Ft"] + a["F_t"]
    return {
        "total": math.hypot(Fr, Ft),
        "Fr": Fr,
        "Ft": Ft,
        "film": fs * math.hypot(d["Fr"], d["Ft"]),
        "asperity": math.hypot(a["F_r"], a["F_t"]),
        "normal": a["normal"],
        "p_asp_max": a["p_max"],
        "hydro_torque": fs * c * d["torque"],
        "cavitated": d["cavitated"],
    }


def _barus_limit(total, lo: float, hi: float, load: float) -> float:
    """The largest u ≤ hi where the Barus film exists (bisection to 10⁻⁶ in u), or hi; ValueError
    naming the load if the film cannot carry it there [T317]."""

    def ok(u):
        try:
            return total(u)
        except ValueError:
            return None

    if ok(hi) is not None:
        return hi
    a, z = lo, hi
    while z - a > 1e-6:
        m = 0.5 * (a + z)
        a, z = (m, z) if ok(m) is not None else (a, m)
    cap = ok(a)
    if cap is not None and cap < load:
        raise ValueError(
            f"load = {load!r} [N]: beyond the Barus film's range (it carries {cap:.4g} N where "
            f"α·p_iso,max reaches 1, eps = {1 - math.exp(-a):.4f}); reduce pressure_viscosity or the load"
        )
    return a


def operating_point(b: Bearing, load: float, speed: float, mesh=DEFAULT_MESH) -> dict:
    """Mixed-lubrication equilibrium at load W [N] and journal speed N [rev/s] [T271].

    Returns dict: eps [-], attitude_deg [deg], h_min [m], lambda_min = h_min/σ [-], film_load,
    asperity_load [N], asperity_load_fraction [-], friction_torque (hydrodynamic + boundary,
    resisting, on the journal) [N·m], boundary_torque [N·m], friction_coefficient = T/(WR) [-],
    power_loss [W], hersey = μN/P (N in rev/s, P = W/(2RL)) [-], p_asp_max [Pa].
    """
    for name, v, unit in (("load", load, "N"), ("speed", speed, "rev/s")):
        if not (math.isfinite(v) and v > 0.0):
            raise ValueError(f"{name} = {v!r} [{unit}]: must be finite and > 0")
    from scipy.optimize import brentq

    omega = 2.0 * math.pi * speed
    warm = [None]

    def total(u):
        s = _state(b, 1.0 - math.exp(-u), omega, mesh, warm[0])
        warm[0] = s["cavitated"]
        return s["total"]

    lo, hi = 1e-4, -math.log(1.0 - EPS_MAX)
    if b.pressure_viscosity > 0.0:  # the Barus film exists up to α·p_iso,max < 1 [T317]
        hi = _barus_limit(total, lo, hi, load)
    top = total(hi)
    if top < load:
        raise ValueError(
            f"load = {load!r} [N]: the bearing cannot carry it even in boundary contact (film + "
            f"asperities carry {top:.4g} N at eps = {EPS_MAX}, h_min = "
            f"{b.clearance * (1 - EPS_MAX):.3g} m); reduce the load or stiffen the contact"
        )
    if total(lo) > load:
        raise ValueError(f"load = {load!r} [N]: too light, eps < 1e-4 at this speed (Petroff's film)")
    u = brentq(lambda x: math.log(total(x) / load), lo, hi, xtol=1e-10, rtol=1e-10)
    eps = 1.0 - math.exp(-u)
    s = _state(b, eps, omega, mesh, warm[0])
    R = b.radius
    v = omega * R
    Tb = R * b.boundary_friction * math.tanh(v / b.slip_speed) * s["normal"]
    T = s["hydro_torque"] + Tb
    P = load / (2.0 * R * b.length)
    h_min = b.clearance * (1.0 - eps)
    return {
        "eps": eps,
        "attitude_deg": math.degrees(math.atan2(s["Ft"], -s["Fr"])),
        "h_min": h_min,
        "lambda_min": h_min / b.contact.sigma,
        "film_load": s["film"],
        "asperity_load": s["asperity"],
        "asperity_load_fraction": s["asperity"] / load,
        "friction_torque": T,
        "boundary_torque": Tb,
        "friction_coefficient": T / (load * R),
        "power_loss": T * omega,
        "hersey": b.viscosity * speed / P,
        "p_asp_max": s["p_asp_max"],
        "load_residual": s["total"] / load - 1.0,
    }


def stribeck(b: Bearing, load: float, speeds_rpm, mesh=DEFAULT_MESH) -> dict:
    """Stribeck curve at constant load W [N] over journal speeds [rev/min] [T272]: dict column →
    list (``STRIBECK_COLUMNS``), one entry per speed, in the given order."""
    speeds = [float(x) for x in speeds_rpm]
    if not speeds:
        raise ValueError("speeds: give at least one speed in rev/min")
    for x in speeds:
        if not (math.isfinite(x) and x > 0.0):
            raise ValueError(f"speed = {x!r} [rev/min]: must be finite and > 0")
    rows = []
    for n in speeds:
        interrupts.check()  # a signal recorded by a caller's catching() stops here [T332]
        op = operating_point(b, load, n / 60.0, mesh)
        op["speed_rpm"] = n
        rows.append(op)
    return {k: [r[k] for r in rows] for k in STRIBECK_COLUMNS}
