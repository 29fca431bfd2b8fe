"""The package's layers (README, Design): each sub-package imports only the layers below it, the
root holds the public API only, no module is too long to read. Read from the sources with
``ast`` (every import, including the ones inside functions), so a new upward import fails here
before it grows into a circle."""

from __future__ import annotations

import ast
from pathlib import Path

PKG = Path(__file__).resolve().parents[1] / "src" / "jointdyn"

# bottom to top; a module may import its own layer and the layers before it
LAYERS = [
    "errors",
    "units",
    "core",
    "film",
    "forces",
    "multibody",
    "integrators",
    "simulation",
    "post",
    "models",
    "io",
    "viz",
    "bearing",
    "studies",
    "cli",
    "__init__",
    "__main__",
]


def _layer(path: Path) -> str:
    rel = path.relative_to(PKG)
    return rel.parts[0] if len(rel.parts) > 1 else rel.stem


def _imported_layers(path: Path) -> list[tuple[int, str]]:
    found = []
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            parts = node.module.split(".")
            if parts[0] != "jointdyn":
                continue
            if len(parts) > 1:
                found.append((node.lineno, parts[1]))
            else:  # from jointdyn import post, simulate, ...
                for alias in node.names:
                    found.append((node.lineno, alias.name if alias.name in LAYERS else "__init__"))
        elif isinstance(node, ast.ImportFrom) and node.level > 0:
            found.append((node.lineno, "relative"))
        elif isinstance(node, ast.Import):
            for alias in node.names:
                parts = alias.name.split(".")
                if parts[0] == "jointdyn":
                    found.append((node.lineno, parts[1] if len(parts) > 1 else "__init__"))
    return found


def test_every_import_goes_down_the_layers():
    bad = []
    for path in sorted(PKG.rglob("*.py")):
        me = _layer(path)
        assert me in LAYERS, f"{path.relative_to(PKG)}: not in a known layer; add it to LAYERS"
        for line, target in _imported_layers(path):
            if target == "relative":
                bad.append(f"{path.relative_to(PKG)}:{line}: relative import (use jointdyn.<layer>...)")
            elif LAYERS.index(target) > LAYERS.index(me):
                bad.append(f"{path.relative_to(PKG)}:{line}: {me} imports {target}, a layer above it")
    assert not bad, "\n".join(bad)


def test_the_root_holds_the_public_api_only():
    root = sorted(p.name for p in PKG.glob("*.py"))
    assert len(root) <= 12, root  # the bound for the package root


def test_no_module_is_over_450_lines():
    long = {
        str(p.relative_to(PKG)): n for p in PKG.rglob("*.py") if (n := len(p.read_text().splitlines())) > 450
    }
    assert not long, long


def _module(path: Path) -> str:
    rel = path.relative_to(PKG.parent).with_suffix("")
    parts = list(rel.parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def test_no_import_circles_between_modules():
    mods = {_module(p): p for p in PKG.rglob("*.py")}
    graph: dict[str, set[str]] = {m: set() for m in mods}
    for m, path in mods.items():
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("jointdyn"):
                for alias in node.names:  # "from pkg import module" imports the module
                    sub = f"{node.module}.{alias.name}"
                    graph[m].add(sub if sub in mods else node.module)
    graph = {
        m: {t for t in ts if t in mods and t != m and not m.startswith(t + ".")} for m, ts in graph.items()
    }
    # Tarjan's strongly connected components
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    circles = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                circles.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    assert not circles, circles
