"""The Magic Formula room's own rules, checked on the package's source.

* ``frictionlaws/tyre/mf/`` holds the Magic Formula: no ``_fit_mf_*`` / ``_mf_*`` fragment at
  ``tyre/``'s top, no module of ``tyre/`` over 800 lines; the modules left at ``tyre/``'s top
  under the Magic Formula's earlier import paths are plain public re-exports (imports from
  ``tyre/mf/`` and ``__all__``, nothing else), their docstrings saying so;
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

from source_tree import MODULES, PACKAGE, TREES, cycles, full_import_graph, source_of

TYRE = PACKAGE / "tyre"
#: Third-party modules whose import may be deferred (start-up time).
DEFERRABLE = ("matplotlib", "sympy", "dask", "xarray")
MAX_MF_LINES = 800


TYRE_MODULES = {m: p for m, p in MODULES.items() if m.startswith("frictionlaws.tyre")}


def _imports(module: str) -> Iterator[tuple[ast.stmt, str, list[str], bool]]:
    """(node, imported module, names, at the top) for every import statement of ``module``;
    relative imports resolved."""
    tree = TREES[module]
    top = {id(n) for n in tree.body}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield node, alias.name, [], id(node) in top
        elif isinstance(node, ast.ImportFrom):
            yield (node, source_of(module, node), [a.name for a in node.names],
                   id(node) in top)


def test_the_magic_formula_is_a_room_of_modules_under_800_lines():
    top = [p.name for p in TYRE.glob("*.py")]
    assert [n for n in top if n.startswith(("_fit_mf", "_mf"))] == []
    assert (TYRE / "mf" / "model.py").is_file() and (TYRE / "mf" / "fit" / "staged.py").is_file()
    long = {str(p.relative_to(TYRE)): n for p in TYRE.rglob("*.py")
            if (n := len(p.read_text(encoding="utf-8").splitlines())) > MAX_MF_LINES}
    assert long == {}


#: The modules at ``tyre/``'s top that hold the Magic Formula's import paths of earlier
#: releases: plain public re-exports, nothing else.
SHIMS = ("magic_formula", "mf_coefficients", "mf_outputs", "tir")


def test_the_earlier_import_paths_are_plain_public_re_exports():
    for name in SHIMS:
        tree = ast.parse((TYRE / f"{name}.py").read_text(encoding="utf-8"))
        doc = ast.get_docstring(tree) or ""
        assert "import path of earlier releases" in doc and "re-exports" in doc, name
        body = [n for n in tree.body
                if not (isinstance(n, ast.Expr) and isinstance(n.value, ast.Constant))]
        imported: list[str] = []
        for node in body:
            if isinstance(node, ast.ImportFrom) and node.module != "__future__":
                assert node.level == 1 and (node.module or "").startswith("mf."), name
                imported += [a.asname or a.name for a in node.names]
            elif isinstance(node, ast.Assign):
                assert [t.id for t in node.targets if isinstance(t, ast.Name)] == ["__all__"]
                exported = ast.literal_eval(node.value)
            else:
                assert isinstance(node, ast.ImportFrom), (name, ast.dump(node)[:80])
        assert sorted(exported) == sorted(imported), name
        assert not [n for n in imported if n.startswith("_")], name


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
    """Every import statement counts (deferred, type-only, ``from . import`` of a package:
    its ``__init__`` runs); the graph and the circle search are the code rules'."""
    graph = full_import_graph()
    assert "frictionlaws.tyre.mf.model" in graph["frictionlaws.tyre.reduce"]  # sees imports
    assert "frictionlaws.tyre.mf.fit.stages" in graph["frictionlaws.tyre.mf.fit.bootstrap"]
    assert [c for c in cycles(graph) if any(m in TYRE_MODULES for m in c)] == []
    assert cycles({"p": {"p.a"}, "p.a": {"p.b"}, "p.b": {"p"}, "q": {"p"}}) == [
        ["p", "p.a", "p.b"]]  # p.b: "from . import"


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
