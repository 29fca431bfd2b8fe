"""``python -m jointdyn`` = the ``jointdyn`` command."""

from .cli import app

app()
