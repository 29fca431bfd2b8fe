"""Animation of a saved run: the mechanism moving, with journal orbits in insets.

Bodies are drawn as polylines through their named points (body frame, from the provenance
stored in ``results.nc``); ground points as triangles. For every journal element an inset shows
the journal-centre path e/c in the clearance circle (the eccentricity is invisible at mechanism
scale, so it is magnified there), with the current position marked.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np


def _body_outline(points: dict) -> np.ndarray:
    """Local coordinates of the outline: the points in insertion order (≥ 2), else a cross."""
    pts = np.array(list(points.values()), float).reshape(-1, 2)
    if len(pts) >= 2:
        return pts
    return np.array([[-0.005, 0.0], [0.005, 0.0]]) + (pts[0] if len(pts) else 0.0)


def animate(results_file, out, frames: int = 120, fps: int = 20):
    """Write a GIF (pillow) or MP4 (ffmpeg, optional) of the run in ``results_file``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.animation import FFMpegWriter, FuncAnimation, PillowWriter

    from .results import load

    ds = load(results_file)
    model = json.loads(ds.attrs["model"])
    bodies = list(model["bodies"])
    q = ds["q"].values
    t = ds["time"].values
    idx = np.linspace(0, len(t) - 1, min(frames, len(t))).astype(int)
    outlines = {b: _body_outline(model["bodies"][b]["points"]) for b in bodies}
    journals = [k for k, v in model["items"].items() if v["type"] in ("journal_bearing", "clearance_joint")]
    eout = ds["element_outputs"]
    elements = list(ds["element"].values)

    def world(b, i):
        x, y, phi = q[i, 3 * bodies.index(b) : 3 * bodies.index(b) + 3]
        c, s = np.cos(phi), np.sin(phi)
        loc = outlines[b]
        return x + c * loc[:, 0] - s * loc[:, 1], y + s * loc[:, 0] + c * loc[:, 1]

    allx = np.concatenate([world(b, i)[0] for b in bodies for i in idx])
    ally = np.concatenate([world(b, i)[1] for b in bodies for i in idx])
    pad = 0.1 * max(np.ptp(allx), np.ptp(ally), 1e-3)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.set_xlim(allx.min() - pad, allx.max() + pad)
    ax.set_ylim(ally.min() - pad, ally.max() + pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    gp = np.array(list(model["ground_points"].values()) or [[0.0, 0.0]], float)
    ax.plot(gp[:, 0], gp[:, 1], "k^", ms=8)
    lines = {b: ax.plot([], [], "-o", lw=3, ms=4, label=b)[0] for b in bodies}
    title = ax.set_title("")
    insets = []
    for n, name in enumerate(journals):
        k = elements.index(name)
        c = model["items"][name]["bearing_radius"] - model["items"][name]["journal_radius"]
        ex, ey = eout.values[:, k, 0] / c, eout.values[:, k, 1] / c
        ins = ax.inset_axes([0.70 - 0.30 * n, 0.62, 0.28, 0.36])
        th = np.linspace(0, 2 * np.pi, 181)
        ins.plot(np.cos(th), np.sin(th), "k-", lw=0.6)
        ins.plot(ex, ey, "-", lw=0.5, color="0.6")
        dot = ins.plot([], [], "ro", ms=4)[0]
        ins.set_aspect("equal")
        ins.set_xticks([])
        ins.set_yticks([])
        ins.set_title(f"{name}: e/c", fontsize=7)
        insets.append((dot, ex, ey))
    ax.legend(loc="lower left", fontsize=7)

    def draw(j):
        i = idx[j]
        for b in bodies:
            lines[b].set_data(*world(b, i))
        for dot, ex, ey in insets:
            dot.set_data([ex[i]], [ey[i]])
        title.set_text(f"t = {t[i] * 1e3:.2f} ms")
        return list(lines.values()) + [d for d, _, _ in insets] + [title]

    anim = FuncAnimation(fig, draw, frames=len(idx), blit=False)
    out = Path(out)
    if out.suffix == ".mp4":
        try:  # the [video] extra ships an ffmpeg binary inside its wheel
            import imageio_ffmpeg

            matplotlib.rcParams["animation.ffmpeg_path"] = imageio_ffmpeg.get_ffmpeg_exe()
        except ImportError:
            if not FFMpegWriter.isAvailable():
                plt.close(fig)
                raise RuntimeError("MP4 needs ffmpeg: pip install -e '.[video]' (or write a .gif)") from None
        writer = FFMpegWriter(fps=fps)
    else:
        writer = PillowWriter(fps=fps)
    anim.save(out, writer=writer)
    plt.close(fig)
    return out
