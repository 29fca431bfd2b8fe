"""Type-level element kinds: compile only the force-element kinds a model contains [T175].

numba compiles everything a function can reach. A loop that chooses the element kind from the
run-time code ``fint[k, TYPE]`` therefore compiles every registered kind (journal with all film
models and contact laws, tables, springs, torsion) for every model, a perfect joint included.

Here the set of kinds a system contains is carried in the *type* of an argument: ``kinds`` is a
tuple with one entry per code 0 … max code, ``1`` where the system has an element of that code
and ``None`` where it has none (numba types it as e.g. ``Tuple(none, int64, none, …)``). The
functions made here — :func:`kind_loop` (the loop over the elements), :func:`kind_switch` (one
element) and :func:`kind_gate` (a hook of one kind) — are numba ``@overload`` functions, inlined into
their caller, whose code is generated at typing time: an ``if typ == code: kernel(...)`` chain
over the present codes only. The absent kinds are never typed, lowered or optimised.
``kinds=None`` (or omitted) means every registered kind.

The compiled callers keep ``cache=True``: the kinds tuple type is part of their signature, so
numba's on-disk cache holds one specialisation per combination of kinds (the trade-off: a model
with a new combination compiles once more), and the cache key stays independent of the process
(no compiled function or closure cell enters it).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence

from numba import types
from numba.extending import overload

from jointdyn.core.layout import TYPE


def kinds_tuple(codes: Sequence[int], known: Sequence[int]) -> tuple:
    """The kinds argument for a system whose elements have registry ``codes``: entry c is 1 if c
    occurs in ``codes``, else None, for c = 0 … max(known)."""
    present = {int(c) for c in codes}
    unknown = present - set(known)
    if unknown:
        raise ValueError(f"element codes {sorted(unknown)} have no registered kernel; known {sorted(known)}")
    return tuple(1 if c in present else None for c in range(max(known, default=-1) + 1))


def codes_of(kinds, known: Sequence[int]) -> tuple[int, ...]:
    """The present codes encoded in the numba type of a kinds argument (None/omitted: all)."""
    if kinds is None or isinstance(kinds, (types.NoneType, types.Omitted)):
        return tuple(sorted(known))
    if not isinstance(kinds, types.BaseTuple):
        raise TypeError(f"kinds must be a tuple of 1/None per element code; got {kinds}")
    return tuple(c for c, t in enumerate(kinds.types) if not isinstance(t, types.NoneType) and c in known)


def _overload(name: str, params: str, build: Callable[..., Callable]):
    """A function ``name(params)`` for compiled callers only: its compiled body is the function
    ``build(kinds)`` returns, generated at typing time from the numba type of ``kinds``, and is
    inlined into the caller (the Python stub only raises)."""
    src = f"def {name}({params}):\n    raise NotImplementedError('compiled only')\n"
    src += f"def typed({params}):\n    return build(kinds)\n"
    ns: dict = {"__name__": __name__, "build": build}
    exec(compile(src, f"<{__name__}:{name}>", "exec"), ns)  # noqa: S102
    overload(ns[name], prefer_literal=False, inline="always")(ns["typed"])
    return ns[name]


def _generated(name: str, lines: Sequence[str], namespace: Mapping) -> Callable:
    """The function ``name`` defined by source ``lines`` with globals ``namespace`` (module name
    included)."""
    ns = {"__name__": __name__, **namespace}
    exec(compile("\n".join(lines), f"<{__name__}:{name}>", "exec"), ns)  # noqa: S102
    return ns[name]


def kind_switch(name: str, kernels: Mapping[int, Callable], args: Sequence[str], default: str | None = None):
    """A compiled dispatch ``name(kinds, typ, *args)``: calls ``kernels[typ](*args)`` for the codes
    present in ``kinds`` and returns its result; for another ``typ`` it returns ``default`` (an
    expression; None: nothing, the kernels return nothing)."""
    arglist = ", ".join(args)

    def build(kinds):
        codes = codes_of(kinds, tuple(kernels))
        lines = [f"def {name}(kinds, typ, {arglist}):"]
        for i, c in enumerate(codes):
            call = f"_k{c}({arglist})"
            lines.append(f"    {'if' if i == 0 else 'elif'} typ == {c}:")
            lines.append(f"        {'return ' + call if default is not None else call}")
        lines.append(f"    return {default}" if default is not None else "    return")
        return _generated(name, lines, {f"_k{c}": kernels[c] for c in codes})

    return _overload(name, f"kinds, typ, {arglist}", build)


def kind_gate(name: str, code: int, kernel: Callable, args: Sequence[str], default: str):
    """A compiled ``name(kinds, *args)``: ``kernel(*args)`` if ``kinds`` contains ``code`` (or is
    None), else the constant expression ``default`` without compiling ``kernel`` (e.g. the
    contact-onset checks of journal elements in a model that has none)."""
    arglist = ", ".join(args)

    def build(kinds):
        body = f"_kernel({arglist})" if code in codes_of(kinds, (code,)) else default
        return _generated(name, [f"def {name}(kinds, {arglist}):", f"    return {body}"], {"_kernel": kernel})

    return _overload(name, f"kinds, {arglist}", build)


def kind_loop(name: str, kernels: Mapping[int, Callable | tuple], args: Sequence[str], constants: Mapping):
    """A compiled ``name(kinds, *args)`` that loops over the element rows k of ``fint`` (one of
    ``args``) and calls, for the codes present in ``kinds``, ``kernel(*args with k)`` — the element
    signature: ``args`` with ``k`` inserted after the third — or, for an entry ``(kernel, "expr")``,
    ``kernel(expr)`` with its own argument expressions (names of ``args``, ``k`` and ``constants``).
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
            lines.append(f"            _k{c}({call_args})")
        return _generated(name, lines, namespace)

    return _overload(name, f"kinds, {arglist}", build)
