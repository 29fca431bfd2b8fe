"""numba settings for jointdyn's own compiled kernels, and for nothing else [T171, T225].

Importing jointdyn changes no numba configuration (``numba.config`` stays as the user set it);
two settings are applied to functions *defined in this package* only:

* **Optimisation level** -O1 (numba's default is -O3; measured faster to compile and to run on
  these small loops, trajectories bit-identical, [T171]): a compile-event listener lowers
  ``numba.config.OPT`` while numba compiles one of jointdyn's functions and restores it when that
  compilation ends. ``NUMBA_OPT`` in the environment wins (then nothing is changed).
* **Cache directory** ``~/.cache/jointdyn/numba-<hash of the package sources and the level>``: a
  cache locator that serves only functions whose source file lies in this package (numba
  invalidates a cached function only when its *own* file changes, not when a compiled function
  it calls from another module does, so a per-source-hash directory makes every edit or upgrade
  start clean). Other packages' functions keep numba's own cache rules; ``NUMBA_CACHE_DIR``,
  when set, is numba's choice for every function, jointdyn's included.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

from numba.core import caching, config, event

#: LLVM optimisation level of jointdyn's kernels unless NUMBA_OPT is set [T171]
OPT_LEVEL = 1
PACKAGE = Path(__file__).resolve().parents[1]


def _source_hash() -> str:
    h = hashlib.sha1()
    h.update(os.environ.get("NUMBA_OPT", f"jointdyn-O{OPT_LEVEL}").encode())  # code of another level
    for f in sorted(PACKAGE.rglob("*.py")):
        h.update(f.relative_to(PACKAGE).as_posix().encode())
        h.update(f.read_bytes())
    return h.hexdigest()[:16]


def cache_base() -> Path:
    """jointdyn's cache directory, ``$XDG_CACHE_HOME/jointdyn`` or ``~/.cache/jointdyn``."""
    return Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "jointdyn"


def cache_root() -> Path:
    """The directory of jointdyn's compiled-kernel cache for these sources (content-keyed)."""
    return cache_base() / f"numba-{_source_hash()}"


def cache_entries() -> list[dict]:
    """What jointdyn keeps in :func:`cache_base`: one entry per directory with its ``kind``
    ("kernels" for these sources, "stale kernels" of other sources, "film tables"), ``path``,
    ``files`` and ``bytes`` [B]."""
    base, current = cache_base(), cache_root().name
    out = []
    for d in sorted(base.iterdir()) if base.is_dir() else ():
        if not d.is_dir() or d.is_symlink():
            continue
        if d.name.startswith("numba-"):
            kind = "kernels" if d.name == current else "stale kernels"
        elif d.name == "finite_tables":
            kind = "film tables"
        else:
            continue
        files = [f for f in d.rglob("*") if f.is_file() and not f.is_symlink()]
        out.append(
            {"kind": kind, "path": d, "files": len(files), "bytes": sum(f.stat().st_size for f in files)}
        )
    return out


def clear_cache(stale_only: bool = False) -> list[dict]:
    """Delete jointdyn's cache directories (only the stale kernels with ``stale_only``); returns
    the entries removed. Nothing else under the cache directory is touched."""
    import shutil

    gone = [e for e in cache_entries() if not stale_only or e["kind"] == "stale kernels"]
    for e in gone:
        shutil.rmtree(e["path"])
    return gone


_ROOT: str | None = None


class _JointdynCacheLocator(caching._SourceFileBackedLocatorMixin, caching._CacheLocator):
    """Cache files of jointdyn's functions in :func:`cache_root` (only those)."""

    def __init__(self, py_func, py_file):
        self._py_file = py_file
        self._lineno = py_func.__code__.co_firstlineno
        self._cache_path = os.path.join(_ROOT or "", self.get_suitable_cache_subpath(py_file))

    def get_cache_path(self):
        return self._cache_path

    def get_source_stamp(self):
        """The sources' content hash, not the file's mtime: the directory is already keyed to the
        content, so a reinstall of unchanged sources (new mtimes) keeps its compiled kernels."""
        return _ROOT

    @classmethod
    def from_function(cls, py_func, py_file):
        global _ROOT
        if config.CACHE_DIR or not _inside_package(py_file):
            return None
        if _ROOT is None:
            try:
                root = cache_root()
                root.mkdir(parents=True, exist_ok=True)
                _ROOT = str(root)
            except OSError:  # read-only home: numba's own locators (__pycache__) take over
                return None
        return super().from_function(py_func, py_file)


def _inside_package(py_file) -> bool:
    try:
        return Path(py_file).resolve().is_relative_to(PACKAGE)
    except (OSError, ValueError):
        return False


class _ScopedOptLevel(event.Listener):
    """Sets numba's LLVM level to :data:`OPT_LEVEL` while one of jointdyn's functions compiles
    (nested compilations included) and restores the user's level afterwards."""

    def __init__(self):
        self._saved: list = []

    def on_start(self, ev) -> None:
        func = getattr(ev.data.get("dispatcher"), "py_func", None)
        module = getattr(func, "__module__", "") or ""
        self._saved.append(config.OPT)
        if module == "jointdyn" or module.startswith("jointdyn."):
            from numba.core.config import _OptLevel

            config.OPT = _OptLevel(OPT_LEVEL)

    def on_end(self, ev) -> None:
        if self._saved:
            config.OPT = self._saved.pop()


_installed = False


def install() -> None:
    """Apply the two settings above to jointdyn's functions (idempotent; called on import of the
    package, before any kernel is defined)."""
    global _installed
    if _installed:
        return
    _installed = True
    caching.CacheImpl._locator_classes.insert(0, _JointdynCacheLocator)
    if "NUMBA_OPT" not in os.environ:
        event.register("numba:compile", _ScopedOptLevel())
