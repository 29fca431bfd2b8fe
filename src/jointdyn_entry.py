"""The ``jointdyn`` console script: imports the CLI inside a guard, so that Ctrl-C while the
libraries load (the first second or so) ends with one line and exit code 130, not a traceback
of the import machinery (a module outside the package: importing ``jointdyn`` itself is the
slow part)."""

from __future__ import annotations

import sys


def main() -> None:
    """Run the ``jointdyn`` command line (:mod:`jointdyn.cli`)."""
    try:
        from jointdyn.cli import app
    except KeyboardInterrupt:
        print("interrupted by SIGINT while starting", file=sys.stderr)
        raise SystemExit(130) from None
    app()


if __name__ == "__main__":
    main()
