"""Memory and disk checks of a run before it starts: the result arrays must fit [T141], and so
must its files [T331]."""

from __future__ import annotations

import math
import os
import shutil
from pathlib import Path


def available_memory() -> int:
    """Bytes of memory available to a new allocation (MemAvailable, else physical memory)."""
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:  # pragma: no cover - not Linux
        pass
    return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")


def _sizes(obj) -> tuple[int, int, int]:
    """(coordinates, multiplier rows, per-sample element columns) of a Model or System."""
    if hasattr(obj, "items") and hasattr(obj, "bodies"):  # a Model: count without compiling
        items = list(obj.items.values())
        n = 3 * len(obj.bodies)
        m = sum(type(i).rows for i in items if hasattr(type(i), "rows"))
        els = [i for i in items if hasattr(type(i), "OUTPUTS")]
    else:
        n, m, els = obj.n, sum(b - a for a, b in obj.constraint_rows), list(obj.elements)
    return n, m, sum(len(type(e).OUTPUTS) + len(type(e).MEMORY) for e in els)


def check_memory(model_or_system, n_out, what: str = "n_out") -> None:
    """Refuse a run whose result arrays cannot fit: the estimate counts the time-first arrays
    of :class:`~jointdyn.simulation.results.Results` (y, q̈, λ, element outputs and memory, drift) three
    times (integrator chunks, concatenation, writing) [T141]."""
    n, m, e = _sizes(model_or_system)
    need = 3 * 8 * (3 * n + m + 2 + e) * float(n_out)
    have = available_memory()
    if not math.isfinite(need) or need > 0.8 * have:
        raise ValueError(
            f"{what}: {float(n_out):.6g} output samples need ≈ {need / 2**30:.3g} GiB of memory, "
            f"{have / 2**30:.3g} GiB are available; lower the number of samples or the duration"
        )


#: upper estimate of the bytes one output sample writes per column: 8 in results.nc (float64)
#: plus 24 in timeseries.csv (17 significant digits, sign, exponent, separator) [T331]
BYTES_PER_VALUE = 8 + 24


def check_disk(model_or_system, n_out, out, what: str = "n_out") -> float:
    """Refuse a run whose results.nc and timeseries.csv cannot fit on the file system of ``out``
    (its nearest existing parent) before any work [T331]; returns the estimate [bytes]."""
    n, m, e = _sizes(model_or_system)
    need = BYTES_PER_VALUE * (3 * n + m + 2 + e) * float(n_out)
    where = Path(out).absolute()
    while not where.exists() and where != where.parent:
        where = where.parent
    free = shutil.disk_usage(where).free
    if not math.isfinite(need) or need > free:
        raise ValueError(
            f"{what}: {float(n_out):.6g} output samples write ≈ {need / 2**30:.3g} GiB "
            f"(results.nc + timeseries.csv), {free / 2**30:.3g} GiB are free on {where}; "
            "lower the number of samples or the duration, or free space"
        )
    return need
