"""Viscous shear torque of the film on journal and bushing, and power loss [T75]; compiled
kernels for the bearing element.

Film velocity u(y) = U_J(1 − y/h) + U_B y/h + (∂p/∂x)(y² − yh)/(2μ) (y from the journal,
x = Rθ), U_J − U_B = (ω_J − ω_B)R. Shear tractions integrated over the surfaces and the
Poiseuille part integrated by parts (p = 0 at the film ends or periodic; h_θ = −cξ sin θ) give,
with the film force F_t on the journal along t (the models' kernels),

    M_J = −M_C − (e/2)·F_t,   M_B = +M_C − (e/2)·F_t,   e = cξ,
    M_C = μ(ω_J − ω_B)R³ ∫∫ dθ dz / h = 2πμ(ω_J − ω_B)R³L / (c√(1−ξ²)),

torques about +z on the journal (M_J) and on the bushing body (M_B) [N·m]. The Couette integral
is taken over the full circumference (the cavitated region carries the Couette shear of a full
film, the Raimondi–Boyd treatment, validated by their friction variable to ≤ 3 %; docs/theory.md
[T75]; the mass-conserving film shears its lubricant only, θ_f, [T375]). M_J + M_B = −e F_t:
together with the film force pair (F on the journal centre, −F on the bushing centre) the film
exerts no net moment — angular momentum is balanced. Petroff (ξ → 0): M_J = −2πμωR³L/c.
"""

from __future__ import annotations

from numba import njit

from jointdyn.film.finite import finite_force
from jointdyn.film.models import film_force
from jointdyn.film.shear_kernels import shear_torques


@njit(cache=True)
def film_power_loss(xi, F_r, F_t, mu, R, L, c, omega_journal, omega_bearing, e_dot_r, gamma_dot):
    """Power dissipated in the film [W] = −(work rate of the film on both bodies) [T75]:
    −(M_J ω_J + M_B ω_B + F·ė), with ė = (ė_r, eγ̇) the journal-centre velocity relative to
    the bushing centre in (u, t) (F on the journal, −F on the bushing) [m/s, rad/s]."""
    mj, mb = shear_torques(xi, F_t, mu, R, L, c, omega_journal, omega_bearing)
    e = c * xi
    return -(mj * omega_journal + mb * omega_bearing + F_r * e_dot_r + F_t * e * gamma_dot)


@njit(cache=True)
def finite_torques(xi, xi_dot, xi_Omega, mu, R, L, c, p, table, omega_journal, omega_bearing):
    """(M_J, M_B) [N·m] of the tabulated ``finite`` film: :func:`shear_torques` with its F_t [T75]
    (state arguments and parameter block ``p`` as the film kernels, then ω_J, ω_B [rad/s])."""
    fr, ft = finite_force(xi, xi_dot, xi_Omega, mu, R, L, c, p, table)
    return shear_torques(xi, ft, mu, R, L, c, omega_journal, omega_bearing)


def film_torques(code, xi, xi_dot, xi_Omega, mu, R, L, c, p, table, omega_journal, omega_bearing):
    """(M_J, M_B) [N·m] for the film model with registry code ``code`` (any of ``FILM_MODELS``):
    :func:`shear_torques` with that model's F_t [T75]. State arguments, parameter block ``p``
    and ``table`` as the film kernels, then ω_J, ω_B [rad/s]; torques about +z on journal and
    bushing."""
    fr, ft = film_force(code, xi, xi_dot, xi_Omega, mu, R, L, c, p, table)
    return shear_torques(xi, ft, mu, R, L, c, omega_journal, omega_bearing)
