"""Type-level element kinds: compile only the force-element kinds a model contains [T175].

numba compiles everything a function can reach. A loop that chooses the element kind from the
run-time code ``fint[k, TYPE]`` therefore compiles every registered kind (journal with all film
models and contact laws, tables, springs, torsion) for every model, a perfect joint included.

Here the set of kinds a system contains is carried in the *type* of an argument: ``kinds`` is a
tuple with one entry per code 0 … max code, an identity where the system has an element of that
code (``1`` for a kind of this package; a plugin's hash, or a journal element's own tuple of the
film, contact and friction laws it uses [T229], see :mod:`jointdyn.core.dispatch`) and ``None``
where it has none (numba types it as e.g. ``Tuple(none, int64, none, …)``). The
functions made here — :func:`kind_loop` (the loop over the elements), :func:`kind_switch` (one
element) and :func:`kind_gate` (a hook of one kind) — are numba ``@overload`` functions whose code
is generated at typing time: an ``if typ == code: kernel(...)`` chain over the present codes
only. The loop is inlined into its caller (the right-hand side's path); a switch or a gate is
compiled as a function of its own, called once per step or per Jacobian ([T381]: copying a
whole hook's IR into its caller cost more compile time than the call costs). The absent kinds
are never typed, lowered or optimised.
``kinds=None`` (or omitted) means every registered kind (and, for the laws, every built-in law).
The machinery (generated ``@overload`` functions) is :mod:`jointdyn.core.dispatch`, shared with
the law dispatch of the film models, contact and friction laws [T229].

The functions taking ``kinds`` are compiled per combination of kinds only in the four kernels
of :mod:`jointdyn.forces.kernel_set` (closures over the kinds, cached on disk per kinds); the
driver, the methods and the right-hand side reach them by address and are compiled once for all
models [T379].
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping, Sequence

from numba import types

from jointdyn.core.dispatch import codes_of, generated, generated_overload, present_tuple
from jointdyn.core.layout import TYPE

__all__ = ["codes_of", "kind_gate", "kind_loop", "kind_switch", "kinds_tuple"]


def kinds_tuple(codes: Sequence[int], known: Sequence[int], identities: Mapping | None = None) -> tuple:
    """The kinds argument for a system whose elements have registry ``codes``: entry c is its
    identity (``identities[c]``, default 1; see :mod:`jointdyn.core.dispatch`) if c occurs in
    ``codes``, else None, for c = 0 … max(known)."""
    try:
        return present_tuple(codes, known, identities)
    except ValueError as err:
        raise ValueError(f"element {err}") from None


def _with_kind(call_args: str, kinds, code: int) -> str:
    """``call_args`` with the token ``kind`` (the kinds entry of the element's own code, e.g. the
    laws a journal element uses) spelled out: ``kinds[code]``, or None when ``kinds`` is None."""
    return re.sub(r"\bkind\b", f"kinds[{code}]" if isinstance(kinds, types.BaseTuple) else "None", call_args)


def kind_switch(
    name: str, kernels: Mapping[int, Callable | tuple], args: Sequence[str], default: str | None = None
):
    """A compiled dispatch ``name(kinds, typ, *args)``: calls ``kernels[typ](*args)`` — or, for an
    entry ``(kernel, "expr")``, ``kernel(expr)`` with its own argument expressions (names of
    ``args`` and ``kind``) — for the codes present in ``kinds`` and returns its result; for another
    ``typ`` it returns ``default`` (an expression; None: nothing, the kernels return nothing)."""
    arglist = ", ".join(args)

    def build(kinds):
        codes = codes_of(kinds, tuple(kernels))
        lines = [f"def {name}(kinds, typ, {arglist}):"]
        ns = {}
        for i, c in enumerate(codes):
            entry = kernels[c]
            fn, call_args = entry if isinstance(entry, tuple) else (entry, arglist)
            ns[f"_k{c}"] = fn
            call = f"_k{c}({_with_kind(call_args, kinds, c)})"
            lines.append(f"    {'if' if i == 0 else 'elif'} typ == {c}:")
            lines.append(f"        {'return ' + call if default is not None else call}")
        lines.append(f"    return {default}" if default is not None else "    return")
        return generated(name, lines, ns)

    return generated_overload(name, f"kinds, typ, {arglist}", build, inline="never")  # [T381]


def kind_gate(name: str, code: int, kernel: Callable, args: Sequence[str], default: str):
    """A compiled ``name(kinds, *args)``: ``kernel(*args)`` if ``kinds`` contains ``code`` (or is
    None), else the constant expression ``default`` without compiling ``kernel`` (e.g. the
    contact memory of journal elements in a model that has none)."""
    arglist = ", ".join(args)

    def build(kinds):
        body = f"_kernel({arglist})" if code in codes_of(kinds, (code,)) else default
        return generated(name, [f"def {name}(kinds, {arglist}):", f"    return {body}"], {"_kernel": kernel})

    return generated_overload(name, f"kinds, {arglist}", build, inline="never")  # [T381]


def kind_loop(name: str, kernels: Mapping[int, Callable | tuple], args: Sequence[str], constants: Mapping):
    """A compiled ``name(kinds, *args)`` that loops over the element rows k of ``fint`` (one of
    ``args``) and calls, for the codes present in ``kinds``, ``kernel(*args with k)`` — the element
    signature: ``args`` with ``k`` inserted after the third — or, for an entry ``(kernel, "expr")``,
    ``kernel(expr)`` with its own argument expressions (names of ``args``, ``k``, ``constants`` and
    ``kind``, the element's entry of ``kinds``).
    The call expressions are written into the loop as in hand-written code: no wrapper, no extra
    call level per element (measured: either costs ≈ 15 % of a journal element's evaluation)."""
    arglist = ", ".join(args)
    element_args = ", ".join([*args[:3], "k", *args[3:]])

    def build(kinds):
        codes = codes_of(kinds, tuple(kernels))
        lines = [f"def {name}(kinds, {arglist}):", "    for k in range(fint.shape[0]):"]
        lines.append(f"        typ = fint[k, {TYPE}]" if codes else "        pass")
        namespace = dict(constants)
        for i, c in enumerate(codes):
            entry = kernels[c]
            fn, call_args = entry if isinstance(entry, tuple) else (entry, element_args)
            namespace[f"_k{c}"] = fn
            lines.append(f"        {'if' if i == 0 else 'elif'} typ == {c}:")
            lines.append(f"            _k{c}({_with_kind(call_args, kinds, c)})")
        return generated(name, lines, namespace)

    return generated_overload(name, f"kinds, {arglist}", build)
