"""One look for every figure, static (matplotlib) and interactive (plotly): a colour-blind-safe
palette (Okabe & Ito, 2008) paired with line styles, so that ≥ 8 curves stay distinguishable in
colour, in grey and for colour-blind readers, and legends placed outside the data."""

from __future__ import annotations

#: Okabe–Ito colours (black first: the reference curve), distinguishable under the common
#: colour-vision deficiencies
OKABE_ITO = (
    "#000000",  # black
    "#E69F00",  # orange
    "#56B4E9",  # sky blue
    "#009E73",  # bluish green
    "#D55E00",  # vermillion
    "#0072B2",  # blue
    "#CC79A7",  # reddish purple
    "#F0E442",  # yellow (last: weak on white)
)
#: matplotlib dash patterns paired with the colours (the pair is unique for 7 × 4 curves)
DASHES = ("-", "--", "-.", ":")
#: the same dash patterns in plotly's names
PLOTLY_DASH = {"-": "solid", "--": "dash", "-.": "dashdot", ":": "dot"}

#: the reproduction's paper cases keep one look in every figure
PAPER_STYLE = {
    "perfect": ("#000000", "--"),
    "dry": ("#D55E00", "-"),
    "ott": ("#E69F00", "-"),
    "alshaer2005": ("#0072B2", "-"),
}


def styles(names, fixed: dict | None = None) -> dict[str, tuple[str, str]]:
    """``{name: (colour, dash)}``: the names of ``fixed`` keep theirs; the others take the
    Okabe–Ito colours (not black, not yellow) in order, the dash pattern changing each time the
    colours run out, so no two names share both."""
    fixed = PAPER_STYLE if fixed is None else fixed
    out = {n: fixed[n] for n in names if n in fixed}
    taken = set(fixed.values())
    for n in names:
        if n in out:
            continue
        free = [(c, d) for d in DASHES for c in OKABE_ITO[1:7] if (c, d) not in taken]
        if not free:  # more than 24 curves: the pairs repeat
            taken = set(fixed.values())
            free = [(c, d) for d in DASHES for c in OKABE_ITO[1:7] if (c, d) not in taken]
        # the least used colour among the non-fixed names, then the plainest dash
        uses = {c: sum(c == o[0] for k, o in out.items() if k not in fixed) for c, _ in free}
        out[n] = min(free, key=lambda cd: (uses[cd[0]], DASHES.index(cd[1])))
        taken.add(out[n])
    return {n: out[n] for n in names}


def legend_below(ax, ncol: int = 2, fontsize: float = 8, **kw):
    """A legend under the axes (outside the data), ``ncol`` columns, no frame."""
    handles, labels = ax.get_legend_handles_labels()
    if not handles:
        return None
    return ax.legend(
        fontsize=fontsize,
        loc="upper center",
        bbox_to_anchor=(0.5, kw.pop("y", -0.16)),
        ncol=ncol,
        frameon=False,
        **kw,
    )


def legend_right(ax, fontsize: float = 8, **kw):
    """A legend to the right of the axes (outside the data)."""
    return ax.legend(fontsize=fontsize, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False, **kw)


def cycle():
    """A matplotlib property cycle of the :func:`styles` pairs (colour and dash), for axes whose
    curves have no names known in advance."""
    from cycler import cycler

    pairs = list(styles(range(24), fixed={}).values())
    return cycler(color=[c for c, _ in pairs], linestyle=[d for _, d in pairs])
