"""The library speaks of its arguments; only the command line speaks of flags."""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

import frictionlaws as fl
from frictionlaws.base.errors import InputError
from frictionlaws.cli import main

PACKAGE = Path(fl.__file__).resolve().parent
FLAG = re.compile(r"(?<![\w-])--[a-z][a-z0-9-]*")


def _message_strings(path: Path) -> list[tuple[int, str]]:
    """String constants of a module that are not docstrings (f-string pieces included)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    docs = {id(node.body[0].value) for node in ast.walk(tree)
            if isinstance(node, ast.Module | ast.FunctionDef | ast.AsyncFunctionDef
                          | ast.ClassDef)
            and node.body and isinstance(node.body[0], ast.Expr)
            and isinstance(node.body[0].value, ast.Constant)}
    return [(node.lineno, node.value) for node in ast.walk(tree)
            if isinstance(node, ast.Constant) and isinstance(node.value, str)
            and id(node) not in docs]


@pytest.mark.slow
def test_no_library_message_names_a_command_line_flag() -> None:
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        if "cli" in path.relative_to(PACKAGE).parts:
            continue
        found += [f"{path.relative_to(PACKAGE)}:{line}: {FLAG.search(text).group()}"
                  for line, text in _message_strings(path) if FLAG.search(text)]
    for path in sorted(PACKAGE.rglob("*.json")):
        found += [f"{path.relative_to(PACKAGE)}: {m.group()}"
                  for m in FLAG.finditer(path.read_text(encoding="utf-8"))]
    assert not found, found


def test_a_singular_row_names_the_argument_in_the_api_and_the_flag_on_the_cli(capsys) -> None:
    with pytest.raises(InputError) as err:
        fl.fit("savkoor", "thesis-steel")
    assert "on_invalid='drop'" in str(err.value) and "--" not in str(err.value)
    assert main(["fit", "--law", "savkoor", "thesis-steel"]) == 2
    line = capsys.readouterr().err
    assert "(--drop-invalid)" in line and "on_invalid" not in line


def test_undetermined_parameters_are_met_with_the_fix_argument() -> None:
    res = fl.fit("denny", "thesis-steel", free=["E_v"])
    text = " ".join(res.warnings)
    assert "argument fix" in text and "--fix" not in text
