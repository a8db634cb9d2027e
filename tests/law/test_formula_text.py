"""The shipped cache of formula texts (frictionlaws/law/formula_text.json) and its use.

``Law.pretty()`` reads a built-in law's text from the cache, so that printing a fit
report does not load sympy; the cache is only used while the law computes the numbers
it recorded.  Run ``python -m frictionlaws.caches`` to rewrite the cache after changing a
formula (this test then passes again); never edit the file by hand.
"""

from __future__ import annotations

import json
import subprocess
import sys
from dataclasses import replace

import frictionlaws as fl
from frictionlaws.caches import COMMAND
from frictionlaws.law import text as law_module
from frictionlaws.law.registry import builtin_laws
from frictionlaws.law.text import (
    _CHECK_RTOL,
    FORMULA_TEXT_FILE,
    formula_check,
    formula_text_entries,
    formula_texts_current,
    write_formula_texts,
)


def test_cache_is_current() -> None:
    """The cache holds sympy's rendering of every built-in law, with its check values."""
    assert formula_texts_current(builtin_laws()), (
        f"frictionlaws/law/formula_text.json is out of date: run {COMMAND}")


def test_the_currency_check_sees_a_changed_text_and_a_changed_value(tmp_path) -> None:
    """A copy with one text changed, or one check value off by more than the tolerance
    numpy's last digit needs, is stale; rewritten, it is current again."""
    laws = builtin_laws()
    doc = formula_text_entries(laws)
    copy = tmp_path / "formula_text.json"
    entry = doc["laws"]["thirion"]
    for changed in ({**entry, "text": entry["text"] + " "},
                    {**entry, "mu": [entry["mu"][0] * (1 + 100 * _CHECK_RTOL), entry["mu"][1]]}):
        copy.write_text(json.dumps({**doc, "laws": {**doc["laws"], "thirion": changed}}))
        assert not formula_texts_current(laws, copy)
    near = {**entry, "mu": [entry["mu"][0] * (1 + _CHECK_RTOL / 10), entry["mu"][1]]}
    copy.write_text(json.dumps({**doc, "laws": {**doc["laws"], "thirion": near}}))
    assert formula_texts_current(laws, copy)
    assert write_formula_texts(laws, copy) == copy and formula_texts_current(laws, copy)


def test_every_builtin_law_is_cached() -> None:
    """Each built-in law has a finite check (a cache entry), persson aside or not."""
    stored = json.loads(FORMULA_TEXT_FILE.read_text(encoding="utf-8"))["laws"]
    missing = [law.id for law in builtin_laws() if law.id not in stored]
    assert missing in ([], ["persson"]), missing


def test_pretty_is_the_rendering() -> None:
    for law in builtin_laws():
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

