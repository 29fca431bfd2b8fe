"""Command-line interface (thin shell over the library).

Every command checks all its inputs before any work, writes its outputs atomically, and ends
a problem with one line on stderr and a non-zero exit code: 2 bad input or output path, 1 a
failed simulation (partial results written with their status), 130 Ctrl-C (SIGINT), 143
SIGTERM — never a traceback. The commands live in modules named after what they do and
register themselves on the one application of :mod:`jointdyn.cli.common`; importing them here
fixes the order of ``jointdyn --help``.
"""

from __future__ import annotations

from jointdyn.cli import (
    bearing,  # noqa: F401  bearing-table
    chaos,  # noqa: F401  ensemble, poincare, bifurcation, lyapunov, spectrum
    files,  # noqa: F401  plot, plot-sweep, animate, film-force, list
    main,  # noqa: F401  run, reproduce, sweep
)

# isort: off  (registration order is the order of ``jointdyn --help``)
from jointdyn.cli.common import _progress, app

# isort: on

__all__ = ["_progress", "app", "main"]
