"""Film forces of the steady mass-conserving (`jfo`) film for given bearing states [T343]
(``film-force --model finite --cavitation jfo``).

Per state the plain bearing is fed at ambient pressure through a supply line at the maximum
film (the Raimondi–Boyd bearing of ``bearing-table``, so the film is the same whatever the line
of centres) and solved by :func:`jointdyn.film.grooved.film_at` on its uniform mesh, with the
squeeze rate acting on frozen content (∂θ_f/∂t = 0, the convention of the `jfo` damping
coefficients [T242, T247]): a state has no history here. A dynamically loaded bearing that keeps
its history is the multibody loop's business.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from jointdyn.core import interrupts
from jointdyn.film.grooved import GROOVED_MESH, film_at

XI_MAX = 0.99  # the uniform 2° mesh resolves h_min ≥ 0.01c


@dataclass(frozen=True)
class SteadyJFO:
    """The steady line-fed mass-conserving film of a finite bearing, evaluated state by state."""

    mesh: tuple[int, int] = GROOVED_MESH
    """cells around the circumference, cells on the half length [-]"""

    def forces(
        self, xi, xi_dot, gamma, gamma_dot, omega_journal, omega_bearing, viscosity, length, radius, clearance
    ):
        """``dict(Fr, Ft, Fx, Fy)`` [N] for arrays of states, arguments as
        :func:`jointdyn.film.models.film_forces` (SI, global rates, Ω = ω_J + ω_B − 2γ̇ [T20]);
        ValueError naming the first state outside 0 < ξ ≤ ``XI_MAX`` (by its flat index)."""
        a = np.broadcast_arrays(
            *[np.asarray(v, dtype=float) for v in (xi, xi_dot, gamma, gamma_dot, omega_journal)],
            *[np.asarray(v, dtype=float) for v in (omega_bearing, viscosity, length, radius, clearance)],
        )
        x, xd, g, gd, wj, wb, mu, L, R, c = (v.ravel() for v in a)
        bad = np.flatnonzero(~((x > 0.0) & (x <= XI_MAX)))
        if bad.size:
            raise ValueError(
                f"xi = {float(x[bad[0]])!r} [-]: the steady jfo film needs 0 < xi <= {XI_MAX} "
                f"at index {bad[0]}"
            )
        fr, ft = np.empty(x.size), np.empty(x.size)
        for k in range(x.size):
            interrupts.check()  # [T332]
            omega = wj[k] + wb[k] - 2.0 * gd[k]
            # rates in units of ω_ref = 1 rad/s: t·ė = ξ(1 − Ω)/2 makes ξ − 2t·ė = ξΩ [T246]
            e, edot = (x[k], 0.0), (xd[k], 0.5 * x[k] * (1.0 - omega))
            F = film_at(L[k] / (2.0 * R[k]), e, edot, "jfo", ("line", math.pi), self.mesh)[0]
            scale = mu[k] * R[k] ** 4 / c[k] ** 2  # [μωR⁴/c²] with ω_ref = 1 rad/s
            fr[k], ft[k] = F[0] * scale, F[1] * scale
        cg, sg = np.cos(a[2]), np.sin(a[2])
        shape = a[0].shape
        fr, ft = fr.reshape(shape), ft.reshape(shape)
        return {"Fr": fr, "Ft": ft, "Fx": fr * cg - ft * sg, "Fy": fr * sg + ft * cg}  # [T27]
