"""The analytic Jacobians (frictionlaws/fitting/derivatives.py, fitting/_jacobians.py) and the
lean solver."""

from __future__ import annotations

import re

import numpy as np
import pytest

import frictionlaws as fl
from frictionlaws.caches import COMMAND
from frictionlaws.fitting import derivatives
from frictionlaws.fitting import diagnosis as fit_diagnosis
from frictionlaws.fitting import search as fit_search
from frictionlaws.law.registry import builtin_laws
from frictionlaws.validation.law_examples import EXAMPLES

#: Laws without a symbolic form (numerical integral): finite differences are used.
NOT_SYMBOLIC = {"persson"}


def _sample(law, n=40, seed=3):
    ex = EXAMPLES[law.id].battery
    rng = np.random.default_rng(seed)
    x = {}
    for var in law.variables:
        lo, hi = ex.ranges.get(var, law.typical_range(var))
        x[var] = (np.exp(rng.uniform(np.log(lo), np.log(hi), n)) if var in ex.log
                  else rng.uniform(lo, hi, n))
    return x, law.resolve({**ex.params, **ex.fix})


def _synthetic(law_id, n, seed=0):
    law = fl.get_law(law_id)
    ex = EXAMPLES[law_id].battery
    x, values = _sample(law, n, seed)
    mu = np.asarray(law.evaluate(x, values), float)
    mu = mu + 0.02 * np.mean(np.abs(mu)) * np.random.default_rng(seed + 1).standard_normal(n)
    return {**x, "mu": mu}, dict(ex.fix)


def test_generated_module_covers_every_symbolic_builtin_law():
    have = {law.id for law in fl.list_laws() if derivatives.jacobian_function(law)}
    assert have == {law.id for law in fl.list_laws()} - NOT_SYMBOLIC


def test_generated_module_is_current():
    assert derivatives.module_current(builtin_laws()), (
        f"frictionlaws/fitting/_jacobians.py is stale: run {COMMAND}")


def test_the_currency_check_sees_changed_code_but_not_numpys_last_digit(tmp_path):
    laws = builtin_laws()
    copy = tmp_path / "_jacobians.py"
    text = derivatives.generate_source(laws)
    copy.write_text(text.replace("numpy.exp", "numpy.expm1", 1))
    assert "numpy.exp" in text and not derivatives.module_current(laws, copy)
    check = re.search(r"'mu': \[(-?\d\.\d{12,})", text)  # 13+ significant digits
    assert check is not None
    last_digit = f"{check.group(1)[:-1]}{(int(check.group(1)[-1]) + 1) % 10}"
    copy.write_text(text.replace(check.group(1), last_digit, 1))
    assert derivatives.module_current(laws, copy)
    assert derivatives.write_module(laws, copy) == copy
    assert copy.read_text() == text


@pytest.mark.parametrize("law_id", sorted(EXAMPLES))
def test_analytic_jacobian_matches_finite_differences(law_id):
    law = fl.get_law(law_id)
    func = derivatives.jacobian_function(law)
    if law_id in NOT_SYMBOLIC:
        assert func is None
        return
    x, values = _sample(law)
    names = [p.name for p in law.params] + [s.name for s in law.settings]
    n = next(iter(x.values())).size if x else 5
    prepared = law.prepare_variables(x)
    exact = derivatives.model_jacobian(func, prepared, values, names, n)

    def model(theta):
        vals = {**values, **dict(zip(names, theta))}
        return np.broadcast_to(np.asarray(law.formula(fl.law.NUMPY, **prepared, **vals),
                                          float), (n,))

    theta = np.array([values[k] for k in names])
    approx = fit_diagnosis._jacobian(model, theta, np.where(theta == 0, 1.0, theta))
    scale = np.maximum(np.max(np.abs(approx), axis=0), 1e-12)
    np.testing.assert_allclose(exact / scale, approx / scale, rtol=1e-5, atol=2e-5,
                               err_msg=law_id)


def test_a_changed_formula_is_not_given_stale_derivatives():
    from dataclasses import replace

    law = fl.get_law("thirion")
    changed = replace(law, formula=lambda m, p, a, b: 2.0 / (a + b * p))
    assert derivatives.jacobian_function(law) is not None
    assert derivatives.jacobian_function(changed) is None
    p = np.linspace(1e4, 1e6, 3000)
    res = fl.fit(changed, {"p": p, "mu": 2.0 / (0.3 + 3e-6 * p)})
    assert res.params["a"].value == pytest.approx(0.3, rel=1e-6)


@pytest.mark.parametrize("law_id", ["thirion", "savkoor", "wriggers", "burckhardt"])
def test_the_lean_solver_ends_where_lmfit_does(law_id):
    """From the same start, the library's solve and lmfit's least_squares agree."""
    lmfit = pytest.importorskip("lmfit")
    data, fix = _synthetic(law_id, 120)
    law = fl.get_law(law_id)
    ours = fl.fit(law, data, fix=fix, weights=None, starts=0)
    from frictionlaws.law.interop import lmfit_model

    model = lmfit_model(law)
    params = model.make_params()
    guess = law.initial_guess(data)
    for p in law.params:
        if p.name in fix:
            params[p.name].set(value=fix[p.name], vary=False)
        else:
            params[p.name].set(value=guess[p.name], min=p.bounds[0], max=p.bounds[1])
    xs = {k: data[k] for k in law.variables}
    with np.errstate(all="ignore"):
        theirs = model.fit(data["mu"], params, method="least_squares", **xs)
    assert ours.metrics["chisqr"] <= theirs.chisqr * (1 + 1e-9)
    if ours.metrics["chisqr"] >= theirs.chisqr * (1 - 1e-9):  # the same minimum
        for k in law.param_names:
            assert ours.params[k].value == pytest.approx(theirs.params[k].value, rel=1e-6,
                                                         abs=1e-12)
    assert isinstance(ours.lmfit_result, lmfit.model.ModelResult)


@pytest.mark.parametrize("law_id", ["thirion", "pacejka", "burckhardt", "savkoor"])
def test_large_fits_with_analytic_jacobians_reach_the_finite_difference_optimum(
        law_id, monkeypatch):
    data, fix = _synthetic(law_id, 3000)
    fast = fl.fit(law_id, data, fix=fix, weights=None)
    monkeypatch.setattr(fit_search, "ANALYTIC_FROM", 10**9)
    slow = fl.fit(law_id, data, fix=fix, weights=None)
    assert fast.metrics["chisqr"] <= slow.metrics["chisqr"] * (1 + 1e-7)
    for k, est in slow.params.items():
        if not est.fixed:
            assert fast.params[k].value == pytest.approx(est.value, rel=1e-4, abs=1e-9), k
            # finite differences step by 1.5e-8 absolute: for b ~ 2e-6 (thirion) that is
            # 0.7 % of the value, so their standard errors are off by up to ~0.5 %
            assert fast.params[k].stderr == pytest.approx(est.stderr, rel=1e-2), k
    assert fast.non_identifiable == slow.non_identifiable


def test_starts_stop_once_one_reproduces_the_best(monkeypatch):
    """burckhardt has eight deterministic starts; two in the same basin are enough."""
    runs = []
    original = fit_search._Search.run

    def counted(self, start, pinned=()):
        runs.append(dict(start))
        original(self, start, pinned)

    monkeypatch.setattr(fit_search._Search, "run", counted)
    data, fix = _synthetic("burckhardt", 400)
    res = fl.fit("burckhardt", data, fix=fix, weights=None)
    assert res.success
    law = fl.get_law("burckhardt")
    assert len(fit_search._starts(law, law.initial_guess(data), list(law.param_names))) > 3
    assert len(runs) == 2


def test_reproduced_needs_two_fits_at_the_same_chi2():
    assert not fit_search._reproduced([1.0])
    assert fit_search._reproduced([1.0, 1.0 + 1e-9])
    assert not fit_search._reproduced([1.0, 1.1])
    assert fit_search._reproduced([1.1, 1.0, 1.0])
    assert not fit_search._reproduced([1.0, 1.1, 1.2])


def test_a_fit_does_not_import_lmfit_or_scipy_stats():
    import subprocess
    import sys

    code = ("import sys, frictionlaws as fl; r = fl.fit('thirion', 'thesis-steel'); "
            "r.report(); print(sorted(m for m in ('lmfit', 'scipy.stats') "
            "if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "[]"


def test_lean_fit_gives_the_same_values_without_diagnostics():
    full = fl.fit("savkoor", "thesis-steel", on_invalid="drop")
    lean = fl.fit("savkoor", "thesis-steel", on_invalid="drop", lean=True)
    # savkoor has parameters these data cannot determine: their values are one point of a
    # flat valley, which the solver's path picks (rounding in the linear algebra moves it
    # by 1e-3), so they are compared through what is determined: the optimum's chi^2 to
    # 1e-9, every other metric and the determined parameters to 1e-6.
    assert lean.metrics.keys() == full.metrics.keys()
    for key, value in full.metrics.items():
        rel = 1e-9 if key == "chisqr" else 1e-6
        assert lean.metrics[key] == pytest.approx(value, rel=rel, abs=1e-12), key
    for name, value in full.values.items():
        if name not in full.non_identifiable:
            assert lean.values[name] == pytest.approx(value, rel=1e-6), name
    assert lean.success == full.success
    assert lean.derived == {} and lean.provenance == {}
    assert all(p.ci95 is None for p in lean.params.values())
    # the identifiability check stays: the same names, their errors withheld
    assert full.non_identifiable and lean.non_identifiable == full.non_identifiable
    for name in lean.non_identifiable:
        assert lean.params[name].stderr is None and not lean.params[name].identifiable


@pytest.mark.parametrize("bad", [{"lean": 1}, {"lean": "yes"},
                                 {"lean": True, "uncertainty": "bootstrap"}])
def test_lean_refuses_nonsense(bad):
    with pytest.raises(fl.InputError, match="lean"):
        fl.fit("thirion", "thesis-steel", **bad)


def test_cross_validation_refits_are_lean():
    from frictionlaws.comparison.cv import refit
    from frictionlaws.fitting import as_fit_data

    res = refit(fl.get_law("thirion"), as_fit_data("thesis-steel"))
    assert res.provenance == {} and "lean fit" in " ".join(res.notes)


def _pacejka_search(n):
    data, fix = _synthetic("pacejka", n, seed=4)
    law = fl.get_law("pacejka")
    setup = fit_search._setup(law, data, fix, (), None, None, "error", {})
    return setup, fit_search._Search(setup, "least_squares")


def test_large_fits_refine_later_starts_on_a_subsample(monkeypatch):
    runs = []
    original = fit_search._Search.run

    def counted(self, start, pinned=()):
        runs.append(self.setup.y.size)
        original(self, start, pinned)

    monkeypatch.setattr(fit_search._Search, "run", counted)
    data, fix = _synthetic("pacejka", 5000, seed=4)
    res = fl.fit("pacejka", data, fix=fix, weights=None)
    assert res.success and runs.count(5000) == 1  # one full solve, after the scout's
    assert runs[-1] == 5000 and set(runs[:-1]) == {fit_search.SCOUT_ROWS}
    monkeypatch.setattr(fit_search, "SCOUT_ROWS", 10**6)
    slow = fl.fit("pacejka", data, fix=fix, weights=None)
    assert res.metrics["chisqr"] <= slow.metrics["chisqr"] * (1 + 1e-9)


def test_the_best_basin_found_on_the_subsample_is_refined_on_every_row():
    setup, search = _pacejka_search(5000)
    starts = fit_search._starts(setup.law, setup.guess, setup.vary_names)
    ends = [search.solve_from(s) for s in starts]
    chis = [e.chisqr if e is not None else np.inf for e in ends]
    worst = int(np.argmax(np.where(np.isfinite(chis), chis, -np.inf)))
    best = int(np.argmin(chis))
    assert chis[worst] > chis[best] * 1.01  # two basins among the deterministic starts
    setup, search = _pacejka_search(5000)
    assert not fit_search._scout(search, [starts[worst], starts[best]])  # two basins
    assert search.finals == [search.best.chisqr]  # one solve on every row, from the best
    assert search.best.chisqr == pytest.approx(chis[best], rel=1e-6)


@pytest.mark.parametrize("law_id", ["pacejka", "schallamach"])
def test_a_start_equal_to_an_earlier_one_is_not_tried_twice(law_id):
    """A preset equal to the defaults (pacejka's dry road, schallamach's hertz) is one
    start, so it cannot "reproduce" itself and end the search."""
    law = fl.get_law(law_id)
    names = [k for k in law.param_names if k not in ("S_h", "S_v")]
    guess = law.initial_guess(_synthetic(law_id, 60)[0])
    starts = fit_search._starts(law, guess, names)
    keys = [tuple(s[k] for k in names) for s in starts]
    assert len(keys) == len(set(keys))
    assert len(starts) == 1 + len(law.presets)  # the guess, and defaults = one preset
