"""The fit methods are one table: every entry fits, the search follows the table, and a
name outside it is refused naming those there are."""

from __future__ import annotations

from dataclasses import replace

import pytest

import frictionlaws as fl
from frictionlaws.base.errors import InputError
from frictionlaws.fitting import methods
from frictionlaws.fitting.data import check_fit_options


@pytest.fixture(scope="module")
def default_fit() -> fl.FitResult:
    return fl.fit("thirion", "thesis-steel")


@pytest.mark.parametrize("name", sorted(methods.FIT_METHODS))
def test_every_method_reaches_the_optimum(name: str, default_fit: fl.FitResult) -> None:
    res = fl.fit("thirion", "thesis-steel", method=name)
    assert res.success
    # a two-parameter convex problem: every minimiser ends at the same chi^2
    assert res.metrics["rmse"] == pytest.approx(default_fit.metrics["rmse"], rel=1e-4)
    for k, v in default_fit.values.items():
        assert res.values[k] == pytest.approx(v, rel=1e-3)


@pytest.mark.parametrize("bad", ["LEAST_SQUARES", "newton", "", None, 3])
def test_a_name_outside_the_table_is_refused_naming_the_table(bad: object) -> None:
    with pytest.raises(InputError) as info:
        check_fit_options(bad, None, 0, "error")
    assert info.value.option == "method"
    assert all(name in str(info.value) for name in methods.FIT_METHODS)
    with pytest.raises(InputError, match="method must be one of"):
        fl.fit("thirion", "thesis-steel", method=bad)  # type: ignore[arg-type]


def test_the_search_dispatches_through_the_table(monkeypatch: pytest.MonkeyPatch) -> None:
    """A new entry is a fit method at once: accepted by the check, solved by its own
    solve, polished (``lean=True``) when it says so."""
    calls: list[float] = []
    lean = methods.FIT_METHODS[methods.DEFAULT_METHOD]

    def counted(search, start, pinned, tol):  # noqa: ANN001, ANN202
        calls.append(tol)
        return lean.solve(search, start, pinned, tol)

    entry = replace(lean, name="counted-lean", description="the lean solver, counted",
                    solve=counted)
    monkeypatch.setitem(methods.FIT_METHODS, entry.name, entry)
    res = fl.fit("thirion", "thesis-steel", method="counted-lean", lean=True)
    assert calls and min(calls) < 1e-8  # the polish's tight tolerance was asked for
    polished = fl.fit("thirion", "thesis-steel", lean=True)
    assert res.values == pytest.approx(polished.values, rel=1e-9)
    monkeypatch.setitem(methods.FIT_METHODS, entry.name, replace(entry, polished=False))
    calls.clear()
    fl.fit("thirion", "thesis-steel", method="counted-lean", lean=True)
    assert calls and min(calls) == 1e-8  # no polish
