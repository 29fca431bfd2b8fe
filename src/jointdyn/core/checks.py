"""One input check for every edge (CLI options, model files, sweep files, CSV tables).

``check(field, value, unit, rule)`` raises :class:`FieldError` — a ``ValueError`` carrying the
field, unit, value and rule as attributes, so callers (e.g. the model-file loader adding a file
and line) never parse message text. Rules are written as they read in the message:
``"> 0"``, ``">= 0"``, ``"< 1"``, ``"in (0, 1)"``, ``"in [0, 1]"``, ``"in (0, 0.01]"``,
``"!= 0"`` or ``"finite"``; every rule implies a finite number.
"""

from __future__ import annotations

import math
import numbers
import operator
import re

_OPS = {">": operator.gt, ">=": operator.ge, "<": operator.lt, "<=": operator.le, "!=": operator.ne}
_INTERVAL = re.compile(r"in ([\(\[])\s*(\S+)\s*,\s*(\S+)\s*([\)\]])")


class FieldError(ValueError):
    """A value outside its allowed range; ``field``, ``unit``, ``value``, ``rule`` say which."""

    def __init__(self, field: str, value, unit: str, rule: str, owner: str = "", note: str = ""):
        self.field, self.value, self.unit, self.rule, self.owner = field, value, unit, rule, owner
        name = f"{owner}.{field}" if owner else field
        super().__init__(f"{name} = {value!r} [{unit}]: must be {rule}" + (f" ({note})" if note else ""))


def satisfies(value: float, rule: str) -> bool:
    """True if the finite number ``value`` obeys ``rule`` (see the module docstring)."""
    if rule == "finite":
        return True
    m = _INTERVAL.fullmatch(rule.strip())
    if m:
        lo_b, lo, hi, hi_b = m.group(1), float(m.group(2)), float(m.group(3)), m.group(4)
        return (value > lo if lo_b == "(" else value >= lo) and (value < hi if hi_b == ")" else value <= hi)
    op, _, bound = rule.strip().partition(" ")
    if op not in _OPS:
        raise ValueError(f"unknown rule {rule!r}")
    return bool(_OPS[op](value, float(bound)))


def check(field: str, value, unit: str, rule: str, owner: str = "", note: str = "", integer=False) -> float:
    """Return ``value`` if it is a finite real number (an integer with ``integer``) obeying
    ``rule``; else raise :class:`FieldError` naming field, unit and rule."""
    ok_type = isinstance(value, numbers.Integral if integer else numbers.Real) and not isinstance(value, bool)
    shown = rule if not integer else f"an integer {rule}"
    if not ok_type:
        raise FieldError(field, value, unit, f"a {'integer' if integer else 'number'} {rule}", owner, note)
    if not math.isfinite(value):
        raise FieldError(field, value, unit, f"finite and {rule}" if rule != "finite" else rule, owner, note)
    if not satisfies(float(value), rule):
        raise FieldError(field, value, unit, shown, owner, note)
    return value
