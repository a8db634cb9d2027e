"""One battery of checks applied to every registered law the same way.

The completeness guard fails when a law has no entry in ``tests/laws/law_cases.py``.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from law_cases import CASES

from frictionlaws import fit, get_law, list_laws
from frictionlaws.base.errors import DomainError, InputError
from frictionlaws.law import EVIDENCE_TAGS, VARIABLES

LAW_IDS = [law.id for law in list_laws()]


def sample(case, rng, n=None):
    """Random points of every variable of a case (SI)."""
    n = n or case.n
    out = {}
    for var, (lo, hi) in case.ranges.items():
        if var in case.log:
            out[var] = np.exp(rng.uniform(np.log(lo), np.log(hi), n))
        else:
            out[var] = rng.uniform(lo, hi, n)
    return out


def case_for(law):
    case = CASES[law.id]
    missing = [v for v in law.variables if v not in case.ranges]
    assert not missing, f"test case of {law.id} lacks ranges for {missing}"
    return case


def raw(law, preset=None, **kw):
    """The formula's numbers without the checks of ``law(...)`` (the battery tests the
    formula itself; the checks are tested in ``test_law_call_refuses_*``)."""
    variables = {k: v for k, v in kw.items() if k in VARIABLES}
    return law.evaluate(variables, law.resolve({k: v for k, v in kw.items()
                                                if k not in VARIABLES}, preset))


def test_law_call_refuses_negative_mu_and_a_strict_domain():
    poly3 = get_law("thesis-poly3")
    assert raw(poly3, p=0.25e6, v=2.77, preset="steel") < 0  # the published polynomial
    with pytest.raises(DomainError, match="negative mu"):
        poly3(p=0.25e6, v=2.77, preset="steel")
    # a negative mu in a late block of a large call: named at its index in the array
    from frictionlaws.law.evaluation import BLOCKED_FROM

    p, v = np.full(BLOCKED_FROM + 9, 0.1e6), np.full(BLOCKED_FROM + 9, 1.0)
    p[-3], v[-3] = 0.25e6, 2.77
    with pytest.raises(DomainError, match=f"negative mu .* at index {p.size - 3}"):
        poly3(p=p, v=v, preset="steel")
    with pytest.raises(DomainError, match="must not be extrapolated"):
        get_law("thesis-poly2")(p=0.0, v=7.0, preset="steel")
    assert get_law("thesis-poly2")(p=0.1e6, v=1.0, preset="steel") > 0


def test_completeness_guard():
    registered = set(LAW_IDS)
    tested = set(CASES)
    assert registered - tested == set(), (
        f"laws without an entry in frictionlaws/validation/law_examples.py: {registered - tested}")
    assert tested - registered == set(), f"test cases naming no law: {tested - registered}"


@pytest.mark.parametrize("law_id", LAW_IDS)
def test_declaration_is_complete(law_id):
    law = get_law(law_id)
    assert law.family in ("sliding", "slip")
    assert law.title and law.description and law.references
    tags = {t for t in EVIDENCE_TAGS if t in law.evidence.replace("(", " ").replace(",", " ")
            .split()}
    assert tags, f"{law_id}: evidence tag {law.evidence!r} names no known tag"
    for p in law.params:
        lo, hi = p.bounds
        assert lo < hi and lo <= p.default <= hi, f"{law_id}.{p.name} default outside bounds"
        assert isinstance(p.unit, str) and p.meaning
    for name, preset in law.presets.items():
        for k, v in preset.items():
            if k in law.param_names:
                lo, hi = law.param(k).bounds
                assert lo <= v <= hi, f"{law_id} preset {name}: {k}={v} outside [{lo}, {hi}]"
    json.dumps(law.summary())
    assert get_law(law_id.upper()) is law
    for alias in law.aliases:
        assert get_law(alias) is law


@pytest.mark.parametrize("law_id", LAW_IDS)
def test_finite_over_ranges_and_presets(law_id):
    law = get_law(law_id)
    case = case_for(law)
    rng = np.random.default_rng(1)
    x = sample(case, rng, 500)
    sets = [case.params] + [dict(p) for p in law.presets.values()]
    for params in sets:
        mu = raw(law, **x, **params)
        assert np.all(np.isfinite(mu)), f"{law_id} not finite with {params}"
        derived = law.derived_values(law.resolve(params))
        assert all(np.isfinite(v) or np.isinf(v) for v in derived.values())


@pytest.mark.parametrize("law_id", LAW_IDS)
def test_scalar_in_scalar_out_and_broadcasting(law_id):
    law = get_law(law_id)
    case = case_for(law)
    mids = {v: float(np.mean(case.ranges[v])) for v in law.variables}
    out = raw(law, **mids, **case.params)
    assert isinstance(out, float)
    # broadcasting: first variable as a column, the others as rows
    rng = np.random.default_rng(2)
    x = sample(case, rng, 5)
    shaped = {}
    for i, v in enumerate(law.variables):
        shaped[v] = x[v].reshape((5, 1) if i == 0 else (1, 5))
    if not law.variables:
        shaped = {"p": np.ones((5, 1))}
    grid = raw(law, **shaped, **case.params)
    expect_shape = np.broadcast_shapes(*(np.shape(a) for a in shaped.values()))
    assert np.shape(grid) == expect_shape
    # element-wise agreement with scalar calls
    idx = (3, 1) if len(expect_shape) == 2 and expect_shape[1] > 1 else (3, 0)
    one = {v: float(np.broadcast_to(a, expect_shape)[idx]) for v, a in shaped.items()}
    assert np.asarray(grid)[idx] == pytest.approx(raw(law, **one, **case.params), rel=1e-12)
    # variables whose shapes do not fit together are refused, each shape named
    if len(law.variables) >= 2:
        first, second = law.variables[:2]
        bad = {v: float(np.mean(case.ranges[v])) for v in law.variables}
        bad[first], bad[second] = x[first][:2], x[second][:3]
        with pytest.raises(InputError, match=rf"{first} \(2,\), {second} \(3,\)"):
            raw(law, **bad, **case.params)


@pytest.mark.parametrize("law_id", LAW_IDS)
def test_series_in_series_out(law_id):
    law = get_law(law_id)
    case = case_for(law)
    x = sample(case, np.random.default_rng(3), 7)
    series = {v: pd.Series(x[v], index=range(10, 17)) for v in (law.variables or ["p"])}
    if not law.variables:
        series = {"p": pd.Series(np.ones(7), index=range(10, 17))}
    out = raw(law, **series, **case.params)
    assert isinstance(out, pd.Series)
    assert list(out.index) == list(range(10, 17))


@pytest.mark.parametrize("law_id", LAW_IDS)
def test_large_checked_call_is_evaluated_in_blocks_with_the_same_result(
        law_id, monkeypatch):
    """A call on many points goes block by block (checks while each block is in cache):
    the numbers are those of the whole-array formula, and a bad value in a late block is
    named with its index in the whole array, as without blocks.  (Blocks of 64 values
    from 256 values here, so that a slow law is quick to test.)"""
    import frictionlaws.law.evaluation as law_module

    monkeypatch.setattr(law_module, "BLOCK_ROWS", 64)
    monkeypatch.setattr(law_module, "BLOCKED_FROM", 256)
    law = get_law(law_id)
    case = case_for(law)
    n = 256 + 37
    x = sample(case, np.random.default_rng(11), n)
    x = {v: x[v] for v in law.variables}
    if not x:
        return
    params = law.resolve(case.params)
    assert law._evaluate_blocks(x, params) is not None
    whole = raw(law, **x, **case.params)
    # equal to round-off (persson's quadrature sums in an order that depends on the block)
    np.testing.assert_allclose(law(**x, **case.params), whole, rtol=1e-13, atol=0)
    name = law.variables[-1]
    broken = {**x, name: x[name].copy()}
    broken[name][n - 5] = np.nan
    with pytest.raises(InputError, match=f"{name} has a non-finite value .* at index {n - 5}"):
        law(**broken, **case.params)


@pytest.mark.parametrize("law_id", LAW_IDS)
def test_bind_matches_call(law_id):
    law = get_law(law_id)
    case = case_for(law)
    x = sample(case, np.random.default_rng(4), 50)
    f = law.bind(case.params)
    direct = raw(law, **x, **case.params)
    bound = f(*(x[v] for v in law.variables))
    np.testing.assert_allclose(np.broadcast_to(bound, np.shape(direct)), direct, rtol=1e-14)


@pytest.mark.parametrize("law_id", LAW_IDS)
def test_symbolic_equals_numeric(law_id):
    import sympy

    law = get_law(law_id)
    case = case_for(law)
    expr = law.symbolic()
    syms = law.symbols()
    free = sorted(expr.free_symbols, key=str)
    assert {str(s) for s in free} <= set(syms), f"{law_id}: stray symbols in {expr}"
    f = sympy.lambdify(free, expr, modules="mpmath")
    rng = np.random.default_rng(5)
    x = sample(case, rng, 25)
    values = law.resolve(case.params)
    numeric = raw(law, **x, **case.params)
    numeric = np.broadcast_to(numeric, (25,))
    for i in range(25):
        point = {}
        for v in law.variables:
            xv = abs(x[v][i]) if v == "v" else x[v][i]
            point[v] = max(xv, law.floors.get(v, -math.inf))
        point.update(values)
        ref = float(f(*(point[str(s)] for s in free)))
        assert numeric[i] == pytest.approx(ref, rel=1e-9, abs=1e-12), (law_id, point)


@pytest.mark.parametrize("law_id", LAW_IDS)
def test_initial_guess_is_finite_and_within_bounds(law_id):
    law = get_law(law_id)
    case = case_for(law)
    x = sample(case, np.random.default_rng(6))
    mu = raw(law, **x, **case.params)
    guess = law.initial_guess({**x, "mu": np.broadcast_to(mu, (case.n,))})
    for p in law.params:
        lo, hi = p.bounds
        assert np.isfinite(guess[p.name]) and lo <= guess[p.name] <= hi


@pytest.mark.parametrize("law_id", LAW_IDS)
def test_parameter_recovery_with_2_percent_noise(law_id):
    law = get_law(law_id)
    case = case_for(law)
    rng = np.random.default_rng(case.seed)
    x = sample(case, rng)
    mu_true = np.broadcast_to(raw(law, **x, **case.params), (case.n,))
    # 2 % noise: Gaussian with a standard deviation of 2 % of the mean friction level
    mu = mu_true + 0.02 * np.mean(np.abs(mu_true)) * rng.standard_normal(case.n)
    data = {**x, "mu": mu}
    if not law.variables:
        data["p"] = np.full(case.n, 1e5)
    result = fit(law, data, fix=case.fix)
    assert set(result.non_identifiable) == set(case.non_identifiable), result.warnings
    for name, est in result.params.items():
        if name in case.fix or name in case.non_identifiable:
            continue
        true = law.resolve(case.params)[name]
        assert est.stderr is not None and est.stderr > 0, (name, result.warnings)
        assert abs(est.value - true) <= 3 * est.stderr, (
            f"{law_id}.{name}: fitted {est.value:.6g} +/- {est.stderr:.3g}, true {true:.6g}")
    assert result.metrics["r2"] > 0.5 or law.id == "coulomb"


@pytest.mark.parametrize("law_id", LAW_IDS)
def test_missing_variable_is_a_clear_error(law_id):
    from frictionlaws.base.errors import InputError

    law = get_law(law_id)
    if not law.variables:
        pytest.skip("a constant law needs no variable")
    with pytest.raises(InputError, match=law.variables[0]):
        law(**CASES[law_id].params)


@given(n=st.integers(1, 40), m=st.integers(1, 5))
@settings(max_examples=25, deadline=None)
def test_broadcast_shapes_property(n, m):
    """Every law broadcasts arbitrary (n, 1) x (1, m) shapes."""
    rng = np.random.default_rng(n * 100 + m)
    for law in list_laws():
        case = CASES[law.id]
        x = sample(case, rng, n * m)
        shaped = {}
        for i, v in enumerate(law.variables):
            shaped[v] = x[v][:n].reshape(n, 1) if i == 0 else x[v][:m].reshape(1, m)
        out = (raw(law, **shaped, **case.params) if shaped
               else raw(law, p=np.ones((n, m)), **case.params))
        assert np.shape(out) == ((n, m) if len(law.variables) > 1 else (
            (n, 1) if law.variables else (n, m)))


def test_unknown_law_suggests_close_names():
    from frictionlaws.base.errors import UnknownLawError

    with pytest.raises(UnknownLawError, match="thirion"):
        get_law("thirio")


def test_duplicate_registration_is_rejected():
    from frictionlaws.law.registry import REGISTRY

    law = get_law("thirion")
    with pytest.raises(ValueError, match="already"):
        REGISTRY.register(law)


def test_variables_table_is_si():
    assert VARIABLES["p"].unit == "Pa" and VARIABLES["v"].unit == "m/s"
    assert VARIABLES["T"].unit == "K" and VARIABLES["F_N"].unit == "N"


def test_temperature_aware_variant_by_name():
    """``<law>+wlf`` resolves to the law at reduced velocity, without joining list_laws()."""
    base = get_law("savkoor")
    law = get_law("Savkoor+WLF")
    assert law is get_law("savkoor+wlf")
    assert "T" in law.variables and law.id == "savkoor+wlf"
    assert law.id not in {x.id for x in list_laws()}
    params = CASES["savkoor"].params
    T_ref = law.setting_values["T_ref"]
    assert law(p=1e5, v=0.3, T=T_ref, **params) == pytest.approx(base(p=1e5, v=0.3, **params))
    # 10 K warmer acts as a lower velocity: v * a_T(T)
    log_aT = -8.86 * 10 / (101.6 + 10)
    assert law(p=1e5, v=0.3, T=T_ref + 10, **params) == pytest.approx(
        base(p=1e5, v=0.3 * 10**log_aT, **params), rel=1e-12)


@pytest.mark.parametrize("law", list_laws(), ids=lambda law: law.id)
def test_derived_quantities_at_every_finite_bound_never_raise(law):
    """A parameter held at a bound (``--fix b=0``) gives inf/nan derived values, no error."""
    base = law.resolve(CASES[law.id].params)
    for p in law.params:
        for bound in p.bounds:
            if math.isfinite(bound):
                values = law.derived_values({**base, p.name: bound})
                assert set(values) == {d.name for d in law.derived}


def test_fit_with_a_parameter_fixed_at_a_pole_of_a_derived_quantity(capsys):
    from frictionlaws.cli import main

    assert main(["fit", "--law", "thirion", "thesis-steel", "--fix", "b=0"]) == 0
    assert "tau_sat = n/a" in capsys.readouterr().out
