"""Declared data layouts: named slots of the flat arrays that the compiled kernels read.

A force element or a law declares its parameters by name; :class:`Layout` turns the list of
names (and of named sub-blocks, e.g. "the contact law's parameters") into slot numbers, packs
values into a row and unpacks a row back into names. The compiled kernels read slots through the
integer constants a layout hands out (``R_B, R_J = LAYOUT.slots("bearing_radius",
"journal_radius")``), never through a literal offset, so adding a name changes no kernel.

A law's parameter block is its ``PARAMS`` tuple of dataclass field names (all real-valued, SI); the
block width an element reserves for a family of laws is the widest ``PARAMS`` in that family's
registry (:func:`block_width`), so registering a law with more parameters widens the block and
every offset behind it without an edit anywhere else.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Iterable, Mapping

import numpy as np

HEADER = ("type", "body_i", "body_j")
"""the first integer slots of every element/constraint row: registry code, body indices (−1 = ground)"""
POINTS = ("xi_i", "eta_i", "xi_j", "eta_j")
"""the first real slots of every element/constraint row: point_i and point_j in their body frames [m]"""


class Layout:
    """Ordered named slots, optionally followed by named blocks of given widths.

    >>> L = Layout(("a", "b"), blocks={"law": 3})
    >>> L.slots("a", "b"), L.block("law"), L.width
    ((0, 1), slice(2, 5, None), 5)
    """

    def __init__(self, names: Iterable[str], blocks: Mapping[str, int] | None = None, start: int = 0):
        self.names = tuple(names)
        if len(set(self.names)) != len(self.names):
            raise ValueError(f"duplicate slot names in {self.names}")
        self.start = start
        self._slot = {n: start + i for i, n in enumerate(self.names)}
        self._block: dict[str, slice] = {}
        o = start + len(self.names)
        for name, w in (blocks or {}).items():
            self._block[name] = slice(o, o + int(w))
            o += int(w)
        self.width = o

    def slots(self, *names: str) -> tuple[int, ...]:
        """Slot numbers of ``names`` (KeyError naming the valid slots otherwise)."""
        try:
            return tuple(self._slot[n] for n in names)
        except KeyError as err:
            raise KeyError(f"no slot {err.args[0]!r}; slots are {list(self.names)}") from None

    def block(self, name: str) -> slice:
        """The columns of the named block."""
        return self._block[name]

    def pack(self, row: np.ndarray, values: Mapping[str, float], blocks: Mapping | None = None) -> None:
        """Write ``values`` (every named slot) and ``blocks`` (name -> sequence, at most the
        block's width) into ``row`` in place."""
        missing = set(self.names) - set(values)
        if missing:
            raise ValueError(f"layout: no value for slots {sorted(missing)}")
        for n, v in values.items():
            row[self._slot[n]] = v
        for name, vals in (blocks or {}).items():
            s = self._block[name]
            vals = tuple(vals)
            if len(vals) > s.stop - s.start:
                raise ValueError(f"block {name!r} holds {s.stop - s.start} values; got {len(vals)}")
            row[s.start : s.start + len(vals)] = vals

    def unpack(self, row: np.ndarray) -> dict:
        """``{slot name: value}`` of a packed row (blocks as arrays under their names)."""
        out = {n: row[i] for n, i in self._slot.items()}
        out.update({n: np.asarray(row[s]) for n, s in self._block.items()})
        return out


def params_of(law) -> tuple[float, ...]:
    """The values of a law instance's declared ``PARAMS`` fields, as floats, in order [SI]."""
    return tuple(float(getattr(law, n)) for n in type(law).PARAMS)


def block_width(registry: Mapping[str, type]) -> int:
    """Widest ``PARAMS`` declaration in a registry (at least 1, so a block is never empty)."""
    return max([1, *(len(getattr(cls, "PARAMS", ())) for cls in registry.values())])


def check_codes(registry: Mapping[str, type], family: str) -> None:
    """Every entry carries a distinct non-negative integer ``code`` (−1 means "none")."""
    codes = [cls.code for cls in registry.values()]
    if len(set(codes)) != len(codes) or min(codes, default=0) < 0:
        raise RuntimeError(f"{family} registry: codes must be distinct and ≥ 0; got {codes}")


def check_finite(owner: str, name: str, v, unit: str, rule: str, ok) -> None:
    """Raise :class:`~jointdyn.core.checks.FieldError` (a ``ValueError``: "owner.name = v [unit]: must
    be rule") unless v is a finite number
    satisfying ``ok(v)``; any real type counts (numpy ``float32``, ``int64`` …: ``numbers.Real``)."""
    real = isinstance(v, numbers.Real) and not isinstance(v, bool)
    if not (real and math.isfinite(float(v)) and ok(float(v))):
        from jointdyn.core.checks import FieldError  # a ValueError carrying field/unit/rule (no text parsing)

        raise FieldError(name, v, unit, rule, owner)


TYPE, BODY_I, BODY_J = Layout(HEADER).slots(*HEADER)
XI_I, ETA_I, XI_J, ETA_J = Layout(POINTS).slots(*POINTS)
