"""Where a key is in a model file: dotted key paths -> line numbers, and keyed one-line
:class:`~jointdyn.errors.ModelError` messages ``<file>:<line>: <dotted.key>: <problem>``."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

from jointdyn.core import atomic
from jointdyn.errors import ModelError


def _key_path(src: str) -> tuple | None:
    """The key path of a TOML key expression (``a.b``, ``"x y".c``), parsed by tomllib itself."""
    try:
        d = tomllib.loads(f"{src} = 0")
    except tomllib.TOMLDecodeError:
        return None
    path = []
    while isinstance(d, dict) and len(d) == 1:
        k = next(iter(d))
        path.append(k)
        d = d[k]
    return tuple(path)


_HEADER = re.compile(r"^\[\s*([^\[\]]+?)\s*\]")
_KEYLINE = re.compile(
    r"^((?:[A-Za-z0-9_\-]+|\"[^\"]*\"|'[^']*')(?:\s*\.\s*(?:[A-Za-z0-9_\-]+|\"[^\"]*\"|'[^']*'))*)\s*="
)


def _line_index(text: str) -> dict[tuple, int]:
    """Map key paths (tables and keys) to their first line number (1-based)."""
    index: dict[tuple, int] = {}
    current: tuple = ()
    for n, line in enumerate(text.splitlines(), 1):
        s = line.strip()
        if not s or s.startswith("#"):
            continue
        m = _HEADER.match(s)
        if m and not s.startswith("[["):
            p = _key_path(m.group(1))
            if p is not None:
                current = p
                for i in range(1, len(p) + 1):
                    index.setdefault(p[:i], n)
            continue
        m = _KEYLINE.match(s)
        if m:
            p = _key_path(m.group(1))
            if p is not None:
                for i in range(1, len(p) + 1):
                    index.setdefault(current + p[:i], n)
    return index


class _Context:
    """Where a document came from, for error messages."""

    def __init__(self, source: str, text: str = "", overridden: dict | None = None):
        self.source = source
        self.index = _line_index(text) if text else {}
        self.overridden = overridden or {}

    def where(self, key: tuple) -> str:
        for i in range(len(key), 0, -1):
            if key[:i] in self.overridden:
                return f"{self.source} (--set {self.overridden[key[:i]]})"
        for i in range(len(key), 0, -1):
            if key[:i] in self.index:
                return f"{self.source}:{self.index[key[:i]]}"
        return self.source

    def error(self, key: tuple, msg: str) -> ModelError:
        dotted = ".".join(str(k) for k in key) if key else "(file)"
        text = " ".join(f"{self.where(tuple(key))}: {dotted}: {msg}".split())
        return ModelError(text)


def toml_error(path, text: str, err: tomllib.TOMLDecodeError) -> ModelError:
    """A TOML syntax error as ``<file>:<line>: <dotted.key>: invalid TOML: <what>``."""
    msg = str(err)
    m = re.search(r"\(at line (\d+), column (\d+)\)", msg)
    line = int(m.group(1)) if m else None
    bare = re.sub(r"\s*\(at (line \d+, column \d+|end of document)\)", "", msg)
    key = ""
    if line is not None:
        src = text.splitlines()[line - 1].strip() if line <= len(text.splitlines()) else ""
        h = _HEADER.match(src)
        k = _KEYLINE.match(src)
        p = _key_path(h.group(1)) if h else None
        if p is None and k:
            table = ()
            for prev in text.splitlines()[: line - 1]:
                hh = _HEADER.match(prev.strip())
                if hh and _key_path(hh.group(1)) is not None:
                    table = _key_path(hh.group(1))
            p = table + (_key_path(k.group(1)) or ())
        key = ".".join(p) + ": " if p else ""
    if "twice" in bare or "overwrite" in bare:
        bare = f"duplicate name: TOML forbids defining a key or table twice ({bare})"
    loc = f"{path}:{line}" if line is not None else f"{path}"
    return ModelError(" ".join(f"{loc}: {key}invalid TOML: {bare}".split()))


def read_toml(path, what: str = "model file") -> tuple[dict, str]:
    """Read a UTF-8 TOML file (``what``: "model file", "sweep file") -> (document, text); every
    failure is one :class:`ModelError` line naming the file (and line and key for syntax errors)."""
    path = Path(path)
    try:
        atomic.regular_input(path, what)  # a FIFO or device would block or never end
        text = path.read_text(encoding="utf-8").removeprefix("\ufeff")
    except FileNotFoundError:
        raise ModelError(f"{path}: no such {what}") from None
    except IsADirectoryError:
        raise ModelError(f"{path}: is a directory, not a {what}") from None
    except UnicodeDecodeError as err:
        raise ModelError(f"{path}: not a UTF-8 text file ({err.reason} at byte {err.start})") from None
    except ValueError as err:  # not a regular file
        raise ModelError(str(err)) from None
    try:
        return tomllib.loads(text), text
    except tomllib.TOMLDecodeError as err:
        raise toml_error(path, text, err) from None
    except RecursionError:
        raise ModelError(f"{path}: tables or arrays nested too deeply to be a {what}") from None
