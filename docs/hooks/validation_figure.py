"""MkDocs hook: render the Validation page's figure (computed design table over the published
Raimondi–Boyd and Butenschön points) into the built site as ``figures/validation_raimondi_boyd.png``.

Nothing is written into ``docs/``: the figure is whatever the current solver produces."""

from __future__ import annotations

import tempfile
from pathlib import Path

from mkdocs.structure.files import File

NAME = "figures/validation_raimondi_boyd.png"


def on_files(files, config):
    from jointdyn.bearing.validation import plot_validation

    root = Path(config.config_file_path).resolve().parent
    tmp = Path(tempfile.mkdtemp(prefix="jointdyn-validation-"))
    (tmp / "figures").mkdir()
    data = root / "tests" / "data"
    plot_validation(data / "raimondi_boyd_1958.csv", tmp / NAME, data / "butenschoen_1976.csv")
    files.append(File(NAME, str(tmp), config["site_dir"], config["use_directory_urls"]))
    return files
