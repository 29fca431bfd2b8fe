"""Safe file output: every file jointdyn writes goes through :func:`replacing`.

* A new file is written under an **exclusive, unpredictable temporary name** in the target's
  directory — ``.NAME.<pid>.<16 random hex>.tmp<suffix>``, created with
  ``O_CREAT|O_EXCL|O_NOFOLLOW`` (a planted file or symbolic link at that name makes the
  creation fail and another name is drawn; it is never followed) — then fsynced, given mode
  ``0666 & ~umask`` (like any other file the user creates) and renamed over the target. A reader
  (or a process killed mid-write) sees the old complete file or the new one, never a truncated
  one; the pid in the name lets a later run remove the temporaries of dead processes, and of
  a pid reused by a process started after the file was last written (:func:`stale_temps`).
* The target is **never followed or replaced** when it is a symbolic link, a directory, a FIFO,
  a socket or a device (:class:`OutputError`, one line) — except that a character device the
  user names on purpose as an output file (``/dev/null``, ``/dev/stdout``, a terminal;
  ``devices=True``, the single-file ``--out`` options) is written straight into, never replaced.
* Input files are checked with :func:`regular_input`: a FIFO or device named as an input is
  refused instead of blocking.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import re
import secrets
import stat
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path

_TEMP = re.compile(r"^\..+\.(\d+)\.[0-9a-f]{16}\.tmp(\.[^.]*)?$")
#: the process's own streams by the names a user gives them (written to the open descriptor)
STREAMS = {"/dev/stdout": 1, "/dev/stderr": 2, "/dev/fd/1": 1, "/dev/fd/2": 2}
STREAMS |= {"/proc/self/fd/1": 1, "/proc/self/fd/2": 2}


class OutputError(ValueError):
    """An output path that cannot be used (a file, a link, a device, read-only, busy, foreign)."""


def temp_name(path: Path) -> Path:
    """A fresh temporary sibling of ``path`` (pid and 64 random bits in the name)."""
    return path.with_name(f".{path.name}.{os.getpid()}.{secrets.token_hex(8)}.tmp{path.suffix}")


def is_temp(path: Path) -> bool:
    """True for a temporary file of :func:`temp_name` (any process)."""
    return _TEMP.match(Path(path).name) is not None


def alive(pid: int) -> bool:
    """Whether process ``pid`` exists (on this machine)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def _started(pid: int) -> float | None:
    """Start time of process ``pid`` [s since the epoch] (Linux /proc; None where unknown)."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
        ticks = int(stat.rsplit(")", 1)[1].split()[19])  # field 22: starttime [clock ticks]
        btime = next(int(ln.split()[1]) for ln in open("/proc/stat") if ln.startswith("btime"))
        return btime + ticks / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError, StopIteration):
        return None


def _writing(pid: int, temp: Path) -> bool:
    """Whether process ``pid`` may still be writing ``temp``: it exists and it did not start
    after the file was last modified (a reused pid of a killed run's temporary) [T333]."""
    if not alive(pid):
        return False
    start = _started(pid)
    try:
        return start is None or start <= temp.stat().st_mtime + 2.0  # 2 s: btime's resolution
    except OSError:
        return False


def stale_temps(directory) -> list[Path]:
    """Temporary files in ``directory`` left by jointdyn processes that are dead (or whose pid
    now belongs to a process started after the file was last written)."""
    out = []
    with contextlib.suppress(OSError):
        for p in Path(directory).iterdir():
            m = _TEMP.match(p.name)
            if m and not p.is_dir() and not _writing(int(m.group(1)), p):
                out.append(p)
    return out


def file_mode() -> int:
    """The mode a newly created file gets: ``0666`` without the process's umask bits."""
    try:  # Linux: read without changing it (os.umask would, briefly, for every thread)
        with open("/proc/self/status", encoding="ascii") as f:
            mask = next(int(ln.split()[1], 8) for ln in f if ln.startswith("Umask:"))
    except (OSError, StopIteration, ValueError, IndexError):
        mask = os.umask(0o022)
        os.umask(mask)
    return 0o666 & ~mask


def describe(mode: int) -> str:
    for test, name in (
        (stat.S_ISLNK, "a symbolic link"),
        (stat.S_ISDIR, "a directory"),
        (stat.S_ISFIFO, "a FIFO"),
        (stat.S_ISSOCK, "a socket"),
        (stat.S_ISCHR, "a character device"),
        (stat.S_ISBLK, "a block device"),
    ):
        if test(mode):
            return name
    return "not a regular file"


def target_kind(path, devices: bool = False, option: str = "--out") -> str:
    """``"new"``, ``"file"`` (a regular file, replaced) or ``"device"`` (written straight into;
    only with ``devices``); anything else raises :class:`OutputError`."""
    path = Path(path)
    if devices and str(path) in STREAMS:
        return "device"
    try:
        st = os.lstat(path)
    except FileNotFoundError:
        return "new"
    except OSError as err:
        raise OutputError(f"{option} {path}: cannot be used ({err.strerror})") from None
    if stat.S_ISREG(st.st_mode):
        return "file"
    if devices and (stat.S_ISCHR(st.st_mode) or stat.S_ISLNK(st.st_mode)):
        with contextlib.suppress(OSError):
            if stat.S_ISCHR(os.stat(path).st_mode):  # a link the user named to a device, e.g. a tty
                return "device"
    raise OutputError(
        f"{option} {path}: is {describe(st.st_mode)}; jointdyn writes regular files only "
        "and never follows or replaces links or special files"
        + (" (a character device such as /dev/null is written into)" if devices else "")
    )


def _exclusive(path: Path) -> Path:
    """Create an empty temporary sibling of ``path`` exclusively (never through a link)."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC
    parent = path.parent
    if not parent.is_dir():
        raise OutputError(f"{path}: the directory {parent} does not exist")
    for _ in range(100):
        tmp = temp_name(path)
        try:
            os.close(os.open(tmp, flags, 0o600))
            return tmp
        except FileExistsError:
            continue  # someone's file (or link) at this name: draw another
        except OSError as err:
            raise OutputError(f"{path}: cannot write in {parent} ({err.strerror})") from None
    raise OutputError(f"{path}: no free temporary name in {parent}")  # pragma: no cover


@contextlib.contextmanager
def replacing(path, devices: bool = False, option: str = "--out") -> Iterator[Path]:
    """Yield a fresh temporary path for ``path``; on a clean exit make it ``path`` (see the
    module docstring); on any exception remove it and leave ``path`` untouched. With
    ``devices``, a character device at ``path`` is written straight into."""
    path = Path(path)
    if target_kind(path, devices, option) == "device":
        with _into_device(path) as tmp:
            yield tmp
        return
    tmp = _exclusive(path)
    try:
        yield tmp
        fd = os.open(tmp, os.O_RDONLY | os.O_NOFOLLOW | os.O_CLOEXEC)
        try:
            os.fsync(fd)
            os.fchmod(fd, file_mode())
        finally:
            os.close(fd)
        target_kind(path, False, option)  # still absent or a regular file: replaced, never followed
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            tmp.unlink()
        raise


@contextlib.contextmanager
def _into_device(path: Path) -> Iterator[Path]:
    """Write into a private temporary file, then copy it into the device (never replaced)."""
    fd, name = tempfile.mkstemp(prefix="jointdyn-", suffix=path.suffix)
    os.close(fd)
    tmp = Path(name)
    try:
        yield tmp
        with open(tmp, "rb") as src:
            if str(path) in STREAMS:
                stream = sys.stdout if STREAMS[str(path)] == 1 else sys.stderr
                with contextlib.suppress(Exception):
                    stream.flush()
                _copy(src, STREAMS[str(path)])
            else:
                dst = os.open(path, os.O_WRONLY | os.O_NOCTTY | os.O_CLOEXEC)
                try:
                    _copy(src, dst)
                finally:
                    os.close(dst)
    finally:
        tmp.unlink(missing_ok=True)


def _copy(src, fd: int) -> None:
    for block in iter(lambda: src.read(1 << 16), b""):
        view = memoryview(block)
        while view:
            view = view[os.write(fd, view) :]


def write_bytes(path, data: bytes, devices: bool = False) -> None:
    """Write ``data`` to ``path`` safely (:func:`replacing`)."""
    with replacing(path, devices) as tmp:
        tmp.write_bytes(data)


def write_text(path, text: str, devices: bool = False) -> None:
    """Write UTF-8 ``text`` to ``path`` safely."""
    write_bytes(path, text.encode("utf-8"), devices)


def write_json(path, data) -> None:
    """Write ``data`` as indented JSON to ``path`` safely (non-JSON values via ``str``)."""
    write_text(path, json.dumps(data, indent=2, default=str) + "\n")


def regular_input(path, option: str = "input") -> Path:
    """``path`` if it is a regular file (links followed); a FIFO, socket or device raises a
    one-line ``ValueError`` (reading it could block forever). Missing files and directories are
    left to the caller's own message."""
    path = Path(path)
    try:
        mode = os.stat(path).st_mode
    except OSError:
        return path
    if not (stat.S_ISREG(mode) or stat.S_ISDIR(mode)):
        raise ValueError(f"{option} {path}: is {describe(mode)}, not a regular file")
    return path


def sha256(path) -> str:
    """Hex SHA-256 of a file's bytes (streamed)."""
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()
