"""jointdyn: planar multibody dynamics with ideal, clearance and lubricated joints."""

from __future__ import annotations


def _numba_cache_dir() -> None:
    """Key numba's on-disk cache to a hash of this package's sources.

    numba invalidates a cached function only when *its own* file changes, not when a compiled
    function it calls (in another module) does; a stale cache then silently runs old code. A
    cache directory per source hash makes every edit or upgrade start clean. An explicit
    ``NUMBA_CACHE_DIR`` is respected (e.g. the cold-start benchmark)."""
    import hashlib
    import os
    from pathlib import Path

    if os.environ.get("NUMBA_CACHE_DIR"):
        return
    h = hashlib.sha1()
    root = Path(__file__).parent
    for f in sorted(root.rglob("*.py")):
        h.update(f.relative_to(root).as_posix().encode())
        h.update(f.read_bytes())
    base = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "jointdyn"
    try:
        target = base / f"numba-{h.hexdigest()[:16]}"
        target.mkdir(parents=True, exist_ok=True)
    except OSError:  # read-only home: fall back to numba's default (__pycache__)
        return
    import numba

    numba.config.CACHE_DIR = str(target)


_numba_cache_dir()
