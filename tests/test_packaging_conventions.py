"""Packaging conventions: dependencies declared where they are imported,
comparisons as DataFrames, ``validate --list --json`` as strict JSON."""

from __future__ import annotations

import ast
import json
import re
import sys
from pathlib import Path

import pytest

import frictionlaws
from frictionlaws.cli import main

PACKAGE = Path(frictionlaws.__file__).resolve().parent
PYPROJECT = Path(__file__).resolve().parents[1] / "pyproject.toml"

#: Import name -> distribution name where they differ.
DISTRIBUTION = {"dask": "dask", "distributed": "dask", "yaml": "pyyaml"}


def _toml() -> dict:
    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover - Python 3.10
        import tomli as tomllib
    return tomllib.loads(PYPROJECT.read_text(encoding="utf-8"))


def _names(requirements: list[str]) -> set[str]:
    return {re.split(r"[<>=!~;\[ ]", r, maxsplit=1)[0].strip().lower() for r in requirements}


def _imported() -> set[str]:
    """Top-level third-party packages the library imports anywhere (also lazily)."""
    stdlib = set(sys.stdlib_module_names) | {"tomllib"}  # stdlib from 3.11 (tomli before)
    found: set[str] = set()
    for path in PACKAGE.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                tops = [a.name.split(".")[0] for a in node.names]
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                tops = [node.module.split(".")[0]]
            else:
                continue
            found.update(t for t in tops if t not in stdlib and t != "frictionlaws")
    return found


@pytest.mark.skipif(not PYPROJECT.exists(), reason="needs the source tree's pyproject.toml")
def test_every_imported_package_is_declared_and_pytest_is_not_a_runtime_dependency():
    project = _toml()["project"]
    runtime = _names(project["dependencies"])
    extras = set().union(*(_names(v) for v in project["optional-dependencies"].values()))
    assert "pytest" not in runtime
    missing = sorted(m for m in _imported()
                     if DISTRIBUTION.get(m, m).lower() not in runtime | extras)
    assert not missing, f"imported but not declared in pyproject.toml: {missing}"


def test_a_comparison_is_a_tidy_frame():
    from frictionlaws.comparison import compare

    cmp = compare(data="thesis-steel", laws=["thirion", "coulomb"], folds=3, progress=False)
    frame = cmp.to_frame()
    assert len(frame) == 2
    assert {"thirion", "coulomb"} <= set(frame.astype(str).to_numpy().ravel())


def test_validate_list_json_is_strict(capsys):
    assert main(["validate", "--list", "--json"]) == 0
    cases = json.loads(capsys.readouterr().out,
                       parse_constant=lambda c: pytest.fail(f"non-strict JSON constant {c}"))
    assert cases and all({"id", "title", "source"} <= set(c) for c in cases)
