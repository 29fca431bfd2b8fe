"""Type-level dispatch: compiled if-chains generated at typing time from a registry [T175, T229].

numba compiles everything a function can reach. A dispatch that chooses a kernel from a run-time
code therefore compiles every registered kernel, and a hand-written chain does not know a kernel
registered later (a plugin). Here the set of codes a system contains is carried in the *type* of
an argument: a tuple with one entry per code 0 … max code, ``None`` where the system has no entry
of that code and an *identity* where it has one (numba types it as e.g. ``Tuple(none, int64,
none, …)``). :func:`generated_overload` makes a numba ``@overload`` (inlined into its caller)
whose body is built from that type when the caller is typed — an ``if code == c: kernel(...)``
chain over the present codes only, read from the registry at that moment.

The identity of a code is ``1`` for an entry defined in this package (numba's cache directory
is keyed to a hash of the package sources, ``jointdyn/__init__.py``) and, for an entry defined
elsewhere (registered from user code), a tuple of 1/None spelling 32 bits of a hash of its
module, name and kernel sources (:func:`identity`). The compiled callers keep ``cache=True``:
their on-disk cache holds one specialisation per combination of codes and identities, so a
process with another plugin under the same code, or an edited plugin, never loads a stale chain.
"""

from __future__ import annotations

import hashlib
import inspect
import math
from collections.abc import Callable, Mapping, Sequence

from numba import types
from numba.extending import overload

_IDENTITY_BITS = 32
_identities: dict = {}


def identity(entry, sources: Sequence = ()) -> object:
    """The type-level identity of a registry entry (a class or a kernel): 1 if it is defined in
    jointdyn, else a tuple of 1/None spelling 32 bits of a hash of its module, name and the
    sources of ``entry`` and ``sources`` (its kernels)."""
    module = getattr(entry, "__module__", None) or ""
    if module.split(".")[0] == "jointdyn":
        return 1
    key = (entry, *sources)
    if key not in _identities:
        h = hashlib.sha1(f"{module}.{getattr(entry, '__qualname__', repr(entry))}".encode())
        for obj in (entry, *sources):
            fn = getattr(obj, "py_func", obj)
            try:
                h.update(inspect.getsource(fn).encode())
            except (OSError, TypeError):  # no source (an exec'd kernel): its name only
                h.update(repr(fn).encode())
        bits = int.from_bytes(h.digest()[:4], "little")
        _identities[key] = tuple(1 if bits >> i & 1 else None for i in range(_IDENTITY_BITS))
    return _identities[key]


def present_tuple(codes: Sequence[int], known: Sequence[int], identities: Mapping | None = None) -> tuple:
    """The type-level set of ``codes``: entry c is its identity (``identities[c]``, default 1)
    if c occurs in ``codes``, else None, for c = 0 … max(known). Negative codes (none) are skipped."""
    present = {int(c) for c in codes if c >= 0}
    unknown = present - set(known)
    if unknown:
        raise ValueError(f"codes {sorted(unknown)} have no registered kernel; known {sorted(known)}")
    ids = identities or {}
    return tuple(ids.get(c, 1) if c in present else None for c in range(max(known, default=-1) + 1))


def codes_of(kinds, known: Sequence[int]) -> tuple[int, ...]:
    """The present codes encoded in the numba type of a kinds argument (None/omitted: all
    ``known``)."""
    if kinds is None or isinstance(kinds, (types.NoneType, types.Omitted)):
        return tuple(sorted(known))
    if not isinstance(kinds, types.BaseTuple):
        raise TypeError(f"kinds must be a tuple of identities/None per code; got {kinds}")
    return tuple(c for c, t in enumerate(kinds.types) if not isinstance(t, types.NoneType) and c in known)


def generated_overload(name: str, params: str, build: Callable[..., Callable], inline: str = "always"):
    """A function ``name(params)`` for compiled callers only: its compiled body is the function
    ``build(<type of the first parameter>)`` returns, generated at typing time (the Python stub
    only raises). ``inline="always"`` inlines it into the caller (small bodies that fold to a
    constant or a direct call on the hot path); ``"never"`` compiles it once per signature as a
    function of its own (a whole hook: copying its IR into the caller costs more compile time
    than the call costs at run time, [T381])."""
    first = params.split(",")[0].strip()
    src = f"def {name}({params}):\n    raise NotImplementedError('compiled only')\n"
    src += f"def typed({params}):\n    return build({first})\n"
    ns: dict = {"__name__": __name__, "build": build}
    exec(compile(src, f"<{__name__}:{name}>", "exec"), ns)  # noqa: S102
    overload(ns[name], prefer_literal=False, inline=inline)(ns["typed"])
    return ns[name]


def generated(name: str, lines: Sequence[str], namespace: Mapping) -> Callable:
    """The function ``name`` defined by source ``lines`` with globals ``namespace``."""
    ns = {"__name__": __name__, **namespace}
    exec(compile("\n".join(lines), f"<{__name__}:{name}>", "exec"), ns)  # noqa: S102
    return ns[name]


def law_codes(laws, family: int, registry: Mapping) -> tuple[int, ...]:
    """The codes of law family ``family`` (0 film, 1 contact, 2 friction) present in the numba
    type of ``laws``: a tuple of three code tuples (:func:`present_tuple`), or None (omitted, or
    an integer identity): every registry entry defined in jointdyn, in code order (a law from
    user code needs its identity in the type, see the module docstring)."""
    by_code = {cls.code: cls for cls in registry.values()}
    if isinstance(laws, types.BaseTuple):
        return codes_of(laws.types[family], tuple(by_code))
    return tuple(c for c in sorted(by_code) if identity(by_code[c]) == 1)


def law_switch(name: str, family: int, registry: Mapping, args: Sequence[str], fd: str | None, default: str):
    """A compiled ``name(laws, code, *args)`` over the laws of ``registry`` (read at typing time)
    present in ``laws`` (:func:`law_codes`): ``return kernel(*args)`` for the law whose ``code``
    matches (``fd`` None), or ``return jacobian(*args)`` — for a law without a ``jacobian`` the
    source lines ``fd`` (central differences of ``KERNEL``, the law's kernel, ending in a
    return), written into the branch; ``default`` (an expression) for another code. Everything
    is one generated function, so the compiled callers stay cacheable."""
    arglist = ", ".join(args)

    def build(laws):
        by_code = {cls.code: cls for cls in registry.values()}
        codes = law_codes(laws, family, registry)
        lines = [f"def {name}(laws, code, {arglist}):"]
        ns: dict = {"math": math}
        for i, c in enumerate(codes):
            cls = by_code[c]
            lines.append(f"    {'if' if i == 0 else 'elif'} code == {c}:")
            fn = cls.kernel if fd is None else getattr(cls, "jacobian", None)
            if fn is not None:
                ns[f"_k{c}"] = fn
                lines.append(f"        return _k{c}({arglist})")
            else:
                ns[f"_l{c}"] = cls.kernel
                lines += ["        " + ln.replace("KERNEL", f"_l{c}") for ln in fd.strip().splitlines()]
        lines.append(f"    return {default}")
        return generated(name, lines, ns)

    return generated_overload(name, f"laws, code, {arglist}", build)


def law_present(laws, slot: int) -> bool:
    """Whether the optional piece in place ``slot`` of a laws type (after the three families,
    e.g. a journal element's oil temperature or asperity contact) is compiled: its entry is not
    None, or the laws carry no entry for it (None, omitted, an integer identity, three families
    only: every piece) [T322]."""
    if isinstance(laws, types.BaseTuple) and len(laws.types) > slot:
        return not isinstance(laws.types[slot], (types.NoneType, types.Omitted))
    return True


def law_gate(name: str, slot: int, kernel: Callable, args: Sequence[str], default: str):
    """A compiled ``name(laws, *args)``: ``kernel(*args)`` if the piece ``slot`` is present in
    ``laws`` (:func:`law_present`), else the expression ``default`` (in the names of ``args``)
    without compiling ``kernel`` [T322]."""
    arglist = ", ".join(args)

    def build(laws):
        body = f"_kernel({arglist})" if law_present(laws, slot) else default
        return generated(name, [f"def {name}(laws, {arglist}):", f"    return {body}"], {"_kernel": kernel})

    return generated_overload(name, f"laws, {arglist}", build)


def law_tuple(registry: Mapping, codes: Sequence[int]) -> tuple:
    """The type-level set of the laws of ``registry`` with ``codes`` (negative: none), with their
    identities (:func:`identity` of the class and its kernels)."""
    by_code = {cls.code: cls for cls in registry.values()}
    ids = {
        c: identity(cls, [k for k in (cls.kernel, getattr(cls, "jacobian", None)) if k is not None])
        for c, cls in by_code.items()
    }
    return present_tuple(codes, tuple(by_code), ids)


_all: dict = {}


def all_laws(registry: Mapping, family: int) -> tuple:
    """The laws argument that holds every law of ``registry`` in place ``family`` (the other two
    families empty): for the Python-level dispatchers (tests, tables, the Python API)."""
    key = (id(registry), family, tuple(registry.items()))
    if key not in _all:
        codes = [cls.code for cls in registry.values()]
        _all[key] = tuple(law_tuple(registry, codes) if f == family else () for f in range(3))
    return _all[key]
