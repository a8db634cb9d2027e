"""The code rules, checked on the installed package's source.

* no module in ``frictionlaws/`` over 1000 lines, no function longer than 80;
* none above cyclomatic complexity 15 (ruff's C901);
* every module declares ``__all__``;
* the ``py.typed`` marker is installed with the package;
* no import circle among the package's modules, counting every import (deferred,
  type-only, and ``from . import`` of a package as an import of that package);
* the package is rooms: at most six loose modules at its top, no private name imported
  from another room, imports at the top of the file (at most 15 % of the in-package ones
  inside functions, third-party ones there only from a short list of heavy libraries).

``KNOWN_PENDING`` lists, narrowly, what other work in progress still has to bring
under these rules; each entry must still be a violation (a fixed entry makes the
test fail until it is removed from the list), so the list can only shrink.
"""

from __future__ import annotations

import argparse
import ast
import json
import re
import subprocess
import sys
from collections.abc import Iterator
from importlib import metadata, resources
from pathlib import Path

import pytest
from source_tree import (
    MODULES,
    PACKAGE,
    TREES,
    cycles,
    every_target,
    full_import_graph,
    source_of,
    targets,
)

REPO = Path(__file__).resolve().parents[1]
MAX_LINES = 80
MAX_COMPLEXITY = 15
MAX_MODULE_LINES = 1000

#: Violations in modules other work is splitting now; emptied when that work is merged.
KNOWN_PENDING: dict[str, frozenset[str]] = {
    # qualified names of functions longer than MAX_LINES / above MAX_COMPLEXITY
    "length": frozenset(),
    "complexity": frozenset(),
    "all": frozenset(),  # modules without __all__
    # private names imported from another room ("importer -> module.name")
    "private": frozenset(),
    # imports inside functions of modules neither of the package nor heavy ("module: name")
    "deferred": frozenset(),
}


def _functions(tree: ast.Module, module: str) -> Iterator[tuple[str, ast.AST]]:
    """(qualified name, node) of every function and method, nested ones included."""
    def walk(node: ast.AST, prefix: str) -> Iterator[tuple[str, ast.AST]]:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                name = f"{prefix}.{child.name}"
                if not isinstance(child, ast.ClassDef):
                    yield name, child
                yield from walk(child, name)
            else:
                yield from walk(child, prefix)

    yield from walk(tree, module)


def _check(kind: str, found: set[str]) -> None:
    pending = KNOWN_PENDING[kind]
    new = sorted(found - pending)
    fixed = sorted(pending - found)
    assert not new, f"{kind}: {new}"
    assert not fixed, f"{kind}: fixed, remove from KNOWN_PENDING: {fixed}"


def test_the_package_is_found():
    assert "frictionlaws.law" in MODULES and "frictionlaws.cli" in MODULES
    assert len(MODULES) > 50


def test_no_module_is_over_1000_lines():
    """A module that grows past this is split by concern (a package of rooms)."""
    long = {mod: n for mod, path in MODULES.items()
            if (n := len(path.read_text(encoding="utf-8").splitlines())) > MAX_MODULE_LINES}
    assert long == {}


def test_no_function_is_longer_than_80_lines():
    long = {name: node.end_lineno - node.lineno + 1
            for mod, tree in TREES.items() for name, node in _functions(tree, mod)
            if node.end_lineno - node.lineno + 1 > MAX_LINES}
    _check("length", set(long))


def _ruff_c901(path: Path, limit: int) -> list[dict]:
    cmd = [sys.executable, "-m", "ruff", "check", "--isolated", "--no-cache",
           "--select", "C901", "--config", f"lint.mccabe.max-complexity={limit}",
           "--output-format", "json", "--exit-zero", str(path)]
    proc = subprocess.run(cmd, capture_output=True, text=True, check=False)
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


def _qualname_at(file: str, row: int) -> str:
    mod = next(m for m, p in MODULES.items() if p == Path(file).resolve())
    return next(name for name, node in _functions(TREES[mod], mod) if node.lineno == row)


def test_no_function_is_more_complex_than_15():
    pytest.importorskip("ruff")
    found = {_qualname_at(d["filename"], d["location"]["row"])
             for d in _ruff_c901(PACKAGE, MAX_COMPLEXITY)}
    _check("complexity", found)


def test_the_complexity_check_sees_complex_functions(tmp_path):
    """The ruff call above reports a function of complexity 16 (the check can fail)."""
    pytest.importorskip("ruff")
    body = "".join(f"    if x == {i}:\n        return {i}\n" for i in range(15))
    (tmp_path / "m.py").write_text(f"def f(x):\n{body}    return -1\n")
    found = _ruff_c901(tmp_path, MAX_COMPLEXITY)
    assert [d["code"] for d in found] == ["C901"]
    assert "(16 > 15)" in found[0]["message"]


def _declares_all(tree: ast.Module) -> bool:
    for node in tree.body:
        targets = (node.targets if isinstance(node, ast.Assign)
                   else [node.target] if isinstance(node, ast.AnnAssign) else [])
        if any(isinstance(t, ast.Name) and t.id == "__all__" for t in targets):
            return True
    return False


def test_every_module_declares_all():
    _check("all", {mod for mod, tree in TREES.items() if not _declares_all(tree)})


def test_public_names_in_all_exist():
    """Every name a module lists in ``__all__`` is defined by it."""
    import importlib

    for mod, tree in TREES.items():
        if mod == "frictionlaws.__main__" or not _declares_all(tree):
            continue
        module = importlib.import_module(mod)
        missing = [n for n in module.__all__ if not hasattr(module, n)]
        assert not missing, f"{mod}.__all__ names undefined {missing}"


def test_py_typed_is_installed():
    assert resources.files("frictionlaws").joinpath("py.typed").is_file()
    dist = metadata.distribution("frictionlaws")
    text = dist.read_text("direct_url.json")
    editable = bool(text) and bool(json.loads(text).get("dir_info", {}).get("editable"))
    if not editable:  # an installed wheel lists the marker among its files
        assert "frictionlaws/py.typed" in {str(f).replace("\\", "/") for f in dist.files or ()}
    pyproject = REPO / "pyproject.toml"
    if pyproject.is_file():  # and the build configuration ships it
        try:
            import tomllib
        except ModuleNotFoundError:  # Python 3.10
            import tomli as tomllib
        conf = tomllib.loads(pyproject.read_text(encoding="utf-8"))
        assert "py.typed" in conf["tool"]["setuptools"]["package-data"]["frictionlaws"]


# ----------------------------------------------------------------- import circles


def _is_type_checking(test: ast.expr) -> bool:
    return ((isinstance(test, ast.Name) and test.id == "TYPE_CHECKING")
            or (isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"))


def _import_time_nodes(body: list[ast.stmt]) -> Iterator[ast.stmt]:
    """Import statements run when the module is imported (not in functions, not for types)."""
    for node in body:
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            yield node
        elif isinstance(node, ast.If):
            if not _is_type_checking(node.test):
                yield from _import_time_nodes(node.body)
            yield from _import_time_nodes(node.orelse)
        elif isinstance(node, ast.Try):
            for block in (node.body, node.orelse, node.finalbody,
                          *[h.body for h in node.handlers]):
                yield from _import_time_nodes(block)
        elif isinstance(node, (ast.With, ast.ClassDef)):
            yield from _import_time_nodes(node.body)


def import_graph() -> dict[str, set[str]]:
    """Module -> the package modules its import-time statements execute."""
    return {mod: set().union(*[targets(mod, n) for n in _import_time_nodes(tree.body)])
            for mod, tree in TREES.items()}


def test_no_import_circle():
    graph = import_graph()
    assert "frictionlaws.law.registry" in graph["frictionlaws.fitting.core"]  # sees imports
    assert cycles(graph) == []


def test_the_circle_check_finds_circles():
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}, "e": {"e"}}
    assert cycles(graph) == [["a", "b", "c"], ["e"]]
    assert cycles({"a": {"b"}, "b": set()}) == []


def test_imports_inside_functions_and_for_types_do_not_count():
    src = ("from typing import TYPE_CHECKING\n"
           "from ..law import Law\n"
           "if TYPE_CHECKING:\n    from ..io import Dataset\n"
           "def f():\n    from ..comparison import compare\n")
    nodes = list(_import_time_nodes(ast.parse(src).body))
    got = set().union(*[targets("frictionlaws.fitting.core", n) for n in nodes])
    assert got == {"frictionlaws.law"}


# ------------------------------------------------------------- one place per fact


def _unit_columns() -> dict[str, dict[str, str]]:
    """Each per-quantity column of the one unit table: SI unit, display unit, example."""
    from frictionlaws.base.units import QUANTITIES

    return {col: {k: getattr(q, attr) for k, q in QUANTITIES.items()}
            for col, attr in (("SI unit", "si"), ("display unit", "display"),
                              ("example", "example"))}


def _copied_columns(tree: ast.AST, columns: dict[str, dict[str, str]]) -> Iterator[str]:
    """Dict literals ``{"p": "Pa", "v": "m/s", ...}`` repeating a column of the unit table.

    A literal is a copy when at least two of its keys name quantities and every value is
    that quantity's entry in one column (a unit system such as mm-N-s is not a copy).
    """
    for node in ast.walk(tree):
        if not isinstance(node, ast.Dict) or len(node.keys) < 2:
            continue
        pairs = [(k.value, v.value) for k, v in zip(node.keys, node.values)
                 if isinstance(k, ast.Constant) and isinstance(v, ast.Constant)]
        if len(pairs) != len(node.keys):
            continue
        for col, table in columns.items():
            if all(k in table and table[k] == v for k, v in pairs):
                yield f"line {node.lineno}: the {col} of {', '.join(k for k, _ in pairs)}"


def test_units_of_a_quantity_are_declared_once():
    """SI and display units live in ``units.QUANTITIES`` only; nothing copies a column."""
    from dataclasses import fields

    from frictionlaws.base.units import QUANTITIES
    from frictionlaws.law import VARIABLES, Variable

    assert not {"unit", "display_unit", "si", "display"} & {f.name for f in fields(Variable)}
    for name, var in VARIABLES.items():
        assert (var.unit, var.display_unit) == (QUANTITIES[name].si, QUANTITIES[name].display)
    columns = _unit_columns()
    copies = {mod: list(_copied_columns(tree, columns)) for mod, tree in TREES.items()
              if mod != "frictionlaws.base.units"}
    assert not {m: c for m, c in copies.items() if c}
    built = {mod for mod, tree in TREES.items() if mod != "frictionlaws.base.units"
             and any(isinstance(n, ast.Call) and isinstance(n.func, ast.Name)
                     and n.func.id == "Quantity" for n in ast.walk(tree))}
    assert not built, f"Quantity declared outside frictionlaws.base.units: {sorted(built)}"


def test_the_copy_check_finds_a_copied_unit_column():
    columns = _unit_columns()
    copied = ast.parse('S = {"SI": {"p": "Pa", "v": "m/s", "T": "K", "F_N": "N", "s": ""}}\n'
                       'E = {"area": "314.16 mm^2", "p": "0.2 MPa"}\n'
                       'D = {"p": "MPa", "T": "degC"}\n')
    assert len(list(_copied_columns(copied, columns))) == 3
    system = ast.parse('M = {"p": "MPa", "v": "mm/s", "T": "K", "F_N": "N", "s": ""}\n')
    assert list(_copied_columns(system, columns)) == []


def test_dataset_columns_come_from_the_variable_list():
    """io's columns and aliases are keyed from the one variable list and the unit table."""
    from frictionlaws import io
    from frictionlaws.base.units import QUANTITIES
    from frictionlaws.law import VARIABLES

    assert io.VARIABLE_COLUMNS == tuple(VARIABLES)
    assert tuple(io.ALIASES) == io.CANONICAL  # one alias entry per column, same order
    assert set(io.CANONICAL) - set(io.TEXT_COLUMNS) <= set(QUANTITIES)
    assert set(VARIABLES) <= set(QUANTITIES)


def test_export_formats_and_unit_systems_have_one_list():
    """The CLI's --format choices, its format flags, its help and the docs read the
    library's tables (``fe_export.formats``, ``fe_export.systems``)."""
    from frictionlaws.cli import build_parser, cmd_export
    from frictionlaws.fe_export.formats import FORMATS, OPTIONS
    from frictionlaws.fe_export.systems import SYSTEMS
    from frictionlaws.law import VARIABLES

    assert cmd_export._BOX == tuple(VARIABLES)
    for mod in ("frictionlaws.cli.cmd_export", "frictionlaws.fe_export.api"):
        assert not any(isinstance(n, ast.Tuple) and {"csv", "abaqus"} <= {
            getattr(e, "value", None) for e in n.elts} for n in ast.walk(TREES[mod]))
        assert not {"lsdyna_ssid", "ansys_mat", "radioss_id"} & {
            n.value for n in ast.walk(TREES[mod]) if isinstance(n, ast.Constant)}
    sub = next(a for a in build_parser()._actions
               if isinstance(a, argparse._SubParsersAction))
    export = sub.choices["export"]
    fmt = next(a for a in export._actions if "--format" in a.option_strings)
    assert list(fmt.choices) == list(FORMATS)
    assert {a.dest for a in export._actions} >= set(OPTIONS)
    text = export.format_help()
    for name, entry in FORMATS.items():
        assert f"  {name} " in text and entry.line in text
    for name in SYSTEMS:
        assert name in text.split("unit systems:")[1]
    guide = (REPO / "docs" / "user-guide" / "export.rst").read_text(encoding="utf-8")
    table = guide.split("Formats\n-------")[1].split("\nUnits\n")[0]
    assert ".. include:: ../generated/export-formats.rst" in table  # written from FORMATS
    units = guide.split("\nUnits\n-----")[1].split("\n\n")[1]
    assert set(re.findall(r"``([A-Za-z-]+)`` \([^)`]*,", units)) == set(SYSTEMS)


# ---------------------------------------------------- where the law ids are listed

#: Directories the docs build writes (ignored by git): generated from the registry.
_GENERATED_DOCS = ("_build", "auto_examples", "gen_modules", "generated")
#: The one file outside the law modules that names every law: the example table.
LAW_TABLE = "frictionlaws/validation/law_examples.py"


def _names_every_law(text: str, ids: list[str]) -> bool:
    return all(re.search(rf"(?<![\w-]){re.escape(i)}(?![\w-])", text) for i in ids)


def _files_naming_every_law(ids: list[str]) -> list[str]:
    laws = PACKAGE / "laws"
    files = [p for p in PACKAGE.rglob("*") if p.is_file() and laws not in p.parents]
    docs = REPO / "docs"
    if docs.is_dir():  # a source checkout
        files += [p for p in docs.rglob("*") if p.is_file()
                  and not set(p.relative_to(docs).parts) & set(_GENERATED_DOCS)]
    out = []
    for path in files:
        try:
            text = path.read_text(encoding="utf-8")
        except (UnicodeDecodeError, OSError):
            continue  # images, compiled files
        if _names_every_law(text, ids):
            base = PACKAGE.parent if PACKAGE in path.parents else REPO
            out.append(path.relative_to(base).as_posix())
    return sorted(out)


def test_at_most_one_file_outside_the_law_modules_lists_every_law():
    """Adding a law touches its module and one entry of the example table, nothing else."""
    from frictionlaws import list_laws

    ids = [law.id for law in list_laws()]
    assert len(ids) > 10
    assert _files_naming_every_law(ids) == [LAW_TABLE]


def test_the_law_list_check_sees_a_list():
    ids = ["coulomb", "thesis-poly2", "park"]
    assert _names_every_law("laws: coulomb, thesis-poly2 and park", ids)
    assert not _names_every_law("coulomb, thesis-poly3 and park", ids)  # poly2 missing
    assert not _names_every_law("coulomb, thesis-poly2 and parker", ids)


# ------------------------------------------------- circles counting every import


def test_no_circle_counting_deferred_and_type_only_imports():
    """No circle even when every import statement counts: inside functions, under
    ``if TYPE_CHECKING``, and ``from . import`` as an import of the package (a class whose
    methods hand work to a module that imports the class would be one)."""
    graph = full_import_graph()
    # deferred, type-only and package imports are seen
    assert "frictionlaws.comparison" in graph["frictionlaws.fitting.campaign"]
    assert "frictionlaws.law.bound" in graph["frictionlaws.fitting.result"]
    assert "frictionlaws.law" in graph["frictionlaws.law.registry"]  # from . import Law
    assert cycles(graph) == []


def test_the_law_package_imports_only_the_layers_below_it():
    """The law room imports only itself and the base room's errors and units; its
    declaration rooms never import the registry or bound laws, which import them (every
    import counted)."""
    graph = full_import_graph()
    rooms = [m for m in graph if m == "frictionlaws.law" or m.startswith("frictionlaws.law.")]
    assert {"frictionlaws.law.core", "frictionlaws.law.registry"} <= set(rooms)
    below = ("frictionlaws.base", "frictionlaws.base.errors", "frictionlaws.base.units")
    outside = {f"{m} -> {t}" for m in rooms for t in graph[m]
               if not (t == "frictionlaws.law" or t.startswith("frictionlaws.law.")
                       or t in below)}
    assert outside == set()
    outer = ("frictionlaws.law.registry", "frictionlaws.law.bound")
    upward = {f"{m} -> {t}" for m in rooms if m not in outer for t in graph[m] if t in outer}
    assert upward == set()


#: The one module that calls a least-squares solver or lmfit's minimisation.
SOLVER_MODULE = "frictionlaws.fitting.lsq"
_SOLVER_NAMES = {"least_squares", "leastsq", "curve_fit", "minimize", "Minimizer"}


def test_least_squares_and_lmfit_are_called_in_one_module():
    offenders = []
    for mod, tree in TREES.items():
        if mod == SOLVER_MODULE:
            continue
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.module in ("scipy.optimize", "lmfit"):
                offenders += [f"{mod} imports {a.name}" for a in node.names
                              if a.name in _SOLVER_NAMES]
            elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                  and (node.func.attr in _SOLVER_NAMES or (
                      node.func.attr == "fit" and "Model" in ast.unparse(node.func.value)
                      or node.func.attr == "fit" and ast.unparse(node.func.value).endswith(
                          "model")))):
                offenders.append(f"{mod}:{node.lineno} {ast.unparse(node.func)}")
    assert offenders == []


def test_from_dot_import_counts_as_an_import_of_the_package():
    node = ast.parse("from . import FAMILIES, Law").body[0]
    assert "frictionlaws.law" in every_target("frictionlaws.law.registry", node)
    assert "frictionlaws.law" not in targets("frictionlaws.law.registry", node)  # a parent
    sub = ast.parse("from . import core").body[0]
    assert every_target("frictionlaws.law.registry", sub) == {"frictionlaws.law",
                                                               "frictionlaws.law.core"}


# -------------------------------------------------------------------------- rooms

#: Loose modules allowed at the package's top, besides ``__init__`` and ``__main__``.
MAX_LOOSE_MODULES = 6


def room_of(module: str) -> str:
    """The room of a module: the sub-package of frictionlaws it lies in, or, for a loose
    module, the module itself; ``""`` for the package's own ``__init__``."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ""


def test_at_most_six_loose_modules():
    loose = sorted(p.name for p in PACKAGE.glob("*.py")
                   if p.stem not in ("__init__", "__main__"))
    assert len(loose) <= MAX_LOOSE_MODULES, loose
    assert room_of("frictionlaws.fitting.lsq") == "fitting"
    assert room_of("frictionlaws.caches") == "caches" and room_of("frictionlaws") == ""


def _private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def private_names_across_rooms(trees: dict[str, ast.Module],
                               modules: set[str]) -> set[str]:
    """``importer -> module.name`` for each private name (or module) an importer takes from
    another room: imported by name, or read as an attribute of a module it imported."""
    found = set()
    for mod, tree in trees.items():
        aliases: dict[str, str] = {}  # local name -> the module it is bound to
        for node in ast.walk(tree):
            if not isinstance(node, ast.ImportFrom):
                continue
            source = source_of(mod, node)
            for alias in node.names:
                full = f"{source}.{alias.name}"
                name = full if full in modules else source
                if full in modules:
                    aliases[alias.asname or alias.name] = full
                if room_of(name) in ("", room_of(mod)) or not source.startswith("frictionlaws"):
                    continue
                if any(_private(part) for part in full.split(".")[1:]):
                    found.add(f"{mod} -> {full}")
        for node in ast.walk(tree):
            if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
                    and node.value.id in aliases and _private(node.attr)
                    and room_of(aliases[node.value.id]) not in ("", room_of(mod))):
                found.add(f"{mod} -> {aliases[node.value.id]}.{node.attr}")
    return found


def test_no_private_name_crosses_a_room():
    """What a room uses of another is public (in ``__all__``, documented there)."""
    _check("private", private_names_across_rooms(TREES, set(MODULES)))


def test_the_private_name_check_sees_names_modules_and_attributes():
    # frictionlaws.tyre.sample: a module, not a package (no such file in the package)
    modules = {"frictionlaws.io", "frictionlaws.io.reading", "frictionlaws.tyre",
               "frictionlaws.tyre.sample", "frictionlaws.tyre._plot", "frictionlaws.io._cells"}
    trees = {"frictionlaws.tyre.sample": ast.parse(
        "from ..io import _Table, read_table\n"
        "from ..io import reading\n"
        "from . import _plot\n"  # the same room: allowed
        "def f():\n    from ..io._cells import parse\n    return reading._split(1)\n")}
    assert private_names_across_rooms(trees, modules) == {
        "frictionlaws.tyre.sample -> frictionlaws.io._Table",
        "frictionlaws.tyre.sample -> frictionlaws.io._cells.parse",
        "frictionlaws.tyre.sample -> frictionlaws.io.reading._split"}


#: Third-party libraries that may be imported inside a function: start-up
#: (``frictionlaws --help``, ``fit`` on a packaged dataset: benchmarks/bench_startup.py)
#: must not load them, or only a command that needs them does (numpy: ``--help`` loads
#: none, and base.errors is on its path).
DEFERRED_LIBRARIES = frozenset({
    "numpy", "scipy", "pandas", "matplotlib", "sympy", "lmfit", "pint", "xarray", "dask",
    "distributed", "joblib", "tqdm", "mpmath", "shtab",
})
#: The largest share of the package's own import statements that sit inside functions.
MAX_DEFERRED_SHARE = 0.15


def _in_function(tree: ast.Module) -> Iterator[tuple[ast.stmt, bool]]:
    """Each import statement of ``tree`` and whether it sits inside a function."""
    def walk(node: ast.AST, inside: bool) -> Iterator[tuple[ast.stmt, bool]]:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.Import, ast.ImportFrom)):
                yield child, inside
            yield from walk(child, inside or isinstance(
                child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)))

    yield from walk(tree, False)


def _imported(module: str, node: ast.stmt) -> list[str]:
    if isinstance(node, ast.Import):
        return [a.name for a in node.names]
    assert isinstance(node, ast.ImportFrom)
    return [source_of(module, node)]


def deferred_imports(trees: dict[str, ast.Module]) -> tuple[int, int, set[str]]:
    """In-package import statements, those inside functions, and the other imports inside
    functions that are not of :data:`DEFERRED_LIBRARIES` (``"module: name"``)."""
    total = deferred = 0
    others = set()
    for mod, tree in trees.items():
        for node, inside in _in_function(tree):
            names = _imported(mod, node)
            if any(n.split(".")[0] == "frictionlaws" for n in names):
                total += 1
                deferred += inside
            elif inside:
                others |= {f"{mod}: {n}" for n in names
                           if n.split(".")[0] not in DEFERRED_LIBRARIES}
    return total, deferred, others


def test_imports_sit_at_the_top_of_the_file():
    """The dependency graph reads from the top of each file: at most 15 % of the package's
    own import statements inside functions (where start-up needs one deferred), and no
    other import there except of the heavy libraries start-up must not load."""
    total, deferred, others = deferred_imports(TREES)
    assert total > 400
    assert deferred / total <= MAX_DEFERRED_SHARE, f"{deferred} of {total} inside functions"
    _check("deferred", others)


def test_the_deferred_import_count_sees_functions_and_methods():
    trees = {"frictionlaws.io.reading": ast.parse(
        "import csv\nfrom ..base.errors import InputError\n"
        "if True:\n    from . import columns\n"
        "def f():\n    import numpy\n    import json\n    from .columns import x\n"
        "class C:\n    def m(self):\n        from frictionlaws.base import units\n")}
    assert deferred_imports(trees) == (4, 2, {"frictionlaws.io.reading: json"})


def _classes(body: list[ast.stmt], prefix: str) -> Iterator[str]:
    """Qualified names of the classes defined in ``body`` (nested ones and those under
    ``if``/``try`` included; those inside functions are local and left out)."""
    for node in body:
        if isinstance(node, ast.ClassDef):
            yield f"{prefix}{node.name}"
            yield from _classes(node.body, f"{prefix}{node.name}.")
        elif isinstance(node, (ast.If, ast.Try, ast.With)):
            for block in ("body", "orelse", "finalbody", "handlers"):
                yield from _classes(getattr(node, block, []), prefix)
        elif isinstance(node, ast.ExceptHandler):
            yield from _classes(node.body, prefix)


def public_class_names(trees: dict[str, ast.Module]) -> dict[str, list[str]]:
    """Public class name -> the ``module.Class`` paths that define a class of that name
    (public: no part of the module path nor of the class path starts with ``_``)."""
    seen: dict[str, list[str]] = {}
    for mod, tree in trees.items():
        for qual in _classes(tree.body, ""):
            path = f"{mod}.{qual}"
            if not any(_private(part) for part in path.split(".")[1:]):
                seen.setdefault(qual.rpartition(".")[2], []).append(path)
    return seen


def test_one_public_class_per_name():
    """No two public classes of the package share a name (``Comparison`` was two:
    comparison.results and persson.published), so a name in the docs is one class."""
    seen = public_class_names(TREES)
    assert len(seen) > 100 and "Law" in seen
    assert {k: v for k, v in seen.items() if len(v) > 1} == {}


def test_the_class_name_check_sees_nested_and_guarded_classes():
    trees = {"frictionlaws.a.x": ast.parse(
                 "class Result: pass\nclass _Hidden:\n    class Inner: pass\n"
                 "def f():\n    class Result: pass\n"),
             "frictionlaws.b.y": ast.parse(
                 "try:\n    class Result: pass\nexcept ImportError:\n    class Inner: pass\n"
                 "class Outer:\n    class Row: pass\n"),
             "frictionlaws.b._z": ast.parse("class Result: pass\n")}
    seen = public_class_names(trees)
    assert seen["Result"] == ["frictionlaws.a.x.Result", "frictionlaws.b.y.Result"]
    assert seen["Inner"] == ["frictionlaws.b.y.Inner"]  # _Hidden.Inner is private
    assert seen["Row"] == ["frictionlaws.b.y.Outer.Row"]


#: The smallest share of the test files that sit in a folder named after a room.
MIN_TESTS_IN_ROOMS = 0.80


def test_tests_are_laid_out_like_the_package():
    """``tests/<room>/`` for each room's tests (the package's sub-packages); the project's
    own checks (code rules, docs, packaging) stay at the top.  Basenames are unique
    across the tree (pytest imports each test module by its name)."""
    tests = Path(__file__).resolve().parent
    files = sorted(tests.rglob("test_*.py"))
    rooms = {p.name for p in PACKAGE.iterdir() if (p / "__init__.py").is_file()}
    folders = {p.parent.name for p in files if p.parent != tests}
    assert folders <= rooms, f"test folders that are no room: {sorted(folders - rooms)}"
    in_rooms = [p for p in files if p.parent != tests]
    assert len(in_rooms) / len(files) >= MIN_TESTS_IN_ROOMS, (len(in_rooms), len(files))
    names = [p.name for p in files]
    assert len(names) == len(set(names)), sorted({n for n in names if names.count(n) > 1})
