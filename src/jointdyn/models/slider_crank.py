"""The paper's slider-crank (spec/benchmark.md): crank, connecting rod, slider; 5000 rpm.

Bodies: ``crank`` (pinned to the ground at the origin, driven at constant speed),
``rod``, ``slider`` (translational joint along the global x axis through the crank pivot).
The joint under study is between rod and slider (the piston pin). For imperfect joints the
**bearing (bushing) is in the rod eye (body i = rod)** and the **journal is the pin on the
slider (body j = slider)**, so Ω = φ̇_slider + φ̇_rod − 2γ̇ = φ̇_rod − 2γ̇ (spec §7).
"""

from __future__ import annotations

from ..joints.constraints import AngleDriver, Revolute, Translational
from ..model import Model
from ..units import rpm

#: benchmark parameters (spec/benchmark.md), SI
CRANK_LENGTH = 0.05  # [m]
ROD_LENGTH = 0.12  # [m]
CRANK_MASS, CRANK_INERTIA = 0.30, 1.0e-4  # [kg], [kg·m²]
ROD_MASS, ROD_INERTIA = 0.21, 2.5e-4
SLIDER_MASS, SLIDER_INERTIA = 0.14, 1.0e-4
SPEED = rpm(5000.0)  # [rad/s]

JOINTS = ("perfect",)


def slider_crank(joint: str = "perfect", speed: float = SPEED, gravity: float = 9.81) -> Model:
    """Build the benchmark slider-crank with the rod–slider joint of kind ``joint``.

    speed: crank speed, counter-clockwise [rad/s]; gravity: along −y [m/s²].
    The crank driving moment is the multiplier of the constraint named ``"drive"``.
    """
    if joint not in JOINTS:
        raise ValueError(f"joint = {joint!r}: unknown; valid: {list(JOINTS)}")
    r, l = CRANK_LENGTH, ROD_LENGTH
    m = Model(f"slider-crank ({joint})", gravity=(0.0, -gravity))
    m.add_ground_point("O", (0.0, 0.0))
    m.add_body("crank", CRANK_MASS, CRANK_INERTIA, position=(r / 2, 0.0), angle=0.0,
               velocity=(0.0, speed * r / 2, speed), points={"O": (-r / 2, 0.0), "A": (r / 2, 0.0)})
    m.add_body("rod", ROD_MASS, ROD_INERTIA, position=(r + l / 2, 0.0), angle=0.0,
               points={"A": (-l / 2, 0.0), "B": (l / 2, 0.0)})
    m.add_body("slider", SLIDER_MASS, SLIDER_INERTIA, position=(r + l, 0.0), angle=0.0,
               points={"B": (0.0, 0.0)})
    m.add("crank_pivot", Revolute("ground", "O", "crank", "O"))
    m.add("drive", AngleDriver("ground", "crank", phi0=0.0, omega=speed))
    m.add("crank_pin", Revolute("crank", "A", "rod", "A"))
    m.add("guide", Translational("ground", "O", "slider", "B", axis=(1.0, 0.0), angle=0.0))
    m.add("piston_pin", Revolute("rod", "B", "slider", "B"))
    return m
