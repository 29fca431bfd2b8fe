"""Atomic file output: write to a temporary name in the same directory, then ``os.replace``.

A reader (or a process killed mid-write) therefore sees either the previous complete file or
the new complete file under the final name, never a truncated one. Temporary names start with
``.`` and end in ``.tmp<pid>`` so they are recognisable and never mistaken for results.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
from collections.abc import Iterator
from pathlib import Path


def temp_name(path: Path) -> Path:
    """The temporary sibling of ``path`` used while it is being written."""
    return path.with_name(f".{path.name}.tmp{os.getpid()}")


def is_temp(path: Path) -> bool:
    """True for a leftover temporary file of :func:`temp_name` (any process)."""
    return path.name.startswith(".") and ".tmp" in path.name


@contextlib.contextmanager
def replacing(path) -> Iterator[Path]:
    """Yield a temporary path next to ``path``; on a clean exit fsync it and rename it onto
    ``path``; on any exception remove it and leave ``path`` untouched."""
    path = Path(path)
    tmp = temp_name(path)
    try:
        yield tmp
        with open(tmp, "rb") as f:
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            tmp.unlink()
        raise


def write_bytes(path, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically."""
    with replacing(path) as tmp:
        tmp.write_bytes(data)


def write_text(path, text: str) -> None:
    """Write UTF-8 ``text`` to ``path`` atomically."""
    write_bytes(path, text.encode("utf-8"))


def write_json(path, data) -> None:
    """Write ``data`` as indented JSON to ``path`` atomically (non-JSON values via ``str``)."""
    write_text(path, json.dumps(data, indent=2, default=str) + "\n")


def sha256(path) -> str:
    """Hex SHA-256 of a file's bytes (streamed)."""
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()
