"""Arrays without reference counting inside a compiled loop [T208].

numba counts references to every array it holds (its ``meminfo``) and updates the count with an
*atomic* increment or decrement each time an array or a view of it is created, passed to a
compiled function or dropped: dozens of locked instructions per right-hand side of a small
system. An array whose ``meminfo`` is NULL is never counted (the update is a null test). numba
gives such arrays to memory it does not own (``numba.carray``); :func:`borrowed` makes the same
from an array the caller owns.

Use only where the owner provably outlives the borrowed value: the borrowed arrays (and every
view of them) must stay local to the compiled call that made them — never returned, stored in
a container that outlives the call, or handed back to Python.
"""

from __future__ import annotations

from numba import types
from numba.core import cgutils
from numba.extending import intrinsic


def _strip(context, builder, ty, val):
    """``val`` of numba type ``ty`` with the meminfo and parent of each array set to NULL."""
    if isinstance(ty, types.Array):
        ary = cgutils.create_struct_proxy(ty)(context, builder, value=val)
        ary.meminfo = cgutils.get_null_value(ary.meminfo.type)
        ary.parent = cgutils.get_null_value(ary.parent.type)
        return ary._getvalue()
    if isinstance(ty, types.BaseTuple):
        out = val
        for i, t in enumerate(ty.types):
            out = builder.insert_value(out, _strip(context, builder, t, builder.extract_value(val, i)), i)
        return out
    if context.enable_nrt:  # anything else is returned as a new reference, as numba expects
        context.nrt.incref(builder, ty, val)
    return val


@intrinsic
def borrowed(typingctx, x):
    """(compiled only) ``x`` — an array or a (named) tuple holding arrays — with the same data,
    shapes and type, whose arrays are not reference-counted: a view, not a copy. Valid while the
    caller's original is alive; see the module docstring."""

    def codegen(context, builder, sig, args):
        return _strip(context, builder, x, args[0])

    return x(x), codegen
