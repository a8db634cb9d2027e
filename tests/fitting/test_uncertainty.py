"""Uncertainty methods of a fit (asymptotic, sandwich, bootstrap) and the global stage."""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import least_squares

import frictionlaws as fl
from frictionlaws.base.errors import InputError
from frictionlaws.cli import main
from frictionlaws.fitting import load_result
from frictionlaws.fitting.robust import condition_ids, residual_structure, sandwich_cov
from frictionlaws.io import load_dataset


def _thesis_steel() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    frame = load_dataset("thesis-steel").frame
    return (frame["p"].to_numpy(float), frame["v"].to_numpy(float),
            frame["mu"].to_numpy(float))


def _case_resampling_se_a(n_boot: int = 1000, seed: int = 12345) -> float:
    """SE(a) of mu = 1/(a + b p) by naive case resampling, written out here."""
    p, _v, mu = _thesis_steel()
    p_mpa = p * 1e-6
    rng = np.random.default_rng(seed)
    a_values = []
    for _ in range(n_boot):
        i = rng.integers(0, p.size, p.size)
        sol = least_squares(lambda t, i=i: 1.0 / (t[0] + t[1] * p_mpa[i]) - mu[i], [0.15, 4.7])
        a_values.append(sol.x[0])
    return float(np.std(a_values, ddof=1))


@pytest.fixture(scope="module")
def boot_result() -> fl.FitResult:
    return fl.fit("thirion", "thesis-steel", uncertainty="bootstrap", n_boot=1000, seed=3)


def test_thesis_steel_rows_are_distinct_conditions() -> None:
    p, v, _mu = _thesis_steel()
    assert len(set(zip(p, v))) == p.size  # so condition resampling = case resampling


@pytest.mark.slow
def test_bootstrap_se_matches_an_independent_case_resampling(boot_result) -> None:
    ref = _case_resampling_se_a()
    se = boot_result.params["a"].stderr
    assert abs(se / ref - 1) < 0.2, (se, ref)
    asym = boot_result.uncertainty["asymptotic_stderr"]["a"]
    assert se > 1.5 * asym
    assert boot_result.uncertainty["method"] == "bootstrap"
    assert boot_result.uncertainty["conditions"] == 19
    assert any("exceed the asymptotic" in w for w in boot_result.warnings)


def test_bootstrap_propagates_to_derived_quantities() -> None:
    res = fl.fit("thirion", "thesis-steel", uncertainty="bootstrap", n_boot=400,
                 interval="percentile")
    lo, hi = res.params["a"].ci95
    mu0 = res.derived["mu_0"]
    # mu_0 = 1/a is monotone: percentile intervals map through it
    assert mu0["ci95"][0] == pytest.approx(1 / hi, rel=0.03)
    assert mu0["ci95"][1] == pytest.approx(1 / lo, rel=0.03)
    assert mu0["stderr"] > 1.3 * fl.fit("thirion", "thesis-steel").derived["mu_0"]["stderr"]
    assert res.uncertainty["interval"] == "percentile"


def test_bootstrap_is_seeded_and_parallel_gives_the_same_numbers() -> None:
    one = fl.fit("thirion", "thesis-steel", uncertainty="bootstrap", n_boot=40, seed=7)
    again = fl.fit("thirion", "thesis-steel", uncertainty="bootstrap", n_boot=40, seed=7)
    par = fl.fit("thirion", "thesis-steel", uncertainty="bootstrap", n_boot=40, seed=7,
                 n_jobs=2)
    other = fl.fit("thirion", "thesis-steel", uncertainty="bootstrap", n_boot=40, seed=8)
    assert one.params["a"].stderr == again.params["a"].stderr
    assert par.params["a"].stderr == pytest.approx(one.params["a"].stderr, rel=1e-9)
    assert other.params["a"].stderr != one.params["a"].stderr


def test_asymptotic_default_warns_on_thesis_steel_and_names_the_bootstrap() -> None:
    res = fl.fit("thirion", "thesis-steel")
    assert res.uncertainty["method"] == "asymptotic"
    msgs = [w for w in res.warnings if "show structure" in w]
    assert msgs and "bootstrap" in msgs[0]
    assert "warning: residuals ordered by" in res.report()


def test_no_structure_warning_for_a_law_that_fits() -> None:
    rng = np.random.default_rng(0)
    p = np.tile(np.linspace(0.03e6, 0.25e6, 10), 2)
    v = np.repeat([0.5, 1.5], 10)
    mu = 1 / (0.15 + 4.7e-6 * p) * (1 + 0.02 * rng.standard_normal(p.size))
    res = fl.fit("thirion", {"mu": mu, "p": p, "v": v})
    assert not any("show structure" in w for w in res.warnings)
    s = residual_structure(res.residual, {"p": p, "v": v}, ["p", "v"])
    assert s is not None and not s.significant


def test_sandwich_is_hc3_of_the_linear_least_squares() -> None:
    rng = np.random.default_rng(4)
    p = np.tile(np.linspace(0.03e6, 0.25e6, 8), 3)
    v = np.repeat([0.1, 1.0, 2.5], 8)
    mu = 1.2 - 2e-6 * p + 0.1 * v + 0.02 * (1 + 4 * v) * rng.standard_normal(p.size)
    res = fl.fit("thesis-poly2", {"mu": mu, "p": p, "v": v}, uncertainty="sandwich")
    x = np.column_stack([np.ones_like(p), 1e-6 * p, 1e-12 * p**2, v, v**2])
    beta, *_ = np.linalg.lstsq(x, mu, rcond=None)
    e = mu - x @ beta
    bread = np.linalg.inv(x.T @ x)
    h = np.sum((x @ bread) * x, axis=1)
    hc3 = bread @ (x.T * (e / (1 - h)) ** 2) @ x @ bread
    se = np.sqrt(np.diag(hc3))
    got = [res.params[k].stderr for k in ("a0", "a1", "a2", "a3", "a4")]
    np.testing.assert_allclose(got, se, rtol=1e-4)
    assert res.uncertainty["method"] == "sandwich"
    assert "sandwich (HC3" in res.report()


def test_sandwich_cov_refuses_a_singular_jacobian() -> None:
    jac = np.column_stack([np.ones(5), np.ones(5)])
    assert sandwich_cov(jac, np.arange(5.0)) is None


def test_conditions_group_repeats_and_a_condition_column(tmp_path) -> None:
    arrays = {"mu": np.ones(6), "p": np.array([1, 1, 2, 2, 3, 3.0]), "v": np.ones(6)}
    assert len(set(condition_ids(arrays, ["p", "v"]))) == 3
    ids = condition_ids(arrays, ["p", "v"], np.array(list("aabbbc")))
    assert ids.tolist() == [0, 0, 1, 1, 1, 2]
    path = tmp_path / "runs.csv"
    rows = ["mu,p [MPa],condition_id"] + [
        f"{1 / (0.15 + 4.7 * pp) * (1 + 0.01 * k):.5f},{pp},c{j}"
        for j, pp in enumerate([0.03, 0.06, 0.09, 0.12, 0.15, 0.18, 0.21, 0.24, 0.27])
        for k in (-1, 0, 1)]
    path.write_text("\n".join(rows) + "\n", encoding="utf-8")
    res = fl.fit("thirion", path, uncertainty="bootstrap", n_boot=40)
    assert res.uncertainty["conditions"] == 9


def test_the_method_survives_to_dict_save_and_load(tmp_path, boot_result) -> None:
    doc = json.loads(boot_result.to_json())
    assert doc["uncertainty"]["method"] == "bootstrap"
    path = boot_result.save(tmp_path / "fit.json")
    back = load_result(path)
    assert back.uncertainty["method"] == "bootstrap"
    assert back.params["a"].stderr == pytest.approx(boot_result.params["a"].stderr)
    assert "bootstrap (1000 resamples of 19 conditions" in back.report()
    doc["uncertainty"]["method"] = "jackknife"
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(doc), encoding="utf-8")
    with pytest.raises(InputError, match="uncertainty.method"):
        load_result(bad)


@pytest.mark.parametrize("kw, option", [
    ({"uncertainty": "jackknife"}, "uncertainty"),
    ({"n_boot": 5}, "n_boot"),
    ({"n_boot": True}, "n_boot"),
    ({"n_jobs": 0}, "n_jobs"),
    ({"interval": "normal"}, "interval"),
    ({"global_stage": "maybe"}, "global_stage"),
])
def test_bad_uncertainty_options_are_refused(kw, option) -> None:
    with pytest.raises(InputError) as exc:
        fl.fit("thirion", "thesis-steel", **kw)
    assert exc.value.option == option


def test_bootstrap_reports_the_identifiable_parameters_only() -> None:
    asym = fl.fit("savkoor", "thesis-steel", on_invalid="drop")
    boot = fl.fit("savkoor", "thesis-steel", on_invalid="drop", uncertainty="bootstrap",
                  n_boot=200)
    assert boot.uncertainty["method"] == "bootstrap"
    assert boot.non_identifiable and boot.non_identifiable == asym.non_identifiable
    for name in boot.non_identifiable:
        assert boot.params[name].stderr is None
    assert boot.params["n"].stderr > 1.2 * asym.params["n"].stderr
    sandwich = fl.fit("savkoor", "thesis-steel", on_invalid="drop", uncertainty="sandwich")
    assert sandwich.uncertainty["method"] == "asymptotic"
    assert any("the bootstrap gives" in w for w in sandwich.warnings)


# ------------------------------------------------------------------ global stage


def test_wriggers_reaches_the_good_fit_from_the_default_call() -> None:
    res = fl.fit("wriggers", "thesis-steel")
    assert res.metrics["r2"] >= 0.9
    assert res.success
    assert any("global stage" in n for n in res.notes)
    off = fl.fit("wriggers", "thesis-steel", global_stage="off")
    assert off.metrics["r2"] < 0.9  # the stage, not the local starts, finds it


def test_well_converging_fits_skip_the_global_stage() -> None:
    for law in ("thirion", "savkoor", "huemer"):
        res = fl.fit(law, "thesis-steel", on_invalid="drop")
        assert not any("global stage" in n for n in res.notes), law


def test_global_stage_on_keeps_a_good_fit() -> None:
    auto = fl.fit("savkoor", "thesis-steel", on_invalid="drop")
    on = fl.fit("savkoor", "thesis-steel", global_stage="on", on_invalid="drop")
    assert on.metrics["r2"] >= auto.metrics["r2"] - 1e-9


# ------------------------------------------------------------------------- CLI


def test_cli_fit_wriggers_default(capsys) -> None:
    code = main(["fit", "--law", "wriggers", "thesis-steel", "--json"])
    doc = json.loads(capsys.readouterr().out)
    assert code == 0 and doc["metrics"]["r2"] >= 0.9


def test_cli_uncertainty_bootstrap(capsys) -> None:
    code = main(["fit", "--law", "thirion", "thesis-steel", "--uncertainty", "bootstrap",
                 "--boot", "60", "--boot-interval", "percentile", "--json"])
    doc = json.loads(capsys.readouterr().out)
    assert code == 0
    assert doc["uncertainty"]["method"] == "bootstrap"
    assert doc["uncertainty"]["n_boot"] == 60
    assert doc["uncertainty"]["interval"] == "percentile"


def test_cli_sandwich_report(capsys) -> None:
    code = main(["fit", "--law", "thirion", "thesis-steel", "--uncertainty", "sandwich"])
    out = capsys.readouterr().out
    assert code == 0 and "standard errors: sandwich" in out


@pytest.mark.parametrize("argv, fragment", [
    (["--boot", "100"], "--boot"),
    (["--uncertainty", "sandwich", "--boot-jobs", "2"], "--boot-jobs"),
    (["--boot-interval", "percentile"], "--boot-interval"),
    (["--uncertainty", "bootstrap", "--boot", "5"], "--boot"),
    (["--uncertainty", "jackknife"], "--uncertainty"),
    (["--uncertainty", "bootstrap", "--boot-jobs", "0"], "--boot-jobs"),
])
def test_cli_bootstrap_options_are_checked(capsys, argv, fragment) -> None:
    code = main(["fit", "--law", "thirion", "thesis-steel", *argv])
    err = capsys.readouterr().err
    assert code == 2 and fragment in err


def test_cli_shared_refuses_uncertainty(capsys, tmp_path) -> None:
    path = tmp_path / "temps.csv"
    path.write_text("mu,p [MPa],T [degC]\n" + "\n".join(
        f"{1 / (0.15 + 4.7 * p) * (1 + 0.01 * T / 20):.4f},{p},{T}"
        for T in (20, 40) for p in (0.03, 0.06, 0.09, 0.12)) + "\n", encoding="utf-8")
    code = main(["fit", "--law", "thirion", str(path), "--by", "T", "--shared", "b",
                 "--uncertainty", "sandwich"])
    err = capsys.readouterr().err
    assert code == 2 and "--uncertainty" in err


@pytest.mark.parametrize("levels", [None, 3, 40])
def test_residual_order_is_lexsorts_with_and_without_ties(levels):
    """The fast order of residual_structure is exactly np.lexsort's (ties: others, then row)."""
    from frictionlaws.fitting.robust import _order_by

    rng = np.random.default_rng(levels or 0)
    for n in (8, 57, 3000):
        key = (rng.uniform(0, 1, n) if levels is None
               else rng.integers(0, levels, n).astype(float))
        others = [rng.integers(0, 4, n).astype(float), rng.uniform(0, 1, n)]
        for extra in ([], others[:1], others):
            assert np.array_equal(_order_by(key, extra), np.lexsort([*extra, key]))


@settings(max_examples=60, deadline=None)
@given(st.lists(st.integers(0, 12), min_size=1, max_size=80), st.integers(0, 2**32 - 1))
def test_resampled_rows_are_the_drawn_conditions_rows_in_order(groups, seed):
    from frictionlaws.fitting.robust import _Resampler

    g = np.asarray(groups)
    res = _Resampler(g)
    members = [np.flatnonzero(g == u) for u in np.unique(g)]
    chosen = np.random.default_rng(seed).integers(0, len(members), size=len(members))
    assert np.array_equal(res.rows(chosen), np.concatenate([members[c] for c in chosen]))
    jack = list(res.jackknife())
    assert len(jack) == len(members)  # at most JACKKNIFE_SETS conditions: one left out each
    for j, rows in enumerate(jack):  # the other conditions' rows, condition after condition
        assert np.array_equal(rows, np.concatenate(
            [m for i, m in enumerate(members) if i != j] or [np.zeros(0, int)]))


class _CountRows:
    """A stand-in refit: the 'parameter' of a row set is its size."""

    def solve(self, theta0, rows):
        return np.array([float(rows.size)])


def test_bootstrap_memory_stays_near_the_data_with_many_conditions():
    """20 000 rows, every one its own condition: the leave-one-out sets alone were
    G x N = 4e8 indices (3.2 GB); now blocks of conditions, made one at a time."""
    import tracemalloc

    from frictionlaws.fitting.robust import JACKKNIFE_SETS, bootstrap

    n = 20_000
    groups = np.arange(n)
    tracemalloc.start()
    try:
        res = bootstrap(_CountRows(), np.zeros(1), groups, n_boot=30, seed=1)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 40 * 8 * n  # a few dozen index arrays of the data's size, not G of them
    assert res.samples.shape == (30, 1) and np.all(res.samples == n)
    assert res.jackknife.shape == (JACKKNIFE_SETS, 1)
    assert np.all(res.jackknife == n - n // JACKKNIFE_SETS)  # one block of 200 left out
    pct = bootstrap(_CountRows(), np.zeros(1), groups, n_boot=30, seed=1, jackknife=False)
    assert pct.jackknife.shape == (0, 1) and np.array_equal(pct.samples, res.samples)


def test_bootstrap_does_not_advise_itself_about_a_cut_symmetric_interval():
    rng = np.random.default_rng(3)
    p = np.repeat(np.linspace(1e4, 3e5, 12), 3)
    data = {"p": p, "mu": 0.6 + 0.01 * rng.standard_normal(p.size)}  # b at its bound 0
    cut = [w for w in fl.fit("thirion", data).warnings if "reaches past its bounds" in w]
    assert len(cut) == 1 and "uncertainty 'bootstrap' gives a better one" in cut[0]
    boot = fl.fit("thirion", data, uncertainty="bootstrap", n_boot=50)
    assert not [w for w in boot.warnings if "reaches past its bounds" in w]
    assert boot.params["b"].ci95[0] >= 0.0


# ------------------------------------------------ one rule for every method

METHODS = ("asymptotic", "sandwich", "bootstrap")


def _check_honest(result) -> None:
    """No zero error, no interval past a bound unremarked, no derived error without parents."""
    law = fl.get_law(result.law.id)
    for name, est in result.params.items():
        assert est.stderr is None or est.stderr > 0, (name, est)
        if est.ci95 is None:
            continue
        lo, hi = law.param(name).bounds
        assert lo <= est.ci95[0] <= est.ci95[1] <= hi, (name, est.ci95)
        if result.uncertainty["method"] != "bootstrap" and (lo in est.ci95 or hi in est.ci95):
            assert any(f"interval of {name}" in w for w in result.warnings), result.warnings
    none = [k for k, e in result.params.items() if not e.fixed and e.stderr is None]
    for name, d in result.derived.items():
        assert d.get("stderr") is None or d["stderr"] > 0, (name, d)
        if len(none) == len([e for e in result.params.values() if not e.fixed]):
            assert d.get("stderr") is None, (name, d)


@settings(max_examples=12, deadline=None)
@given(levels=st.integers(1, 5), repeats=st.integers(1, 3),
       noise=st.sampled_from([0.0, 0.002, 0.03]), method=st.sampled_from(METHODS),
       seed=st.integers(0, 2**16))
def test_every_method_withholds_what_the_data_cannot_tell(levels, repeats, noise, method,
                                                          seed) -> None:
    rng = np.random.default_rng(seed)
    p = np.repeat(np.linspace(1e5, 6e5, levels), repeats)
    if p.size < 2:
        p = np.array([1e5, 1e5])
    mu = 1.0 / (1.0 + 2e-6 * p) + noise * rng.standard_normal(p.size)
    result = fl.fit("thirion", {"mu": mu, "p": p}, uncertainty=method, n_boot=40)
    _check_honest(result)
    if np.unique(p).size <= 2 and method == "bootstrap":
        assert all(e.stderr is None for e in result.params.values())
        assert any(("conditions" in w and "withheld" in w) or "more rows" in w
                   or "cannot determine" in w for w in result.warnings), result.warnings


def test_bootstrap_on_two_conditions_reports_undetermined_errors() -> None:
    p = np.repeat([1e5, 4e5], 3)
    mu = np.array([.83, .84, .82, .56, .55, .57])
    result = fl.fit("thirion", {"mu": mu, "p": p}, uncertainty="bootstrap", n_boot=50)
    assert all(e.stderr is None and e.ci95 is None for e in result.params.values())
    assert all(d["stderr"] is None for d in result.derived.values())
    assert any("2 conditions" in w and "withheld" in w for w in result.warnings)
    assert "refused" in result.report()


def test_bootstrap_withholds_a_parameter_whose_resamples_do_not_spread() -> None:
    from frictionlaws.fitting.robust import intervals

    flat = np.full((50, 1), 0.4) + np.r_[np.zeros(49), 1e-13][:, None]
    se, ci, _ = intervals(flat, np.array([0.4]), np.full((5, 1), 0.4))
    assert np.isnan(se[0]) and np.all(np.isnan(ci[0]))


def test_bootstrap_resample_of_too_few_conditions_is_not_a_replicate() -> None:
    from frictionlaws.fitting.robust import Refit

    law = fl.get_law("thirion")
    p = np.repeat([1e5, 2e5, 4e5], 2)
    mu = 1.0 / (1.0 + 2e-6 * p)
    refit = Refit(law, dict(law.setting_values), ["a", "b"], np.array([1e-9, 0.0]),
                  np.array([np.inf, np.inf]), {"p": p}, mu, None, 1e-5, 2)
    theta = np.array([1.0, 2e-6])
    assert np.all(np.isnan(refit.solve(theta, np.array([0, 1, 0, 1]))))  # one condition
    assert np.all(np.isfinite(refit.solve(theta, np.arange(6))))


@pytest.mark.parametrize("method", METHODS)
def test_rows_equal_to_parameters_give_no_error_to_derived_quantities(method) -> None:
    result = fl.fit("thirion", {"mu": np.array([0.8, 0.6]), "p": np.array([1e5, 4e5])},
                    uncertainty=method, n_boot=20)
    assert all(e.stderr is None for e in result.params.values())
    assert result.derived and all(d["stderr"] is None for d in result.derived.values())


@pytest.mark.parametrize("method", ["asymptotic", "sandwich"])
def test_exact_data_give_no_zero_error(method) -> None:
    p = np.array([1e5, 2e5, 4e5, 6e5])
    result = fl.fit("thirion", {"mu": 1.0 / (1.0 + 2e-6 * p), "p": p}, uncertainty=method)
    assert all(e.stderr is None for e in result.params.values())
    assert all(d["stderr"] is None for d in result.derived.values())
    assert any("0 to rounding" in w for w in result.warnings)


def test_sandwich_interval_past_a_bound_is_cut_and_remarked() -> None:
    rng = np.random.default_rng(3)
    v = np.repeat([0.001, 0.01, 0.05, 0.1, 0.3, 1, 3], 2)
    mu = 0.5 + 0.4 * np.exp(-v / 0.05) + rng.normal(0, 0.05, v.size) * np.where(
        v > 0.2, 3, 0.3)
    result = fl.fit("exponential-decay", {"mu": mu, "v": v}, uncertainty="sandwich")
    assert result.uncertainty["method"] == "sandwich"
    _check_honest(result)
    cut = [w for w in result.warnings if "reaches past its bounds" in w]
    assert cut
    # the remarks are the sandwich's own intervals, not the replaced asymptotic ones
    asym = fl.fit("exponential-decay", {"mu": mu, "v": v})
    assert not set(cut) & {w for w in asym.warnings if "reaches past" in w}


def test_shared_fit_withholds_undetermined_and_zero_errors(tmp_path) -> None:
    from frictionlaws.fitting.shared import fit_shared

    p = np.array([1e5, 2e5, 4e5, 6e5])
    rows = ["surface,p [Pa],mu"]
    for surface, b in (("steel", 2e-6), ("glass", 3e-6)):
        rows += [f"{surface},{x:g},{float(1.0 / (1.0 + b * x))!r}" for x in p]
    path = tmp_path / "exact.csv"
    path.write_text("\n".join(rows) + "\n")
    result = fit_shared("thirion", str(path), by="surface", shared=["a"])
    for group in result.groups:
        for name, est in group["params"].items():
            assert est["stderr"] is None, (name, est)
    assert any("0 to rounding" in w for w in result.warnings)
    report = result.report()  # withheld errors read n/a, never 0
    assert "+/- n/a" in report and "+/- 0 " not in report


def test_a_condition_id_column_is_the_bootstraps_unit(tmp_path) -> None:
    rows = ["condition_id,p [MPa],mu"]
    for j, cond in enumerate("AABBCCDDEE"):  # two pressures per condition
        p = 0.05 + 0.05 * j
        rows.append(f"{cond},{p:.3f},{1 / (1 + 2 * p) * (1 + 0.01 * (-1) ** j):.6f}")
    path = tmp_path / "runs.csv"
    path.write_text("\n".join(rows) + "\n", encoding="utf-8")
    ds = load_dataset(path)
    assert list(ds.column("condition_id")) == list("AABBCCDDEE")
    back = load_dataset(ds.to_csv(tmp_path / "back.csv"))
    assert list(back.column("condition_id")) == list("AABBCCDDEE")
    res = fl.fit("thirion", path, uncertainty="bootstrap", n_boot=40)
    assert res.uncertainty["conditions"] == 5  # not the 10 pressures
    one = tmp_path / "one.csv"
    one.write_text("\n".join([rows[0]] + [f"A,{r.split(',', 1)[1]}" for r in rows[1:]]) + "\n")
    res = fl.fit("thirion", one, uncertainty="bootstrap", n_boot=40)
    assert all(e.stderr is None for e in res.params.values())
    assert any("cannot vary (the data hold one test condition" in w for w in res.warnings)


def _persson_rows_below_its_additive_floor(tmp_path) -> str:
    """Persson data at two temperatures, shifted down so mu_a ends at its bound 0."""
    law = fl.get_law("persson")
    v = np.logspace(-4, 1, 10)
    lines = ["T [degC],p [MPa],v [m/s],mu"]
    for t_c in (0.0, 20.0):
        mu = law(p=0.2e6, v=v, T=t_c + 273.15, q1=3e5, mu_a=0.0) - 0.03
        lines += [f"{t_c},0.2,{vi:.6g},{m:.9g}" for vi, m in zip(v, mu, strict=True)]
    path = tmp_path / "pers.csv"
    path.write_text("\n".join(lines) + "\n")
    return str(path)


def test_a_parameter_at_its_bound_of_zero_has_a_slope_and_an_error(tmp_path) -> None:
    from frictionlaws.fitting.views import confidence_band

    res = fl.fit("persson", _persson_rows_below_its_additive_floor(tmp_path))
    mu_a = res.params["mu_a"]
    assert mu_a.value == pytest.approx(0.0, abs=1e-9)
    assert "mu_a" not in res.non_identifiable and mu_a.stderr is not None
    assert mu_a.stderr > 0 and mu_a.ci95 is not None and mu_a.ci95[0] >= 0.0
    assert any("mu_a" in w and "past its bounds" in w for w in res.warnings)
    where = {"p": np.full(3, 0.2e6), "v": np.array([1e-3, 1e-2, 1.0]), "T": np.full(3, 293.15)}
    assert np.all(np.isfinite(confidence_band(res, where)))
    res.params["mu_a"] = replace(mu_a, stderr=None, ci95=None)  # mu moves with mu_a at 0 too
    assert np.all(np.isnan(confidence_band(res, where)))


@settings(max_examples=25, deadline=None, derandomize=True)
@given(exponent=st.integers(-300, -7), slope=st.floats(0.1, 10.0))
def test_the_fit_jacobian_sees_a_slope_at_a_value_next_to_zero(exponent, slope) -> None:
    from frictionlaws.fitting.diagnosis import _jacobian

    x = np.array([10.0 ** exponent])
    jac = _jacobian(lambda t: slope * t[0] + np.linspace(0.5, 1.5, 7), x, np.array([0.0]))
    assert jac[:, 0] == pytest.approx(np.full(7, slope), rel=1e-6)


@settings(max_examples=8, deadline=None, derandomize=True)
@given(rows=st.integers(3, 12), seed=st.integers(0, 2**16))
def test_the_confidence_band_is_as_wide_as_the_parameter_interval(rows, seed) -> None:
    from frictionlaws.fitting.views import confidence_band

    rng = np.random.default_rng(seed)
    data = {"p": np.linspace(1e5, 5e5, rows), "mu": 0.8 + 0.05 * rng.standard_normal(rows)}
    res = fl.fit("coulomb", data)
    low, high = res.params["mu0"].ci95
    half = confidence_band(res, {"p": np.array([2e5])})
    assert half[0] == pytest.approx((high - low) / 2, rel=1e-6)
