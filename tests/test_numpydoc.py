"""numpydoc validation of the public API, with an allow-list that can only shrink.

Every function and class in ``frictionlaws.__all__``, and the public methods and
properties each of those classes defines, is checked with
:func:`numpydoc.validate.validate`.  Not checked: SA01 (See Also), EX01 (Examples),
ES01 (extended summary) and GL08 (no docstring: a property or method whose name says it
all may go without one).

``KNOWN_FAILURES`` lists the objects that still fail.  The test asserts that the failing
set is *exactly* that list: a new failure fails the test, and so does an allow-listed
object that has become clean (then delete it from the list).  Objects may be listed only
from the modules in ``PENDING_MODULES``; everything else must validate.

numpydoc is in the ``docs`` and ``test`` extras; without it the test is skipped.
"""

from __future__ import annotations

import inspect
from collections.abc import Iterator

import pytest

import frictionlaws

numpydoc_validate = pytest.importorskip("numpydoc.validate")

#: Checks not enforced (see the module docstring).
IGNORED = frozenset({"SA01", "EX01", "ES01", "GL08"})

#: Modules whose docstrings were left for later (they were being changed elsewhere when
#: the rest of the public API was made clean); only their objects may be allow-listed.
PENDING_MODULES: tuple[str, ...] = ()

#: Public objects whose docstrings still fail validation.  Remove a name when its
#: docstring is fixed (the test tells you); never add one.
KNOWN_FAILURES: frozenset[str] = frozenset()


def public_objects() -> Iterator[str]:
    """Yield the import path of every public API object that is validated.

    Yields
    ------
    str
        ``module.qualname`` of each function and class in ``frictionlaws.__all__``,
        and of the public methods and properties each of those classes defines.
    """
    for name in frictionlaws.__all__:
        obj = getattr(frictionlaws, name)
        if not (inspect.isfunction(obj) or inspect.isclass(obj)):
            continue
        path = f"{obj.__module__}.{obj.__qualname__}"
        yield path
        if inspect.isclass(obj):
            for attr, value in vars(obj).items():
                if attr.startswith("_"):
                    continue
                if inspect.isfunction(value) or isinstance(value, property):
                    yield f"{path}.{attr}"


def failures() -> dict[str, list[str]]:
    """Validate the public API.

    Returns
    -------
    dict of str to list of str
        Import path -> ``"CODE message"`` of each enforced check it fails; only
        objects with at least one failure.
    """
    out: dict[str, list[str]] = {}
    for path in public_objects():
        result = numpydoc_validate.validate(path)
        errors = [f"{code} {msg}" for code, msg in result["errors"] if code not in IGNORED]
        if errors:
            out[path] = errors
    return out


def test_the_public_api_is_validated():
    objects = list(public_objects())
    assert len(objects) == len(set(objects))
    assert "frictionlaws.io.packaged.load_dataset" in objects
    assert "frictionlaws.tyre.brush.model.BrushModel.cornering" in objects


def test_known_failures_are_only_in_pending_modules():
    outside = sorted(n for n in KNOWN_FAILURES
                     if not any(n.startswith(m + ".") for m in PENDING_MODULES))
    assert not outside, f"allow-listed outside {PENDING_MODULES}: {outside}"


def test_numpydoc_validation_matches_the_allow_list():
    found = failures()
    new = {k: v for k, v in found.items() if k not in KNOWN_FAILURES}
    fixed = sorted(KNOWN_FAILURES - set(found))
    report = []
    if new:
        report.append("docstrings failing numpydoc validation:\n" + "\n".join(
            f"  {k}: {e}" for k, errs in sorted(new.items()) for e in errs))
    if fixed:
        report.append("now clean, delete from KNOWN_FAILURES in tests/test_numpydoc.py:\n"
                      + "\n".join(f"  {k}" for k in fixed))
    assert not report, "\n".join(report)
    assert set(found) == KNOWN_FAILURES
