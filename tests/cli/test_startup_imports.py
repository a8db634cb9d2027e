"""`frictionlaws fit` on a packaged dataset loads no heavy module it does not need.

The fit path needs numpy and scipy.optimize (the solver); the formula text comes from
the cached rendering (no sympy), the units of the packaged data from the unit table
(no pint), the CSV through the table reader into numpy columns (no pandas), and the
t quantile from scipy.special (no scipy.stats).  Not timed: benchmarks/bench_startup.py
measures the start-up time.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

#: Modules the fit command must not load.
HEAVY = ("sympy", "pint", "pandas", "matplotlib", "scipy.stats", "lmfit")

_SCRIPT = r'''
import builtins, json, sys

asked = set()
_import = builtins.__import__


def _record(name, globals=None, locals=None, fromlist=(), level=0):
    caller = (globals or {}).get("__name__") or ""
    if level == 0 and caller.split(".")[0] == "frictionlaws":
        asked.add(name)
        asked.update(f"{name}.{item}" for item in fromlist or ())
    return _import(name, globals, locals, fromlist, level)


builtins.__import__ = _record
from frictionlaws.cli import main

code = main(sys.argv[2:])
with open(sys.argv[1], "w") as fh:
    json.dump({"code": code, "modules": sorted(sys.modules), "asked": sorted(asked)}, fh)
'''


def _under(name: str, module: str) -> bool:
    return name == module or name.startswith(module + ".")


@pytest.fixture(scope="module")
def fit_run(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    tmp = tmp_path_factory.mktemp("startup")
    out, saved = tmp / "imports.json", tmp / "fit.json"
    argv = ["fit", "--law", "thirion", "thesis-steel", "--save", str(saved)]
    proc = subprocess.run([sys.executable, "-c", _SCRIPT, str(out), *argv], cwd=tmp,
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    run = json.loads(out.read_text())
    run["saved"] = saved
    run["stdout"] = proc.stdout
    return run


def test_fit_runs_and_saves(fit_run: dict[str, Any]) -> None:
    assert fit_run["code"] == 0
    assert "formula: mu = 1.0/(a + b*p)" in fit_run["stdout"]
    assert "p 0.03119..0.2496 MPa" in fit_run["stdout"]
    assert json.loads(Path(fit_run["saved"]).read_text())["law"] == "thirion"


@pytest.mark.parametrize("module", HEAVY)
def test_frictionlaws_code_does_not_import(fit_run: dict[str, Any], module: str) -> None:
    """No import statement of frictionlaws on the fit path names a heavy module."""
    asked = [name for name in fit_run["asked"] if _under(name, module)]
    assert not asked, f"the fit path imports {asked}"


@pytest.mark.parametrize("module", HEAVY)
def test_fit_does_not_load(fit_run: dict[str, Any], module: str) -> None:
    """Nothing on the fit path loads a heavy module."""
    loaded = [name for name in fit_run["modules"] if _under(name, module)]
    assert not loaded, f"the fit path loads {loaded[:5]}"


def test_fit_loads_numpy_and_scipy_optimize(fit_run: dict[str, Any]) -> None:
    assert {"numpy", "scipy.optimize"} <= set(fit_run["modules"])
    assert "numpy" in fit_run["asked"]  # the import record works (the checks above can fail)
