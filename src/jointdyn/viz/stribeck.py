"""Figure of a Stribeck curve (``jointdyn stribeck``) [T272]: friction coefficient against the
Hersey number μN/P, the minimum marked, the asperity share of the load on a second axis."""

from __future__ import annotations

import numpy as np


def stribeck_figure(table: dict, title: str = ""):
    """Matplotlib figure of ``table`` (columns of :func:`jointdyn.bearing.mixed.stribeck`)."""
    import matplotlib.pyplot as plt

    x = np.asarray(table["hersey"], dtype=float)
    f = np.asarray(table["friction_coefficient"], dtype=float)
    a = np.asarray(table["asperity_load_fraction"], dtype=float)
    k = int(np.argmin(f))
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.loglog(x, f, "o-", label="friction coefficient f = T/(WR)")
    ax.plot([x[k]], [f[k]], "v", ms=10, label=f"minimum f = {f[k]:.3g} at {table['speed_rpm'][k]:.4g} rpm")
    ax.set_xlabel("Hersey number μN/P [-] (N in rev/s)")
    ax.set_ylabel("friction coefficient [-]")
    ax2 = ax.twinx()
    ax2.semilogx(x, a, "s--", color="tab:red", alpha=0.6, label="asperity share of the load")
    ax2.set_ylabel("asperity load / W [-]")
    ax2.set_ylim(-0.02, 1.02)
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    ax.legend(h1 + h2, l1 + l2, loc="upper center", fontsize=8)
    if title:
        ax.set_title(title)
    fig.tight_layout()
    return fig
