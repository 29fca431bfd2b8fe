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
