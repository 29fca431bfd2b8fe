"""Journal-in-bearing force elements: dry clearance joint and lubricated journal bearing.

Both are *force elements* (no multipliers, the paper's point): the bearing hole (centre P_i,
radius R_B) is on body i, the journal (centre P_j, radius R_J) on body j, c = R_B − R_J.
One compiled kernel serves both: a film force (lubricated bearing) and/or a contact force
(dry joint; mixed film/contact regime of a bearing), each optional.

Kinematics [T14] (the paper's eqs 12–19 corrected): **e** = P_j − P_i, ξ = |e|/c, u = e/|e|,
t = ẑ × u, ξ̇ = (u·ė)/c, ξγ̇_e = (t·ė)/c, Ω = ω_J + ω_B − 2γ̇_e; the film kernels take the
product ξΩ = ξ(ω_J + ω_B) − 2(t·ė)/c, regular at ξ = 0 [T24].

Film force on the journal [T15]: **F** = F_r u + F_t t at the journal centre, −**F** on the
bearing through the same point (the paper's eqs 20–22 corrected) [T8, T15].

Contact [T16]: penetration δ = |e| − c_c with c_c = c (dry joint) or c − h_a (bearing with
asperity height h_a); normal force F_n from the contact law, friction −μ(v_t)F_n t with the
slip velocity v_t of the journal surface relative to the bearing surface at the contact point
P_c = P_j + R_J u; force on the journal −F_n u − μF_n t at P_c, the opposite on the bearing at
the same point. The film is evaluated at min(ξ, ξ_c), ξ_c = c_c/c, so it hands over to the
contact law continuously when h_min = c(1 − ξ) falls below h_a.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import ClassVar

from numba import njit

from jointdyn.core.layout import HEADER, POINTS, Layout, check_finite
from jointdyn.errors import PhysicsWarning
from jointdyn.film.models import FILM_MODELS, FILM_WIDTH, film_dispatch, film_model, film_name
from jointdyn.film.models import NONE as NO_FILM
from jointdyn.film.shear_kernels import couette_torque
from jointdyn.forces.contact_laws import CONTACT_LAWS, CONTACT_WIDTH, contact_dispatch
from jointdyn.forces.contact_laws import NONE as NO_CONTACT
from jointdyn.forces.friction_laws import FRICTION_LAWS, FRICTION_WIDTH, friction_dispatch
from jointdyn.forces.friction_laws import NONE as NO_FRICTION
from jointdyn.forces.jfo_film import BASE as JFO_BASE
from jointdyn.forces.jfo_film import MEMORY as JFO_MEMORY
from jointdyn.forces.jfo_film import OUTPUTS as JFO_OUTPUTS
from jointdyn.forces.journal_geometry import CLR as GEOM_CLR
from jointdyn.forces.journal_geometry import H_ASP as GEOM_H_ASP
from jointdyn.forces.journal_geometry import journal_kinematics, penetration  # noqa: F401  (re-exported)
from jointdyn.forces.journal_pack import (
    check_jfo,
    failure_hint,
    memory0,
    memory_slots,
    memory_width,
    output_slots,
    pack_journal,
)
from jointdyn.forces.journal_pieces import asperity_terms, film_viscosity, jfo_terms
from jointdyn.forces.mixed import ASPERITY_MODELS
from jointdyn.forces.mixed import WIDTH as ASPERITY_WIDTH
from jointdyn.forces.thermal import BASE as THERMAL_BASE
from jointdyn.forces.thermal import MEMORY as THERMAL_MEMORY
from jointdyn.forces.thermal import THERMAL_MODELS
from jointdyn.forces.thermal import WIDTH as THERMAL_WIDTH
from jointdyn.forces.transfer import apply_pair, pair_power

JOURNAL = 1

# declared layouts (names -> slots of the element's rows); the kernels read these constants only
REAL = Layout(
    POINTS
    + (
        "bearing_radius",
        "journal_radius",
        "length",
        "viscosity",
        "clearance",
        "asperity_height",
        "onset_tolerance",
        "min_impact_velocity",
    ),
    blocks={
        "film": FILM_WIDTH,
        "contact": CONTACT_WIDTH,
        "friction": FRICTION_WIDTH,
        "thermal": THERMAL_WIDTH,
        "asperity": ASPERITY_WIDTH,
    },
)
INT = Layout(HEADER + ("film", "contact", "friction", "table", "shear", "thermal", "asperity", "jfo"))
OUTPUTS = {
    "ex": "m",
    "ey": "m",
    "xi": "-",
    "h_min": "m",
    "Fx": "N",
    "Fy": "N",
    "power": "W",
    "contact_force": "N",
    "friction_torque": "N·m",
    "power_loss": "W",
    "power_exchanged": "W",
}
BEARING_OUTPUTS = OUTPUTS | JFO_OUTPUTS  # the jfo film's outputs, used by a bearing with one [T306]
MEMORY = {"in_contact": "-", "onset_velocity": "m/s", "impacts": "-", "max_penetration": "m"}
assert len(MEMORY) == THERMAL_BASE and len(MEMORY) + len(THERMAL_MEMORY) == JFO_BASE

R_B, R_J, LEN, MU, CLR, H_ASP, ONSET_TOL, V_MIN = REAL.slots(*REAL.names[4:])
assert (CLR, H_ASP) == (GEOM_CLR, GEOM_H_ASP)
FILM_P0, FILM_P1 = REAL.block("film").start, REAL.block("film").stop
CONTACT_P0, CONTACT_P1 = REAL.block("contact").start, REAL.block("contact").stop
FRICTION_P0, FRICTION_P1 = REAL.block("friction").start, REAL.block("friction").stop
FILM, CONTACT, FRICTION, TABLE, SHEAR, THERMAL, ASPERITY, JFO = INT.slots(*INT.names[3:])
ASP_P0 = REAL.block("asperity").start
THERMAL_P0, THERMAL_P1 = REAL.block("thermal").start, REAL.block("thermal").stop
IN_CONTACT, ONSET_VEL, IMPACTS, MAX_PEN = Layout(MEMORY).slots(*MEMORY)
O_EX, O_EY, O_XI, O_HMIN, O_FX, O_FY, O_POWER, O_FN, O_TORQUE, O_LOSS, O_EXCH = Layout(OUTPUTS).slots(
    *OUTPUTS
)
O_CONTENT, O_INFLOW, O_SIDE = Layout(BEARING_OUTPUTS).slots(*list(JFO_OUTPUTS)[:3])  # then per feature
ASPERITY_MAX = 0.5  # asperity height ≤ this fraction of the clearance [T283]
XI_GUARD = 1.0 - 1e-9  # film evaluated at most here when no contact law catches ξ → 1


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
    REAL: ClassVar[Layout] = REAL
    INT: ClassVar[Layout] = INT
    OUTPUTS: ClassVar[dict[str, str]] = OUTPUTS
    """output columns written by the kernel (name -> unit), world frame, force on the journal"""
    MEMORY: ClassVar[dict[str, str]] = MEMORY
    """memory slots (name -> unit), changed only after accepted steps"""
    STIFF: ClassVar[bool] = False
    """capability: the element makes the equations stiff (``solver="auto"`` then picks radau5 [T116])"""
    ORBIT: ClassVar[tuple[str, str]] = ("ex", "ey")
    """capability: the outputs holding the journal-centre offset e = P_j − P_i, world frame [m];
    with ``clearance`` they give the orbit e/c (``Results.journals``/``orbit``)"""

    @property
    def clearance(self) -> float:
        """c = R_B − R_J [m]"""
        return self.bearing_radius - self.journal_radius

    def validate(self):
        o = type(self).__name__
        check_finite(o, "bearing_radius", self.bearing_radius, "m", "> 0", lambda v: v > 0)
        check_finite(
            o,
            "journal_radius",
            self.journal_radius,
            "m",
            f"in (0, bearing_radius = {self.bearing_radius})",
            lambda v: 0 < v < self.bearing_radius,
        )
        check_finite(o, "onset_tolerance", self.onset_tolerance, "m", "> 0", lambda v: v > 0)
        check_finite(o, "min_impact_velocity", self.min_impact_velocity, "m/s", "> 0", lambda v: v > 0)
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

    def _film(self):
        return None

    def error_length(self) -> float:
        """Capability: the length the error test measures this element's positions against, the
        clearance c [m] [T186] (``SimConfig.error_scale = "clearance"``)."""
        return self.clearance

    failure_hint = failure_hint

    @classmethod
    def example(cls):
        """The benchmark's dry pin (R_B = 10.5 mm, R_J = 10 mm, Lankarani–Nikravesh) between
        points "A" of body "a" and "B" of body "b" (contract tests)."""
        from jointdyn.forces.contact_laws import LankaraniNikravesh

        return cls("a", "A", "b", "B", 0.0105, 0.0100, contact=LankaraniNikravesh.example())

    def pack(self, tables: list, body_index) -> tuple[dict, dict, dict]:
        """Element-specific slots (ints, reals, blocks) of the declared layouts [T14–T16]."""
        return pack_journal(self, tables, body_index)


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
    viscosity: float | None = None
    """μ [Pa·s], > 0; required unless ``thermal`` is set (then omitted: the film follows μ(T) of
    the oil [T311])"""
    film: object = "alshaer2005"
    """film model: a name in ``FILM_MODELS`` or an instance of a registered model"""
    contact: object | None = None
    """contact law for the mixed regime, or None (then ξ ≥ 1 stops the simulation)"""
    friction: object | None = None
    """friction law for asperity contact, or None"""
    shear: bool = True
    """apply the film's viscous shear torques to journal and bushing [T75] (False: pressure
    forces only, the assumption of the long-bearing papers)"""
    asperity_height: float = 0.0
    """h_a: contact starts when h_min = c(1 − ξ) < h_a [m], 0 ≤ h_a ≤ c/2 [T283]"""
    onset_tolerance: float = 1e-8
    """penetration at which a contact onset counts as resolved [m]"""
    min_impact_velocity: float = 1e-4
    """floor of the stored onset velocity δ̇⁻ [m/s]"""
    asperity: object | None = None
    """Greenwood–Tripp asperity contact in parallel with the film, with boundary friction
    (``forces.mixed.GreenwoodTrippContact``) [T314]; None: smooth surfaces"""
    thermal: object | None = None
    """lumped oil temperature (``forces.thermal.LumpedOil``) [T310]; the film's viscosity then
    follows μ(T) of its oil (omit ``viscosity``); None: constant ``viscosity``"""
    code: ClassVar[int] = JOURNAL
    centred: ClassVar[bool] = True
    REAL: ClassVar[Layout] = REAL
    INT: ClassVar[Layout] = INT
    OUTPUTS: ClassVar[dict[str, str]] = BEARING_OUTPUTS
    """output columns written by the kernel (name -> unit), world frame, force on the journal;
    the jfo film's (content, flows) only with ``film`` finite with cavitation jfo [T306]"""
    MEMORY: ClassVar[dict[str, str]] = MEMORY | THERMAL_MEMORY | JFO_MEMORY
    """memory slots (name -> unit), changed only after accepted steps (oil temperature [T311],
    the jfo film [T306]; its cell contents follow the named slots)"""
    STIFF: ClassVar[bool] = True
    """capability: the film makes the equations stiff (``solver="auto"`` then picks radau5 [T116])"""
    ORBIT: ClassVar[tuple[str, str]] = ("ex", "ey")
    """capability: the outputs holding the journal-centre offset e = P_j − P_i, world frame [m]"""

    clearance = ClearanceJoint.clearance
    pack = ClearanceJoint.pack
    error_length = ClearanceJoint.error_length
    failure_hint = ClearanceJoint.failure_hint

    def _film(self):
        return film_model(self.film)

    memory_slots = memory_slots
    output_slots = output_slots
    memory_width = memory_width
    memory0 = memory0

    @classmethod
    def example(cls, film="alshaer2005"):
        """The benchmark's lubricated pin (c = 0.5 mm, L = 40 mm, μ = 0.4 Pa·s) between points
        "A" of body "a" and "B" of body "b" (contract tests)."""
        return cls("a", "A", "b", "B", 0.0105, 0.0100, 0.04, 0.4, film=film)

    def validate(self):
        o = type(self).__name__
        ClearanceJoint.validate(self)
        for field, registry in (("thermal", THERMAL_MODELS), ("asperity", ASPERITY_MODELS)):
            v = getattr(self, field)
            if v is not None:
                if type(v) not in registry.values():
                    raise ValueError(f"{o}.{field} = {v!r}: valid: {sorted(registry)}")
                v.validate()
        check_finite(o, "length", self.length, "m", "> 0", lambda v: v > 0)
        if self.thermal is None or self.viscosity is not None:
            if self.viscosity is None:
                raise ValueError(f"{o}.viscosity [Pa·s]: required (> 0) unless thermal is set")
            check_finite(o, "viscosity", self.viscosity, "Pa·s", "> 0", lambda v: v > 0)
        if self.thermal is not None and self.viscosity is not None:
            warnings.warn(
                f"{o}: viscosity = {self.viscosity!r} [Pa·s] is unused: with thermal the film follows "
                f"μ(T) of {self.thermal.oil} from T_in = {self.thermal.inlet_temp!r} °C [T311]; omit it",
                PhysicsWarning,
                stacklevel=2,
            )
        check_finite(
            o,
            "asperity_height",
            self.asperity_height,
            "m",
            f"in [0, clearance/2 = {ASPERITY_MAX * self.clearance:.6g}] (a roughness, not a gap) [T283]",
            lambda v: 0 <= v <= ASPERITY_MAX * self.clearance,
        )
        try:
            name = film_name(self.film)
        except ValueError:
            raise ValueError(
                f"{o}.film = {self.film!r}: unknown film model; valid: {sorted(FILM_MODELS)}"
            ) from None
        check_jfo(self)
        limit = getattr(film_model(self.film), "max_length_over_diameter", math.inf)
        ld = self.length / (2.0 * self.journal_radius)
        if ld > limit:
            warnings.warn(
                f"{o}: film model {name!r} is meant for L/D ≤ {limit:g}; this bearing has L/D = {ld:.3g}",
                PhysicsWarning,
                stacklevel=2,
            )


@njit(cache=True)
def journal_element(t, q, qd, mem, bi, bj, ip, r, tables, Q, out, laws):
    """Film and/or contact forces of one journal element into Q [T14–T16]; fills ``out``
    (``OUTPUTS``). ξ ≥ 1 probed with no contact law is evaluated guarded at ξ = 1 − 1e-9 (film
    breakdown is reported on accepted steps by ``elements.advance_memory``). ``laws``: the film,
    contact and friction laws compiled into the dispatch (the element's entry of the kinds) [T229]."""
    ex, ey, edx, edy, six, siy, sjx, sjy, wi, wj = journal_kinematics(q, qd, bi, bj, r)
    c = r[CLR]
    e = math.sqrt(ex * ex + ey * ey)
    if e > 0.0:
        ux = ex / e
        uy = ey / e
    else:
        sp = math.sqrt(edx * edx + edy * edy)  # any unit vector works at e = 0 [T24]
        ux = edx / sp if sp > 0.0 else 1.0
        uy = edy / sp if sp > 0.0 else 0.0
    tx = -uy
    ty = ux
    xi = e / c
    power = 0.0
    ffx = 0.0
    ffy = 0.0
    mu_f = film_viscosity(laws, ip[THERMAL], mem, r[MU])  # μ(T) of the oil temperature [T311, T322]
    if ip[FILM] != NO_FILM:
        xi_cap = (c - r[H_ASP]) / c if ip[CONTACT] != NO_CONTACT else XI_GUARD
        xi_f = min(xi, xi_cap, XI_GUARD)
        xid = (ux * edx + uy * edy) / c
        xi_om = xi_f * (wj + wi) - 2.0 * (tx * edx + ty * edy) / c  # ξΩ [T14]
        dmc = 0.0  # the Couette torque a jfo film's gas does not carry [T375]
        if ip[JFO] != 0:  # the transient jfo film from its committed contents [T306]
            cap = min(xi_cap, XI_GUARD)
            fr, ft, dmc = jfo_terms(  # writes the outputs from O_CONTENT on [T376]
                laws, t, mem, tables, ip[JFO], q, bi, ex, ey, edx, edy, wi, wj, ux, uy, mu_f, r[R_J], c, cap,
                out, O_CONTENT,
            )  # fmt: skip
        else:
            tab = tables[ip[TABLE]]
            fr, ft = film_dispatch(
                laws, ip[FILM], xi_f, xid, xi_om, mu_f, r[R_J], r[LEN], c, r[FILM_P0:FILM_P1], tab
            )
        # asperities in parallel with the film, boundary friction [T314, T322]
        fa, tb = asperity_terms(laws, ip[ASPERITY], xi, wj - wi, tables, r[R_J], r[ASP_P0], r[ASP_P0 + 1])
        ffx = (fr + fa) * ux + ft * tx
        ffy = (fr + fa) * uy + ft * ty
        # film force at the journal centre, reaction through the same point [T8, T15]
        apply_pair(Q, bi, bj, ffx, ffy, sjx, sjy, six + ex, siy + ey)
        film_power = pair_power(qd, bi, bj, ffx, ffy, sjx, sjy, six + ex, siy + ey)
        # dissipation of the film at the state its model sees [T282]: pressure −F_r·cξ̇ + F_t·cξΩ/2
        loss = c * (0.5 * ft * xi_om - fr * xid)
        if ip[SHEAR] != 0:
            # shear torques [T75]: M_J = −M_C − (e/2)F_t on the journal; on the bushing
            # M_C − (e/2)F_t with −F at the bushing centre, i.e. M_C + (e/2)F_t with −F through
            # the journal centre as applied above: the film exerts no net moment
            mc = couette_torque(xi_f, mu_f, r[R_J], r[LEN], c, wj - wi) - dmc  # minus the jfo gas's [T375]
            mj = -mc - 0.5 * e * ft
            mb = mc + 0.5 * e * ft
            if bj >= 0:
                Q[3 * bj + 2] += mj
            if bi >= 0:
                Q[3 * bi + 2] += mb
            film_power += mj * wj + mb * wi
            loss += mc * (wj - wi)  # Couette shear M_C·(ω_J − ω_B) ≥ 0
            out[O_TORQUE] = mj
        else:
            out[O_TORQUE] = 0.0
        if tb != 0.0:  # boundary friction couple [T270, T314]
            if bj >= 0:
                Q[3 * bj + 2] -= tb
            if bi >= 0:
                Q[3 * bi + 2] += tb
            film_power += tb * (wi - wj)
            loss += tb * (wj - wi)
            out[O_TORQUE] -= tb
        out[O_LOSS] = loss
        out[O_EXCH] = -film_power - loss  # 0 unless ξ > ξ_cap or shear = false [T282]
        power += film_power
    fn = 0.0
    fcx = 0.0
    fcy = 0.0
    if ip[CONTACT] != NO_CONTACT:
        delta = e - (c - r[H_ASP])
        if delta > 0.0:
            dd = ux * edx + uy * edy
            v0 = mem[ONSET_VEL] if mem[IN_CONTACT] > 0.5 else max(dd, r[V_MIN])
            fn = contact_dispatch(laws, ip[CONTACT], delta, dd, v0, r[CONTACT_P0:CONTACT_P1])
            # slip of the journal surface relative to the bearing surface at P_c [T16]
            vt = tx * edx + ty * edy + wj * r[R_J] - wi * r[R_B]
            mu = (
                friction_dispatch(laws, ip[FRICTION], vt, r[FRICTION_P0:FRICTION_P1])
                if ip[FRICTION] != NO_FRICTION
                else 0.0
            )
            fcx = -fn * ux - mu * fn * tx
            fcy = -fn * uy - mu * fn * ty
            cx = r[R_J] * ux  # P_c − P_j
            cy = r[R_J] * uy
            apply_pair(Q, bi, bj, fcx, fcy, sjx + cx, sjy + cy, six + ex + cx, siy + ey + cy)
            power += pair_power(qd, bi, bj, fcx, fcy, sjx + cx, sjy + cy, six + ex + cx, siy + ey + cy)
    out[O_FX] = ffx + fcx
    out[O_FY] = ffy + fcy
    out[O_POWER] = power
    out[O_FN] = fn
    out[O_EX] = ex
    out[O_EY] = ey
    out[O_XI] = xi
    out[O_HMIN] = c - e
