"""What the reproduction's figures draw, as plain arrays and strings (no Results): computed in
the reproducing process, handed to the drawing process, which then needs numpy and matplotlib
only, not jointdyn's compiled kernels or numba [T360]."""

from __future__ import annotations

import numpy as np

from jointdyn import post

PAPER = ("perfect", "dry", "ott", "alshaer2005")
PIN = "piston_pin"


def _deg(res) -> np.ndarray:
    """Crank angle from the run's first sample [deg]."""
    a = res.crank_angle()
    return np.degrees(a - a[0])


def _force(res) -> np.ndarray:
    """|F| on the piston pin at each sample [N]."""
    return np.hypot(res.element(PIN, "Fx"), res.element(PIN, "Fy"))


def record(res) -> str:
    """The run's largest sampled |F| on the pin and where, and its recorded peak penetration
    (between samples included, [T202]) with the elastic force K·δⁿ there (a lower bound of the
    peak force: the damping term vanishes at the deepest point)."""
    f = _force(res)
    i = int(np.argmax(f))
    a = _deg(res)[i]
    text = f"whole run: largest sample {f[i] / 1e3:.3g} kN at {a:.0f}° (revolution {int(a // 360) + 1})"
    el = res.system.elements[res.system.element_names.index(PIN)]
    law = getattr(el, "contact", None)
    pen = post.max_penetration(res, PIN)
    if pen > 0 and law is not None and hasattr(law, "stiffness"):
        fk = law.stiffness * pen ** getattr(law, "exponent", 1.0)
        text += f"; recorded peak penetration {pen * 1e6:.3g} µm → K·δⁿ = {fk / 1e3:.3g} kN"
    return text


def figure_data(runs: dict, revs: float) -> dict[str, dict]:
    """``{case: {key: array or str}}`` of ``runs`` ({case: (Results, columns, summary, Case)}):
    ``label``, ``joint``; the last revolution (or the whole run when shorter): ``deg`` [deg from its
    start], ``moment`` [N·m]; the paper's cases also over the whole run: ``angle_all`` [rad from the
    start], ``moment_all`` [N·m]; a piston pin: ``ex``, ``ey`` (path in the bushing frame [c]), and
    in a paper case ``force`` (|F| [N]) and ``record`` (the whole run's largest, :func:`record`); a film:
    ``h_min`` [µm]; the perfect joint: ``reaction`` (|reaction| on the pin [N])."""
    out: dict[str, dict] = {}
    for n, (res, _, _, case) in runs.items():
        last = res.last_revolutions(min(1.0, revs))
        d: dict = {"label": case.label, "joint": case.joint, "deg": _deg(last)}
        d["moment"] = post.driving_moment(last)
        if n in PAPER:
            d["angle_all"] = res.crank_angle() - res.crank_angle()[0]
            d["moment_all"] = post.driving_moment(res)
        if PIN in res.journals():
            d["ex"], d["ey"] = last.orbit(PIN, frame="bushing")
            if n in PAPER:
                d["force"] = _force(last)
                d["record"] = record(res)
            if case.joint not in ("perfect", "dry"):
                d["h_min"] = last.element(PIN, "h_min") * 1e6
        if n == "perfect":
            d["reaction"] = np.hypot(*post.joint_reaction(last, PIN).T)
        out[n] = d
    return out
