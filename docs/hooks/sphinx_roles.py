"""MkDocs hook: render the Sphinx roles of the docstrings as code, not as raw text.

The docstrings cross-reference with reStructuredText roles (``:class:`~jointdyn.simulation.results.Results```,
``:func:`simulate```, ``:meth:`save```). mkdocstrings reads them as plain Markdown, so the page
would show ``:class:`` followed by the code span. This hook turns every such pair into the code span
alone, shortening ``~a.b.C`` to ``C`` as Sphinx does.
"""

from __future__ import annotations

import re

ROLE = re.compile(r":(?:py:)?(?:class|func|meth|mod|attr|data|exc|obj|const|ref|term):<code>(~?)([^<]+)</code>")


def _sub(m: re.Match) -> str:
    target = m.group(2)
    return f"<code>{target.rsplit('.', 1)[-1] if m.group(1) else target}</code>"


def strip_roles(html: str) -> str:
    """HTML with ``:role:<code>x</code>`` replaced by ``<code>x</code>``."""
    return ROLE.sub(_sub, html)


def on_page_content(html, page, config, files):
    return strip_roles(html)
