"""The ``hostile`` marker lives only in ``test_hostile*.py`` files (in any folder of
``tests/``).

``tests/conftest.py`` collects only those files under ``-m hostile`` (so the CI run of the
harness does not import the whole suite): a hostile case placed in another file would be
silently left out of that run.  This test fails first.
"""

from __future__ import annotations

import re
from pathlib import Path

HERE = Path(__file__).resolve().parent
MARK = re.compile(r"\bmark\.hostile\b|\bHOSTILE\b")


def test_the_hostile_marker_is_used_only_in_the_harness_files() -> None:
    outside = [p.name for p in sorted(HERE.rglob("test_*.py"))
               if not p.name.startswith("test_hostile") and p != Path(__file__).resolve()
               and MARK.search(p.read_text(encoding="utf-8"))]
    assert not outside, f"hostile cases outside test_hostile*.py files: {outside}"
    inside = [p for p in HERE.rglob("test_hostile*.py") if MARK.search(p.read_text("utf-8"))]
    assert len({p.parent for p in inside}) > 1, "the harness files are spread over rooms"
    assert inside, "the pattern no longer finds the marker: update MARK"
