"""The transient mass-conserving (jfo) film as part of a journal element [T306–T308, T345].

The cell contents Hθ_f of the film (uniform mesh fixed in the bushing, natural order k = i·nz + j)
are element memory, after the named slots ``MEMORY``, followed by the journal position e_n of the
last commit: committed only on accepted steps, with the commit time t_n (``film_time``), as the
oil temperature [T311]. The right-hand side is the stage-consistent film [T345]: at the journal
position e the committed fill θ_f = Hθ_f/H(e_n) is frozen (full cells full, cavitated cells keep
their θ_f), and the squeeze acts on it through one backward-Euler step over the short
dt_min = ``DT_MIN_TURN``/max(|ω|, 1 rad/s) to e + ė·dt_min, so the force is a function of the
journal state (e, ė, ω) only, without the stage time. The accepted step commits the contents at
t_(n+1) by the backward-Euler step over [t_n, t_(n+1)] and adds Δt·inflow, Δt·side outflow to the
volumes in memory, so that content(t) − content(t₀) = inflow volume − side volume to round-off
[T301, T307]. The mesh's geometry is packed into seven consecutive element tables (:func:`pack`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from jointdyn.film.grooved import CircumferentialGroove, FeedHoles, Grooves
from jointdyn.film.jfo_step import couette_gas, geometry, jfo_step
from jointdyn.film.jfo_transient import TransientFilm

#: named memory slots of the jfo film, after the journal element's and the oil temperature's
MEMORY = {
    "film_time": "s",
    "film_content": "m³",
    "inflow_volume": "m³",
    "side_volume": "m³",
    "content_rate": "1/s",
}
BASE = 10
FILM_TIME, CONTENT, IN_VOL, SIDE_VOL, RATE = range(BASE, BASE + len(MEMORY))
CELLS = BASE + len(MEMORY)  # the cell contents Hθ_f [-] start here
#: element outputs of the jfo film (name -> unit): content and flows, then one flow slot per supply
#: feature, up to ``MAX_FEATURES`` (an element names its own, :func:`feature_names`) [T376]
FILM_OUTPUTS = {"film_content": "m³", "inflow": "m³/s", "side_outflow": "m³/s"}
MAX_FEATURES = 8
OUTPUTS = FILM_OUTPUTS | {f"feature_flow_{k + 1}": "m³/s" for k in range(MAX_FEATURES)}
DT_MIN_TURN = 1e-4  # the shortest backward-Euler step, in radians of relative rotation [T306]
DCONTENT_STEP = 0.05  # largest change of a cell's content Hθ_f per accepted step [-] [T308]
MAX_ITER = 200  # active-set iterations of one step
NTABLES = 7


def pack(film, length: float, journal_radius: float, viscosity: float, clearance: float) -> list:
    """The seven (rows, 2) tables of a jfo film [T306]: (nt, nz); (cos, sin) of the cells; of the
    faces i+1/2; (cv, axial face gaps); (area, supply pressure P_f [1/s] or −1 off the supply);
    (zig-zag order, its inverse); (supply feature of the cell, 0 … count − 1, or −1 off the supply;
    0) [T376]."""
    R = journal_radius
    feed = film.supply_pressure * clearance**2 / (6.0 * viscosity * R * R)  # P_f [1/s] [T300]
    grooves = supply_feature(film, length, R, feed)
    mesh = (int(film.cells_around), int(film.cells_half_length))
    tf = TransientFilm(length / (2.0 * R), grooves, mesh)
    g = geometry(tf)
    return [
        np.array([[float(g.nt), float(g.nz)]]),
        np.stack([g.cn, g.sn], axis=1),
        np.stack([g.cf, g.sf], axis=1),
        np.stack([g.cv, g.dzf], axis=1),
        np.stack([g.area, np.where(g.fixed, g.pfix, -1.0)], axis=1),
        np.stack([g.perm.astype(float), g.inv.astype(float)], axis=1),
        np.stack([tf.labels.astype(float), np.zeros(tf.labels.size)], axis=1),
    ]


def feature_names(film) -> list[str]:
    """Output names of the flows per supply feature of a jfo film, as the ``bearing-table`` columns
    (``groove_flow_k``, ``hole_flow_k``, ``circumferential_flow_1``; k = 1 at ``supply_angle``)
    [T366, T376]."""
    kind = {"axial_grooves": Grooves, "feed_holes": FeedHoles}.get(film.supply, CircumferentialGroove)
    n = 1 if kind is CircumferentialGroove else int(film.supply_count)
    return [f"{kind.flow_name}_{k + 1}" for k in range(n)]


def supply_feature(film, length: float, journal_radius: float, feed: float):
    """The supply feature of a jfo film [T366] in the bushing frame (first at ``supply_angle``,
    ``supply_count`` evenly spaced), feed P_f [1/s]; sizes against the bearing ``length`` [m]."""
    n = 1 if film.supply == "circumferential_groove" else int(film.supply_count)
    a0 = math.radians(film.supply_angle)
    centres = tuple((a0 + 2.0 * math.pi * k / n) % (2.0 * math.pi) for k in range(n))
    try:
        if film.supply == "axial_grooves":
            return Grooves(centres, math.radians(film.supply_width), feed)
        if not film.supply_diameter < length:
            raise ValueError(f"must be < the bearing length = {length!r} [m]")
        size = film.supply_diameter / journal_radius
        if film.supply == "feed_holes":
            return FeedHoles(centres, size, feed)
        return CircumferentialGroove(size, feed)
    except ValueError as err:
        key = "supply_width" if film.supply == "axial_grooves" else "supply_diameter"
        raise ValueError(f"Finite.{key} (supply = {film.supply!r}, supply_count = {n}): {err}") from None


def cells(film) -> int:
    """Memory slots of a jfo film after ``MEMORY``: its cells, then the committed position e_n [c]."""
    return int(film.cells_around) * int(film.cells_half_length) + 2


@njit(cache=True)
def _unpack(tables, slot):
    nt = int(tables[slot, 0, 0])
    nz = int(tables[slot, 0, 1])
    n = nt * nz
    cn = tables[slot + 1, :nt, 0].copy()
    sn = tables[slot + 1, :nt, 1].copy()
    cf = tables[slot + 2, :nt, 0].copy()
    sf = tables[slot + 2, :nt, 1].copy()
    cv = tables[slot + 3, :nz, 0].copy()
    dzf = tables[slot + 3, :nz, 1].copy()
    area = tables[slot + 4, :n, 0].copy()
    pfix = tables[slot + 4, :n, 1].copy()
    fixed = pfix >= 0.0
    perm = np.empty(n, np.int64)
    inv = np.empty(n, np.int64)
    for k in range(n):
        perm[k] = int(tables[slot + 5, k, 0])
        inv[k] = int(tables[slot + 5, k, 1])
        if not fixed[k]:
            pfix[k] = 0.0
    return nt, nz, cn, sn, cf, sf, cv, dzf, area, fixed, pfix, perm, inv


@njit(cache=True)
def _films(ex, ey, nt, nz, cn, sn):
    H = np.empty(nt * nz)
    for i in range(nt):
        h = 1.0 - ex * cn[i] - ey * sn[i]
        for j in range(nz):
            H[i * nz + j] = h
    return H


@njit(cache=True)
def _step(ex, ey, omega, dt, content0, g, cav, max_iter):
    """One step of [T304] over dt [s] to e = (ex, ey) [c] from ``content0``; ``cav`` (N,) bool the
    start set (``max_iter`` = 0: the set, frozen [T348])."""
    nt, nz, cn, sn, cf, sf, cv, dzf, area, fixed, pfix, perm, inv = g
    H = _films(ex, ey, nt, nz, cn, sn)
    P, fill, fx, fy, inflow, side, content, net, its = jfo_step(
        ex,
        ey,
        omega,
        dt,
        content0,
        cav,
        nt,
        nz,
        cn,
        sn,
        cf,
        sf,
        cv,
        dzf,
        area,
        fixed,
        pfix,
        perm,
        inv,
        max_iter,
    )
    return H, fill, fx, fy, inflow, side, content, net, its


@njit(cache=True)
def _capped(ex, ey, cap):
    xi = math.sqrt(ex * ex + ey * ey)
    if xi > cap:
        return ex * cap / xi, ey * cap / xi
    return ex, ey


@njit(cache=True)
def jfo_force(t, mem, tables, slot, ex, ey, vx, vy, omega, mu, R, c, cap):
    """Film force (F_x, F_y) [N] on the journal in the bushing frame, content [m³], inflow and
    side outflow [m³/s] of the stage-consistent film [T345] with the journal at e = (ex, ey) [c]
    moving at (vx, vy) [c/s] (bushing frame), relative rotation ω [rad/s], viscosity μ [Pa·s],
    radius R and clearance c [m]; |e| at most ``cap`` [T306]: the committed fill θ_f frozen at e,
    its squeeze from ė, with the committed active set (θ_f < 1: cavitated) frozen [T348], so the
    force is smooth in (e, ė, ω). Independent of the time t [s]. Then the Couette integral of
    that film's gas, :func:`~jointdyn.film.jfo_step.couette_gas` [-] [T375], and the net outflow
    of every supply cell (N,) [m³/s] [T376]."""
    g = _unpack(tables, slot)
    nt, nz, cn, sn = g[0], g[1], g[2], g[3]
    n = nt * nz
    ex, ey = _capped(ex, ey, cap)
    H = _films(ex, ey, nt, nz, cn, sn)
    content0 = H.copy()  # before the first commit (the run's start): the full film here
    cav = np.zeros(n, np.bool_)
    if mem[FILM_TIME] == mem[FILM_TIME]:  # the committed fill θ_f = Hθ_f/H(e_n), frozen at e [T345]
        Hn = _films(mem[CELLS + n], mem[CELLS + n + 1], nt, nz, cn, sn)
        for k in range(n):
            fill = mem[CELLS + k] / Hn[k]
            content0[k] = H[k] * fill
            cav[k] = fill < 1.0 and not g[9][k]  # the committed active set, frozen [T348]
    dt = DT_MIN_TURN / max(abs(omega), 1.0)
    ex1, ey1 = _capped(ex + vx * dt, ey + vy * dt, cap)
    H1, fill, fx, fy, inflow, side, content, net, its = _step(ex1, ey1, omega, dt, content0, g, cav, 0)
    gas = couette_gas(fill, H1, g[8], g[6], g[7])
    sf = mu * R**4 / (c * c)
    sv = R * R * c
    return fx * sf, fy * sf, content * sv, inflow * sv, side * sv, gas, net * sv


@njit(cache=True)
def feature_flows(tables, slot, net, out, o):
    """Sum the supply cells' net outflows ``net`` (N,) [m³/s] per supply feature into out[o + g]
    (the features' own slots; the others stay 0) [T376]."""
    n = int(tables[slot, 0, 0]) * int(tables[slot, 0, 1])
    for g in range(MAX_FEATURES):
        out[o + g] = 0.0
    for k in range(n):
        lab = int(tables[slot + 6, k, 0])
        if lab >= 0:
            out[o + lab] += net[k]


@njit(cache=True)
def jfo_commit(t, mem, tables, slot, ex, ey, omega, R, c, cap):
    """Commit the film of an accepted step at time t [s] with the journal at e = (ex, ey) [c]
    (bushing frame): the backward-Euler step from the last commit, its contents into memory, the
    volumes Δt·inflow and Δt·side outflow added [T307]. The first call (film_time NaN) starts the
    full film. Returns 0, or 1 if the active set does not settle."""
    g = _unpack(tables, slot)
    n = g[0] * g[1]
    ex, ey = _capped(ex, ey, cap)
    t_n = mem[FILM_TIME]
    sv = R * R * c
    if not (t_n == t_n):
        H = _films(ex, ey, g[0], g[1], g[2], g[3])
        total = 0.0
        for k in range(n):
            mem[CELLS + k] = H[k]
            total += 2.0 * g[8][k] * H[k]
        mem[FILM_TIME] = t
        mem[CELLS + n] = ex
        mem[CELLS + n + 1] = ey
        mem[CONTENT] = total * sv
        mem[IN_VOL] = 0.0
        mem[SIDE_VOL] = 0.0
        mem[RATE] = 0.0
        return 0
    dt = t - t_n
    if dt <= 0.0:
        return 0
    content0 = np.empty(n)
    for k in range(n):
        content0[k] = mem[CELLS + k]
    H = _films(ex, ey, g[0], g[1], g[2], g[3])
    cav = np.empty(n, np.bool_)
    for k in range(n):  # warm start: cells the committed content does not fill here
        cav[k] = content0[k] < H[k] * (1.0 - 1e-12) and not g[9][k]
    H, fill, fx, fy, inflow, side, content, net, its = _step(ex, ey, omega, dt, content0, g, cav, MAX_ITER)
    if its < 0:
        return 1
    rate = 0.0
    for k in range(n):
        new = H[k] * fill[k]
        rate = max(rate, abs(new - content0[k]) / dt)
        mem[CELLS + k] = new
    mem[FILM_TIME] = t
    mem[CELLS + n] = ex
    mem[CELLS + n + 1] = ey
    mem[CONTENT] = content * sv
    mem[IN_VOL] += dt * inflow * sv
    mem[SIDE_VOL] += dt * side * sv
    mem[RATE] = rate
    return 0


@njit(cache=True)
def jfo_step_limit(mem):
    """Largest step [s] over which a cell's content changes by at most ``DCONTENT_STEP`` at the
    last accepted step's largest rate [T308] (1e300 before the film has a rate)."""
    r = mem[RATE]
    return DCONTENT_STEP / r if r > 0.0 else 1e300


@njit(cache=True)
def jfo_jacobian(mem, tables, slot, ex, ey, vx, vy, omega, mu, R, c, cap):
    """Film force (F_x, F_y) [N] of :func:`jfo_force` in the bushing frame, its gas Couette
    integral [-] and the derivatives (3, 5) of the three by (e_x, e_y [c], v_x, v_y [c/s],
    ω [rad/s]) by central differences [T346, T375]: ten film steps. The last value is 1 where a
    step's active set does not settle, else 0."""
    x = np.array([ex, ey, vx, vy, omega])
    fx, fy, _, _, _, gas, _ = jfo_force(0.0, mem, tables, slot, ex, ey, vx, vy, omega, mu, R, c, cap)
    J = np.empty((3, 5))
    xi = math.sqrt(ex * ex + ey * ey)
    speed = math.sqrt(vx * vx + vy * vy)
    for k in range(5):
        scale = max(xi, 1e-3) if k < 2 else (max(speed, 1.0) if k < 4 else max(abs(omega), 1.0))
        h = 6.055454452393343e-06 * scale  # ε^(1/3) [T100]
        xp = x.copy()
        xm = x.copy()
        xp[k] += h
        xm[k] -= h
        fpx, fpy, _, _, _, gp, _ = jfo_force(
            0.0, mem, tables, slot, xp[0], xp[1], xp[2], xp[3], xp[4], mu, R, c, cap
        )
        fmx, fmy, _, _, _, gm, _ = jfo_force(
            0.0, mem, tables, slot, xm[0], xm[1], xm[2], xm[3], xm[4], mu, R, c, cap
        )
        J[0, k] = (fpx - fmx) / (2.0 * h)
        J[1, k] = (fpy - fmy) / (2.0 * h)
        J[2, k] = (gp - gm) / (2.0 * h)
    bad = 0 if (fx == fx and np.all(J == J)) else 1
    return fx, fy, gas, J, bad
