"""The shipped cache of formula texts (frictionlaws/law/formula_text.json) and its use.

``Law.pretty()`` reads a built-in law's text from the cache, so that printing a fit
report does not load sympy; the cache is only used while the law computes the numbers
it recorded.  Run ``python tests/law/test_formula_text.py`` to rewrite the cache after
changing a formula (this test then passes again); never edit the file by hand.
"""

from __future__ import annotations

import json
import subprocess
import sys
from dataclasses import replace

import pytest

import frictionlaws as fl
from frictionlaws.law import text as law_module
from frictionlaws.law.text import (
    _CHECK_RTOL,
    FORMULA_TEXT_FILE,
    formula_check,
    formula_text_entries,
)


def _builtin_laws() -> list[fl.Law]:
    return [law for law in fl.list_laws() if law.formula.__module__.startswith("frictionlaws.")]


def test_cache_is_current() -> None:
    """The cache holds sympy's rendering of every built-in law, with its check values."""
    fresh = json.loads(json.dumps(formula_text_entries(_builtin_laws())))
    stored = json.loads(FORMULA_TEXT_FILE.read_text(encoding="utf-8"))
    stale = ("frictionlaws/law/formula_text.json is out of date: run "
             "python tests/law/test_formula_text.py")
    assert stored.keys() == fresh.keys() and stored["laws"].keys() == fresh["laws"].keys(), stale
    for law_id, entry in fresh["laws"].items():
        # Text and symbols to the letter; the check values (numpy's mu at two points)
        # within the tolerance the library itself applies, since their last digit
        # differs between numpy versions.
        old = stored["laws"][law_id]
        assert (old["text"], old["symbols"]) == (entry["text"], entry["symbols"]), stale
        assert old["mu"] == pytest.approx(entry["mu"], rel=_CHECK_RTOL, abs=0), stale


def test_every_builtin_law_is_cached() -> None:
    """Each built-in law has a finite check (a cache entry), persson aside or not."""
    stored = json.loads(FORMULA_TEXT_FILE.read_text(encoding="utf-8"))["laws"]
    missing = [law.id for law in _builtin_laws() if law.id not in stored]
    assert missing in ([], ["persson"]), missing


def test_pretty_is_the_rendering() -> None:
    for law in _builtin_laws():
        assert law.pretty() == law.rendered_text(), law.id


def test_changed_formula_is_rendered_not_read() -> None:
    """A law whose numbers differ from the cache's (same id) is rendered by sympy."""
    thirion = fl.get_law("thirion")
    changed = replace(thirion, formula=lambda m, p, a, b: 1.0 / (a + 2.0 * b * p))
    assert law_module._cached_text(thirion) == "mu = 1.0/(a + b*p)"
    assert law_module._cached_text(changed) is None
    assert changed.pretty() == "mu = 1.0/(a + 2.0*b*p)"
    renamed = replace(thirion, floors={"p": 1.0})  # sympy's assumptions differ
    assert law_module._cached_text(renamed) is None


def test_check_refuses_a_formula_that_cannot_run() -> None:
    def broken(m, p, a, b):  # noqa: ANN001, ANN202
        raise ZeroDivisionError

    law = replace(fl.get_law("thirion"), formula=broken)
    assert formula_check(law) is None
    assert law_module._cached_text(law) is None


def test_pretty_without_sympy() -> None:
    code = ("import sys, frictionlaws as fl\n"
            "text = fl.get_law('savkoor').pretty()\n"
            "assert text.startswith('mu = (p/p_ref)**n'), text\n"
            "assert 'sympy' not in sys.modules\n")
    subprocess.run([sys.executable, "-c", code], check=True)


def _write() -> None:
    doc = formula_text_entries(_builtin_laws())
    FORMULA_TEXT_FILE.write_text(json.dumps(doc, indent=1, sort_keys=True) + "\n",
                                 encoding="utf-8")
    print(f"wrote {FORMULA_TEXT_FILE} ({len(doc['laws'])} laws)")


if __name__ == "__main__":
    _write()
