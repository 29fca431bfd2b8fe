"""Kernel sets: the element-kind code of a model compiled on its own and called by address [T379].

Every compiled function that needs the force elements of the model's kinds — the right-hand
side, the system Jacobian, the accepted-step memory and step limit of the driver, the accuracy
guard — calls them through the four kernels of :data:`SLOTS` (the contact-event hooks and the
film-gap check read only a journal's geometry: they are kinds-independent functions of the step
loop, [T383]). For a set of element kinds (``forces.elements.kinds_of``, with the
journal element's laws, [T175, T229]) :func:`kernel_addresses` compiles those kernels with
the kinds bound (numba closures, cached on disk per kinds) and returns their machine addresses
as an int64 array; the packed system carries that array (``Packed.kernels``) and the callers
reach a kernel through ``call_<slot>(kernels, (arguments…))`` (a numba intrinsic: an indirect call
with numba's calling convention, so an exception raised in a kernel propagates like a direct
call's).

The type of the packed system is therefore the same for every model: the driver, the step
attempts of each method, the right-hand side, the output samples and the projection are
compiled once per method and shared by all models; a new combination of kinds compiles only its
kernels (before, every function taking the packed system was specialised on the kinds and
a new combination compiled the whole chain again, [T374]). The addresses belong to this process:
a packed system is rebuilt, not pickled, in another process (``Packed.__reduce__``).
"""

from __future__ import annotations

import numpy as np
from numba import njit, types
from numba.core import cgutils
from numba.core.errors import TypingError
from numba.extending import intrinsic

from jointdyn.forces.element_jacobians import force_jacobian
from jointdyn.forces.elements import advance_memory, eval_forces, step_limit

_F = types.float64
_I = types.int64
_V = types.Array(_F, 1, "C")
_M = types.Array(_F, 2, "C")
_FINT = types.Array(_I, 2, "C")
_TABLES = types.Array(_F, 3, "C")

#: slot name -> signature of the kernel (the callers pass contiguous arrays)
SLOTS = {
    "forces": types.none(_F, _V, _V, _M, _FINT, _M, _TABLES, _V, _M),
    "jacobian": _I(_F, _V, _V, _M, _FINT, _M, _TABLES, _M, _M, _V),
    "memory": _I(_F, _V, _V, _M, _FINT, _M, _TABLES),
    "step_limit": _F(_V, _V, _M, _FINT, _M),
}
INDEX = {name: i for i, name in enumerate(SLOTS)}


def _kernels(kinds):
    """The kernels of :data:`SLOTS` with ``kinds`` bound (a closure's cell enters numba's cache key, so the
    disk cache holds one compiled kernel per kinds)."""

    @njit(cache=True)
    def forces(t, q, qd, mem, fint, freal, tables, Q, out):
        eval_forces(t, q, qd, mem, fint, freal, tables, Q, out, kinds)

    @njit(cache=True)
    def jacobian(t, q, qd, mem, fint, freal, tables, dQdq, dQdqd, dQdt):
        return force_jacobian(t, q, qd, mem, fint, freal, tables, dQdq, dQdqd, dQdt, kinds)

    @njit(cache=True)
    def memory(t, q, qd, mem, fint, freal, tables):
        return advance_memory(t, q, qd, mem, fint, freal, tables, kinds)

    @njit(cache=True)
    def limit(q, qd, mem, fint, freal):
        return step_limit(q, qd, mem, fint, freal, kinds)

    return (forces, jacobian, memory, limit)


_SETS: dict = {}  # kinds -> (addresses, dispatchers): the dispatchers keep the code alive
_KINDS: dict = {}  # address of an addresses array -> its kinds


def compiled_address(disp, sig) -> int:
    """Machine address of the dispatcher ``disp`` compiled for ``sig`` (numba calling convention)."""
    disp.compile(sig)
    cres = disp.get_compile_result(sig)
    return cres.library.get_pointer_to_function(cres.fndesc.llvm_func_name)


def kernel_addresses(kinds: tuple, jacobian: bool = False) -> np.ndarray:
    """Addresses (int64, one per :data:`SLOTS` entry) of the kernels compiled for ``kinds``,
    compiled (or loaded from the cache) at the first call in this process; the exact element
    Jacobian only when asked (``jacobian``, or later :func:`require_jacobian`): a method without
    it never compiles it (its slot holds 0 and a call raises)."""
    if kinds not in _SETS:
        dispatchers = _kernels(kinds)
        addresses = np.zeros(len(SLOTS), dtype=np.int64)
        for i, (disp, sig) in enumerate(zip(dispatchers, SLOTS.values(), strict=True)):
            if i != INDEX["jacobian"]:
                addresses[i] = compiled_address(disp, sig)
        _SETS[kinds] = (addresses, dispatchers)
        _KINDS[addresses.ctypes.data] = kinds
    if jacobian:
        require_jacobian(_SETS[kinds][0])
    return _SETS[kinds][0]


def kernel_kinds(kernels: np.ndarray) -> tuple:
    """The kinds a kernel set (``Packed.kernels``) was compiled for."""
    return _KINDS[kernels.ctypes.data]


def require_jacobian(kernels: np.ndarray) -> None:
    """Compile the exact element Jacobian of the kernel set ``kernels`` (``Packed.kernels``) if
    it is not yet, and enter its address."""
    i = INDEX["jacobian"]
    if kernels[i] == 0:
        kinds = kernel_kinds(kernels)
        kernels[i] = compiled_address(_SETS[kinds][1][i], SLOTS["jacobian"])


_NO_JACOBIAN = "exact element Jacobian not compiled for this packed system: use System.packed(jacobian=True)"


def _caller(slot: str):
    sig = SLOTS[slot]
    index = INDEX[slot]

    @intrinsic
    def call_kernel(typingctx, kernels, args):
        if not (isinstance(kernels, types.Array) and kernels.dtype == _I and kernels.ndim == 1):
            raise TypingError(
                f"kernel {slot!r}: the kernel set is {kernels}, expected Packed.kernels (int64)"
            )
        if not isinstance(args, types.BaseTuple) or len(args) != len(sig.args):
            raise TypingError(f"kernel {slot!r} takes {len(sig.args)} arguments, got {args}")
        for i, (have, want) in enumerate(zip(args, sig.args, strict=True)):
            if typingctx.can_convert(have, want) is None:
                raise TypingError(f"kernel {slot!r}: argument {i} is {have}, expected {want}")

        def codegen(context, builder, signature, llargs):
            table, values = llargs
            ary = context.make_array(signature.args[0])(context, builder, table)
            address = builder.load(cgutils.gep_inbounds(builder, ary.data, index))
            if slot == "jacobian":  # compiled on request only (kernel_addresses)
                with cgutils.if_unlikely(builder, cgutils.is_null(builder, address)):
                    context.call_conv.return_user_exc(builder, RuntimeError, (_NO_JACOBIAN,))
            argv = [
                context.cast(builder, builder.extract_value(values, i), args[i], sig.args[i])
                for i in range(len(sig.args))
            ]
            fnty = context.call_conv.get_function_type(sig.return_type, sig.args)
            fn = builder.inttoptr(address, fnty.as_pointer())
            status, res = context.call_conv.call_function(builder, fn, sig.return_type, sig.args, argv)
            with cgutils.if_unlikely(builder, status.is_error):
                context.call_conv.return_status_propagate(builder, status)
            return res

        return sig.return_type(kernels, args), codegen

    call_kernel.__name__ = f"call_{slot}"
    return call_kernel


call_forces = _caller("forces")
call_jacobian = _caller("jacobian")
call_memory = _caller("memory")
call_step_limit = _caller("step_limit")
