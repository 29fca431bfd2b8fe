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


UNITS = {
    "clearance": "m",
    "viscosity": "Pa·s",
    "speed": "rad/s",
    "length": "m",
    "gravity": "m/s²",
    "restitution": "-",
    "peak_moment": "N·m",
    "min_moment": "N·m",
    "rms_moment": "N·m",
    "max_xi": "-",
    "min_h_min": "m",
    "impacts": "-",
    "energy_dissipated": "J",
    "wall_time_s": "s",
}


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
                ax.text(
                    j + 0.5,
                    i + 0.5,
                    f"{da.values[i, j]:.4g}",
                    ha="center",
                    va="center",
                    fontsize=8,
                    color="w",
                )
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


def saved_run(ds, what: str, ax=None):
    """Draw ``what`` (moment | orbit | film | contact | energy) from a saved results Dataset."""
    import json

    ax = _axes(ax)
    rows = [str(r) for r in ds["row"].values]
    model = json.loads(ds.attrs["model"])
    t = ds["time"].values
    journals = [k for k, v in model["items"].items() if v["type"] in ("journal_bearing", "clearance_joint")]
    if what == "moment":
        drivers = [
            r
            for r in rows
            if any(r.startswith(f"{n}[") for n, v in model["items"].items() if v["type"] == "angle_driver")
        ]
        if not drivers:
            raise ValueError("the run has no angle driver: no driving moment to plot")
        for r in drivers:
            ax.plot(t, ds["lam"].sel(row=r).values, label=r)
        ax.set_xlabel("t [s]")
        ax.set_ylabel("driving moment [N·m]")
    elif what in ("orbit", "film", "contact"):
        if not journals:
            raise ValueError("the run has no journal element (bearing or clearance joint)")
        for name in journals:
            e = ds["element_outputs"].sel(element=name)
            c = model["items"][name]["bearing_radius"] - model["items"][name]["journal_radius"]
            if what == "orbit":
                journal_orbit(e.sel(output="ex").values / c, e.sel(output="ey").values / c, ax=ax, label=name)
            elif what == "film":
                ax.plot(t, e.sel(output="h_min").values * 1e6, label=name)
                ax.set_xlabel("t [s]")
                ax.set_ylabel("minimum film thickness / gap h_min [µm]")
            else:
                ax.plot(t, e.sel(output="contact_force").values, label=name)
                ax.set_xlabel("t [s]")
                ax.set_ylabel("contact normal force [N]")
    elif what == "energy":
        p = ds["element_outputs"].sel(output="power").values  # (t, element)
        for k, name in enumerate(ds["element"].values):
            w = np.concatenate([[0.0], np.cumsum(0.5 * (p[1:, k] + p[:-1, k]) * np.diff(t))])
            ax.plot(t, -w, label=f"{name}: energy dissipated")
        ax.set_xlabel("t [s]")
        ax.set_ylabel("energy [J]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return ax
