"""Output directories a run or sweep owns: checked before any work, locked while written,
described by a manifest written last.

Policy (``docs/user-guide/cli.md``): a directory that already holds files is refused unless
``overwrite`` (then the files jointdyn wrote there — those its manifest lists and jointdyn's
own output names — are removed first; anything else present is refused, never deleted) or, for
a sweep, ``resume`` with the same spec. One writer at a time: ``.jointdyn.lock`` is held with
``flock`` for the whole run (released by the kernel when the process dies, so a killed run never
leaves a stale lock). Every file is written atomically (:mod:`jointdyn.core.atomic`);
``manifest.json`` — files with size and SHA-256, jointdyn version, the input spec, status
``complete``/``partial``/``failed``/``interrupted`` and the reason — is written last, so a
directory without a manifest was never finished.
"""

from __future__ import annotations

import contextlib
import datetime
import fcntl
import fnmatch
import json
import os
import shutil
import socket
import sys
import time
from pathlib import Path

from jointdyn.core import atomic

MANIFEST = "manifest.json"
LOCK = ".jointdyn.lock"
#: names jointdyn writes into a directory of each kind (patterns); all else is foreign
OWN_NAMES = {
    "run": ("results.nc", "timeseries.csv", "summary.json", "model.toml", "*.png", "*.gif", "*.mp4"),
    "sweep": ("cases", "sweep.nc", "spec.json", "*.png"),
    "reproduce": ("*.csv", "*.png", "report.html", "interactive.html", "summary.md"),
}


#: lock file descriptors held by this process (forked workers close their inherited copies)
HELD: set[int] = set()
#: how long a lock whose recorded owner is dead may still be held by its dying children [s]
ORPHAN_WAIT = 5.0


def _flock(fd: int) -> bool:
    """Take the exclusive lock; if it is held but its recorded owner process is dead (its
    workers are being killed with it), wait up to ``ORPHAN_WAIT`` for the release."""
    deadline = None
    while True:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            return True
        except BlockingIOError:
            pass
        if deadline is None:
            words = os.pread(fd, 512, 0).decode("utf-8", "replace").split()
            pid = int(words[1]) if len(words) > 1 and words[0] == "pid" and words[1].isdigit() else None
            if pid is None or _alive(pid):
                return False
            deadline = time.monotonic() + ORPHAN_WAIT
        if time.monotonic() > deadline:
            return False
        time.sleep(0.05)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def close_inherited() -> None:
    """In a forked worker: close the lock descriptors inherited from the parent, so the lock
    ends with the parent."""
    for fd in list(HELD):
        with contextlib.suppress(OSError):
            os.close(fd)
    HELD.clear()


class OutputError(ValueError):
    """An output path that cannot be used (a file, read-only, busy, foreign or stale)."""


def version() -> str:
    """The installed jointdyn version ("unknown" from a bare source tree)."""
    from importlib.metadata import PackageNotFoundError
    from importlib.metadata import version as v

    try:
        return v("jointdyn")
    except PackageNotFoundError:  # pragma: no cover
        return "unknown"


def _now() -> str:
    return datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")


def read_manifest(path: Path) -> dict | None:
    """The manifest of directory ``path`` (None if absent or unreadable)."""
    try:
        return json.loads((Path(path) / MANIFEST).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None


def _entries(path: Path) -> list[Path]:
    """Visible entries of ``path`` (the lock and temporary files aside)."""
    return sorted(p for p in path.iterdir() if p.name != LOCK and not atomic.is_temp(p))


def _own(kind: str, name: str, manifest: dict | None) -> bool:
    listed = set((manifest or {}).get("files", {})) | {MANIFEST}
    return name in listed or any(fnmatch.fnmatch(name, pat) for pat in OWN_NAMES[kind])


def check_path(path, option: str = "--out") -> Path:
    """Fail early (before simulating) if ``path`` cannot become an output directory."""
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise OutputError(f"{option} {path}: is a file, not a directory; choose a directory path")
    probe = path
    while not probe.exists():
        probe = probe.parent
    if not probe.is_dir():
        raise OutputError(f"{option} {path}: {probe} is a file, so the directory cannot be created")
    if not os.access(probe, os.W_OK | os.X_OK):
        raise OutputError(f"{option} {path}: {probe} is not writable; choose a writable directory")
    return path


class OutputDir:
    """An output directory claimed for one run or sweep (see the module docstring).

    ``claim()`` locks it and clears (or refuses) old contents; ``write(name)`` yields a temporary
    path that becomes ``name`` on success; ``finish(status, reason)`` writes the manifest and
    releases the lock.
    """

    def __init__(self, path, kind: str, spec: dict, option: str = "--out"):
        self.path = Path(path)
        self.kind = kind
        self.spec = spec
        self.option = option
        self.files: dict[str, dict] = {}
        self._fd: int | None = None

    # -- claiming ---------------------------------------------------------------------------
    def claim(self, overwrite: bool = False, resume: bool = False) -> OutputDir:
        check_path(self.path, self.option)
        if self.path.is_dir() and not (overwrite or resume):
            self._clear(False, False)  # refuse a non-empty directory before leaving a lock in it
        try:
            self.path.mkdir(parents=True, exist_ok=True)
        except OSError as err:
            raise OutputError(f"{self.option} {self.path}: cannot create ({err.strerror})") from None
        self._lock()
        try:
            self._clear(overwrite, resume)
        except BaseException:
            self.release()
            raise
        return self

    def _lock(self) -> None:
        try:
            fd = os.open(self.path / LOCK, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o644)
        except OSError as err:
            raise OutputError(
                f"{self.option} {self.path}: cannot create a lock file ({err.strerror})"
            ) from None
        if not _flock(fd):
            holder = os.pread(fd, 512, 0).decode("utf-8", "replace").strip() or "unknown process"
            os.close(fd)
            raise OutputError(
                f"{self.option} {self.path}: another jointdyn process is writing there ({holder}); "
                "wait for it to finish or choose another directory"
            ) from None
        os.ftruncate(fd, 0)
        os.pwrite(fd, f"pid {os.getpid()} on {socket.gethostname()} since {_now()}\n".encode(), 0)
        self._fd = fd
        HELD.add(fd)

    def _clear(self, overwrite: bool, resume: bool) -> None:
        entries = _entries(self.path)
        old = read_manifest(self.path)
        if not entries:
            return
        if resume and self.kind == "sweep":
            return  # the sweep checks the spec itself (ownership) and keeps finished cases
        names = [p.name for p in entries]
        if not overwrite:
            what = f"results of a previous {old.get('kind', 'run')}" if old else "files"
            raise OutputError(
                f"{self.option} {self.path}: not empty (holds {what}: {', '.join(names[:5])}"
                f"{' …' if len(names) > 5 else ''}); pass --overwrite to replace jointdyn's files there"
                + (" or --resume to continue the sweep" if self.kind == "sweep" else "")
                + ", or choose another directory"
            )
        foreign = [n for n in names if not _own(self.kind, n, old)]
        if foreign:
            raise OutputError(
                f"{self.option} {self.path}: holds files jointdyn did not write ({', '.join(foreign[:5])}); "
                "--overwrite removes only jointdyn's own files, so choose another directory"
            )
        for p in entries:
            if p.is_dir() and not p.is_symlink():
                shutil.rmtree(p)
            else:
                p.unlink()

    # -- writing ----------------------------------------------------------------------------
    @contextlib.contextmanager
    def write(self, name: str):
        """Yield a temporary path for file ``name``; renamed to it (and recorded) on success."""
        final = self.path / name
        with atomic.replacing(final) as tmp:
            yield tmp
        self.record(name)

    def record(self, name: str) -> None:
        """Add an already complete file to the manifest's list."""
        p = self.path / name
        self.files[name] = {"bytes": p.stat().st_size, "sha256": atomic.sha256(p)}

    def finish(self, status: str = "complete", reason: str = "", **extra) -> None:
        """Write ``manifest.json`` (last) and release the lock."""
        manifest = {
            "kind": self.kind,
            "status": status,
            "reason": reason,
            "jointdyn_version": version(),
            "python": sys.version.split()[0],
            "written": _now(),
            "command": sys.argv,
            "spec": self.spec,
            "files": self.files,
            **extra,
        }
        try:
            atomic.write_json(self.path / MANIFEST, manifest)
        finally:
            self.release()

    def release(self) -> None:
        if self._fd is not None:
            HELD.discard(self._fd)
            with contextlib.suppress(OSError):
                fcntl.flock(self._fd, fcntl.LOCK_UN)
                os.close(self._fd)
            self._fd = None
