"""Journal-in-bearing force elements: dry clearance joint and lubricated journal bearing.

Both are *force elements* (no multipliers, the paper's point): the bearing hole (centre P_i,
radius R_B) is on body i, the journal (centre P_j, radius R_J) on body j, c = R_B − R_J.
One compiled kernel serves both: a film force (lubricated bearing) and/or a contact force
(dry joint; mixed film/contact regime of a bearing), each optional.

Kinematics [T14] (spec §7, eqs 12–19 corrected): **e** = P_j − P_i, ξ = |e|/c, u = e/|e|,
t = ẑ × u, ξ̇ = (u·ė)/c, ξγ̇_e = (t·ė)/c, Ω = ω_J + ω_B − 2γ̇_e; the film kernels take the
product ξΩ = ξ(ω_J + ω_B) − 2(t·ė)/c, regular at ξ = 0 (spec §6).

Film force on the journal [T15]: **F** = F_r u + F_t t at the journal centre, −**F** on the
bearing through the same point (spec §7 eqs 20–22 corrected) [T8].

Contact [T16]: penetration δ = |e| − c_c with c_c = c (dry joint) or c − h_a (bearing with
asperity height h_a); normal force F_n from the contact law, friction −μ(v_t)F_n t with the
slip velocity v_t of the journal surface relative to the bearing surface at the contact point
P_c = P_j + R_J u; force on the journal −F_n u − μF_n t at P_c, the opposite on the bearing at
the same point. The film is evaluated at min(ξ, ξ_c), ξ_c = c_c/c, so it hands over to the
contact law continuously when h_min = c(1 − ξ) falls below h_a.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from numba import njit

from ..kinematics import body_state, point_kinematics
from .contact_laws import CONTACT_LAWS, contact_force
from .film_models import FILM_MODELS, film_force
from .friction_laws import FRICTION_LAWS, friction_coefficient
from .transfer import apply_pair, pair_power

JOURNAL = 1

# freal columns (after the four point coordinates)
R_B, R_J, LEN, MU, CLR, H_ASP, ONSET_TOL, V_MIN, CP0, FP0 = 4, 5, 6, 7, 8, 9, 10, 11, 12, 16
# fint columns
FILM, CONTACT, FRICTION, TABLE = 3, 4, 5, 6
# declared outputs and memory (name -> unit); the kernel writes them in this order
JOURNAL_OUTPUTS = {
    "ex": "m",
    "ey": "m",
    "xi": "-",
    "h_min": "m",
    "Fx": "N",
    "Fy": "N",
    "power": "W",
    "contact_force": "N",
}
JOURNAL_MEMORY = {"in_contact": "-", "onset_velocity": "m/s", "impacts": "-", "max_penetration": "m"}
# mem columns
IN_CONTACT, ONSET_VEL = 0, 1
XI_GUARD = 1.0 - 1e-9  # film evaluated at most here when no contact law catches ξ → 1


def _check(owner, name, v, unit, rule, ok):
    if not (isinstance(v, (int, float)) and math.isfinite(v) and ok(v)):
        raise ValueError(f"{owner}.{name} = {v!r} [{unit}]: must be {rule}")


@dataclass(frozen=True)
class ClearanceJoint:
    """Dry revolute clearance joint [T14, T16]: hole of ``body_i`` around the pin of ``body_j``.

    ``contact`` is a contact law instance (``CONTACT_LAWS``), ``friction`` a friction law
    instance (``FRICTION_LAWS``) or None.
    """

    body_i: str
    """body carrying point_i (the bearing/hole side; ``"ground"`` allowed)"""
    point_i: str
    """name of a point of body_i (coordinates in the body frame)"""
    body_j: str
    """body carrying point_j (the journal/pin side; ``"ground"`` allowed)"""
    point_j: str
    """name of a point of body_j (coordinates in the body frame)"""
    bearing_radius: float
    """R_B [m]"""
    journal_radius: float
    """R_J [m], < R_B"""
    contact: object
    """normal contact law (e.g. ``LankaraniNikravesh``)"""
    friction: object | None = None
    """friction law or None (frictionless)"""
    onset_tolerance: float = 1e-8
    """penetration at which a contact onset counts as resolved [m]"""
    min_impact_velocity: float = 1e-4
    """floor of the stored onset velocity δ̇⁻ (grazing contacts) [m/s]"""
    code: ClassVar[int] = JOURNAL
    centred: ClassVar[bool] = True
    OUTPUTS: ClassVar[dict[str, str]] = JOURNAL_OUTPUTS
    """output columns written by the kernel (name -> unit), world frame, force on the journal"""
    MEMORY: ClassVar[dict[str, str]] = JOURNAL_MEMORY
    """memory slots (name -> unit), changed only after accepted steps"""

    @property
    def clearance(self) -> float:
        """c = R_B − R_J [m]"""
        return self.bearing_radius - self.journal_radius

    def validate(self):
        o = type(self).__name__
        _check(o, "bearing_radius", self.bearing_radius, "m", "> 0", lambda v: v > 0)
        _check(
            o,
            "journal_radius",
            self.journal_radius,
            "m",
            f"in (0, bearing_radius = {self.bearing_radius})",
            lambda v: 0 < v < self.bearing_radius,
        )
        _check(o, "onset_tolerance", self.onset_tolerance, "m", "> 0", lambda v: v > 0)
        _check(o, "min_impact_velocity", self.min_impact_velocity, "m/s", "> 0", lambda v: v > 0)
        if isinstance(self, ClearanceJoint) and self.contact is None:
            raise ValueError(
                f"{o}.contact: a dry clearance joint needs a contact law; valid: {sorted(CONTACT_LAWS)}"
            )
        if self.contact is not None and type(self.contact) not in CONTACT_LAWS.values():
            raise ValueError(
                f"{o}.contact = {self.contact!r}: not a contact law; valid: {sorted(CONTACT_LAWS)}"
            )
        if self.friction is not None and type(self.friction) not in FRICTION_LAWS.values():
            raise ValueError(
                f"{o}.friction = {self.friction!r}: not a friction law; valid: {sorted(FRICTION_LAWS)}"
            )

    def int_params(self):
        return (-1, self.contact.code, self.friction.code if self.friction is not None else 0, 0)

    def params(self):
        c = self.clearance
        fp = self.friction.params() if self.friction is not None else (0.0, 0.0, 0.0, 0.0)
        return (
            self.bearing_radius,
            self.journal_radius,
            0.0,
            0.0,
            c,
            0.0,
            self.onset_tolerance,
            self.min_impact_velocity,
            *self.contact.params(),
            *fp,
        )


@dataclass(frozen=True)
class JournalBearing:
    """Lubricated journal bearing [T14, T15] (force element): bushing on ``body_i``, journal on
    ``body_j``; optional asperity contact for the mixed regime [T16]."""

    body_i: str
    """body carrying point_i (the bearing/hole side; ``"ground"`` allowed)"""
    point_i: str
    """name of a point of body_i (coordinates in the body frame)"""
    body_j: str
    """body carrying point_j (the journal/pin side; ``"ground"`` allowed)"""
    point_j: str
    """name of a point of body_j (coordinates in the body frame)"""
    bearing_radius: float
    """R_B [m]"""
    journal_radius: float
    """R_J [m], < R_B"""
    length: float
    """L [m], > 0"""
    viscosity: float
    """μ [Pa·s], > 0"""
    film: str = "alshaer2005"
    """film model name (``FILM_MODELS``)"""
    contact: object | None = None
    """contact law for the mixed regime, or None (then ξ ≥ 1 stops the simulation)"""
    friction: object | None = None
    """friction law for asperity contact, or None"""
    asperity_height: float = 0.0
    """h_a: contact starts when h_min = c(1 − ξ) < h_a [m], 0 ≤ h_a < c"""
    onset_tolerance: float = 1e-8
    """penetration at which a contact onset counts as resolved [m]"""
    min_impact_velocity: float = 1e-4
    """floor of the stored onset velocity δ̇⁻ [m/s]"""
    code: ClassVar[int] = JOURNAL
    centred: ClassVar[bool] = True
    OUTPUTS: ClassVar[dict[str, str]] = JOURNAL_OUTPUTS
    """output columns written by the kernel (name -> unit), world frame, force on the journal"""
    MEMORY: ClassVar[dict[str, str]] = JOURNAL_MEMORY
    """memory slots (name -> unit), changed only after accepted steps"""

    clearance = ClearanceJoint.clearance

    def validate(self):
        o = type(self).__name__
        ClearanceJoint.validate(self)
        _check(o, "length", self.length, "m", "> 0", lambda v: v > 0)
        _check(o, "viscosity", self.viscosity, "Pa·s", "> 0", lambda v: v > 0)
        _check(
            o,
            "asperity_height",
            self.asperity_height,
            "m",
            f"in [0, clearance = {self.clearance:.6g})",
            lambda v: 0 <= v < self.clearance,
        )
        if self.film not in FILM_MODELS:
            raise ValueError(f"{o}.film = {self.film!r}: unknown film model; valid: {sorted(FILM_MODELS)}")
        limit = getattr(FILM_MODELS[self.film], "max_length_over_diameter", math.inf)
        ld = self.length / (2.0 * self.journal_radius)
        if ld > limit:
            import warnings

            from ..errors import PhysicsWarning

            warnings.warn(
                f"{o}: film model {self.film!r} is meant for L/D ≤ {limit:g}; this bearing has "
                f"L/D = {ld:.3g}",
                PhysicsWarning,
                stacklevel=2,
            )

    def int_params(self):
        return (
            FILM_MODELS[self.film].code,
            self.contact.code if self.contact is not None else -1,
            self.friction.code if self.friction is not None else 0,
            0,
        )

    def params(self):
        fp = self.friction.params() if self.friction is not None else (0.0, 0.0, 0.0, 0.0)
        cp = self.contact.params() if self.contact is not None else (0.0, 0.0, 0.0, 0.0)
        return (
            self.bearing_radius,
            self.journal_radius,
            self.length,
            self.viscosity,
            self.clearance,
            self.asperity_height,
            self.onset_tolerance,
            self.min_impact_velocity,
            *cp,
            *fp,
        )


@njit(cache=True)
def journal_kinematics(q, qd, bi, bj, r):
    """e, ė [m, m/s], arms s_i, s_j [m] and body rates ω_i, ω_j [rad/s] [T14]."""
    pix, piy, six, siy, vix, viy = point_kinematics(q, qd, bi, r[0], r[1])
    pjx, pjy, sjx, sjy, vjx, vjy = point_kinematics(q, qd, bj, r[2], r[3])
    wi = body_state(q, qd, bi)[5]
    wj = body_state(q, qd, bj)[5]
    return pjx - pix, pjy - piy, vjx - vix, vjy - viy, six, siy, sjx, sjy, wi, wj


@njit(cache=True)
def penetration(q, qd, bi, bj, r):
    """Contact penetration δ = |e| − c_c [m] and its rate δ̇ [m/s] [T16]."""
    ex, ey, edx, edy, six, siy, sjx, sjy, wi, wj = journal_kinematics(q, qd, bi, bj, r)
    e = math.sqrt(ex * ex + ey * ey)
    ed = (ex * edx + ey * edy) / e if e > 0.0 else math.sqrt(edx * edx + edy * edy)
    return e - (r[CLR] - r[H_ASP]), ed


@njit(cache=True)
def journal_element(q, qd, mem, bi, bj, ip, r, tables, Q, out):
    """Film and/or contact forces of one journal element into Q [T14–T16]; fills ``out``.

    Returns 0, or 1 if ξ ≥ 1 was probed with no contact law (evaluated guarded at ξ = 1 − 1e-9).
    """
    ex, ey, edx, edy, six, siy, sjx, sjy, wi, wj = journal_kinematics(q, qd, bi, bj, r)
    c = r[CLR]
    e = math.sqrt(ex * ex + ey * ey)
    if e > 0.0:
        ux = ex / e
        uy = ey / e
    else:
        sp = math.sqrt(edx * edx + edy * edy)  # any unit vector works at e = 0 (spec §6)
        ux = edx / sp if sp > 0.0 else 1.0
        uy = edy / sp if sp > 0.0 else 0.0
    tx = -uy
    ty = ux
    xi = e / c
    status = 0
    power = 0.0
    ffx = 0.0
    ffy = 0.0
    if ip[FILM] >= 0:
        xi_cap = (c - r[H_ASP]) / c if ip[CONTACT] >= 0 else XI_GUARD
        if ip[CONTACT] < 0 and xi >= 1.0:
            status = 1
        xi_f = min(xi, xi_cap, XI_GUARD)
        xid = (ux * edx + uy * edy) / c
        xi_om = xi_f * (wj + wi) - 2.0 * (tx * edx + ty * edy) / c  # ξΩ [T14]
        fr, ft = film_force(ip[FILM], xi_f, xid, xi_om, r[MU], r[R_J], r[LEN], c, tables[ip[TABLE]])
        ffx = fr * ux + ft * tx
        ffy = fr * uy + ft * ty
        # film force at the journal centre, reaction through the same point [T8, T15]
        apply_pair(Q, bi, bj, ffx, ffy, sjx, sjy, six + ex, siy + ey)
        power += pair_power(qd, bi, bj, ffx, ffy, sjx, sjy, six + ex, siy + ey)
    fn = 0.0
    fcx = 0.0
    fcy = 0.0
    if ip[CONTACT] >= 0:
        delta = e - (c - r[H_ASP])
        if delta > 0.0:
            dd = ux * edx + uy * edy
            v0 = mem[ONSET_VEL] if mem[IN_CONTACT] > 0.5 else max(dd, r[V_MIN])
            fn = contact_force(ip[CONTACT], delta, dd, v0, r[CP0 : CP0 + 4])
            # slip of the journal surface relative to the bearing surface at P_c [T16]
            vt = tx * edx + ty * edy + wj * r[R_J] - wi * r[R_B]
            mu = friction_coefficient(ip[FRICTION], vt, r[FP0 : FP0 + 4]) if ip[FRICTION] > 0 else 0.0
            fcx = -fn * ux - mu * fn * tx
            fcy = -fn * uy - mu * fn * ty
            cx = r[R_J] * ux  # P_c − P_j
            cy = r[R_J] * uy
            apply_pair(Q, bi, bj, fcx, fcy, sjx + cx, sjy + cy, six + ex + cx, siy + ey + cy)
            power += pair_power(qd, bi, bj, fcx, fcy, sjx + cx, sjy + cy, six + ex + cx, siy + ey + cy)
    out[4] = ffx + fcx
    out[5] = ffy + fcy
    out[6] = power
    out[7] = fn
    out[0] = ex
    out[1] = ey
    out[2] = xi
    out[3] = c - e
    return status
