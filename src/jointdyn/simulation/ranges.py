"""Runs that leave the range of a tabulated film [T249]: the ``finite`` film's table covers
ξ ≤ XI_MAX and extrapolates beyond with the (1−ξ²)^(−3/2) scaling of [T37]; a run that goes
there is reported (a warning from :func:`~jointdyn.simulation.simulate.simulate` and an entry
of ``summary.json``) instead of passing silently."""

from __future__ import annotations

import numpy as np


def film_range_exits(res) -> list[dict]:
    """One dict per journal element with a ``finite`` film whose ξ exceeded the table range at
    an output sample: ``element``, ``xi_limit`` [-], ``first_time`` [s] (first sample beyond),
    ``xi_max`` [-] and ``time_of_max`` [s], ``fraction`` of the samples beyond [-]. Checked at
    the output samples (an excursion shorter than the output spacing can pass unseen)."""
    from jointdyn.film.finite import XI_MAX
    from jointdyn.film.models import Finite, film_model

    out = []
    if len(res.t) == 0:
        return out
    for name, e in zip(res.system.element_names, res.system.elements, strict=True):
        film = getattr(e, "film", None)
        if film is None or "xi" not in getattr(type(e), "OUTPUTS", ()):
            continue
        try:
            fm = film_model(film)
        except (ValueError, TypeError):
            continue
        if not isinstance(fm, Finite) or fm.transient:
            continue  # only the tabulated films have a table range (jfo solves its mesh each step)
        xi = res.element(name, "xi")
        beyond = xi > XI_MAX
        if beyond.any():
            k = int(np.argmax(xi))
            out.append(
                {
                    "element": name,
                    "xi_limit": XI_MAX,
                    "first_time": float(res.t[int(np.argmax(beyond))]),
                    "xi_max": float(xi[k]),
                    "time_of_max": float(res.t[k]),
                    "fraction": float(beyond.mean()),
                }
            )
    return out


def range_message(d: dict) -> str:
    """One line for an entry of :func:`film_range_exits`."""
    return (
        f"element {d['element']!r}: finite film beyond its table (xi > {d['xi_limit']}) from t = "
        f"{d['first_time']:.6g} s, xi_max = {d['xi_max']:.6f} at t = {d['time_of_max']:.6g} s "
        f"({100 * d['fraction']:.3g} % of the samples); the force there is extrapolated [T37]"
    )
