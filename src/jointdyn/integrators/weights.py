"""Error scales measured in the physics of the joints instead of the state's magnitude [T186].

The default error test weights component i with atol + rtol·|y_i| [T110]: a position of
0.1–0.3 m then carries a tolerance of ≈ rtol·0.3 m whatever the clearance, so the eccentricity
of a journal is resolved 10× more loosely (relative to its clearance) at c = 0.05 mm than at
c = 0.5 mm, and a coordinate passing through zero (or a crank angle winding up) changes its
tolerance along the run although nothing physical changed. :func:`clearance_scale` gives fixed
scales Y_i instead (the error test then uses atol + rtol·Y_i):

* translations: Y = c_min, the smallest radial clearance of the system's journal elements [m];
* rotations: Y = c_min/ℓ, ℓ the largest distance of a body's attachment point from its
  reference point [m] (a rotation δφ moves such a point by ℓ·δφ);
* velocities: the position scale times ω_ref, the largest angular speed of the initial state,
  at least 2π over the simulated time span [rad/s].

rtol is then a fraction of the clearance (``SimConfig.error_scale = "clearance"``). The default
``error_scale = "auto"`` uses these scales when ``solver = "auto"`` picks radau5 (a lubricated
bearing) at AUTO_CLEARANCE_RATIO × the user's rtol [T188].
"""

from __future__ import annotations

import math

import numpy as np

from jointdyn.core.layout import ETA_I, ETA_J, XI_I, XI_J

# rtol = 1e-8 (the default) ↔ 3e-6 of the clearance: the loosest clearance rtol of the measured
# ladder that kept every pure-film case of [T116] ≤ 4.1e-5 of the peak moment, and 300 ≈ the
# benchmark's size over its clearance (0.15 m / 0.5 mm), so at that clearance the positions keep
# the weight the state scales gave them [T188]
AUTO_CLEARANCE_RATIO = 300.0


def clearance_scale(system, t_span: float) -> np.ndarray:
    """Fixed error scales Y (2n,) [m, rad, m/s, rad/s] of the state [q, q̇] [T186]; the lengths
    are the ``error_length()`` the elements declare (journal elements: their clearance). Raises
    ValueError when no element declares one (no clearance to measure against)."""
    n = system.n
    declared = enumerate(system.elements)
    lengths = {k: float(e.error_length()) for k, e in declared if hasattr(e, "error_length")}
    if not lengths:
        raise ValueError(
            "SimConfig.error_scale = 'clearance': the system has no journal element (no clearance "
            "to measure the error against); use 'state'"
        )
    freal = system.freal
    c_min = min(lengths.values())
    arms = [math.hypot(freal[k, XI_I], freal[k, ETA_I]) for k in lengths]
    arms += [math.hypot(freal[k, XI_J], freal[k, ETA_J]) for k in lengths]
    for body in system.model_dict.get("bodies", {}).values():  # every point of every body
        arms += [math.hypot(*p) for p in body.get("points", {}).values()]
    ell = max(max(arms), c_min)  # a system of point masses: rotations scaled like translations
    y0 = system.y0
    omega = max(float(np.abs(y0[n + 2 : 2 * n : 3]).max(initial=0.0)), 2 * math.pi / t_span)
    pos = np.tile([c_min, c_min, c_min / ell], n // 3)
    return np.concatenate([pos, pos * omega])
