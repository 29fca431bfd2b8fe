"""Dimensional operating point from a row of Raimondi–Boyd variables [T77]."""

from __future__ import annotations

import math


def dimensional_point(r: dict, eps: float, load, speed, radius, length, clearance, sommerfeld) -> dict:
    """The operating point's quantities at ε from the table row ``r`` (Raimondi–Boyd variables)
    for W [N], N [rev/s], R, L, c [m]: eps, attitude_deg, h_min [m], friction_torque [N·m],
    power_loss [W], peak_pressure [Pa], theta_pmax_deg, theta_end_deg [deg], flow, side_flow
    [m³/s], sommerfeld [-] [T77]."""
    T = r["friction_variable"] * load * clearance  # (R/c)f = T/(W c)
    Q = r["flow_variable"] * radius * clearance * speed * length  # Q/(R c N L)
    return {
        "eps": eps,
        "attitude_deg": r["attitude_deg"],
        "h_min": clearance * (1.0 - eps),
        "friction_torque": T,
        "power_loss": T * 2.0 * math.pi * speed,
        "peak_pressure": load / (2.0 * radius * length) / r["pressure_ratio"],
        "theta_pmax_deg": r["theta_pmax_deg"],
        "theta_end_deg": r["theta_end_deg"],
        "flow": Q,
        "side_flow": Q * r["side_flow_ratio"],
        "sommerfeld": sommerfeld,
    }
