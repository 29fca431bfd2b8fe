"""The ``jointdyn`` console script: SIGINT and SIGTERM become one line from the first instant.

Until a command's own guard (:func:`jointdyn.core.interrupts.catching`) takes the signals over,
a signal raises :class:`_Signalled` here: while the libraries load (the first second or so) and
in the window between the CLI's import and the guard (the command's own imports). Each ends with
one line and the shell's exit code 128 + signal number (130, 143), not a traceback of the import
machinery (SIGINT) or a silent kill (SIGTERM, −15). A module outside the package: importing
``jointdyn`` itself is the slow part [T355].
"""

from __future__ import annotations

import signal
import sys


class _Signalled(BaseException):
    """A signal before (or after) a command's guard; not an ``Exception``, so that no handler in
    the CLI framework takes it for an error of the command."""


def _raise(signum, frame) -> None:
    raise _Signalled(signum)


def main() -> None:
    """Run the ``jointdyn`` command line (:mod:`jointdyn.cli`)."""
    where = " while starting"
    try:
        for s in (signal.SIGINT, signal.SIGTERM):
            signal.signal(s, _raise)
        from jointdyn.cli import app

        where = ""
        app()
    except _Signalled as sig:
        name = signal.Signals(sig.args[0]).name
        print(f"interrupted by {name}{where}", file=sys.stderr)
        raise SystemExit(128 + sig.args[0]) from None


if __name__ == "__main__":
    main()
