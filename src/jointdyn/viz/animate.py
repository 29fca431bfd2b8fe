"""Animation of a saved run: the mechanism moving, the journal orbits and the driving moment.

Bodies are drawn as polylines through their named points (body frame, from the provenance
stored in ``results.nc``); ground points as triangles; a body guided along the ground by a
translational joint as a block on its guide line. The view is fitted to the mechanism's swept
area. Beside it: for every journal element the journal-centre path e/c in the clearance circle
(bushing frame; the eccentricity is invisible at mechanism scale) with the current position,
and the driving moment against crank angle with the current value marked.
"""

from __future__ import annotations

import contextlib
import shutil
import subprocess
from pathlib import Path

import numpy as np


def _body_outline(points: dict) -> np.ndarray:
    """Local coordinates of the outline: the points in insertion order (≥ 2), else a cross."""
    pts = np.array(list(points.values()), float).reshape(-1, 2)
    if len(pts) >= 2:
        return pts
    return np.array([[-0.005, 0.0], [0.005, 0.0]]) + (pts[0] if len(pts) else 0.0)


def _world(q, bodies, b, i, loc):
    x, y, phi = q[i, 3 * bodies.index(b) : 3 * bodies.index(b) + 3]
    c, s = np.cos(phi), np.sin(phi)
    return x + c * loc[:, 0] - s * loc[:, 1], y + s * loc[:, 0] + c * loc[:, 1]


#: the most frames one animation may have (a GIF frame is held as 1 byte per pixel until written)
MAX_FRAMES = 5000


def animate(results_file, out, frames: int = 120, fps: int = 20, last_revs: float | None = None):
    """Write a GIF (pillow) or MP4 (ffmpeg, ``[video]`` extra) of the run in ``results_file``.

    ``frames``: number of frames (2 … :data:`MAX_FRAMES`); ``fps``: frames per second;
    ``last_revs``: animate only the last N crank revolutions [-] (default: the whole run).
    The static parts of the figure are drawn once; each frame redraws only the moving artists
    onto a copy of that background (blitting) and is streamed to the writer [T227]."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Polygon

    from jointdyn.core.constraints import Translational
    from jointdyn.simulation.results import Results
    from jointdyn.viz import plots

    if not 2 <= frames <= MAX_FRAMES:
        raise ValueError(f"frames = {frames!r} [-]: must be 2 … {MAX_FRAMES}")
    res = Results.load(results_file)
    if last_revs:
        res = res.last_revolutions(last_revs)
    s, model = res.system, res.system.model_dict
    bodies, q, t = list(s.body_names), res.q, res.t
    idx = np.linspace(0, len(t) - 1, min(frames, len(t))).astype(int)
    outlines = {b: _body_outline(model["bodies"][b]["points"]) for b in bodies}
    guides = [
        (c.body_j, c.point_j, c.point_i, c.axis)
        for c in s.constraints
        if isinstance(c, Translational) and c.body_i == "ground" and c.body_j != "ground"
    ]
    allx = np.concatenate([_world(q, bodies, b, i, outlines[b])[0] for b in bodies for i in idx])
    ally = np.concatenate([_world(q, bodies, b, i, outlines[b])[1] for b in bodies for i in idx])
    gp = np.array(list(model["ground"]["points"].values()) or [[0.0, 0.0]], float)
    allx, ally = np.concatenate([allx, gp[:, 0]]), np.concatenate([ally, gp[:, 1]])
    span = max(np.ptp(allx), np.ptp(ally), 1e-3)
    pad = 0.12 * span
    journals = res.journals()
    try:
        angle = np.degrees(res.crank_angle() - res.crank_angle()[0])
        moment = res.multipliers(res.driver())[:, 0]
    except KeyError:
        angle, moment = t * 1e3, None
    side = len(journals) + (moment is not None)
    fig = plt.figure(figsize=(10.5, 5.2) if side else (7.5, 4.8))
    gs = fig.add_gridspec(max(side, 1), 2 if side else 1, width_ratios=[2.1, 1] if side else [1])
    ax = fig.add_subplot(gs[:, 0])
    ax.set_xlim(allx.min() - pad, allx.max() + pad)
    ax.set_ylim(ally.min() - pad, ally.max() + pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.grid(True, alpha=0.25)
    ax.plot(gp[:, 0], gp[:, 1], "k^", ms=10, label="ground")
    blocks = []
    for body, p_j, p_i, axis in guides:
        o = np.array(model["ground"]["points"][p_i], float)
        d = np.array(axis, float) / np.hypot(*axis)
        ends = np.array([o + d * (v - o @ d) for v in (allx.min() - pad, allx.max() + pad)])
        ax.plot(ends[:, 0], ends[:, 1], color="0.45", lw=1.2, ls="-.", zorder=1)
        w, h = 0.07 * span, 0.045 * span
        patch = Polygon(np.zeros((4, 2)), closed=True, fc="0.8", ec="k", lw=1.0, zorder=3)
        ax.add_patch(patch)
        local = np.array(model["bodies"][body]["points"][p_j], float) + np.array(
            [[-w, -h], [w, -h], [w, h], [-w, h]]
        )
        blocks.append((patch, body, local))
    lines = {b: ax.plot([], [], "-o", lw=3, ms=5, label=b, zorder=4)[0] for b in bodies}
    ax.legend(loc="upper right", fontsize=8, ncol=2)
    insets = []
    for n, name in enumerate(journals):
        ins = fig.add_subplot(gs[n, 1])
        ex, ey = res.orbit(name)
        plots.journal_orbit(ex, ey, ax=ins, start=False, zoom=False, color="0.55", lw=0.6)
        dot = ins.plot([], [], "o", color="tab:red", ms=6)[0]
        ins.set_title(f"{name}: e/c (bushing frame)", fontsize=8)
        ins.set_xlabel("")
        ins.set_ylabel("")
        ins.tick_params(labelsize=7)
        insets.append((dot, ex, ey))
    mark = None
    if moment is not None:
        mx = fig.add_subplot(gs[len(journals), 1])
        mx.plot(angle, moment, lw=0.8, color="tab:blue")
        mark = mx.plot([], [], "o", color="tab:red", ms=5)[0]
        mx.set_xlabel("crank angle [deg]", fontsize=8)
        mx.set_ylabel("driving moment [N·m]", fontsize=8)
        mx.set_xlim(angle.min(), angle.max())
        plots._angle_ticks(mx, float(np.ptp(angle)))
        mx.tick_params(labelsize=7)
        mx.grid(True, alpha=0.3)
    title = fig.suptitle("", fontsize=10)
    head = plots.describe(res, sep=" — ")

    def draw(j):
        i = idx[j]
        for b in bodies:
            lines[b].set_data(*_world(q, bodies, b, i, outlines[b]))
        for patch, body, local in blocks:
            patch.set_xy(np.column_stack(_world(q, bodies, body, i, local)))
        for dot, ex, ey in insets:
            dot.set_data([ex[i]], [ey[i]])
        if mark is not None:
            mark.set_data([angle[i]], [moment[i]])
        where = f"crank angle {angle[i]:.0f}°, " if moment is not None else ""
        title.set_text(f"{head}\n{where}t = {t[i] * 1e3:.2f} ms")
        return list(lines.values())

    fig.tight_layout()
    moving = [*lines.values(), *(b[0] for b in blocks), *(d[0] for d in insets), title]
    if mark is not None:
        moving.append(mark)
    moving.sort(key=lambda a: a.get_zorder())  # drawn in the order a full draw would use
    for a in moving:
        a.set_animated(True)  # left out of the full draw: the background is static
    out = Path(out)
    from jointdyn.core.atomic import replacing

    try:
        with replacing(out) as tmp:  # the temporary name keeps the suffix
            with _writer(Path(tmp), fig, fps) as write:
                fig.canvas.draw()
                background = fig.canvas.copy_from_bbox(fig.bbox)
                for j in range(len(idx)):
                    draw(j)
                    fig.canvas.restore_region(background)
                    for a in moving:
                        fig.draw_artist(a)
                    write(np.asarray(fig.canvas.buffer_rgba()))
    finally:
        plt.close(fig)
    return out


@contextlib.contextmanager
def _writer(out: Path, fig, fps: int):
    """A frame sink for RGBA arrays: GIF frames quantised to a 256-colour palette as they come
    (1 byte per pixel held until the file is written), MP4 frames piped to ffmpeg as raw video."""
    w, h = (int(v) for v in fig.canvas.get_width_height(physical=True))
    if out.suffix == ".mp4":
        exe = _ffmpeg()
        cmd = [exe, "-v", "error", "-y", "-f", "rawvideo", "-pix_fmt", "rgba", "-s", f"{w}x{h}"]
        cmd += ["-r", str(fps), "-i", "-", "-pix_fmt", "yuv420p", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2"]
        proc = subprocess.Popen([*cmd, str(out)], stdin=subprocess.PIPE, stderr=subprocess.PIPE)
        try:
            yield lambda rgba: proc.stdin.write(np.ascontiguousarray(rgba).tobytes())
        finally:
            proc.stdin.close()
            err = proc.stderr.read().decode(errors="replace")
            if proc.wait() != 0:
                raise RuntimeError(f"ffmpeg failed writing {out}: {err.strip()[-300:]}")
        return
    from PIL import Image

    frames: list = []
    palette = None

    def add(rgba):
        nonlocal palette
        im = Image.fromarray(rgba[..., :3])
        if palette is None:  # one palette for the whole film: no flicker between frames
            palette = im.quantize(colors=256, method=Image.Quantize.MEDIANCUT)
        frames.append(im.quantize(palette=palette, dither=Image.Dither.NONE))

    yield add
    frames[0].save(out, save_all=True, append_images=frames[1:], duration=1000 / fps, loop=0, optimize=False)


def _ffmpeg() -> str:
    """The ffmpeg binary of the ``[video]`` extra (imageio-ffmpeg), else one on the PATH."""
    try:
        import imageio_ffmpeg

        return imageio_ffmpeg.get_ffmpeg_exe()
    except ImportError:
        exe = shutil.which("ffmpeg")
        if exe is None:
            raise RuntimeError("MP4 needs ffmpeg: pip install -e '.[video]' (or write a .gif)") from None
        return exe


def frame_png(results_file, out, fraction: float = 0.5, **kw) -> Path:
    """One frame of :func:`animate` as a PNG (for docs and checks): the frame at ``fraction``
    [-] of the run."""
    import tempfile

    from PIL import Image

    with tempfile.TemporaryDirectory() as tmp:
        gif = animate(results_file, Path(tmp) / "a.gif", frames=kw.pop("frames", 21), **kw)
        im = Image.open(gif)
        im.seek(int(round(fraction * (im.n_frames - 1))))
        from jointdyn.core.atomic import replacing

        with replacing(Path(out)) as t:
            im.convert("RGB").save(t, format=(Path(out).suffix[1:] or "png").upper().replace("JPG", "JPEG"))
    return Path(out)
