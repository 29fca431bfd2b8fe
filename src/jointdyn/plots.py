"""Figures. Each function takes results (or arrays), draws on an Axes and returns it."""

from __future__ import annotations

import numpy as np


def _axes(ax):
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(figsize=(7, 4))
    return ax


def moment_vs_angle(angle, moment, ax=None, label=None, **kw):
    """Crank moment [N·m] vs crank angle [rad] (axis shown in degrees)."""
    ax = _axes(ax)
    ax.plot(np.degrees(angle), moment, label=label, lw=kw.pop("lw", 1.0), **kw)
    ax.set_xlabel("crank angle [deg]")
    ax.set_ylabel("crank driving moment [N·m]")
    ax.grid(True, alpha=0.3)
    return ax


def journal_orbit(ex_over_c, ey_over_c, ax=None, label=None, **kw):
    """Journal-centre path in the clearance circle (e/c), with the unit circle drawn."""
    ax = _axes(ax)
    th = np.linspace(0, 2 * np.pi, 361)
    ax.plot(np.cos(th), np.sin(th), "k-", lw=0.8)
    ax.plot(ex_over_c, ey_over_c, label=label, lw=kw.pop("lw", 0.8), **kw)
    ax.set_aspect("equal")
    ax.set_xlabel("e_x / c [-]")
    ax.set_ylabel("e_y / c [-]")
    ax.grid(True, alpha=0.3)
    return ax


def series_vs_angle(angle, values, ylabel, ax=None, label=None, **kw):
    """Any series vs crank angle (axis in degrees)."""
    ax = _axes(ax)
    ax.plot(np.degrees(angle), values, label=label, lw=kw.pop("lw", 1.0), **kw)
    ax.set_xlabel("crank angle [deg]")
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3)
    return ax


UNITS = {"clearance": "m", "viscosity": "Pa·s", "speed": "rad/s", "length": "m", "gravity": "m/s²",
         "restitution": "-", "peak_moment": "N·m", "min_moment": "N·m", "rms_moment": "N·m", "max_xi": "-",
         "min_h_min": "m", "impacts": "-", "energy_dissipated": "J", "wall_time_s": "s"}


def _label(name):
    return f"{name} [{UNITS[name]}]" if name in UNITS else str(name)


def sweep_metric(da, ax=None):
    """Heat map of a metric over two swept parameters (log axes for positive ranges spanning a
    decade or more), or a line over one."""
    ax = _axes(ax)
    dims = [d for d in da.dims]
    if len(dims) == 2:
        y, x = dims
        X, Y = da[x].values, da[y].values
        m = ax.pcolormesh(np.arange(len(X) + 1), np.arange(len(Y) + 1), da.values, shading="flat")
        ax.set_xticks(np.arange(len(X)) + 0.5, [f"{v:.3g}" for v in X])
        ax.set_yticks(np.arange(len(Y)) + 0.5, [f"{v:.3g}" for v in Y])
        for i in range(len(Y)):
            for j in range(len(X)):
                ax.text(j + 0.5, i + 0.5, f"{da.values[i, j]:.4g}", ha="center", va="center", fontsize=8,
                        color="w")
        ax.set_xlabel(_label(x))
        ax.set_ylabel(_label(y))
        ax.figure.colorbar(m, ax=ax, label=_label(da.name))
    else:
        d = dims[0]
        ax.plot(da[d].values, da.values, "o-")
        ax.set_xlabel(_label(d))
        ax.set_ylabel(_label(da.name))
        ax.grid(True, alpha=0.3)
    return ax
