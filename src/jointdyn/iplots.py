"""Interactive figures (plotly, the ``[interactive]`` extra): zoom into dry-contact spikes, hover
over overlays.

Every figure of :mod:`jointdyn.plots` is drawn first with matplotlib (off-screen, so both
backends show the same data, labels and units) and then converted: :func:`from_axes` turns the
lines, markers, annotations, axis labels, scales and title of an Axes into a plotly Figure.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np


def _plotly():
    try:
        import plotly.graph_objects as go
    except ImportError:
        raise ImportError("interactive figures need plotly: pip install -e '.[interactive]'") from None
    return go


def _color(c) -> str:
    from matplotlib.colors import to_hex

    return to_hex(c)


def _text(s: str) -> str:
    """Matplotlib mathtext of our labels → plain text (plotly does not read $…$)."""
    return (
        s.replace("$e_x/c$", "e_x/c")
        .replace("$e_y/c$", "e_y/c")
        .replace("$h_{min}$", "h_min")
        .replace("$", "")
    )


def from_axes(ax, height: int = 450):
    """A plotly Figure with the lines, markers and annotations of a matplotlib Axes."""
    go = _plotly()
    fig = go.Figure()
    dash = {"--": "dash", "-.": "dashdot", ":": "dot"}
    for ln in ax.get_lines():
        x, y = np.asarray(ln.get_xdata(), float), np.asarray(ln.get_ydata(), float)
        label = ln.get_label()
        marker = ln.get_marker() not in (None, "None", "", " ")
        line_on = ln.get_linestyle() not in ("None", "", " ")
        mode = "+".join([m for m, on in (("lines", line_on), ("markers", marker)) if on]) or "lines"
        fig.add_trace(
            go.Scatter(
                x=x,
                y=y,
                mode=mode,
                name=_text(label) if not label.startswith("_") else None,
                showlegend=not label.startswith("_"),
                line={
                    "color": _color(ln.get_color()),
                    "width": ln.get_linewidth(),
                    "dash": dash.get(ln.get_linestyle(), "solid"),
                },
                marker={
                    "symbol": {"o": "circle-open", "x": "x", "v": "triangle-down"}.get(
                        str(ln.get_marker()), "circle"
                    ),
                    "size": 8,
                },
            )
        )
    for t in ax.texts:
        if t.get_text():
            xy = getattr(t, "xy", t.get_position())
            fig.add_annotation(
                x=xy[0],
                y=np.log10(xy[1]) if ax.get_yscale() == "log" else xy[1],
                text=t.get_text(),
                showarrow=False,
                yshift=10,
            )
    title = ax.get_title() or (ax.figure._suptitle.get_text() if ax.figure._suptitle else "")
    fig.update_layout(
        title={"text": _text(title).replace("\n", "<br>"), "font": {"size": 13}},
        xaxis_title=_text(ax.get_xlabel()),
        yaxis_title=_text(ax.get_ylabel()),
        template="plotly_white",
        height=height,
        legend={"font": {"size": 10}},
    )
    if ax.get_yscale() == "log":
        fig.update_yaxes(type="log")
    if ax.get_aspect() == 1.0:
        fig.update_yaxes(scaleanchor="x", scaleratio=1)
        fig.update_layout(width=height + 100)
    return fig


def run_figure(runs, what: str, **kw):
    """Interactive version of :func:`jointdyn.plots.run_figure` (same arguments)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from . import plots

    ax = plots.run_figure(runs, what, **kw)
    try:
        return from_axes(ax, height=520 if what == "orbit" else 450)
    finally:
        plt.close(ax.figure)


def reproduction_html(runs: dict, out, revs: float) -> Path:
    """One self-contained HTML page (plotly included) with the reproduction's moment curves
    over the whole run (zoom into the dry spikes) and the last-revolution journal orbits."""
    go = _plotly()
    from . import post

    fig = go.Figure()
    for res, _, _, case in runs.values():
        a = res.crank_angle()
        fig.add_trace(
            go.Scatter(
                x=np.degrees(a - a[0]),
                y=post.driving_moment(res),
                mode="lines",
                name=case.label,
                line={"width": 1},
            )
        )
    fig.update_layout(
        title=f"crank driving moment, {revs:g} revolutions (drag to zoom, double-click to reset)",
        xaxis_title="crank angle [deg]",
        yaxis_title="moment [N·m]",
        template="plotly_white",
        height=520,
    )
    parts = [fig.to_html(full_html=False, include_plotlyjs=True)]
    journals = [n for n in runs if "piston_pin" in runs[n][0].journals()]
    if journals:
        orb = go.Figure()
        th = np.linspace(0, 2 * np.pi, 361)
        orb.add_trace(
            go.Scatter(
                x=np.cos(th),
                y=np.sin(th),
                mode="lines",
                name="clearance circle (ξ = 1)",
                line={"color": "black", "dash": "dash", "width": 1},
            )
        )
        for n in journals:
            ex, ey = runs[n][0].last_revolutions(min(1.0, revs)).orbit("piston_pin")
            orb.add_trace(go.Scatter(x=ex, y=ey, mode="lines", name=runs[n][3].label, line={"width": 1}))
        orb.update_layout(
            title="journal centre path e/c, last revolution, rod (bushing) frame",
            xaxis_title="e_x/c [-]",
            yaxis_title="e_y/c [-]",
            template="plotly_white",
            height=620,
            width=760,
        )
        orb.update_yaxes(scaleanchor="x", scaleratio=1)
        parts.append(orb.to_html(full_html=False, include_plotlyjs=False))
    out = Path(out)
    out.write_text(
        "<!DOCTYPE html><html><head><meta charset='utf-8'>"
        "<title>jointdyn — interactive reproduction</title></head>"
        "<body style='font-family:sans-serif;max-width:1100px;margin:auto'>"
        "<h1>Alshaer et al. (2005) reproduction, interactive</h1>" + "".join(parts) + "</body></html>",
        encoding="utf-8",
    )
    return out
