"""Every module-level import of the package is the standard library, the package itself or a
declared base dependency of pyproject.toml: a fresh ``pip install -e .`` (the README's main
command, no extras) can import every module. (Optional packages — dask, plotly, exudyn — are
imported inside the functions that need them.) A regression of this kind once broke the main
command on a fresh machine: ``import click``, which typer no longer installs."""

from __future__ import annotations

import ast
import re
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
IMPORT_NAME = {"pyyaml": "yaml"}  # distribution -> import name where they differ


def base_dependencies() -> set[str]:
    deps = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["dependencies"]
    names = {re.match(r"[A-Za-z0-9_.-]+", d).group(0).lower().replace("-", "_") for d in deps}
    return {IMPORT_NAME.get(n, n) for n in names}


def module_level_imports(path: Path) -> set[str]:
    """Top-level package names imported at module level (not inside functions, not in a
    ``try: ... except ImportError`` guard)."""
    found = set()
    for node in ast.parse(path.read_text(encoding="utf-8")).body:
        if isinstance(node, ast.Try) and any(
            isinstance(h.type, ast.Name) and h.type.id in ("ImportError", "ModuleNotFoundError")
            for h in node.handlers
        ):
            continue
        for sub in ast.walk(node) if isinstance(node, (ast.If, ast.Try, ast.With)) else [node]:
            if isinstance(sub, ast.Import):
                found |= {a.name.split(".")[0] for a in sub.names}
            elif isinstance(sub, ast.ImportFrom) and sub.level == 0 and sub.module:
                found.add(sub.module.split(".")[0])
    return found


def test_module_level_imports_are_declared():
    allowed = base_dependencies() | set(sys.stdlib_module_names) | {"jointdyn", "__future__"}
    bad = {
        str(p.relative_to(ROOT)): sorted(module_level_imports(p) - allowed)
        for p in sorted((ROOT / "src" / "jointdyn").rglob("*.py"))
    }
    bad = {k: v for k, v in bad.items() if v}
    assert not bad, f"undeclared module-level imports (add to [project].dependencies or import lazily): {bad}"


def test_the_check_sees_an_undeclared_import(tmp_path):
    f = tmp_path / "m.py"
    f.write_text("import os\nimport click\nfrom numpy import pi\ndef g():\n    import dask\n")
    assert module_level_imports(f) - base_dependencies() - set(sys.stdlib_module_names) == {"click"}
