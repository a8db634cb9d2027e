"""Shared test configuration.

* The suite tests the *installed* package: the repository root (put on ``sys.path`` by
  ``python -m pytest`` and by pytest-xdist's workers) is taken off the path before
  anything imports frictionlaws, so ``import frictionlaws`` finds what ``pip install``
  put in site-packages (or the editable install's finder, for developers).
  ``tests/test_installed.py`` proves it.
* ``tests/`` is importable (``law_cases``); matplotlib draws with Agg.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def _is_root(entry: str) -> bool:
    try:
        return Path(entry or ".").resolve() == ROOT
    except OSError:
        return False


if "frictionlaws" not in sys.modules:
    sys.path[:] = [p for p in sys.path if not _is_root(p)]
os.environ.setdefault("MPLBACKEND", "Agg")
sys.path.insert(0, str(Path(__file__).parent))
