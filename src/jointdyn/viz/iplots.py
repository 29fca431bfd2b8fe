"""Interactive figures (plotly, the ``[interactive]`` extra): zoom into dry-contact spikes, hover
over overlays.

Every figure of :mod:`jointdyn.viz.plots` is drawn first with matplotlib (off-screen, so both
backends show the same data, labels and units) and then converted: :func:`from_axes` turns the
lines, markers, annotations, axis labels, scales and title of an Axes into a plotly Figure.
"""

from __future__ import annotations

import json
import shutil
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


def _marker(ln) -> dict:
    """The plotly marker of a matplotlib line (direction heads of an orbit keep their angle)."""
    gid = ln.get_gid() or ""
    if gid.startswith("direction:"):  # plotly's angle: degrees clockwise from up
        return {"symbol": "triangle-up", "angle": 90.0 - float(gid.split(":")[1]), "size": 9}
    symbol = {"o": "circle-open", "x": "x", "v": "triangle-down"}.get(str(ln.get_marker()), "circle")
    return {"symbol": symbol, "size": 8}


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
                marker=_marker(ln),
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
    """Interactive version of :func:`jointdyn.viz.plots.run_figure` (same arguments)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from jointdyn.viz import plots

    ax = plots.run_figure(runs, what, **kw)
    try:
        return from_axes(ax, height=520 if what == "orbit" else 450)
    finally:
        plt.close(ax.figure)


def _copy_plotly_js(f) -> None:
    """Copy plotly.js as shipped in the plotly package (the ``[interactive]`` extra) into the
    binary file ``f``, in chunks (3.5 MB: never held as one string), for offline pages."""
    from importlib.resources import files

    try:
        src = files("plotly").joinpath("package_data", "plotly.min.js").open("rb")
    except (ModuleNotFoundError, FileNotFoundError):
        raise ImportError("interactive figures need plotly: pip install -e '.[interactive]'") from None
    with src:
        shutil.copyfileobj(src, f)


def _js(obj) -> str:
    """A figure spec as a JavaScript literal: arrays as lists, NaN/±inf as JavaScript's own
    (the page draws gaps there, as plotly does), and no ``</`` that could end the script tag."""

    def plain(o):
        if isinstance(o, np.ndarray):  # Python floats and ints (nested lists) at once [T372]
            return o.tolist()
        if isinstance(o, dict):
            return {k: plain(v) for k, v in o.items()}
        if isinstance(o, list | tuple):
            return [plain(v) for v in o]
        return o

    return json.dumps(plain(obj), ensure_ascii=False).replace("</", "<\\/")


_LAYOUT = {  # plotly's "plotly_white" look, written out: no template machinery needed
    "paper_bgcolor": "white",
    "plot_bgcolor": "white",
    "xaxis": {"gridcolor": "#EBF0F8", "zerolinecolor": "#EBF0F8", "automargin": True},
    "yaxis": {"gridcolor": "#EBF0F8", "zerolinecolor": "#EBF0F8", "automargin": True},
}


def _plot(div: str, data: list[dict], title: str, xlabel: str, ylabel: str, **layout) -> str:
    lay = {
        **_LAYOUT,
        "title": {"text": title},
        "xaxis": {**_LAYOUT["xaxis"], "title": {"text": xlabel}},
        "yaxis": {**_LAYOUT["yaxis"], "title": {"text": ylabel}, **layout.pop("yaxis", {})},
        **layout,
    }
    return (
        f"<div id='{div}'></div><script>Plotly.newPlot('{div}', {_js(data)}, {_js(lay)}, "
        "{responsive: true});</script>"
    )


def reproduction_html(runs: dict, out, revs: float) -> Path:
    """One self-contained HTML page (plotly.js included) with the reproduction's moment curves
    over the whole run (zoom into the dry spikes) and the last-revolution journal orbits.

    The figure specs are written directly as plotly.js data and layout (no plotly Figure objects:
    building and validating those took ≈ 40 MB and most of the page's time, [T173])."""
    from jointdyn import post
    from jointdyn.viz.orbit import direction_points
    from jointdyn.viz.style import PLOTLY_DASH, styles

    st = styles(list(runs))  # the colours and dashes of the report's PNGs

    def line(n: str) -> dict:
        return {"width": 1, "color": st[n][0], "dash": PLOTLY_DASH[st[n][1]]}

    moments = []
    for n, (res, _, _, case) in runs.items():
        a = res.crank_angle()
        x, y = np.degrees(a - a[0]), post.driving_moment(res)
        moments.append(
            {"type": "scatter", "mode": "lines", "x": x, "y": y, "name": case.label, "line": line(n)}
        )
    parts = [
        _plot(
            "moment",
            moments,
            f"crank driving moment, {revs:g} revolution{'s' * (revs != 1)}"
            " (drag to zoom, double-click to reset)",
            "crank angle [deg]",
            "moment [N·m]",
            height=520,
        )
    ]
    journals = [n for n in runs if "piston_pin" in runs[n][0].journals()]
    if journals:
        th = np.linspace(0, 2 * np.pi, 361)
        orbits = [
            {
                "type": "scatter",
                "mode": "lines",
                "x": np.cos(th),
                "y": np.sin(th),
                "name": "clearance circle (ξ = 1)",
                "line": {"color": "black", "dash": "dash", "width": 1},
            }
        ]
        for n in journals:
            ex, ey = runs[n][0].last_revolutions(min(1.0, revs)).orbit("piston_pin")
            orbits.append(
                {
                    "type": "scatter",
                    "mode": "lines",
                    "x": ex,
                    "y": ey,
                    "name": runs[n][3].label,
                    "line": line(n),
                }
            )
            if len(ex):  # start ○, end × and the direction of travel, in the path's colour
                heads = direction_points(ex, ey)
                orbits.append(
                    {
                        "type": "scatter",
                        "mode": "markers",
                        "x": [ex[0], ex[-1], *(ex[i] for i, _ in heads)],
                        "y": [ey[0], ey[-1], *(ey[i] for i, _ in heads)],
                        "name": f"{runs[n][3].label}: start ○, end ×, direction ▲",
                        "showlegend": False,
                        "marker": {
                            "symbol": ["circle-open", "x", *(["triangle-up"] * len(heads))],
                            "angle": [0.0, 0.0, *(90.0 - a for _, a in heads)],  # clockwise from up
                            "size": 9,
                            "color": st[n][0],
                        },
                    }
                )
        parts.append(
            _plot(
                "orbit",
                orbits,
                "journal centre path e/c in the bushing (rod-eye) frame, last revolution (start ○, end ×)",
                "e_x/c [-], bushing frame",
                "e_y/c [-], bushing frame",
                yaxis={"scaleanchor": "x", "scaleratio": 1},
                height=820,
                width=700,
                legend={"orientation": "h", "y": -0.12},
            )
        )
    out = Path(out)
    from jointdyn.core.atomic import replacing

    with replacing(out) as tmp, tmp.open("wb") as f:  # piece by piece: never one string in memory
        f.write(
            b"<!DOCTYPE html><html><head><meta charset='utf-8'>"
            + "<title>jointdyn — interactive reproduction</title><script>".encode()
        )
        _copy_plotly_js(f)
        f.write(
            b"</script></head><body style='font-family:sans-serif;max-width:1100px;margin:auto'>"
            b"<h1>Alshaer et al. (2005) reproduction, interactive</h1>"
        )
        for part in parts:
            f.write(part.encode("utf-8"))
        f.write(b"</body></html>")
    return out
