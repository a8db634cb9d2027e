"""The package's source as the rule tests read it: its modules, their parsed trees and
the import graph (relative imports resolved), shared by :mod:`test_code_rules` and the
rooms' own rule tests (``tests/tyre/test_tyre_room.py``)."""

from __future__ import annotations

import ast
from collections.abc import Iterator
from pathlib import Path

import frictionlaws

__all__ = ["PACKAGE", "MODULES", "TREES", "package_of", "source_of", "targets", "cycles",
           "every_target", "full_import_graph"]

PACKAGE = Path(frictionlaws.__file__).resolve().parent


def modules() -> Iterator[tuple[str, Path]]:
    """(dotted name, file) of every module of the package (``_datasets`` holds no code)."""
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(PACKAGE.parent).with_suffix("")
        parts = rel.parts[:-1] if rel.name == "__init__" else rel.parts
        yield ".".join(parts), path


MODULES = dict(modules())


def _trees() -> dict[str, ast.Module]:
    return {mod: ast.parse(path.read_text(encoding="utf-8"), str(path))
            for mod, path in MODULES.items()}


TREES = _trees()


def package_of(module: str) -> str:
    path = MODULES.get(module)  # a module of a test's own source is no package
    return module if path is not None and path.name == "__init__.py" else module.rpartition(".")[0]


def targets(module: str, node: ast.stmt) -> set[str]:
    """Package modules an import statement executes (besides the importer's own parents)."""
    names: set[str] = set()
    if isinstance(node, ast.Import):
        names = {a.name for a in node.names}
    elif isinstance(node, ast.ImportFrom):
        if node.level:
            base = package_of(module)
            for _ in range(node.level - 1):
                base = base.rpartition(".")[0]
            target = f"{base}.{node.module}" if node.module else base
        else:
            target = node.module or ""
        names = {target} | {f"{target}.{a.name}" for a in node.names}
    out = set()
    for name in names:
        parts = name.split(".")
        for i in range(1, len(parts) + 1):  # importing a.b.c runs a, a.b and a.b.c
            out.add(".".join(parts[:i]))
    parents = {".".join(module.split(".")[:i]) for i in range(1, module.count(".") + 1)}
    if MODULES[module].name == "__init__.py":
        parents.add(module)
    return {t for t in out if t in MODULES and t not in parents}


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (or a self-import)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1 or v in graph[v]:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def source_of(module: str, node: ast.ImportFrom) -> str:
    """The module a ``from X import ...`` statement imports from (resolved)."""
    if not node.level:
        return node.module or ""
    base = package_of(module)
    for _ in range(node.level - 1):
        base = base.rpartition(".")[0]
    return f"{base}.{node.module}" if node.module else base


def every_target(module: str, node: ast.stmt) -> set[str]:
    """:func:`targets`, and the package itself for ``from <package> import ...`` read plainly:
    ``from . import x`` inside a package imports that package, even when it is a parent."""
    out = targets(module, node)
    if isinstance(node, ast.ImportFrom):
        source = source_of(module, node)
        if source in MODULES and source != module:
            out.add(source)
    return out


def full_import_graph() -> dict[str, set[str]]:
    """Module -> the package modules any of its import statements names (deferred and
    type-only ones included, ``from . import`` as an import of the package)."""
    return {mod: set().union(set(), *[every_target(mod, n) for n in ast.walk(tree)
                                      if isinstance(n, (ast.Import, ast.ImportFrom))])
            for mod, tree in TREES.items()}

