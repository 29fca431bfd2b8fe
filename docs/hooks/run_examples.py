"""MkDocs hook: run every ``examples/NN_*.py`` during the build and make a tutorial page of it.

Registered in ``mkdocs.yml`` under ``hooks:``. For each numbered example script the hook

1. runs it with the building interpreter (``sys.executable``) in a fresh temporary directory,
   with ``MPLBACKEND=Agg``, and fails the build (``PluginError``) if it exits non-zero, takes
   longer than ``TIMEOUT_S`` or saves no ``.png`` figure;
2. writes a generated page ``tutorials/<script>.md``: the script's docstring as the
   introduction, the full source, what it printed and every figure it saved;
3. fills the ``Tutorials`` section of the nav with these pages in file-name order.

It also registers a tiny Markdown extension so that the equation tags of the docstrings
(``[T14]``, ``[T60–T62]``) stay literal text: Python-Markdown would otherwise read
``[m/s] [T14]`` as a reference link, and ``mkdocs build --strict`` would fail on it.

Nothing is written into ``docs/``: the pages and figures exist only in the built site, so a
tutorial cannot go stale — it is whatever the current code produces, or the build fails.
"""

from __future__ import annotations

import ast
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import markdown
from markdown.inlinepatterns import InlineProcessor
from mkdocs.exceptions import PluginError
from mkdocs.plugins import event_priority
from mkdocs.structure.files import File

TIMEOUT_S = 300  # generous: a cold numba cache compiles the kernels on the first example
NAV_TITLE = "Tutorials"


def _examples(config) -> list[Path]:
    root = Path(config.config_file_path).resolve().parent
    return sorted((root / "examples").glob("[0-9][0-9]_*.py"))


def _title_and_intro(path: Path) -> tuple[str, str]:
    doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))) or path.stem
    first, _, rest = doc.partition("\n")
    return first.strip().rstrip("."), rest.strip()


class _TagProcessor(InlineProcessor):
    def handleMatch(self, m, data):  # noqa: N802 (Python-Markdown's name)
        return m.group(0), m.start(0), m.end(0)  # the tag as plain text, not a link


class TheoryTags(markdown.Extension):
    """Keep ``[T14]``, ``[T14, T16]``, ``[T60–T62]`` literal (runs before reference links)."""

    PATTERN = r"\[T\d+(?:\s*[–,-]\s*T\d+)*\]"

    def extendMarkdown(self, md):  # noqa: N802
        md.inlinePatterns.register(_TagProcessor(self.PATTERN, md), "jointdyn_theory_tags", 175)


@event_priority(100)  # before mkdocstrings copies the extension list into its handlers
def on_config(config):
    """Register :class:`TheoryTags`; one nav entry per example under ``Tutorials``."""
    config.markdown_extensions.append(TheoryTags())
    entries = [{_title_and_intro(p)[0]: f"tutorials/{p.stem}.md"} for p in _examples(config)]
    for item in config.nav or []:
        if isinstance(item, dict) and NAV_TITLE in item:
            item[NAV_TITLE] = entries
    return config


def _run(path: Path, workdir: Path) -> tuple[str, float]:
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONUNBUFFERED="1")
    t0 = time.perf_counter()
    try:
        proc = subprocess.run(
            [sys.executable, str(path)],
            cwd=workdir,
            env=env,
            capture_output=True,
            text=True,
            timeout=TIMEOUT_S,
        )
    except subprocess.TimeoutExpired:
        raise PluginError(f"example {path.name} did not finish within {TIMEOUT_S} s") from None
    dt = time.perf_counter() - t0
    if proc.returncode != 0:
        raise PluginError(
            f"example {path.name} failed (exit {proc.returncode}):\n"
            f"{proc.stdout[-2000:]}\n{proc.stderr[-4000:]}"
        )
    return proc.stdout, dt


def on_files(files, config):
    """Run the examples and add the generated pages and figures to the site's files."""
    from importlib.metadata import version

    for path in _examples(config):
        title, intro = _title_and_intro(path)
        with tempfile.TemporaryDirectory(prefix=f"jointdyn-{path.stem}-") as tmp:
            stdout, dt = _run(path, Path(tmp))
            figures = sorted(Path(tmp).glob("*.png"))
            if not figures:
                raise PluginError(f"example {path.name} saved no .png figure in its working directory")
            images = []
            for fig in figures:
                uri = f"tutorials/{path.stem}/{fig.name}"
                files.append(File.generated(config, uri, content=fig.read_bytes()))
                images.append(f"![{fig.stem}]({path.stem}/{fig.name})")
        source = path.read_text(encoding="utf-8").rstrip()
        md = [
            f"# {title}",
            "",
            intro,
            "",
            f"Source: `examples/{path.name}`. Run it from the repository root with "
            f"`python examples/{path.name}`; it saves its figure in the working directory.",
            "",
            "```python",
            source,
            "```",
            "",
            "## Output",
            "",
            f"Printed when this page was built (jointdyn {version('jointdyn')}, {dt:.1f} s "
            f"including interpreter start and JIT cache loading):",
            "",
            "```text",
            stdout.rstrip() or "(nothing)",
            "```",
            "",
            "## Figure",
            "",
            *images,
            "",
        ]
        files.append(File.generated(config, f"tutorials/{path.stem}.md", content="\n".join(md)))
    return files
