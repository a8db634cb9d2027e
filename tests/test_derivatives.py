"""The analytic Jacobians (frictionlaws/derivatives.py, laws/_jacobians.py) and lean fits."""

from __future__ import annotations

import numpy as np
import pytest

import frictionlaws as fl
from frictionlaws import derivatives
from frictionlaws._lsq import Problem, numeric_jacobian
from frictionlaws.law_examples import EXAMPLES

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


def test_every_generated_entry_is_used():
    """No stale entry: each law in the generated table exists and its probe still matches.

    The table is a speed cache: a law without an entry (a new law before
    ``python -m frictionlaws.derivatives`` is run, a plugin) fits with finite
    differences, so adding a law needs its module and its example entry only.
    """
    from frictionlaws.laws import _jacobians

    for law_id in _jacobians.JACOBIANS:
        assert derivatives.jacobian_function(fl.get_law(law_id)) is not None, law_id


def test_generated_module_is_current():
    pytest.importorskip("sympy")
    from frictionlaws.laws import _jacobians

    laws = [law for law in fl.list_laws() if law.id in _jacobians.JACOBIANS]
    text = derivatives.generate_source(laws)
    assert derivatives.MODULE_PATH.read_text(encoding="utf-8") == text, (
        "frictionlaws/laws/_jacobians.py is stale: run python -m frictionlaws.derivatives")


def test_a_law_without_a_generated_entry_fits_with_finite_differences():
    from dataclasses import replace

    law = fl.get_law("thirion")
    twin = replace(law, id="thirion-uncached", aliases=())
    assert derivatives.jacobian_function(twin) is None
    p = np.linspace(0.05e6, 0.3e6, 30)
    mu = law(p=p, a=0.2, b=0.4)
    a = fl.fit(law, {"p": p, "mu": mu}).values
    b = fl.fit(twin, {"p": p, "mu": mu}).values
    assert a == pytest.approx(b, rel=1e-6)


@pytest.mark.parametrize("law_id", sorted(EXAMPLES))
def test_analytic_jacobian_matches_finite_differences(law_id):
    law = fl.get_law(law_id)
    if law_id in NOT_SYMBOLIC:
        assert derivatives.jacobian_function(law) is None
        return
    x, values = _sample(law)
    names = [p.name for p in law.params] + [s.name for s in law.settings]
    n = next(iter(x.values())).size if x else 5
    y = np.zeros(n)
    held = {k: v for k, v in values.items() if k not in names}
    lower, upper = np.full(len(names), -np.inf), np.full(len(names), np.inf)
    prob = Problem(law, x, y, None, held, names, lower, upper)
    theta = np.array([values[k] for k in names])
    exact = prob.jacobian(theta)
    approx = numeric_jacobian(prob.model, theta, np.where(theta == 0, 1.0, theta))
    scale = np.maximum(np.max(np.abs(approx), axis=0), 1e-12)
    np.testing.assert_allclose(exact / scale, approx / scale, rtol=1e-5, atol=2e-5,
                               err_msg=law_id)


def test_a_changed_formula_is_not_given_stale_derivatives():
    from dataclasses import replace

    law = fl.get_law("thirion")
    changed = replace(law, formula=lambda m, p, a, b: 2.0 / (a + b * p))
    assert derivatives.jacobian_function(law) is not None
    assert derivatives.jacobian_function(changed) is None
    res = fl.fit(changed, {"p": np.linspace(1e4, 1e6, 30),
                           "mu": 2.0 / (0.3 + 3e-6 * np.linspace(1e4, 1e6, 30))})
    assert res.params["a"].value == pytest.approx(0.3, rel=1e-6)


def test_lean_fit_gives_the_same_values_without_diagnostics():
    full = fl.fit("savkoor", "thesis-steel", on_invalid="drop")
    lean = fl.fit("savkoor", "thesis-steel", on_invalid="drop", lean=True)
    assert lean.values == full.values
    assert lean.metrics == full.metrics
    assert lean.derived == {} and lean.provenance == {} and lean.non_identifiable == []
    assert full.non_identifiable


@pytest.mark.parametrize("bad", [{"lean": 1}, {"lean": True, "uncertainty": "bootstrap"}])
def test_lean_refuses_nonsense(bad):
    with pytest.raises(fl.InputError):
        fl.fit("thirion", "thesis-steel", **bad)


@pytest.mark.parametrize("law_id", sorted(EXAMPLES))
def test_stored_formula_text_is_the_sympy_text(law_id):
    pytest.importorskip("sympy")
    law = fl.get_law(law_id)
    assert derivatives.formula_text(law) == law.pretty()


def test_fit_report_imports_neither_sympy_nor_pint_nor_lmfit():
    import subprocess
    import sys

    code = ("import sys, frictionlaws as fl; r = fl.fit('thirion', 'thesis-steel'); "
            "r.report(); print(sorted(m for m in ('sympy', 'pint', 'lmfit', 'scipy.stats') "
            "if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "[]"
