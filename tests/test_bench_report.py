"""The report benchmark's baseline: the comparison report of another git revision, loaded
beside the current one, whether it was then one module or the package it is now."""

from __future__ import annotations

import runpy
import shutil
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import pytest

REPO = Path(__file__).resolve().parents[1]
BENCH = REPO / "benchmarks" / "bench_report.py"


def _git(*args: str) -> str:
    return subprocess.run(["git", *args], cwd=REPO, check=True, capture_output=True,
                          text=True).stdout.strip()


@pytest.fixture(scope="module")
def bench() -> SimpleNamespace:
    """The benchmark script's functions (run as a script without ``__main__``)."""
    if shutil.which("git") is None or not (REPO / ".git").exists() or not BENCH.exists():
        pytest.skip("needs the repository's git history and benchmarks/")
    return SimpleNamespace(**runpy.run_path(str(BENCH), run_name="bench_report_under_test"))


def _module_era() -> str:
    """A revision whose report is the single module ``report.py`` (the parent of the last
    commit that touched it); skipped in a clone without that history."""
    last = _git("log", "--format=%H", "-1", "--", "frictionlaws/comparison/report.py")
    if not last:
        pytest.skip("no revision with frictionlaws/comparison/report.py in this clone")
    return f"{last}^"


@pytest.mark.parametrize("era", ["package", "module"])
def test_the_report_of_a_revision_loads_beside_the_current_one(bench, era, tmp_path):
    ref = "HEAD" if era == "package" else _module_era()
    aliased = [f"frictionlaws.{old}" for old in bench.MOVED_MODULES
               if f"frictionlaws.{old}" not in sys.modules]
    try:
        old = bench.load_revision(ref, tmp_path)
    finally:
        name = "frictionlaws.comparison._report_at_ref"
        loaded = sys.modules.pop(name, None)
        for sub in [m for m in sys.modules if m.startswith(f"{name}.")]:
            del sys.modules[sub]
        for alias in aliased:  # the old names of moved modules, for that revision only
            sys.modules.pop(alias, None)
    assert loaded is old
    assert callable(old.write_report) and callable(old.format_table)
    files = {p.name for p in tmp_path.rglob("*.py")}
    if era == "package":
        assert {"__init__.py", "figures.py", "text.py"} <= files
    else:
        assert files == {"_report_at_ref.py"}
    from frictionlaws.comparison import report

    assert old.write_report is not report.write_report  # the revision's own code


def test_a_revision_without_the_report_is_named(bench, tmp_path):
    first = _git("rev-list", "--max-parents=0", "HEAD").split()[0]
    with pytest.raises(SystemExit, match="no report module at"):
        bench.load_revision(first, tmp_path)
