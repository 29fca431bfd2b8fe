"""``python -m jointdyn`` = the ``jointdyn`` command."""

from jointdyn.cli import app

app()
