"""Integrators. ``SOLVERS`` maps a name to (runner, projects_on_constraints, description)."""

from __future__ import annotations

from functools import partial

from .dopri5 import dopri5
from .rodas4 import rodas4
from .scipy_ivp import scipy_ivp

SOLVERS = {
    "dopri5": (dopri5, True, "compiled explicit Dormand–Prince 5(4); perfect and dry joints [T12]"),
    "rodas4": (rodas4, True, "compiled L-stable Rosenbrock 4(3); stiff film and contact [T13]"),
    "scipy-radau": (partial(scipy_ivp, method="Radau"), False, "scipy Radau IIA (reference path)"),
    "scipy-dop853": (partial(scipy_ivp, method="DOP853"), False, "scipy DOP853 (reference path)"),
    "scipy-lsoda": (partial(scipy_ivp, method="LSODA"), False, "scipy LSODA (reference path)"),
}
