"""Exceptions and warnings raised by jointdyn."""

from __future__ import annotations


class ModelError(ValueError):
    """A model that cannot be compiled or assembled (bad names, bad values, no assembly)."""


class PhysicsWarning(UserWarning):
    """A model is used outside the domain where its theory is valid."""


class SimulationError(RuntimeError):
    """Integration failed. Keeps what was computed so far.

    Attributes: ``t`` [s] time reached, ``results`` the partial :class:`~jointdyn.simulation.results.Results`.
    """

    def __init__(self, message: str, t: float, results=None):
        super().__init__(message)
        self.t = t
        self.results = results


class Interrupted(SimulationError):
    """The run was stopped by a signal (Ctrl-C = SIGINT, or SIGTERM); ``results`` holds what was
    computed up to ``t`` [s] and ``signal`` names the signal (e.g. ``"SIGINT"``)."""

    def __init__(self, message: str, t: float, results=None, signal: str = "SIGINT"):
        super().__init__(message, t, results)
        self.signal = signal
