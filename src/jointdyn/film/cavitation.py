"""Registry of film cavitation conditions for the finite-volume Reynolds film [T72, T88].

A condition turns the discretised problem (:class:`~jointdyn.film.fv.FVProblem`) and the rates
(A, B) into a pressure field P ≥ 0. Everything downstream — the design table, the operating
point, the pressure field, the dynamic ``finite`` table and hence the bearing element — asks the
registry by name, so a new condition is one class and one :func:`register` call; see
docs/how-to-add-a-model.md. ``jfo`` is the mass-conserving one [T240–T243]. A condition may take
``pfix`` (supply pressures on the ``fixed`` nodes, a lubricant feed [T245]); one without it serves
only ambient supplies. This module imports no solver at load time.
"""

from __future__ import annotations

import inspect
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar

import numpy as np


@dataclass(frozen=True)
class Solution:
    """What a condition returns.

    P           nondimensional pressure ≥ 0 at the FV unknowns (N,) [-] (p = (6μR²/c²)·P)
    state       warm start for a neighbouring solve (e.g. the cavitated set), or None
    iterations  solver iterations [-]
    residual    the condition's convergence measure at the solution [-]
    fill        film fill fraction at the unknowns (N,) [-] for mass-conserving conditions
                (1 in the full film), None otherwise
    """

    P: np.ndarray
    state: Any
    iterations: int
    residual: float
    fill: np.ndarray | None = None


class Gumbel:
    """Half-Sommerfeld: full-film solve, negative pressures set to ambient (not mass conserving)."""

    name: ClassVar[str] = "gumbel"
    #: P ∝ (θ_e − θ)^k near the film end: k = 1 (the full film crosses zero with a slope)
    rupture_exponent: ClassVar[float] = 1.0
    mass_conserving: ClassVar[bool] = False

    def solve(self, prob, A: float, B: float, fixed=None, warm=None, pfix=None) -> Solution:
        from jointdyn.film.lcp import full_film

        b, pf = _dirichlet(prob, A * prob.bA + B * prob.bB, fixed, pfix)
        P = np.maximum(full_film(prob.M, b, fixed) + pf, 0.0)
        return Solution(P, None, 1, 0.0)


class SwiftStieber:
    """Reynolds (Swift–Stieber): the LCP P ≥ 0, MP − b ≥ 0, Pᵀ(MP − b) = 0 by the active-set
    method; state = the cavitated set (warm start) [T72]."""

    name: ClassVar[str] = "reynolds"
    #: P ∝ (θ_e − θ)² at a rupture with ∂P/∂θ = 0
    rupture_exponent: ClassVar[float] = 2.0
    mass_conserving: ClassVar[bool] = False

    def solve(self, prob, A: float, B: float, fixed=None, warm=None, pfix=None) -> Solution:
        from jointdyn.film.lcp import residual, solve_lcp_banded

        b, pf = _dirichlet(prob, A * prob.bA + B * prob.bB, fixed, pfix)
        P, cav, it = solve_lcp_banded(prob, b, fixed, warm)
        return Solution(P + pf, cav, it, residual(prob.M, b, P, fixed))


class JFO:
    """Mass-conserving (Jakobsson–Floberg–Olsson, Elrod–Adams) film: P ≥ 0, fill θ_f ≤ 1,
    P(1 − θ_f) = 0, every cell's balance with the Couette flux carrying the content, by a
    primal–dual active set on the cavitated set [T240–T243]; state = the cavitated set, fill =
    θ_f. Needs a supply (``fixed`` nodes: feed line or grooves, flooded)."""

    name: ClassVar[str] = "jfo"
    #: the rupture boundary of the mass-conserving film has ∂P/∂n = 0, as Swift–Stieber's [T240]
    rupture_exponent: ClassVar[float] = 2.0
    mass_conserving: ClassVar[bool] = True

    def solve(self, prob, A: float, B: float, fixed=None, warm=None, pfix=None) -> Solution:
        from jointdyn.film.jfo import solve_jfo

        P, fill, cav, it, res = solve_jfo(prob, A, B, fixed, pfix, warm)
        return Solution(P, cav, it, res, fill)


def _dirichlet(prob, b: np.ndarray, fixed, pfix):
    """(b − M·P_D, P_D): the right-hand side for the free nodes with P = pfix held on the fixed
    nodes (a supply pressure [T245]); P_D = 0 without ``pfix``."""
    if pfix is None or fixed is None:
        return b, np.zeros(b.size)
    pd = np.where(np.asarray(fixed, bool), np.asarray(pfix, float), 0.0)
    return b - prob.M @ pd, pd


#: name -> condition instance (read through :func:`condition` / :func:`names`)
CAVITATION: dict[str, Any] = {}


def register(cond):
    """Add a condition instance to the registry (returns it). It must have ``name`` (str, new),
    ``rupture_exponent`` (> 0), ``mass_conserving`` (bool) and ``solve(prob, A, B, fixed, warm)``
    returning a :class:`Solution`."""
    name = getattr(cond, "name", None)
    if not isinstance(name, str) or not name:
        raise ValueError(f"cavitation condition {cond!r}: needs a non-empty str attribute 'name'")
    if name in CAVITATION:
        raise ValueError(f"cavitation = {name!r}: already registered")
    k = getattr(cond, "rupture_exponent", None)
    if not (isinstance(k, (int, float)) and k > 0):
        raise ValueError(f"cavitation {name!r}: rupture_exponent = {k!r} must be a number > 0")
    if not isinstance(getattr(cond, "mass_conserving", None), bool):
        raise ValueError(f"cavitation {name!r}: needs a bool attribute 'mass_conserving'")
    if not callable(getattr(cond, "solve", None)):
        raise ValueError(f"cavitation {name!r}: needs a method solve(prob, A, B, fixed, warm)")
    CAVITATION[name] = cond
    return cond


register(Gumbel())
register(SwiftStieber())
register(JFO())


def names() -> tuple[str, ...]:
    """Registered condition names, in registration order."""
    return tuple(CAVITATION)


def condition(name):
    """The registered condition ``name`` (ValueError listing the valid names otherwise)."""
    if not isinstance(name, str) or name not in CAVITATION:
        raise ValueError(f"cavitation = {name!r}: must be one of {', '.join(CAVITATION)}")
    return CAVITATION[name]


def check_cavitation(name) -> None:
    """ValueError unless ``name`` is a registered condition."""
    condition(name)


def source_file(name: str) -> Path | None:
    """Source file of a condition's class (part of the ``finite`` table cache key) or None."""
    try:
        return Path(inspect.getsourcefile(type(condition(name))) or "")
    except TypeError:
        return None
