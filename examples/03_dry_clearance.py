"""Dry clearance joint: impacts in the piston pin.

The perfect piston pin of the shipped slider-crank is replaced by a dry revolute clearance
joint (c = 0.5 mm) with the Lankarani–Nikravesh contact law (n = 1.5, K from Hertz for steel
cylinders, c_r = 0.9). The joint is a force element, not a constraint: the pin flies free in
the hole and hits its wall. Two crank revolutions with DOPRI5 (contact onsets are located by
step rejection, see the user guide); the figure compares the crank moment with the perfect
joint and shows the contact force.
"""

import math

import matplotlib.pyplot as plt

from jointdyn import post
from jointdyn.forces.contact_laws import LankaraniNikravesh, journal_bearing_stiffness
from jointdyn.forces.journal import ClearanceJoint
from jointdyn.models.slider_crank import SPEED, slider_crank
from jointdyn.simulation.simulate import SimConfig, simulate

R_B, R_J = 0.0105, 0.0100  # hole and pin radii [m]
K = journal_bearing_stiffness(R_B, R_J, 207e9, 0.3, 207e9, 0.3)  # [N/m^1.5]
law = LankaraniNikravesh(stiffness=K, exponent=1.5, restitution=0.9)

model = slider_crank("perfect")
del model.items["piston_pin"]  # drop the ideal revolute joint …
model.add("piston_pin", ClearanceJoint("rod", "B", "slider", "B", R_B, R_J, contact=law))

revs = 2
cfg = SimConfig(
    t_end=revs * 2 * math.pi / SPEED,
    n_out=revs * 720 + 1,
    solver="dopri5",
    rtol=1e-7,
    atol=1e-11,
)
dry = simulate(model.compile(), cfg)
perfect = simulate(slider_crank("perfect").compile(), cfg)

k = dry.system.element_names.index("piston_pin")
print(
    f"K = {K:.4g} N/m^1.5, impacts: {int(dry.mem[-1, k, 2])}, "
    f"max penetration: {dry.mem[-1, k, 3] * 1e6:.1f} µm"
)
for name, res in (("perfect", perfect), ("dry", dry)):
    s = post.stats(post.driving_moment(res))
    print(
        f"{name:8s} crank moment peak {s['peak']:8.1f}  min {s['min']:8.1f}"
        f"  rms {s['rms']:6.1f} N·m"
    )

deg = lambda res: 180 / math.pi * post.body_angle(res, "crank")  # noqa: E731
fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
ax1.plot(deg(dry), post.driving_moment(dry), lw=0.8, label="dry, c = 0.5 mm")
ax1.plot(deg(perfect), post.driving_moment(perfect), lw=1.2, label="perfect")
ax1.set_ylabel("crank driving moment [N·m]")
ax1.legend()
ax2.plot(deg(dry), dry.element("piston_pin", "contact_force") / 1e3, lw=0.8)
ax2.set_ylabel("contact normal force [kN]")
ax2.set_xlabel("crank angle [deg]")
for ax in (ax1, ax2):
    ax.grid(True, alpha=0.3)
fig.tight_layout()
fig.savefig("dry_clearance.png", dpi=100)
