"""The Magic Formula room's own rules, checked on the package's source.

* ``frictionlaws/tyre/mf/`` holds the Magic Formula: no ``_fit_mf_*`` / ``_mf_*`` fragment at
  ``tyre/``'s top, no module of ``tyre/mf/`` over 800 lines;
* no private function, class or constant (nor a private module) is imported from another
  module of the tyre package: what is shared is public in its module;
* imports sit at the top of the file (only matplotlib, sympy, dask and xarray may be
  deferred, for start-up time);
* no import circle through a tyre module, counting deferred, type-only and ``from . import``
  imports (``from . import x`` runs the package's ``__init__``: an edge to the package);
* the import paths of earlier releases still give the same objects.
"""

from __future__ import annotations

import ast
import importlib
from collections.abc import Iterator
from pathlib import Path

import frictionlaws

PACKAGE = Path(frictionlaws.__file__).resolve().parent
TYRE = PACKAGE / "tyre"
#: Third-party modules whose import may be deferred (start-up time).
DEFERRABLE = ("matplotlib", "sympy", "dask", "xarray")
MAX_MF_LINES = 800


def _modules(root: Path) -> dict[str, Path]:
    out = {}
    for path in sorted(root.rglob("*.py")):
        rel = path.relative_to(PACKAGE.parent).with_suffix("")
        parts = rel.parts[:-1] if rel.name == "__init__" else rel.parts
        out[".".join(parts)] = path
    return out


MODULES = _modules(PACKAGE)
TYRE_MODULES = {m: p for m, p in MODULES.items() if m.startswith("frictionlaws.tyre")}


def _package(module: str) -> str:
    return module if MODULES[module].name == "__init__.py" else module.rpartition(".")[0]


def _imports(module: str) -> Iterator[tuple[ast.stmt, str, list[str], bool]]:
    """(node, imported module, names, at the top) for every import statement of ``module``;
    relative imports resolved."""
    tree = ast.parse(MODULES[module].read_text(encoding="utf-8"))
    top = {id(n) for n in tree.body}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield node, alias.name, [], id(node) in top
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = _package(module)
                for _ in range(node.level - 1):
                    base = base.rpartition(".")[0]
                target = f"{base}.{node.module}" if node.module else base
            else:
                target = node.module or ""
            yield node, target, [a.name for a in node.names], id(node) in top


def _edges(module: str) -> set[str]:
    """The package modules ``module`` imports, every statement counted: ``from P import x``
    is an edge to P (even a parent package: its ``__init__`` runs) and to P.x when that is
    a module; ``from P.m import x`` an edge to P.m (and P.m.x)."""
    out = set()
    for _, target, names, _top in _imports(module):
        if target in MODULES:
            out.add(target)
        out.update(f"{target}.{n}" for n in names if f"{target}.{n}" in MODULES)
    out.discard(module)
    return out


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    found: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in sorted(graph.get(v, ())):
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
            if len(comp) > 1:
                found.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def test_the_magic_formula_is_a_room_of_modules_under_800_lines():
    top = [p.name for p in TYRE.glob("*.py")]
    assert [n for n in top if n.startswith(("_fit_mf", "_mf"))] == []
    assert (TYRE / "mf" / "model.py").is_file() and (TYRE / "mf" / "fit" / "staged.py").is_file()
    long = {str(p.relative_to(TYRE)): n for p in (TYRE / "mf").rglob("*.py")
            if (n := len(p.read_text(encoding="utf-8").splitlines())) > MAX_MF_LINES}
    assert long == {}


def test_no_private_name_crosses_a_module_of_the_tyre_package():
    crossing = []
    for module in TYRE_MODULES:
        for node, target, names, _ in _imports(module):
            if not target.startswith("frictionlaws.tyre"):
                continue
            private_module = any(part.startswith("_") for part in target.split("."))
            crossing += [f"{module}: {target} import {n}" for n in names
                         if n.startswith("_") or private_module]
            if isinstance(node, ast.Import) and private_module:
                crossing.append(f"{module}: import {target}")
    assert crossing == []


def test_imports_sit_at_the_top_except_the_heavy_third_party_ones():
    deferred = [f"{module}:{node.lineno} {target}" for module in TYRE_MODULES
                for node, target, _, top in _imports(module)
                if not top and not target.startswith(DEFERRABLE)
                and target != "__future__"]
    assert deferred == []


def test_no_import_circle_through_the_tyre_package():
    graph = {m: _edges(m) for m in MODULES}
    assert "frictionlaws.tyre.mf.model" in graph["frictionlaws.tyre.reduce"]  # sees imports
    assert "frictionlaws.tyre.mf.fit.stages" in graph["frictionlaws.tyre.mf.fit.bootstrap"]
    through = [c for c in _cycles(graph) if any(m.startswith("frictionlaws.tyre") for m in c)]
    assert through == []


def test_the_circle_check_counts_from_dot_import_of_the_package():
    graph = {"p": {"p.a"}, "p.a": {"p.b"}, "p.b": {"p"}}  # p.b: "from . import c"
    assert _cycles(graph) == [["p", "p.a", "p.b"]]


def test_the_import_paths_of_earlier_releases_give_the_same_objects():
    from frictionlaws.tyre import mf

    for old, new, names in (
            ("magic_formula", "model", ("MagicFormula", "EXAMPLES", "packaged_example")),
            ("mf_coefficients", "declarations", ("DECLARED", "Coefficient")),
            ("mf_coefficients", "coefficients", ("listing", "fit_bounds", "default")),
            ("mf_outputs", "outputs", ("OUTPUTS", "steady_state", "aligning_moment")),
            ("tir", "tir", ("read_property_file", "format_tir", "json_to_tir")),
            ("tir", "property_file", ("PropertyFile", "DIMENSIONAL", "MF_KEYS"))):
        before = importlib.import_module(f"frictionlaws.tyre.{old}")
        now = importlib.import_module(f"frictionlaws.tyre.mf.{new}")
        for name in names:
            assert getattr(before, name) is getattr(now, name), (old, name)
    import frictionlaws.tyre as tyre

    assert tyre.MagicFormula is mf.MagicFormula and tyre.fit_mf is mf.fit_mf
    assert callable(tyre.fit_mf)
