"""Integrators. ``SOLVERS`` maps a name to (runner, projects_on_constraints, description)."""

from __future__ import annotations

from .dopri5 import dopri5
from .rodas4 import rodas4
from .ros34pw2 import ros34pw2


def _scipy(method):
    def run(*args, **kwargs):
        from .scipy_ivp import scipy_ivp  # scipy.integrate costs ~0.5 s to import: only when used

        return scipy_ivp(*args, method=method, **kwargs)

    run.__name__ = f"scipy_{method.lower()}"
    return run


SOLVERS = {
    "dopri5": (dopri5, True, "compiled explicit Dormand–Prince 5(4); perfect and dry joints [T12]"),
    "rodas4": (rodas4, True, "compiled L-stable Rosenbrock 4(3); stiff film and contact [T13]"),
    "ros34pw2": (ros34pw2, True, "compiled Rosenbrock-W 3(2) with Jacobian reuse; stiff film [T18]"),
    "scipy-radau": (_scipy("Radau"), False, "scipy Radau IIA (reference path)"),
    "scipy-dop853": (_scipy("DOP853"), False, "scipy DOP853 (reference path)"),
    "scipy-lsoda": (_scipy("LSODA"), False, "scipy LSODA (reference path)"),
}
