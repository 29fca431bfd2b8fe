"""Exceptions and warnings raised by jointdyn."""

from __future__ import annotations


class ModelError(ValueError):
    """A model that cannot be compiled or assembled (bad names, bad values, no assembly)."""


class PhysicsWarning(UserWarning):
    """A model is used outside the domain where its theory is valid."""


class SimulationError(RuntimeError):
    """Integration failed. Keeps what was computed so far.

    Attributes: ``t`` [s] time reached, ``results`` the partial :class:`~jointdyn.results.Results`.
    """

    def __init__(self, message: str, t: float, results=None):
        super().__init__(message)
        self.t = t
        self.results = results
