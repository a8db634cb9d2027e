"""The caches derived from the laws' declarations, and the one command that rebuilds them."""

from __future__ import annotations

import json
import subprocess
import sys
from dataclasses import replace

import pytest

from frictionlaws import caches
from frictionlaws.fitting.derivatives import MODULE_PATH
from frictionlaws.law import FORMULA_TEXT_FILE


def test_the_table_holds_every_generated_file_and_each_is_current() -> None:
    assert {c.path for c in caches.CACHES} == {FORMULA_TEXT_FILE, MODULE_PATH}
    assert caches.stale() == [], f"run {caches.COMMAND}"


def test_rebuild_rewrites_a_stale_cache_and_only_it(tmp_path) -> None:
    copies = [replace(c, path=tmp_path / c.path.name) for c in caches.CACHES]
    for original, copy in zip(caches.CACHES, copies):
        copy.path.write_bytes(original.path.read_bytes())
    texts = copies[0]
    texts.path.write_text(texts.path.read_text().replace("mu = ", "mu == ", 1))
    assert caches.stale(copies) == [texts]
    assert caches.rebuild(copies) == [texts.path]
    assert caches.stale(copies) == []
    # The same laws, symbols and sample values; the text itself may be printed differently by
    # another sympy release (2*a or 2.0*a), which the currency check allows.
    rebuilt, committed = (json.loads(p.read_text()) for p in (texts.path, FORMULA_TEXT_FILE))
    assert rebuilt["laws"].keys() == committed["laws"].keys()
    for name, entry in committed["laws"].items():
        assert rebuilt["laws"][name]["symbols"] == entry["symbols"]
        assert rebuilt["laws"][name]["mu"] == pytest.approx(entry["mu"], rel=1e-9)
        assert rebuilt["laws"][name]["text"].startswith("mu = ")
    assert caches.rebuild(copies) == []


def test_the_command_names_what_it_found(tmp_path) -> None:
    # Run away from the source tree, so the command imports the package the tests import
    # (an installed copy in CI, the source tree in an editable install).
    proc = subprocess.run([sys.executable, "-m", "frictionlaws.caches"], capture_output=True,
                          text=True, check=True, cwd=tmp_path)
    assert proc.stdout.startswith("every cache is current: ")
    assert str(FORMULA_TEXT_FILE) in proc.stdout and str(MODULE_PATH) in proc.stdout
