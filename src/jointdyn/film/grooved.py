"""Journal bearings fed through axial grooves, the equilibrium with the load direction fixed, and
the dynamic coefficients of any film end by central differences [T244–T247].

The mesh is fixed in the bearing: uniform in θ (no clustering, so the groove cells stay the same
cells whatever the journal does), angles α measured from the load line (the direction of the load
on the journal) in the direction of rotation; the journal centre at e = ξ(cos φ, sin φ) in that
frame puts the maximum film at α = φ + π (``phase``). Steady scale: ω = 1, R = c = μ = 1,
L = 2λ; forces in μωR⁴/c², pressures P in 6μωR²/c², flows in ωR²c/2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from jointdyn.film.cavitation import condition
from jointdyn.film.fv import assemble, check_ld

#: default mesh of the grooved bearing: uniform cells around (2°), cells on the half length [-]
GROOVED_MESH = (180, 16)
#: central-difference steps of the coefficients: Δe/c and Δė/(cω) [-] [T247]
STEP = 2e-3


@dataclass(frozen=True)
class Grooves:
    """Axial supply grooves over the full length.

    centres  groove centre angles from the load line in the direction of rotation (n,) [rad]
    width    angular width of each groove [rad]
    feed     supply pressure P_f = p_f c²/(6μωR²) [-] (p_f ≥ 0 gauge)
    """

    centres: tuple[float, ...]
    width: float
    feed: float = 0.0
    flow_name: ClassVar[str] = "groove_flow"

    def __post_init__(self):
        check_grooves(self.centres, self.width, self.feed)

    def labels(self, theta: np.ndarray, zeta: np.ndarray) -> np.ndarray:
        """Groove number of every unknown (N,) (−1 elsewhere): :func:`groove_labels`."""
        return groove_labels(theta, zeta.size - 1, self)

    @property
    def count(self) -> int:
        return len(self.centres)


def check_grooves(centres, width, feed) -> None:
    """ValueError naming the parameter unless the grooves are inside the bearing, apart and fed
    at a pressure ≥ 0 [T244]."""
    n = len(centres)
    if n < 1:
        raise ValueError("grooves: give at least one groove (or none for the plain bearing)")
    if not (math.isfinite(width) and 0.0 < width < 2.0 * math.pi / n):
        raise ValueError(
            f"groove width = {math.degrees(width):.6g} [deg]: must be in (0, {360.0 / n:.6g}) for {n} "
            "groove(s) (wider grooves overlap)"
        )
    if not (math.isfinite(feed) and feed >= 0.0):
        raise ValueError(f"feed pressure = {feed!r} [-, or Pa]: must be finite and >= 0 (gauge)")
    c = sorted(float(x) for x in centres)
    for x in c:
        if not (math.isfinite(x) and 0.0 <= x < 2.0 * math.pi):
            raise ValueError(
                f"groove centre = {math.degrees(x):.6g} [deg]: outside the bearing; must be in [0, 360)"
            )
    for a, b in zip(c, c[1:] + [c[0] + 2.0 * math.pi], strict=True):
        if n > 1 and b - a < width:
            raise ValueError(
                f"grooves at {math.degrees(a):.6g} and {math.degrees(b) % 360:.6g} [deg] overlap "
                f"(width {math.degrees(width):.6g} deg)"
            )


def axial_grooves(n: int, width_deg: float, feed: float = 0.0) -> Grooves:
    """n grooves evenly spaced, the first at +90° from the load line: n = 2 is the standard
    two-axial-groove bearing (grooves at ±90° from the load line) [T244]."""
    if not (isinstance(n, int) and n >= 1):
        raise ValueError(f"grooves = {n!r}: number of axial grooves must be an integer >= 1")
    return Grooves(_spaced(n), math.radians(width_deg), feed)


def feed_holes(n: int, diameter: float, feed: float = 0.0) -> FeedHoles:
    """n feed holes of diameter d/R [-] at mid-length, evenly spaced from +90° off the load line
    (as :func:`axial_grooves`) [T366]."""
    if not (isinstance(n, int) and n >= 1):
        raise ValueError(f"feed holes = {n!r}: number of feed holes must be an integer >= 1")
    return FeedHoles(_spaced(n), diameter, feed)


@dataclass(frozen=True)
class PartialArc(Grooves):
    """A partial bearing [T366]: the arc of bearing surface is centred on the load line, the
    rest is open (at the supply pressure) — one axial "groove" of width 2π − arc opposite the load.
    ``arc`` is the bearing surface's angle [rad]; ``open_flow_1`` the flow into the open part."""

    flow_name: ClassVar[str] = "open_flow"

    @property
    def arc(self) -> float:
        return 2.0 * math.pi - self.width


def partial_arc(arc_deg: float, feed: float = 0.0) -> PartialArc:
    """A partial bearing of ``arc_deg`` [deg] centred on the load line [T366]."""
    if not (math.isfinite(arc_deg) and 0.0 < arc_deg < 360.0):
        raise ValueError(f"partial arc = {arc_deg!r} [deg]: must be in (0, 360)")
    return PartialArc((math.pi,), math.radians(360.0 - arc_deg), feed)


def _spaced(n: int) -> tuple[float, ...]:
    """n angles evenly spaced from +90° off the load line [rad]."""
    return tuple((0.5 * math.pi + 2.0 * math.pi * k / n) % (2.0 * math.pi) for k in range(n))


def groove_labels(theta: np.ndarray, nz: int, g: Grooves) -> np.ndarray:
    """Groove number of every unknown (N,) (−1 outside the grooves): the cells whose centre lies
    in [c − w/2, c + w/2) around a groove centre c (half open, so a width that is a whole number
    of cells is exactly that many cells) [T244]."""
    lab = np.full(theta.size, -1)
    tol = 1e-9
    for k, c in enumerate(g.centres):
        d = np.mod(theta - c + math.pi, 2.0 * math.pi) - math.pi
        lab[(d >= -0.5 * g.width - tol) & (d < 0.5 * g.width - tol)] = k
    if not np.any(lab >= 0):
        raise ValueError(f"groove width {math.degrees(g.width):.6g} [deg]: narrower than one mesh cell")
    return np.repeat(lab, nz)


@dataclass(frozen=True)
class FeedHoles:
    """Round feed holes centred at mid-length [T366].

    centres   hole centre angles (n,) [rad], frame as :class:`Grooves`
    diameter  hole diameter over the journal radius d/R [-] (the arc it spans at its centre line)
    feed      supply pressure (unit as :class:`Grooves`) [-], ≥ 0 gauge
    """

    centres: tuple[float, ...]
    diameter: float
    feed: float = 0.0
    flow_name: ClassVar[str] = "hole_flow"

    def __post_init__(self):
        try:
            check_grooves(self.centres, self.diameter, self.feed)
        except ValueError as err:  # same bounds, named for a hole
            msg = str(err).replace("groove width", "hole diameter/R (arc)").replace("groove", "hole")
            raise ValueError(msg) from None

    def labels(self, theta: np.ndarray, zeta: np.ndarray) -> np.ndarray:
        """Hole number of every unknown (N,) (−1 elsewhere): the nodes within d/2 of a hole centre
        on the unrolled surface, (Δθ)² + ζ² ≤ (d/2R)² [T366]."""
        lam = float(zeta[-1])
        if not self.diameter < 2.0 * lam:
            raise ValueError(
                f"feed hole diameter/R = {self.diameter:.6g} [-]: must be < L/R = {2.0 * lam:.6g} "
                "(the hole lies inside the bearing length)"
            )
        ds = 2.0 * math.pi / theta.size
        if self.diameter < ds:
            raise ValueError(
                f"feed hole diameter/R = {self.diameter:.6g} [-]: narrower than one mesh cell ({ds:.4g}); "
                "give a larger hole or a finer mesh"
            )
        z = zeta[:-1]
        lab = np.full((theta.size, z.size), -1)
        r2 = (0.5 * self.diameter) ** 2 * (1.0 + 1e-9)
        for k, c in enumerate(self.centres):
            d = np.mod(theta - c + math.pi, 2.0 * math.pi) - math.pi
            lab[(d[:, None] ** 2 + z[None, :] ** 2) <= r2] = k
        for k in range(len(self.centres)):
            if not np.any(lab == k):
                raise ValueError(
                    f"feed hole diameter/R = {self.diameter:.6g} [-]: hole {k + 1} holds no mesh node; "
                    "give a larger hole or a finer mesh"
                )
        return lab.ravel()

    @property
    def count(self) -> int:
        return len(self.centres)


@dataclass(frozen=True)
class CircumferentialGroove:
    """A supply groove all around the bearing at mid-length [T366]: it splits the film into two
    lands, each a bearing of length (L − w)/2 fed over its whole inner edge.

    width  axial width of the groove over the journal radius w/R [-], 0 < w < L
    feed   supply pressure (unit as :class:`Grooves`) [-], ≥ 0 gauge
    """

    width: float
    feed: float = 0.0
    flow_name: ClassVar[str] = "circumferential_flow"
    count: ClassVar[int] = 1

    def __post_init__(self):
        if not (math.isfinite(self.width) and self.width > 0.0):
            raise ValueError(f"circumferential groove width/R = {self.width!r} [-]: must be finite and > 0")
        if not (math.isfinite(self.feed) and self.feed >= 0.0):
            raise ValueError(f"feed pressure = {self.feed!r} [-, or Pa]: must be finite and >= 0 (gauge)")

    def labels(self, theta: np.ndarray, zeta: np.ndarray) -> np.ndarray:
        """0 for the nodes with ζ < w/2R (all around), −1 elsewhere (N,) [T366]."""
        lam = float(zeta[-1])
        if not self.width < 2.0 * lam:
            raise ValueError(
                f"circumferential groove width/R = {self.width:.6g} [-]: must be < L/R = {2.0 * lam:.6g}"
            )
        row = np.where(zeta[:-1] < 0.5 * self.width - 1e-12, 0, -1)
        row[0] = 0  # the mid-plane row lies in any groove
        return np.tile(row, theta.size)


def film_at(ld, e, edot, cavitation, supply, mesh=GROOVED_MESH, warm=None):
    """Solve the film with the journal at e = (e_L, e_P) [c] moving at ė [cω] (load frame) [T246].

    supply   a :class:`Grooves`, :class:`FeedHoles`, :class:`CircumferentialGroove` [T366],
             ("line", α) for a feed line (one node row at P = 0) at the
             mesh angle α [rad] (the plain bearing's supply at its equilibrium maximum film), or
             None (periodic film without supply)
    Returns (F (2,) film force on the journal in the load frame [μωR⁴/c²], solution, problem,
    fixed mask, groove labels)."""
    check_ld(ld)
    xi = math.hypot(e[0], e[1])
    phi = math.atan2(e[1], e[0])
    A = (e[0] * edot[0] + e[1] * edot[1]) / xi  # ξ̇
    td = -math.sin(phi) * edot[0] + math.cos(phi) * edot[1]  # t·ė = ξγ̇
    B = (xi - 2.0 * td) / (2.0 + xi * xi)  # ξΩ/(2+ξ²), Ω = ω − 2γ̇
    nt, nz = mesh
    theta0 = supply[1] if isinstance(supply, tuple) else 0.0
    prob = assemble(xi, ld, nt, nz, kappa=0.0, phase=phi + math.pi, theta0=theta0)
    pfix = None
    if supply is None:  # periodic film, no supply (not for mass-conserving conditions)
        labels = np.full(nt * nz, -1)
    elif isinstance(supply, tuple):
        labels = np.full(nt * nz, -1)
        labels[:nz] = 0  # node row 0 sits on the line
    else:
        labels = supply.labels(prob.theta, prob.zeta)
        if supply.feed > 0.0:
            pfix = np.full(nt * nz, supply.feed)
    fixed = (labels >= 0) if supply is not None else None
    cond = condition(cavitation)
    s = cond.solve(prob, A, B, fixed, warm, pfix) if pfix is not None else cond.solve(prob, A, B, fixed, warm)
    w = 2.0 * prob.area * s.P
    th = np.repeat(prob.theta, nz)
    F = -6.0 * np.array([np.sum(w * np.cos(th)), np.sum(w * np.sin(th))])
    return F, s, prob, fixed, labels


def equilibrium(ld, eps, cavitation, supply, mesh=GROOVED_MESH, tol=1e-10, max_iter=40):
    """Attitude φ [rad] of the journal at eccentricity ratio ε with the load direction fixed in
    the bearing (grooves fixed relative to the load) [T246]: the film force points against the
    load. ``supply`` as :func:`film_at`, or "line" (feed line at the maximum film, moving with
    the journal: the Raimondi–Boyd bearing). Rotating the journal by Δφ rotates the force of a
    plain film by Δφ; secant iteration on δ(φ) = angle of the force from −load.
    Returns (φ, W, solution, problem, fixed, labels)."""
    sup = supply

    def delta(phi, warm):
        s = ("line", phi + math.pi) if sup == "line" else sup
        e = (eps * math.cos(phi), eps * math.sin(phi))
        F, sol, prob, fixed, lab = film_at(ld, e, (0.0, 0.0), cavitation, s, mesh, warm)
        return math.atan2(-F[1], -F[0]), F, sol, prob, fixed, lab

    phi0 = 0.5 * math.pi * (1.0 - eps)
    d0, *rest0 = delta(phi0, None)
    if not np.any(rest0[0]):  # an empty film: a mass-conserving film the supply does not feed
        raise ValueError(
            f"eps = {eps!r}: the {cavitation} film carries no load; its supply feeds it no oil (a "
            "circumferential groove at ambient pressure feeds a mass-conserving film only with a feed "
            "pressure > 0)"
        )
    phi1 = phi0 - d0
    for _ in range(max_iter):
        d1, F, sol, prob, fixed, lab = delta(phi1, rest0[1].state)
        if abs(d1) < tol:
            return phi1, -F[0], sol, prob, fixed, lab
        step = -d1 * (phi1 - phi0) / (d1 - d0) if d1 != d0 else -d1
        phi0, d0, rest0 = phi1, d1, [F, sol]
        phi1 = phi1 + step
    raise RuntimeError(f"grooved equilibrium at eps = {eps}: attitude did not converge")


def coefficients(ld, eps, cavitation, supply, mesh=GROOVED_MESH, h=STEP) -> dict:
    """Dimensionless dynamic coefficients k = Kc/W, c = Ccω/W at the equilibrium with eccentricity
    ratio ε, by central differences of the converged film in x, y, ẋ, ẏ with steps h·c and
    h·cω, in the convention of :mod:`.coefficients` (load along −y, rotation from x to y) [T247].
    ``supply``: :class:`Grooves` or "line" (the feed line stays where the equilibrium's maximum
    film is). Also ``attitude`` [rad], ``sommerfeld`` [-] and the equilibrium solution."""
    phi, W, sol, prob, fixed, lab = equilibrium(ld, eps, cavitation, supply, mesh)
    s = ("line", phi + math.pi) if supply == "line" else supply

    def film(e, edot):
        return film_at(ld, e, edot, cavitation, s, mesh, sol.state)[0]

    out = differenced_coefficients(film, eps, phi, W, h)
    out.update(sommerfeld=2.0 * ld / (math.pi * W))
    return out


def differenced_coefficients(film, eps: float, phi: float, W: float, h: float = STEP) -> dict:
    """k = Kc/W, c = Ccω/W by central differences of ``film(e, ė)`` → F (2,) [μωR⁴/c²] (load frame
    (e_L, e_P), e in c, ė in cω) at the equilibrium e = ε(cos φ, sin φ) carrying W̄, steps h·c and
    h·cω, in the convention of :mod:`.coefficients` (load along −y, rotation from x to y) [T247].
    Returns kxx … cyy, ``attitude`` φ [rad], ``load`` W̄, ``K`` and ``C`` (2×2)."""
    e0 = np.array([eps * math.cos(phi), eps * math.sin(phi)])
    # project frame: x = e_P (rotation side), y = −e_L (against the load)
    to_load = np.array([[0.0, -1.0], [1.0, 0.0]])  # (e_L, e_P) = to_load @ (x, y)
    zero = np.zeros(2)
    K = np.empty((2, 2))
    C = np.empty((2, 2))
    for j in range(2):
        d = to_load[:, j] * h
        K[:, j] = -(to_load.T @ (film(e0 + d, zero) - film(e0 - d, zero))) / (2.0 * h * W)
        C[:, j] = -(to_load.T @ (film(e0, d) - film(e0, -d))) / (2.0 * h * W)
    names = ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy")
    out = dict(zip(names, [*K.ravel(), *C.ravel()], strict=True))
    out.update(attitude=phi, load=W, K=K, C=C)
    return out
