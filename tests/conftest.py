"""Shared test configuration.

* The suite tests the *installed* package: the repository root (put on ``sys.path`` by
  ``python -m pytest`` and by pytest-xdist's workers) is taken off the path before
  anything imports frictionlaws, so ``import frictionlaws`` finds what ``pip install``
  put in site-packages (or the editable install's finder, for developers).
  ``tests/test_installed.py`` proves it.
* Property tests draw the same examples on every machine and run (hypothesis profile
  ``fixed``: derandomised), so a run's verdict does not depend on luck; set
  ``HYPOTHESIS_PROFILE=explore`` to let hypothesis search afresh (and keep what it finds
  in its database).
* ``tests/`` is importable (the ``hostile`` harness), and so is each room's folder (its
  test modules and helpers such as ``law_cases``); matplotlib draws with Agg.
* ``-m hostile`` (the hostile-input harness, CI budget 60 s) collects only the
  ``test_hostile*.py`` files (in each room's folder), where that marker lives
  (``tests/test_hostile_marker_scope.py`` keeps it so): importing the whole suite
  to deselect it cost about 15 s of CPU in each xdist process.
* The tests marked slow run first, so that the workers share them out early.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Any

import pytest
from hypothesis import settings

ROOT = Path(__file__).resolve().parent.parent


def _is_root(entry: str) -> bool:
    try:
        return Path(entry or ".").resolve() == ROOT
    except OSError:
        return False


if "frictionlaws" not in sys.modules:
    sys.path[:] = [p for p in sys.path if not _is_root(p)]
os.environ.setdefault("MPLBACKEND", "Agg")
settings.register_profile("fixed", derandomize=True, database=None)
settings.register_profile("explore")
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "fixed"))
sys.path.insert(0, str(Path(__file__).parent))
# Each room's folder too, in every process (pytest adds a test file's folder when it
# collects it, but pytest-xdist's controller collects nothing, and it imports a test
# module by name to rebuild a warning class that module defines).
sys.path += [str(p) for p in sorted(Path(__file__).parent.iterdir())
             if p.is_dir() and any(p.glob("test_*.py")) and str(p) not in sys.path]


def pytest_ignore_collect(collection_path: Path, config: Any) -> bool | None:
    """With ``-m hostile``, skip the files that hold no hostile case (module docstring)."""
    if (config.getoption("markexpr", "") == "hostile" and collection_path.suffix == ".py"
            and not collection_path.name.startswith("test_hostile")):
        return True
    return None


@pytest.hookimpl(trylast=True)
def pytest_collection_modifyitems(config: Any, items: list[Any]) -> None:
    """The tests marked slow first, each group in its order (a stable sort): pytest-xdist
    then starts the longest tests early and fills the gaps with the short ones, instead
    of ending on one long test on one worker while the other waits."""
    items.sort(key=lambda item: item.get_closest_marker("slow") is None)


@pytest.fixture(scope="module")
def small_campaign(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A synthetic campaign (rig.toml, manifest.csv, two records sampled at 100 Hz, so
    a Nyquist frequency of 50 Hz), fresh for each test module."""
    from frictionlaws.tribometer.synthetic import ConditionSpec, make_campaign

    root = tmp_path_factory.mktemp("campaign")
    make_campaign(root, [ConditionSpec("c", "steel", 3.0, 1.1, repeats=2)],
                  record_kwargs={"duration": 12.0, "fs": 100.0})
    return root
