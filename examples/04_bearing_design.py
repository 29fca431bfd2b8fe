"""Steady journal-bearing design: the Raimondi–Boyd table and an operating point.

A designer's first questions about a plain journal bearing: for a load W at speed N, how
eccentric does the journal run, how thin is the film, how much power does the film dissipate,
how high is the peak pressure? `bearing_table` gives the classical design table (Reynolds'
film-end condition, lubricant supplied at the maximum film); `equilibrium` solves it for the load. The
figure shows the film pressure at that operating point.
"""

import math

import matplotlib.pyplot as plt

from jointdyn.bearing import bearing_table, equilibrium
from jointdyn.viz.bearing_plot import pressure_figure

R, L, c, mu = 0.025, 0.025, 30e-6, 0.02  # journal radius, length, radial clearance [m], viscosity [Pa·s]
W, N = 4000.0, 25.0  # load [N], journal speed [rev/s]

tab = bearing_table("finite", "reynolds", L / (2 * R), [0.1, 0.2, 0.4, 0.6, 0.8, 0.9, 0.97])
print("  eps      S    phi[deg]  (R/c)f  Q/(RcNL)  Qs/Q  P/pmax")
for k in range(len(tab["eps"])):
    print(
        f"{tab['eps'][k]:5.2f} {tab['sommerfeld'][k]:8.4f} {tab['attitude_deg'][k]:8.2f}"
        f" {tab['friction_variable'][k]:8.3f} {tab['flow_variable'][k]:8.3f}"
        f" {tab['side_flow_ratio'][k]:6.3f} {tab['pressure_ratio'][k]:6.3f}"
    )

op = equilibrium(W, N, R, L, c, mu)
print(f"\nW = {W:g} N at N = {N:g} rev/s: eps = {op['eps']:.3f}, attitude = {op['attitude_deg']:.1f} deg")
print(f"h_min = {op['h_min'] * 1e6:.2f} um, friction torque = {op['friction_torque']:.4f} N m")
print(f"power loss = {op['power_loss']:.1f} W, peak pressure = {op['peak_pressure'] / 1e6:.2f} MPa")

# the operating point as a bearing state: steady journal, bearing fixed, load along −y
omega = 2 * math.pi * N
gamma = -math.pi / 2 + math.radians(op["attitude_deg"])  # line of centres, global [rad]
fig = pressure_figure(op["eps"], 0.0, op["eps"] * omega, mu, R, L, c, gamma=gamma, title="operating point")
fig.savefig("bearing_pressure.png", dpi=110)
plt.close(fig)
