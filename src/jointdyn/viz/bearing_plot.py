"""Figure of the film pressure at one bearing state [T76]: the mid-plane pressure around the
bearing (bearing-frame angle) and the field p(θ, z). For ``jointdyn plot --what pressure``."""

from __future__ import annotations

import math

import numpy as np

from jointdyn.film.field import film_outputs, pressure_field


def pressure_figure(
    xi: float,
    xi_dot: float,
    xi_Omega: float,
    mu: float,
    R: float,
    L: float,
    c: float,
    gamma: float = 0.0,
    cavitation: str = "reynolds",
    title: str = "",
):
    """Matplotlib figure: (left) mid-plane p [MPa] against the angle α − φ_B measured in the
    bearing frame (α = θ + γ + π, γ the line-of-centres angle relative to the bearing body [rad]),
    with the peak and the rupture marked; (right) p(θ, z) over the developed film.
    Arguments as :func:`jointdyn.film.field.pressure_field`."""
    import matplotlib.pyplot as plt

    th, z, p = pressure_field(xi, xi_dot, xi_Omega, mu, R, L, c, cavitation)
    out = film_outputs(xi, xi_dot, xi_Omega, mu, R, L, c, cavitation)
    mid = p[:, p.shape[1] // 2]
    alpha = np.degrees(np.mod(th + gamma + math.pi, 2 * math.pi))
    order = np.argsort(alpha)
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 3.8))
    a1.plot(alpha[order], mid[order] / 1e6, "-")
    ap = math.degrees(math.fmod(out["theta_pmax"] + gamma + math.pi, 2 * math.pi))
    a1.plot([ap], [out["p_max"] / 1e6], "v", label=f"peak {out['p_max'] / 1e6:.3g} MPa at {ap:.1f}°")
    if math.isfinite(out["theta_rupture"]):
        ar = math.degrees(math.fmod(out["theta_rupture"] + gamma + math.pi, 2 * math.pi))
        a1.axvline(ar, ls=":", color="k", label=f"rupture {ar:.1f}°")
    a1.set(xlabel="bearing-frame angle α [deg]", ylabel="mid-plane pressure [MPa]", xlim=(0, 360))
    a1.legend(fontsize=8)
    a1.grid(True, alpha=0.3)
    cs = a2.contourf(np.degrees(th), z * 1e3, p.T / 1e6, levels=20)
    fig.colorbar(cs, ax=a2, label="p [MPa]")
    a2.set(xlabel="θ from the maximum film [deg]", ylabel="z [mm]", title=f"{cavitation}, ε = {xi:.3g}")
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    return fig


def pressure_figure_at(res, element: str, crank_angle_deg: float):
    """Figure of the film pressure of bearing ``element`` at the sample nearest to the crank
    angle ``crank_angle_deg`` [deg] (unwrapped from the run's start): mid-plane pressure around
    the bushing and p(θ, z), from the 2-D Reynolds solver at the bearing's L/D with the run's
    film state (Swift–Stieber rupture unless the bearing's ``finite`` model uses Gümbel) [T70–T76]."""
    from jointdyn.film.models import film_model, film_name
    from jointdyn.post import film_states, film_viscosity

    el = res.system.elements[res._element(element)[0]]
    ang = np.degrees(res.crank_angle() - res.crank_angle()[0])
    if not (ang.min() <= crank_angle_deg <= ang.max()):
        raise ValueError(
            f"--at {crank_angle_deg!r} [deg]: the run covers {ang.min():.4g} … {ang.max():.4g} deg"
        )
    i = int(np.argmin(np.abs(ang - crank_angle_deg)))
    st = film_states(res, element)
    fm = film_model(el.film)
    cav = getattr(fm, "cavitation", "reynolds")
    title = (
        f"{element}: film pressure at crank angle {ang[i]:.1f}° (t = {res.t[i] * 1e3:.3f} ms), "
        f"ξ = {st['xi'][i]:.3f}\nrun with film {film_name(el.film)!r}; pressure from 2-D Reynolds ({cav})"
    )
    return pressure_figure(
        min(st["xi"][i], 0.999),
        st["xi_dot"][i],
        st["xi_Omega"][i],
        film_viscosity(res, element)[i],
        el.journal_radius,
        el.length,
        el.clearance,
        gamma=st["gamma"][i],
        cavitation=cav,
        title=title,
    )
