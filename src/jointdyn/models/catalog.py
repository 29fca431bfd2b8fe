"""The catalogue of shipped models (:class:`~jointdyn.models.shipped.Shipped` records): the
names ``jointdyn run``, sweeps, ensembles, bifurcation diagrams and the Lyapunov command accept
in place of a model file. Adding a shipped model is one module with its record and one line here.
"""

from __future__ import annotations

from jointdyn.models.shipped import Shipped
from jointdyn.models.slider_crank_args import SLIDER_CRANK

#: name -> record
SHIPPED: dict[str, Shipped] = {m.name: m for m in (SLIDER_CRANK,)}
#: the model a sweep or diagram file without ``model``/``file`` means
DEFAULT = SLIDER_CRANK.name


def shipped(name) -> Shipped:
    """The shipped model ``name`` (one ValueError line listing the names otherwise)."""
    if not isinstance(name, str) or name not in SHIPPED:
        raise ValueError(f"MODEL = {name!r}: not a shipped model or a FILE.toml; valid: {', '.join(SHIPPED)}")
    return SHIPPED[name]
