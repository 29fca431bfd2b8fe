"""A one-pass layout for the report's figures [T371]: a column of axes (one or several sharing x,
equal aspect allowed), an optional figure title on top and figure legends at the bottom. Every
axes gets the room its decorations (tick labels, axis labels, title, inset) take, measured once
with the renderer that then draws the picture, so the text extents are computed once and reused by
the drawing; matplotlib's constrained layout measures every axes twice and its titles' neighbours
again (≈ 0.8 s of the report's 17 figures). Positions are set in figure fractions (no layout
engine); a second pass runs only when the new axes sizes change the ticks."""

from __future__ import annotations

import numpy as np

#: room around every block [in] (the constrained layout's default padding)
PAD = 3 / 72


def _ticks(axes) -> list[np.ndarray]:
    """The major and minor tick locations of ``axes`` (what sizes the margins; an inset's tick
    labels lie inside its parent, and the small orbits' inset ticks alternate between two sets as
    the parent is resized, which would cost two more passes for nothing)."""
    out = []
    for a in axes:
        for axis in (a.xaxis, a.yaxis):
            out += [axis.get_majorticklocs(), axis.get_minorticklocs()]
    return out


def _same(a: list[np.ndarray], b: list[np.ndarray]) -> bool:
    return len(a) == len(b) and all(x.shape == y.shape and np.array_equal(x, y) for x, y in zip(a, b))


def column(fig, pad: float = PAD, passes: int = 3) -> None:
    """Place the axes of ``fig`` (top to bottom in creation order, equal heights) so that each
    one's tight bounding box (ticks, labels, title, legend, insets; a title wider than its axes
    overhangs it, as in the constrained layout) lies inside the figure with
    ``pad`` [in] between blocks, under ``fig``'s suptitle and above its legends (``loc="lower
    center"``)."""
    axes = list(fig.axes)
    if not axes:
        return
    renderer = fig.canvas.get_renderer()
    W, H = fig.bbox.width, fig.bbox.height
    p = pad * fig.dpi
    for _ in range(passes):
        before = _ticks(axes)
        margins = []
        for a in axes:
            a.apply_aspect()
            # as the constrained layout: a title's and the x label's width, the y label's height not counted
            box, tight = a.get_window_extent(renderer), a.get_tightbbox(renderer, for_layout_only=True)
            margins.append((box.x0 - tight.x0, tight.x1 - box.x1, box.y0 - tight.y0, tight.y1 - box.y1))
        top = H - p
        if fig._suptitle is not None and fig._suptitle.get_text():
            top = fig._suptitle.get_window_extent(renderer).y0 - p
        bottom = p + max((lg.get_window_extent(renderer).y1 for lg in fig.legends), default=0.0)
        m = np.array(margins)
        left, right = m[:, 0].max() + p, W - m[:, 1].max() - p
        # a title wider than its axes is centred on it: move the axes so that it stays on the canvas
        w = max(a.title.get_window_extent(renderer).width if a.title.get_text() else 0.0 for a in axes)
        if w <= W - 2 * p:
            right = min(right, 2 * (W - p) - w - left)
            left = max(left, 2 * p + w - right)
        h = (top - bottom - m[:, 2].sum() - m[:, 3].sum() - p * (len(axes) - 1)) / len(axes)
        if h <= 0 or right <= left:
            raise ValueError(f"figure of {fig.get_size_inches()} in: no room left for its axes")
        y = top
        for a, (_, _, below, above) in zip(axes, margins):
            y -= above + h
            a.set_position([left / W, y / H, (right - left) / W, h / H])
            a.apply_aspect()
            y -= below + p
        if _same(before, _ticks(axes)):
            return
