"""Integrators. ``SOLVERS`` maps a name to (runner, projects_on_constraints, description).

A compiled solver's runner is its :class:`~jointdyn.integrators.driver.Stepper` record (defined
in the method's own module, [T230]): ``simulate`` drives its step loop through
:func:`.driver.drive` in bounded slices, and called as a function it has the historical signature
``(P, y0, mem0, t0, t_out, rtol, atol, h0, hmax, max_steps, do_project)``. Adding a compiled
method is one module and one line here (docs/how-to-add-a-model.md, "An integrator")."""

from __future__ import annotations

from jointdyn.integrators import aot  # noqa: F401  (registers the copies compiled at install [T382])
from jointdyn.integrators.dopri5 import DOPRI5
from jointdyn.integrators.radau5 import RADAU5
from jointdyn.integrators.rodas4 import RODAS4
from jointdyn.integrators.ros34pw2 import ROS34PW2


def _scipy(method):
    def run(*args, **kwargs):
        from jointdyn.integrators.scipy_ivp import (
            scipy_ivp,  # scipy.integrate costs ~0.5 s to import: only when used
        )

        return scipy_ivp(*args, method=method, **kwargs)

    run.__name__ = f"scipy_{method.lower()}"
    return run


SOLVERS = {
    "dopri5": (DOPRI5, True, "compiled explicit Dormand–Prince 5(4); perfect and dry joints [T12]"),
    "rodas4": (RODAS4, True, "compiled L-stable Rosenbrock 4(3); stiff film and contact [T13]"),
    "ros34pw2": (ROS34PW2, True, "compiled Rosenbrock-W 3(2) with Jacobian reuse; stiff film [T18]"),
    "radau5": (RADAU5, True, "compiled Radau IIA order 5, simplified Newton, Jacobian/LU reuse [T113]"),
    "scipy-radau": (_scipy("Radau"), False, "scipy Radau IIA (reference path)"),
    "scipy-dop853": (_scipy("DOP853"), False, "scipy DOP853 (reference path)"),
    "scipy-lsoda": (_scipy("LSODA"), False, "scipy LSODA (reference path)"),
}
