"""Command-line interface (thin shell over the library).

Every command checks all its inputs before any work, writes its outputs atomically, and ends
a problem with one line on stderr and a non-zero exit code: 2 bad input or output path, 1 a
failed simulation (partial results written with their status), 130 Ctrl-C (SIGINT), 143
SIGTERM — never a traceback. The commands live in modules named after what they do and
register themselves on the one application of :mod:`jointdyn.cli.common`; importing them here
fixes the order of ``jointdyn --help``.
"""

from __future__ import annotations

# the registration order is the order of ``jointdyn --help``
# isort: off
from jointdyn.cli.common import _progress, app
from jointdyn.cli import main  # noqa: F401  run, reproduce, sweep
from jointdyn.cli import files  # noqa: F401  plot, plot-sweep, animate, film-force, list
from jointdyn.cli import bearing  # noqa: F401  bearing-table
from jointdyn.cli import stribeck  # noqa: F401  stribeck
from jointdyn.cli import chaos  # noqa: F401  poincare, bifurcation, lyapunov, spectrum, ensemble
from jointdyn.cli import cache  # noqa: F401  cache info, cache clear

# isort: on

__all__ = ["_progress", "app", "main"]
