"""Output directories a command owns: checked before any work, locked while written, described by
a manifest written last; files are written by :mod:`jointdyn.core.atomic` (exclusive temporary
names, never through links or special files).

Rules (``docs/user-guide/cli.md``):

* A directory that holds files is refused unless ``overwrite`` (or, for a sweep or bifurcation,
  ``resume`` with the same spec). **Ownership is the manifest's list only**: ``overwrite``
  removes exactly the files the previous ``manifest.json`` lists (and the files an unfinished,
  killed run recorded in its lock file, and temporaries of dead jointdyn processes); every other
  file is kept and named in one warning line. A kept file with a name this command writes
  makes it refuse (it would be replaced).
* One writer at a time: ``.jointdyn.lock`` is created exclusively (``O_EXCL|O_NOFOLLOW``; a
  link or special file there is refused, never written through) and held with ``flock``; it
  records the owner's pid and, before each file is renamed into place, that file's name (so a
  killed run's files are known to the next ``--overwrite``). It is removed when the writer ends;
  a lock left by a dead process is taken over.
* Derived outputs (:func:`jointdyn.io.derived.derived`: ``poincare``, ``spectrum``, ``plot``,
  ``plot-sweep``, ``animate``, ``bearing-table``, ``stribeck``, ``film-force`` into a directory
  with a manifest) are added to that manifest under the lock.
"""

from __future__ import annotations

import contextlib
import datetime
import fcntl
import fnmatch
import json
import os
import socket
import stat
import sys
import time
import warnings
from pathlib import Path, PurePosixPath

from jointdyn.core import atomic
from jointdyn.core.atomic import OutputError

__all__ = ["LOCK", "MANIFEST", "OutputDir", "OutputError", "check_path", "read_manifest"]

MANIFEST = "manifest.json"
LOCK = ".jointdyn.lock"
#: names each kind writes (patterns): a kept foreign file matching one makes a claim refuse early
EXPECT = {
    "run": ("results.nc", "timeseries.csv", "summary.json", "model.toml", "moment.png", "orbit.png"),
    "sweep": ("cases", "sweep.nc", "spec.json"),
    "bifurcation": ("sweep", "bifurcation.nc", "bifurcation.png"),
    "reproduce": ("summary.csv", "summary.md", "report.html", "interactive.html", "ensemble_dry.*"),
    "lyapunov": ("summary.json", "lyapunov.csv", "lyapunov.png"),
    "ensemble": ("ensemble.json",),
}

#: lock file descriptors held by this process (forked workers close their inherited copies)
HELD: set[int] = set()
#: how long a lock whose recorded owner is dead may still be held by its dying children [s]
ORPHAN_WAIT = 5.0


class KeptFiles(UserWarning):
    """``--overwrite`` kept files that jointdyn did not write (named in the message)."""


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
            pid = _lock_pid(os.pread(fd, 512, 0))
            if pid is None or atomic.alive(pid):
                return False
            deadline = time.monotonic() + ORPHAN_WAIT
        if time.monotonic() > deadline:
            return False
        time.sleep(0.05)


def _lock_pid(text: bytes) -> int | None:
    words = text.decode("utf-8", "replace").split()
    return int(words[1]) if len(words) > 1 and words[0] == "pid" and words[1].isdigit() else None


def close_inherited() -> None:
    """In a forked worker: close the lock descriptors inherited from the parent, so the lock
    ends with the parent."""
    for fd in list(HELD):
        with contextlib.suppress(OSError):
            os.close(fd)
    HELD.clear()


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
    """The manifest of directory ``path`` (None if absent, unreadable or not a regular file)."""
    try:
        fd = os.open(Path(path) / MANIFEST, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC)
    except OSError:
        return None
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            return None
        with os.fdopen(fd, "rb", closefd=False) as f:
            data = json.loads(f.read().decode("utf-8"))
        return data if isinstance(data, dict) else None
    except (OSError, ValueError):
        return None
    finally:
        os.close(fd)


def _entries(path: Path) -> list[Path]:
    """Visible entries of ``path`` (the lock and temporary files aside)."""
    return sorted(p for p in path.iterdir() if p.name != LOCK and not atomic.is_temp(p))


def _inside(root: Path, name: str) -> Path | None:
    """``root/name`` for a plain relative name whose directories are real (no link, no ``..``)."""
    parts = PurePosixPath(name).parts
    if not parts or name.startswith("/") or any(p in ("..", ".", "") for p in parts):
        return None
    p = root
    for part in parts[:-1]:
        p = p / part
        try:
            if not stat.S_ISDIR(os.lstat(p).st_mode):
                return None
        except OSError:
            return None
    return root.joinpath(*parts)


def check_path(path, option: str = "--out") -> Path:
    """Fail early (before simulating) if ``path`` cannot become an output directory."""
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise OutputError(f"{option} {path}: is a file, not a directory; choose a directory path")
    probe = path
    while not probe.exists():
        if probe.is_symlink():
            raise OutputError(f"{option} {path}: {probe} is a dangling symbolic link")
        probe = probe.parent
    if not probe.is_dir():
        raise OutputError(f"{option} {path}: {probe} is a file, so the directory cannot be created")
    if not os.access(probe, os.W_OK | os.X_OK):
        raise OutputError(f"{option} {path}: {probe} is not writable; choose a writable directory")
    return path


class OutputDir:
    """An output directory claimed for one command (see the module docstring).

    ``claim()`` locks it and clears (or refuses) old contents; ``write(name)`` yields a temporary
    path that becomes ``name`` on success; ``finish(status, reason)`` writes the manifest and
    releases the lock (removing it).
    """

    def __init__(self, path, kind: str, spec: dict, option: str = "--out"):
        self.path = Path(path)
        self.kind = kind
        self.spec = spec
        self.option = option
        self.files: dict[str, dict] = {}
        self.kept: list[str] = []
        self._fd: int | None = None
        self._owned: set[str] = set()  # names of earlier runs this one may replace
        self._core: set[str] = set()  # the extended directory's own outputs: never replaced [T356]
        self._derived: dict[str, str] = {}  # carried names a derived command wrote, and its kind
        self._journal: list[str] = []  # names a killed earlier run recorded, still in the lock file
        self._base: dict | None = None  # the manifest extended by derived outputs
        self._carried: list[str] = []  # files of the run a resumed one continues

    # -- claiming ---------------------------------------------------------------------------
    def claim(self, overwrite: bool = False, resume: bool = False, expect=()) -> OutputDir:
        """Lock the directory and clear it by the rules; ``expect``: further names (patterns)
        this command writes, refused early if a kept file has one."""
        check_path(self.path, self.option)
        self.check(overwrite, resume)  # refuse before leaving a lock in it
        try:
            self.path.mkdir(parents=True, exist_ok=True)
        except OSError as err:
            raise OutputError(f"{self.option} {self.path}: cannot create ({err.strerror})") from None
        self._lock()
        try:
            self._clear(overwrite, resume, (*EXPECT.get(self.kind, ()), *expect))
        except BaseException:
            self.release()
            raise
        return self

    def extend(self) -> None:
        """Lock a directory that has a manifest to add files to it (derived outputs)."""
        self._lock()
        self._base = read_manifest(self.path) or {"kind": self.kind, "status": "complete", "files": {}}
        listed = self._base.get("files", {})
        self._owned = {n for n, e in listed.items() if isinstance(e, dict) and e.get("derived")}
        self._core = set(listed) - self._owned

    def check(self, overwrite: bool = False, resume: bool = False) -> None:
        """Refuse, without touching anything, a non-empty directory when neither flag is given."""
        check_path(self.path, self.option)
        if overwrite or resume or not self.path.is_dir():
            return
        names = [p.name for p in _entries(self.path)]
        if names:
            old = read_manifest(self.path)
            what = f"results of a previous {old.get('kind', 'run')}" if old else "files"
            raise OutputError(
                f"{self.option} {self.path}: not empty (holds {what}: {', '.join(names[:5])}"
                f"{' …' if len(names) > 5 else ''}); pass --overwrite to replace jointdyn's files there"
                + (" or --resume to continue" if self.kind in ("sweep", "bifurcation") else "")
                + ", or choose another directory"
            )

    def _lock(self) -> None:
        p = self.path / LOCK
        for _ in range(100):
            created = True
            try:
                fd = os.open(p, os.O_RDWR | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC, 0o644)
            except FileExistsError:
                created = False
                try:
                    fd = os.open(p, os.O_RDWR | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC)
                except FileNotFoundError:
                    continue
                except OSError as err:  # ELOOP: a symbolic link
                    raise OutputError(
                        f"{self.option} {self.path}: {LOCK} is not a jointdyn lock ({err.strerror}); "
                        "remove it"
                    ) from None
            except OSError as err:
                raise OutputError(
                    f"{self.option} {self.path}: cannot create a lock file ({err.strerror})"
                ) from None
            st = os.fstat(fd)
            if not stat.S_ISREG(st.st_mode):
                os.close(fd)
                what = atomic.describe(st.st_mode)
                raise OutputError(f"{self.option} {self.path}: {LOCK} is {what}; remove it")
            if not _flock(fd):
                holder = os.pread(fd, 512, 0).decode("utf-8", "replace").splitlines()
                os.close(fd)
                raise OutputError(
                    f"{self.option} {self.path}: another jointdyn process is writing there "
                    f"({holder[0] if holder else 'unknown process'}); wait for it to finish or choose "
                    "another directory"
                ) from None
            try:
                same = os.lstat(p).st_ino == st.st_ino
            except FileNotFoundError:
                same = False
            if not same:  # released (removed) while we waited: start again
                os.close(fd)
                continue
            if not created:  # a dead writer's lock: the files it recorded are jointdyn's
                text = os.pread(fd, 1 << 20, 0).decode("utf-8", "replace").splitlines()
                self._journal = [ln[5:] for ln in text if ln.startswith("file ")]
            self._fd = fd
            HELD.add(fd)
            self._rewrite_lock()
            return
        raise OutputError(f"{self.option} {self.path}: cannot take the lock")  # pragma: no cover

    def _rewrite_lock(self) -> None:
        assert self._fd is not None
        head = f"pid {os.getpid()} on {socket.gethostname()} since {_now()}\n"
        lines = [head, *(f"file {n}\n" for n in self._journal)]
        os.ftruncate(self._fd, 0)
        os.pwrite(self._fd, "".join(lines).encode(), 0)

    def _clear(self, overwrite: bool, resume: bool, expect) -> None:
        subdirs = [p for p in self.path.iterdir() if p.is_dir() and not p.is_symlink()]
        for t in [t for d in (self.path, *subdirs) for t in atomic.stale_temps(d)]:
            t.unlink(missing_ok=True)  # temporaries of dead jointdyn processes
        old = read_manifest(self.path)
        listed = set((old or {}).get("files", {})) | set(self._journal)
        entries = _entries(self.path)
        if not entries:
            return
        if resume and self.kind in ("sweep", "bifurcation"):
            self._owned = listed | {MANIFEST}
            self._carried = sorted(listed)  # still listed at the end if still there
            self._derived = {  # carried derived outputs stay marked as such [T356]
                n: e["derived"]
                for n, e in (old or {}).get("files", {}).items()
                if isinstance(e, dict) and e.get("derived")
            }
            return  # the sweep checks the spec itself (ownership) and keeps finished cases
        if not overwrite:
            self.check(False, False)
            return
        doomed, tops = [], set()
        for name in sorted(listed):
            p = _inside(self.path, name)
            if p is not None and p.is_file() and not p.is_symlink():
                doomed.append(p)
                tops.add(PurePosixPath(name).parts[0])
        if read_manifest(self.path) is not None:
            doomed.append(self.path / MANIFEST)
            tops.add(MANIFEST)
        kept = [p.name for p in entries if p.name not in tops]
        clash = [n for n in kept if any(fnmatch.fnmatch(n, pat) for pat in expect)]
        if clash:
            why = (  # listed but now a link or special file: never removed through [T335]
                "is listed in its manifest but is now a link or special file, which jointdyn never removes"
                if clash[0] in listed
                else "jointdyn did not write (not in its manifest)"
            )
            raise OutputError(
                f"{self.option} {self.path}: holds {', '.join(clash[:5])}, which {why} and this command "
                "would replace; move it or choose another directory"
            )
        for p in doomed:
            p.unlink(missing_ok=True)
        for top in tops:  # directories emptied by the removal (e.g. a sweep's cases/)
            d = self.path / top
            if d.is_dir() and not d.is_symlink():
                subs = (q for q in d.rglob("*") if q.is_dir() and not q.is_symlink())
                for sub in sorted(subs, reverse=True):
                    with contextlib.suppress(OSError):
                        sub.rmdir()
                with contextlib.suppress(OSError):
                    d.rmdir()
        self._owned = listed | {MANIFEST}
        self._journal = []
        self._rewrite_lock()
        self.kept = [p.name for p in _entries(self.path)]
        if self.kept:
            warnings.warn(
                f"{self.option} {self.path}: kept {len(self.kept)} file(s) jointdyn did not write: "
                + ", ".join(self.kept[:10])
                + (" …" if len(self.kept) > 10 else ""),
                KeptFiles,
                stacklevel=3,
            )

    # -- writing ----------------------------------------------------------------------------
    @contextlib.contextmanager
    def write(self, name: str):
        """Yield a temporary path for file ``name``; renamed to it (and recorded) on success.
        A file there that jointdyn did not write is refused, never replaced."""
        final = _inside(self.path, name)
        if final is None:
            raise OutputError(f"{self.option} {self.path}: {name!r} is not a plain file name")
        if name in self._core and name not in self.files:
            raise OutputError(
                f"{self.option} {final}: {name} is an output of this {self._base_kind()} (its manifest "
                "lists it), not a derived file, and is never replaced by one; choose another name"
            )
        if os.path.lexists(final) and name not in self.files and name not in self._owned:
            raise OutputError(
                f"{self.option} {self.path}: {name} is there and jointdyn did not write it "
                "(not in its manifest); move it or choose another directory"
            )
        with atomic.replacing(final, option=self.option) as tmp:
            yield tmp
            self.journal(name)
        self.record(name)

    def adopt(self, name: str) -> None:
        """Let this run replace ``name`` (a resumed sweep's ``spec.json``, checked equal)."""
        self._owned.add(name)

    def journal(self, name: str) -> None:
        """Record in the lock file that ``name`` is being written (known to a later
        ``--overwrite`` even if this process is killed)."""
        if self._fd is not None and name not in self._journal:
            self._journal.append(name)
            os.pwrite(self._fd, f"file {name}\n".encode(), os.fstat(self._fd).st_size)

    def record(self, name: str) -> None:
        """Add a complete file (written by this run) to the manifest's list."""
        self.journal(name)
        p = self.path / name
        self.files[name] = {"bytes": p.stat().st_size, "sha256": atomic.sha256(p)}
        if self._base is not None:  # written by a derived command: a later one may replace it
            self.files[name]["derived"] = self.kind

    def _base_kind(self) -> str:
        return str((self._base or {}).get("kind", "run"))

    def finish(self, status: str = "complete", reason: str = "", **extra) -> None:
        """Write ``manifest.json`` (last) and release the lock."""
        for name in self._carried:  # a resumed directory's earlier files it did not rewrite
            p = _inside(self.path, name)
            if name not in self.files and p is not None and p.is_file() and not p.is_symlink():
                self.record(name)
                if name in self._derived:
                    self.files[name]["derived"] = self._derived[name]
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
        if self._base is not None:  # derived outputs added to an existing manifest (io.derived)
            manifest = self._base | {"files": self._base.get("files", {}) | self.files, "updated": _now()}
        try:
            if self._fd is not None:
                with atomic.replacing(self.path / MANIFEST, option=self.option) as tmp:
                    tmp.write_text(json.dumps(manifest, indent=2, default=str) + "\n", encoding="utf-8")
        finally:
            self.release()

    def release(self) -> None:
        """Remove the lock file (unless it still carries a killed run's file list) and unlock."""
        if self._fd is not None:
            HELD.discard(self._fd)
            with contextlib.suppress(OSError):
                if not self._journal or self.files:
                    if os.lstat(self.path / LOCK).st_ino == os.fstat(self._fd).st_ino:
                        os.unlink(self.path / LOCK)
            with contextlib.suppress(OSError):
                fcntl.flock(self._fd, fcntl.LOCK_UN)
            with contextlib.suppress(OSError):
                os.close(self._fd)
            self._fd = None
