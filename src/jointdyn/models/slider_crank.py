"""The paper's slider-crank (benchmark definition [T160]): crank, connecting rod, slider; 5000 rpm.

Bodies: ``crank`` (pinned to the ground at the origin, driven at constant speed),
``rod``, ``slider`` (translational joint along the global x axis through the crank pivot).
The joint under study is between rod and slider (the piston pin). For imperfect joints the
**bearing (bushing) is in the rod eye (body i = rod)** and the **journal is the pin on the
slider (body j = slider)**, so Ω = φ̇_slider + φ̇_rod − 2γ̇ = φ̇_rod − 2γ̇ [T161].
"""

from __future__ import annotations

import math

import numpy as np

from jointdyn import post
from jointdyn.core.constraints import AngleDriver, Revolute, Translational
from jointdyn.film.models import FILM_MODELS
from jointdyn.forces.contact_laws import LankaraniNikravesh, journal_bearing_stiffness
from jointdyn.forces.journal import ClearanceJoint, JournalBearing
from jointdyn.multibody.model import Model
from jointdyn.simulation.simulate import SimConfig
from jointdyn.units import rpm

#: benchmark parameters [T160], SI
CRANK_LENGTH = 0.05  # [m]
ROD_LENGTH = 0.12  # [m]
CRANK_MASS, CRANK_INERTIA = 0.30, 1.0e-4  # [kg], [kg·m²]
ROD_MASS, ROD_INERTIA = 0.21, 2.5e-4
SLIDER_MASS, SLIDER_INERTIA = 0.14, 1.0e-4
SPEED = rpm(5000.0)  # [rad/s]

BEARING_RADIUS = 0.0105  # [m] (c = 0.5 mm)
JOURNAL_RADIUS = 0.0100  # [m]
BEARING_LENGTH = 0.040  # [m]
VISCOSITY = 0.4  # [Pa·s]
YOUNG, POISSON = 207e9, 0.3  # [Pa], [-]
RESTITUTION = 0.9  # [-]

#: joint kinds of the piston pin: ideal, dry clearance, or a lubricated bearing per film model
JOINTS = ("perfect", "dry", *FILM_MODELS)
#: name of the joint under study (the rod–slider pin) in the built model
PIN = "piston_pin"


def slider_crank(
    joint: str = "perfect",
    speed: float = SPEED,
    gravity: float = 9.81,
    clearance: float = BEARING_RADIUS - JOURNAL_RADIUS,
    viscosity: float = VISCOSITY,
    length: float = BEARING_LENGTH,
    restitution: float = RESTITUTION,
    friction=None,
    contact=None,
    asperity_height: float = 0.0,
    shear: bool = False,
    bushing: str = "rod",
) -> Model:
    """Build the benchmark slider-crank with the rod–slider joint of kind ``joint``.

    joint: ``perfect`` (ideal revolute), ``dry`` (clearance joint, Lankarani–Nikravesh,
    n = 1.5, K from the radii and steel), or a film model name (lubricated bearing);
    speed: crank speed, CCW [rad/s]; gravity: along −y [m/s²]; clearance: c = R_B − R_J with
    R_J = 10 mm [m]; viscosity [Pa·s]; length: bearing length [m]; restitution: c_r of the
    dry contact [-]; friction: a friction law for the dry joint or None; contact: a contact law
    for the mixed regime of a lubricated joint (None = pure film); asperity_height [m];
    shear: apply the film's shear torques [T75] (False: the paper's assumption, pressure forces
    only); bushing: the body that carries the bearing hole, ``"rod"`` (the paper's, [T161]) or
    ``"slider"`` (the pin is then fixed in the rod eye).
    The crank driving moment is the multiplier of the constraint named ``"drive"``.
    """
    if joint not in JOINTS:
        raise ValueError(f"joint = {joint!r}: unknown; valid: {list(JOINTS)}")
    r, l = CRANK_LENGTH, ROD_LENGTH
    m = Model(f"slider-crank ({joint})", gravity=(0.0, -gravity))
    m.add_ground_point("O", (0.0, 0.0))
    m.add_body(
        "crank",
        CRANK_MASS,
        CRANK_INERTIA,
        position=(r / 2, 0.0),
        angle=0.0,
        velocity=(0.0, speed * r / 2, speed),
        points={"O": (-r / 2, 0.0), "A": (r / 2, 0.0)},
    )
    m.add_body(
        "rod",
        ROD_MASS,
        ROD_INERTIA,
        position=(r + l / 2, 0.0),
        angle=0.0,
        points={"A": (-l / 2, 0.0), "B": (l / 2, 0.0)},
    )
    m.add_body(
        "slider", SLIDER_MASS, SLIDER_INERTIA, position=(r + l, 0.0), angle=0.0, points={"B": (0.0, 0.0)}
    )
    m.add("crank_pivot", Revolute("ground", "O", "crank", "O"))
    m.add("drive", AngleDriver("ground", "crank", phi0=0.0, omega=speed))
    m.add("crank_pin", Revolute("crank", "A", "rod", "A"))
    m.add("guide", Translational("ground", "O", "slider", "B", axis=(1.0, 0.0), angle=0.0))
    if joint == "perfect":
        m.add(PIN, Revolute("rod", "B", "slider", "B"))
        return m
    if not clearance > 0:
        raise ValueError(f"clearance = {clearance!r} [m]: must be > 0")
    if bushing not in ("rod", "slider"):
        raise ValueError(f"bushing = {bushing!r}: valid: ['rod', 'slider']")
    hole, pin = ("rod", "slider") if bushing == "rod" else ("slider", "rod")
    rb = JOURNAL_RADIUS + clearance
    if joint == "dry":
        K = journal_bearing_stiffness(rb, JOURNAL_RADIUS, YOUNG, POISSON, YOUNG, POISSON)
        law = LankaraniNikravesh(stiffness=K, exponent=1.5, restitution=restitution)
        m.add(
            PIN,
            ClearanceJoint(hole, "B", pin, "B", rb, JOURNAL_RADIUS, contact=law, friction=friction),
        )
    else:
        m.add(
            PIN,
            JournalBearing(
                hole,
                "B",
                pin,
                "B",
                rb,
                JOURNAL_RADIUS,
                length,
                viscosity,
                film=joint,
                contact=contact,
                friction=friction,
                asperity_height=asperity_height,
                shear=shear,
            ),
        )
    return m


def slider_crank_config(
    joint: str,
    revs: float = 4.0,
    samples_per_rev: int = 720,
    solver: str | None = None,
    rtol: float = 1e-8,
    atol: float = 1e-10,
    speed: float = SPEED,
) -> SimConfig:
    """Integration settings for ``revs`` crank revolutions at ``speed`` [rad/s]."""
    if not (math.isfinite(revs) and revs > 0):
        raise ValueError(f"revs = {revs!r} [revolutions]: must be finite and > 0")
    if revs * samples_per_rev < 1:
        raise ValueError(
            f"revs = {revs!r} [revolutions]: must be >= 1/samples_per_rev = {1 / samples_per_rev:.3g} "
            "(at least one output interval)"
        )
    t_end = revs * 2 * math.pi / abs(speed)
    return SimConfig(
        t_end=t_end,
        n_out=int(round(revs * samples_per_rev)) + 1,
        solver=solver or "auto",
        rtol=rtol,
        atol=atol,
    )


#: the shipped model's metric names (README tables, docs, sweeps) as aliases of the generic
#: metrics of :mod:`jointdyn.studies.metrics` [T228]
METRIC_ALIASES = {
    "peak_moment": "drive.moment_peak",
    "min_moment": "drive.moment_min",
    "rms_moment": "drive.moment_rms",
    "max_xi": f"{PIN}.xi_max",
    "min_h_min": f"{PIN}.h_min_min",
    "max_contact_force": f"{PIN}.contact_force_max",
    "max_penetration": f"{PIN}.max_penetration",
    "impacts": f"{PIN}.impacts",
    "energy_dissipated": f"{PIN}.energy_dissipated",
}
#: units of the derived headline columns (element outputs take the element's own)
HEADLINE_UNITS = {
    "t": "s",
    "crank_angle": "rad",
    "crank_moment": "N·m",
    "ex_bushing_over_c": "-",
    "ey_bushing_over_c": "-",
}
#: headline column names before the orbit convention [T290] (world-frame components, named without
#: their frame): new name -> old name, for readers of old run directories
RENAMED = {"ex_bushing_over_c": "ex_over_c", "ey_bushing_over_c": "ey_over_c"}


def table(res) -> dict[str, np.ndarray]:
    """Time series of a slider-crank run: t [s], crank_angle [rad, unwrapped], crank_moment
    [N·m] (the drive's moment on the crank, CCW positive), and for an imperfect piston pin
    ex_bushing_over_c, ey_bushing_over_c [-] (eccentricity over the clearance in the frame of the
    bushing, the rod eye [T290]), h_min [m], joint_force [N] (magnitude on the journal),
    contact_force [N]."""
    cols = {
        "t": res.t,
        "crank_angle": post.body_angle(res, "crank"),
        "crank_moment": post.driving_moment(res, "drive"),
    }
    if PIN in res.system.element_names:
        cols["ex_bushing_over_c"], cols["ey_bushing_over_c"] = res.orbit(PIN, frame="bushing")
        cols["h_min"] = res.element(PIN, "h_min")
        cols["joint_force"] = np.hypot(res.element(PIN, "Fx"), res.element(PIN, "Fy"))
        cols["contact_force"] = res.element(PIN, "contact_force")
    return cols


def headline(res):
    """(columns of :func:`table`, their units): the first columns of ``timeseries.csv``."""
    units = dict(HEADLINE_UNITS)
    if PIN in res.system.element_names:  # the element's declared units; |F| in those of Fx
        outs = type(res.system.elements[res.system.element_names.index(PIN)]).OUTPUTS
        units |= {"h_min": outs["h_min"], "contact_force": outs["contact_force"], "joint_force": outs["Fx"]}
    return table(res), units


def summarize(res, cols: dict, metrics: dict, revs: float) -> dict:
    """The slider-crank's summary: the generic ``metrics`` under their short names
    (:data:`METRIC_ALIASES`; the moment over the last revolution), the moment statistics over the
    whole run (``*_moment_all``) and the piston pin's time in contact [s] and its fraction [-]."""
    out = {"joint": res.system.name, "revolutions": revs}
    out |= {k: metrics[k] for k in METRIC_ALIASES if k in metrics}
    out |= {f"{k}_moment_all": v for k, v in post.stats(cols["crank_moment"]).items()}
    if "contact_force" in cols:
        in_contact = cols["contact_force"] > 0
        dt = np.diff(res.t)
        out["contact_time_s"] = float(np.sum(dt * 0.5 * (in_contact[1:] + in_contact[:-1])))
        out["contact_fraction"] = out["contact_time_s"] / float(res.t[-1] - res.t[0])
    return out
