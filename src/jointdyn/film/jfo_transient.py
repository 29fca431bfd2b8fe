"""Transient mass-conserving (JFO / Elrod–Adams) film in the bearing frame and the orbit of a
dynamically loaded journal [T300–T303].

The mesh is fixed in the bearing (uniform in θ, so the film content of a cell stays that cell's
history); the journal centre e = c·ξ(cos γ, sin γ) in that frame puts the maximum film at
θ = γ + π. Per cell, with the fill θ_f (content / clearance volume), complementary to P ≥ 0:

    (M P)_k + ω·cv_j·(H_(i+1/2) θ_f,i − H_(i−1/2) θ_f,i−1) + 2·area_k·(H θ_f − H⁰ θ_f⁰)_k / Δt = 0

(backward Euler from the content H⁰θ_f⁰ of the last step; ω = ω_J − ω_B the journal's rotation
relative to the bearing [rad/s]; P in 1/s, p = (6μR²/c²)·P) [T300]. Solved by the primal–dual
active set of [T243] (cells leave the full set when P < 0, the cavitated set when θ_f > 1).
Summing the cell balances gives, exactly, inflow (net outflow of the supply cells) = side outflow
+ content change / Δt, so the lubricant balance of a run closes to round-off [T301].
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from jointdyn.core import interrupts
from jointdyn.film.fv import assemble, check_ld
from jointdyn.film.grooved import Grooves
from jointdyn.film.jfo import transport

#: default mesh of the transient film: uniform cells around, cells on the half length [-]
TRANSIENT_MESH = (36, 8)


@dataclass(frozen=True)
class Step:
    """One solved step: P (N,) [1/s], fill θ_f (N,) [-], cavitated set (N,) bool, H (N,) [-],
    force on the journal F (2,) [μR⁴/c²·1/s], flows over both halves in units R²c [1/s]
    (``inflow`` total and ``per_groove``, ``side`` outflow through both ends), ``content``
    Σ 2·area·Hθ_f over both halves [R²c], iterations [T301]."""

    P: np.ndarray
    fill: np.ndarray
    cav: np.ndarray
    H: np.ndarray
    F: np.ndarray
    inflow: float
    per_groove: tuple
    side: float
    content: float
    iterations: int


class TransientFilm:
    """The transient jfo film of a bearing with L/D = ``ld`` fed through ``grooves`` (a
    :class:`~jointdyn.film.grooved.Grooves`, angles in the bearing frame; its ``feed`` here in
    the pressure unit 6μR²/c²·1/s) on ``mesh`` = (cells around, cells on the half length)."""

    def __init__(self, ld: float, grooves: Grooves, mesh=TRANSIENT_MESH):
        check_ld(ld)
        nt, nz = (int(m) for m in mesh)
        if nt < 8 or nz < 2:
            raise ValueError(f"mesh = {mesh!r} [-]: needs at least 8 cells around and 2 on the half length")
        self.ld, self.mesh = float(ld), (nt, nz)
        p0 = assemble(0.0, ld, nt, nz, kappa=0.0)
        self.labels = grooves.labels(p0.theta, p0.zeta)
        self.fixed = self.labels >= 0
        self.pfix = np.where(self.fixed, float(grooves.feed), 0.0)
        self.ngroove = grooves.count
        self.theta = np.repeat(p0.theta, nz)

    def film(self, e) -> tuple:
        """(problem, H (N,)) with the journal at e = (ξ_x, ξ_y) [-], |e| < 1."""
        xi = math.hypot(e[0], e[1])
        gamma = math.atan2(e[1], e[0])
        nt, nz = self.mesh
        prob = assemble(xi, self.ld, nt, nz, kappa=0.0, phase=gamma + math.pi)
        return prob, 1.0 - e[0] * np.cos(self.theta) - e[1] * np.sin(self.theta)

    def flooded(self, e) -> np.ndarray:
        """Content H·1 of a full film at e (the start of a run) [-]."""
        return self.film(e)[1].copy()

    def step(self, e, omega: float, dt: float, content0: np.ndarray, warm=None, max_iter: int = 200) -> Step:
        """Backward-Euler step [T300] to the journal position e = (ξ_x, ξ_y) [-] from the cell
        contents ``content0`` = H⁰θ_f⁰ (N,) [-] over dt [s] at relative rotation ω [rad/s]."""
        if not (math.isfinite(dt) and dt > 0.0):
            raise ValueError(f"dt = {dt!r} [s]: must be > 0")
        if not math.hypot(e[0], e[1]) < 1.0:
            raise ValueError(f"journal position |e|/c = {math.hypot(e[0], e[1])!r} [-]: must be < 1")
        from scipy.sparse import csc_matrix, diags  # imported where used: [T372]
        from scipy.sparse.linalg import splu

        prob, H = self.film(e)
        N = H.size
        M = csc_matrix(prob.M)
        T = csc_matrix(transport(prob, 0.0, 0.0, omega) + diags(2.0 * prob.area * H / dt))
        b0 = 2.0 * prob.area * np.asarray(content0, float) / dt
        pf, rows = self.pfix, ~self.fixed
        free = np.flatnonzero(rows)
        if warm is None:  # start: where the flooded film would be under ambient pressure
            rhs = b0 - M @ pf - T @ np.ones(N)
            P0 = np.zeros(N)
            P0[rows] = splu(csc_matrix(M[rows][:, rows])).solve(rhs[rows])
            cav = (P0 < 0.0) & rows
        else:
            cav = np.asarray(warm, bool) & rows
        for it in range(1, max_iter + 1):
            full = rows & ~cav
            rhs = b0 - M @ pf - T @ np.where(cav, 0.0, 1.0)
            S = (M @ diags(full.astype(float)) + T @ diags(cav.astype(float))).tocsr()[rows]
            x = np.zeros(N)
            x[free] = splu(csc_matrix(S[:, free])).solve(rhs[rows])
            P = np.where(full, x, pf)
            th = np.where(cav, x, 1.0)
            new = np.where(cav, ~(th > 1.0), P < 0.0) & rows
            if np.array_equal(new, cav):
                P[cav] = 0.0
                return self._done(prob, M, T, b0, P, th, H, cav, it)
            cav = new
        raise RuntimeError(f"transient jfo active set did not settle in {max_iter} iterations")

    def _done(self, prob, M, T, b0, P, th, H, cav, it) -> Step:
        MP = M @ P
        r = MP + T @ th - b0  # net outflow of every cell: 0 off the supply [T301]
        inj = r  # both halves (×2) in units R²c/2 (×1/2) = units R²c
        per = tuple(float(np.sum(inj[self.labels == g])) for g in range(self.ngroove))
        w = 2.0 * prob.area * P
        F = -6.0 * np.array([np.sum(w * np.cos(self.theta)), np.sum(w * np.sin(self.theta))])
        return Step(
            P,
            th,
            cav,
            H,
            F,
            float(np.sum(inj[self.fixed])),
            per,
            float(np.sum(MP)),
            2.0 * float(np.sum(prob.area * H * th)),
            it,
        )

    def reynolds(self, e, v, omega: float, warm=None) -> Step:
        """Swift–Stieber film (no content history) at e = (ξ_x, ξ_y) [-] moving at v = ė/c [1/s]
        [T80, T302]: the LCP in the rates A = ξ̇, ξΩ = ξω − 2 t·v, supply cells held at the feed
        pressure; flows and content are not defined here (NaN)."""
        from jointdyn.film.cavitation import condition

        prob, H = self.film(e)
        xi = math.hypot(e[0], e[1])
        if xi > 0.0:
            u = (e[0] / xi, e[1] / xi)
            A = u[0] * v[0] + u[1] * v[1]
            xO = xi * omega - 2.0 * (-u[1] * v[0] + u[0] * v[1])
        else:
            A, xO = 0.0, 0.0
        sol = condition("reynolds").solve(prob, A, xO / (2.0 + xi * xi), self.fixed, warm, self.pfix)
        w = 2.0 * prob.area * sol.P
        F = -6.0 * np.array([np.sum(w * np.cos(self.theta)), np.sum(w * np.sin(self.theta))])
        nan = math.nan
        return Step(
            sol.P, np.ones_like(H), sol.state, H, F, nan, (nan,) * self.ngroove, nan, nan, sol.iterations
        )

    def residual(self, s: Step, e, omega, dt, content0) -> float:
        """Largest imbalance of a non-supply cell relative to the largest cell flux [-] [T301]."""
        from scipy.sparse import csr_matrix, diags

        prob, H = self.film(e)
        T = transport(prob, 0.0, 0.0, omega) + diags(2.0 * prob.area * H / dt)
        b0 = 2.0 * prob.area * np.asarray(content0, float) / dt
        r = csr_matrix(prob.M) @ s.P + T @ s.fill - b0
        scale = max(float(np.max(np.abs(T.diagonal()))), 1e-300)
        return float(np.max(np.abs(r[~self.fixed])) / scale)


def _balance(film, law, e, v, content, warm, dt, W, om, mass, tol, max_newton):
    """One backward-Euler step of the orbit [T302]: (ė, step, Newton iterations), or None when
    Newton does not converge in ``max_newton`` iterations."""
    v0 = v.copy()

    def res(vv, warm_):
        if law == "reynolds":
            s = film.reynolds(e + dt * vv, vv, om, warm_)
        else:
            s = film.step(e + dt * vv, om, dt, content, warm_)
        return s.F + W - mass * (vv - v0) / dt, s

    while np.hypot(*(e + dt * v)) >= 0.999:  # the previous rate as the guess, kept inside
        v = 0.5 * v
    r, s = res(v, warm)
    scale = max(float(np.hypot(*W)), abs(om), 1e-300)  # ω: the film's force unit μωR⁴/c²
    it = 0
    while float(np.hypot(*r)) > tol * scale:
        it += 1
        if it > max_newton:
            return None
        h = 1e-7 * max(1.0, float(np.hypot(*v)))
        J = np.empty((2, 2))
        for j in range(2):
            d = np.zeros(2)
            d[j] = h
            J[:, j] = (res(v + d, s.cav)[0] - r) / h
        dv = -np.linalg.solve(J, r)
        lam = 1.0
        while np.hypot(*(e + dt * (v + lam * dv))) >= 0.999:
            lam *= 0.5
        r_new, s_new = res(v + lam * dv, s.cav)
        while float(np.hypot(*r_new)) > float(np.hypot(*r)) and lam > 1e-3:
            lam *= 0.5
            r_new, s_new = res(v + lam * dv, s.cav)
        v, r, s = v + lam * dv, r_new, s_new
    return v, s, it


def orbit(
    film: TransientFilm,
    omega,
    load,
    times,
    e0,
    law: str = "jfo",
    tol: float = 1e-10,
    max_newton: int = 20,
    max_move: float = 0.05,
    mass: float = 0.0,
) -> dict:
    """Orbit of a journal under the load ``load(t)`` -> (W_x, W_y) [μR⁴/c²·1/s] on the journal
    (bearing frame) at relative rotation ``omega(t)`` [rad/s] [T300, T302]: each step solves
    m̄(ė_(n+1) − ė_n)/Δt = F(e_(n+1)) + W(t_(n+1)) with e_(n+1) = e_n + Δt·ė_(n+1) and the content
    of the backward-Euler step (``mass`` m̄ = m c³/(μR⁴) [s], m the mass moving with the journal
    relative to the bearing [kg]; 0: massless, Booker's problem). Newton on ė (Jacobian by
    differences, steps halved while |e| ≥ 0.999 or the residual grows) to
    a residual ≤ ``tol``·max(|W|, |ω|) (ω: the steady force unit).
    Error control [T303]: an interval of ``times`` is split into halves, recursively, while a
    step moves the journal by more than ``max_move`` [c] or Newton needs more than
    ``max_newton`` iterations. Starts from a full film at ``e0``. ``law``: "jfo" (the transient
    film) or "reynolds" (Swift–Stieber at every instant, no history; content and flows NaN).
    Returns arrays over ``times``: e (n, 2) [-], force (n, 2), content [R²c], inflow, side
    [R²c/s] (of the last sub-step), net_in = ∫(inflow − side)dt over the interval ending there
    [R²c], cavitated fraction, per_groove (n, grooves), Newton iterations and sub-steps per
    interval."""
    if law not in ("jfo", "reynolds"):
        raise ValueError(f"law = {law!r}: must be 'jfo' or 'reynolds'")
    if not (math.isfinite(mass) and mass >= 0.0):
        raise ValueError(f"mass = {mass!r} [s] (m c³/(μR⁴)): must be finite and >= 0")
    if not (0.0 < max_move <= 1.0):
        raise ValueError(f"max_move = {max_move!r} [c]: must be in (0, 1]")
    times = np.asarray(times, float)
    if times.ndim != 1 or times.size < 2 or not np.all(np.diff(times) > 0.0):
        raise ValueError("times [s]: need at least two increasing instants")
    e = np.asarray(e0, float)
    content = film.flooded(e)
    n = times.size
    out = {k: np.full(n, np.nan) for k in ("content", "inflow", "side", "cavitated", "net_in")}
    out["e"] = np.full((n, 2), np.nan)
    out["force"] = np.full((n, 2), np.nan)
    out["per_groove"] = np.full((n, film.ngroove), np.nan)
    out["newton"] = np.zeros(n, int)
    out["substeps"] = np.zeros(n, int)
    out["e"][0] = e
    out["content"][0] = 2.0 * float(np.sum(_area(film) * content))
    v = np.zeros(2)
    warm = None
    for k in range(1, n):
        interrupts.check()  # a signal recorded by a caller's catching() stops here [T336]
        pending = [(times[k - 1], times[k])]
        net = 0.0
        while pending:
            t0, t1 = pending.pop()
            dt = t1 - t0
            W, om = np.asarray(load(t1), float), float(omega(t1))
            got = _balance(film, law, e, v, content, warm, dt, W, om, mass, tol, max_newton)
            if got is None or float(np.hypot(*(dt * got[0]))) > max_move:
                if dt < 1e-9 * (times[-1] - times[0]):
                    raise RuntimeError(f"t = {t1!r} [s]: the journal's force balance did not converge")
                tm = 0.5 * (t0 + t1)
                pending += [(tm, t1), (t0, tm)]
                continue
            v, s, it = got
            e = e + dt * v
            content = s.H * s.fill
            warm = s.cav
            net += dt * (s.inflow - s.side)
            out["newton"][k] += it
            out["substeps"][k] += 1
        out["e"][k] = e
        out["force"][k] = s.F
        out["content"][k] = s.content
        out["inflow"][k] = s.inflow
        out["side"][k] = s.side
        out["net_in"][k] = net
        out["cavitated"][k] = float(np.mean(s.cav))
        out["per_groove"][k] = s.per_groove
    return out


def _area(film: TransientFilm) -> np.ndarray:
    nt, nz = film.mesh
    return assemble(0.0, film.ld, nt, nz, kappa=0.0).area


def balance_error(run: dict) -> float:
    """|content change − Σ Δt·(inflow − side)| relative to the content [-]: the backward-Euler
    balance of [T301] summed over the (sub-)steps of a run of :func:`orbit`."""
    net = float(np.sum(run["net_in"][1:]))
    return abs(run["content"][-1] - run["content"][0] - net) / abs(run["content"][0])
