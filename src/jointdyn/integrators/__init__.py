"""Integrators. ``SOLVERS`` maps a name to (runner, projects_on_constraints, description).

The compiled solvers share one step-control loop (:mod:`.driver`); their runners have the
historical signature ``(P, y0, mem0, t0, t_out, rtol, atol, h0, hmax, max_steps, do_project)``
and ``simulate`` drives them through :func:`.driver.drive` in bounded slices."""

from __future__ import annotations

from functools import partial

from jointdyn.integrators.driver import DOPRI5, RADAU5, RODAS4, ROS34PW2, run

dopri5 = partial(run, DOPRI5)
rodas4 = partial(run, RODAS4)
ros34pw2 = partial(run, ROS34PW2)
radau5 = partial(run, RADAU5)


def _scipy(method):
    def run(*args, **kwargs):
        from jointdyn.integrators.scipy_ivp import (
            scipy_ivp,  # scipy.integrate costs ~0.5 s to import: only when used
        )

        return scipy_ivp(*args, method=method, **kwargs)

    run.__name__ = f"scipy_{method.lower()}"
    return run


SOLVERS = {
    "dopri5": (dopri5, True, "compiled explicit Dormand–Prince 5(4); perfect and dry joints [T12]"),
    "rodas4": (rodas4, True, "compiled L-stable Rosenbrock 4(3); stiff film and contact [T13]"),
    "ros34pw2": (ros34pw2, True, "compiled Rosenbrock-W 3(2) with Jacobian reuse; stiff film [T18]"),
    "radau5": (radau5, True, "compiled Radau IIA order 5, simplified Newton, Jacobian/LU reuse [T113]"),
    "scipy-radau": (_scipy("Radau"), False, "scipy Radau IIA (reference path)"),
    "scipy-dop853": (_scipy("DOP853"), False, "scipy DOP853 (reference path)"),
    "scipy-lsoda": (_scipy("LSODA"), False, "scipy LSODA (reference path)"),
}
