"""Tests of frictionlaws.compare: statistics, CV, extrapolation, plausibility, API."""

from __future__ import annotations

import importlib
import itertools
import json
import math
import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import stats

import frictionlaws
from frictionlaws.base.errors import InputError, UnknownLawError
from frictionlaws.comparison import Comparison, compare
from frictionlaws.comparison.cv import cross_validate, kfold_assignment
from frictionlaws.comparison.extrapolation import (
    _kendall_s_var,
    data_trend,
    data_trends,
    design_of,
    extended_box,
    holdout_splits,
    parse_holdout,
    scan_plausibility,
)
from frictionlaws.comparison.residuals import analyse_residuals, runs_pmf, runs_test
from frictionlaws.fitting import FitData, as_fit_data
from frictionlaws.law import Law, Param

# a small, fast set: a constant, a 2-parameter law, both thesis polynomials and a
# log-velocity law that must drop the v = 0 rows
LAWS = ["coulomb", "thirion", "thesis-poly2", "thesis-poly3", "savkoor"]


@pytest.fixture(scope="module")
def steel() -> FitData:
    return as_fit_data("thesis-steel")


@pytest.fixture(scope="module")
def cmp(steel: FitData) -> Comparison:
    return compare(LAWS, steel, seed=3)


# ------------------------------------------------------------------ residuals


@pytest.mark.parametrize("n1,n2", [(1, 1), (2, 3), (4, 4), (5, 2), (3, 6)])
def test_runs_pmf_matches_enumeration(n1: int, n2: int) -> None:
    seqs = set(itertools.permutations([1] * n1 + [-1] * n2))
    counts: dict[int, int] = {}
    for s in seqs:
        r = 1 + sum(a != b for a, b in zip(s, s[1:]))
        counts[r] = counts.get(r, 0) + 1
    for r in range(1, n1 + n2 + 1):
        assert runs_pmf(r, n1, n2) == pytest.approx(counts.get(r, 0) / len(seqs), abs=1e-12)


def test_runs_test_flags_clustering_not_alternation() -> None:
    clustered = runs_test([1] * 6 + [-1] * 6)
    assert clustered["runs"] == 2 and clustered["expected"] == pytest.approx(7.0)
    assert clustered["p_value"] < 0.01 and clustered["method"] == "exact"
    alternating = runs_test([1, -1] * 6)
    assert alternating["runs"] == 12 and alternating["p_value"] > 0.99
    assert alternating["p_two_sided"] < 0.01
    assert runs_test([1, 1, 0, 1])["p_value"] is None  # one sign only: no test


def test_runs_test_normal_approximation_for_long_sequences() -> None:
    rng = np.random.default_rng(1)
    r = runs_test(rng.normal(size=500))
    assert r["method"] == "normal" and 0.0 < r["p_value"] <= 1.0
    assert runs_test(np.r_[np.ones(250), -np.ones(250)])["p_value"] < 1e-10


def test_residual_analysis_finds_a_systematic_misfit() -> None:
    x = np.linspace(0.0, 1.0, 30)
    resid = (x - 0.5) ** 2 - 1 / 12  # a straight line fitted to a parabola leaves a U
    res = analyse_residuals(resid, 1.0 - x, {"p": x})
    assert res.tests["p"]["runs"]["runs"] == 3
    assert res.tests["p"]["runs"]["p_value"] < 1e-4
    assert any("cluster along p" in s for s in res.structure)
    noise = np.random.default_rng(7).normal(0.0, 0.1, 30)
    calm = analyse_residuals(noise, 1.0 - x, {"p": x})
    assert calm.structure == [], calm.structure
    osm, osr = calm.normal_quantiles
    assert osm.size == 30 and np.all(np.diff(osr) >= 0)


# --------------------------------------------------------------------- trends


def test_kendall_variance_matches_scipy() -> None:
    rng = np.random.default_rng(0)
    for x, y in [(rng.normal(size=15), rng.normal(size=15)),
                 (np.repeat([1.0, 2.0, 3.0, 4.0], 4), rng.integers(0, 5, 16).astype(float))]:
        s, var, _ = _kendall_s_var(x, y)
        fd = FitData({"mu": y, "p": x}, "t", "t")
        tr = data_trend(fd, "p", design_of(fd), continuity=False)
        ref = stats.kendalltau(x, y, method="asymptotic")
        assert tr.p_value == pytest.approx(ref.pvalue, rel=1e-9)
        assert np.sign(s) == np.sign(ref.statistic)


def test_steel_design_and_trends(steel: FitData) -> None:
    design = design_of(steel)
    assert design.varying == ["p", "v"]
    assert design.derived["F_N"][0] == "p"  # F_N = A p on a fixed pin
    trends = data_trends(steel, design)
    assert trends["p"].sign == -1 and trends["p"].p_value < 1e-3
    # within each pressure level mu rises with the velocity class; pooled rows would mix
    # the pressure effect in (the 2.77 m/s row was measured at the lowest pressure only)
    assert trends["v"].sign == 1 and trends["v"].strata == 7
    assert trends["p"].ends["high"]["sign"] == -1 and trends["p"].ends["low"]["sign"] == -1
    box = extended_box(steel, design)
    assert box["p"] == pytest.approx((0.5 * 31190.0, 3 * 249600.0))
    assert box["v"] == pytest.approx((0.0, 3 * 2.77))


def test_end_trends_of_a_peaked_curve() -> None:
    # a slip curve: rises to a peak near s = 0.14, then falls; overall it falls
    s = np.linspace(0.01, 0.6, 25)
    mu = np.sin(1.9 * np.arctan(10 * s)) + np.random.default_rng(0).normal(0, 0.02, 25)
    fd = FitData({"mu": mu, "s": s}, "slip", "synthetic")
    tr = data_trend(fd, "s", design_of(fd))
    assert tr.sign == -1
    assert tr.ends["low"]["sign"] == 1 and "lowest 7 of the 25" in tr.ends["low"]["basis"]
    assert tr.ends["high"]["sign"] == -1


def test_no_trend_without_evidence() -> None:
    rng = np.random.default_rng(5)
    x = np.linspace(1e5, 2e5, 12)
    fd = FitData({"mu": 1.0 + 0.01 * rng.normal(size=12), "p": x}, "flat", "t")
    assert data_trend(fd, "p", design_of(fd)).sign == 0


# ------------------------------------------------------------------- holdout


def test_parse_holdout() -> None:
    assert parse_holdout(0.3) == {"p": 0.3, "v": 0.3}
    assert parse_holdout("0.25") == {"p": 0.25, "v": 0.25}
    assert parse_holdout("p=0.3, v=0.2") == {"p": 0.3, "v": 0.2}
    assert parse_holdout({"T": 0.5}) == {"T": 0.5}
    assert parse_holdout(None) == {} and parse_holdout("0") == {}
    for bad in ("1.5", "p=abc", "x=0.3", "p=0.3,garbage"):
        with pytest.raises(InputError):
            parse_holdout(bad)


def test_holdout_splits_on_steel(steel: FitData) -> None:
    design = design_of(steel)
    splits = {s.variable: s for s in holdout_splits(
        steel, {"p": 0.3, "v": 0.3, "F_N": 0.3, "T": 0.3}, design)}
    p, v = splits["p"], splits["v"]
    assert p.usable and int(p.test.sum()) == 3
    assert p.threshold == pytest.approx(31190 + 0.7 * (249600 - 31190))
    assert np.all(steel.arrays["p"][p.test] > p.threshold)
    assert v.usable and int(v.test.sum()) == 1
    assert "follows p" in splits["F_N"].reason
    assert "no T" in splits["T"].reason


# ---------------------------------------------------------------- the folds


def test_kfold_assignment() -> None:
    a = kfold_assignment(19, 5, seed=11)
    assert np.array_equal(a, kfold_assignment(19, 5, seed=11))
    assert not np.array_equal(a, kfold_assignment(19, 5, seed=12))
    assert sorted(np.bincount(a)) == [3, 4, 4, 4, 4]
    with pytest.raises(InputError):
        kfold_assignment(5, 6, 0)


def test_cv_is_identical_on_rerun_with_the_same_seed(steel: FitData, cmp: Comparison) -> None:
    again = compare(LAWS, steel, seed=3)
    for a, b in zip(cmp.results, again.results):
        assert a.law.id == b.law.id
        assert a.cv.to_dict() == b.cv.to_dict()
        assert np.array_equal(a.cv.predictions, b.cv.predictions, equal_nan=True)
        assert a.cv_rmse_common == b.cv_rmse_common or (
            math.isnan(a.cv_rmse_common) and math.isnan(b.cv_rmse_common))
        assert a.rank_basis == b.rank_basis
    assert np.array_equal(cmp.folds, again.folds)
    other = compare(["thirion"], steel, seed=4)
    assert not np.array_equal(other.folds, cmp.folds)


def test_cv_reports_folds_that_cannot_be_fitted(steel: FitData) -> None:
    from frictionlaws.law.registry import get_law

    law = get_law("thesis-poly3")  # 7 parameters
    few = steel.subset(np.arange(steel.n) < 8)  # 8 rows: a 4-row training fold is too small
    res = cross_validate(law, few, np.ones(8, bool), kfold_assignment(8, 2, 0))
    assert not res.complete and len(res.failed) == 2
    assert "at least as many rows as parameters" in res.failed[0]["error"]
    assert math.isnan(res.rmse)


def test_cv_names_folds_whose_rows_leave_parameters_undetermined(steel: FitData) -> None:
    # thesis-steel has one row at v = 2.77 m/s: the fold holding it out (and the
    # hold-out above v = 1.94 m/s) leaves two velocities for a quadratic in v, whose
    # curvature the other rows cannot then determine, and with it the prediction there
    c = compare(["thesis-poly2", "thirion"], steel, progress=False)
    poly = c["thesis-poly2"]
    assert [u["params"] for u in poly.cv.undetermined] == [["a3", "a4"]]
    assert poly.cv.undetermined[0]["n_undetermined"] == 1
    left_out = steel.arrays["v"][c.folds == poly.cv.undetermined[0]["fold"] - 1]
    assert 2.77 in np.round(left_out, 2)
    assert np.round(steel.arrays["v"][poly.cv.undetermined_mask], 2).tolist() == [2.77]
    notes = [n for n in poly.extra_notes if "cannot determine a3, a4, on which" in n]
    assert len(notes) == 2 and "extrapolation test along v" in notes[1]
    assert "arbitrary point of a flat valley" in notes[0] and "(n/d)" in notes[0]
    # the scores it enters are undetermined: NaN, null in JSON, n/d in the table, unranked
    assert math.isnan(poly.cv.rmse) and math.isnan(poly.cv_rmse_common)
    assert math.isnan(poly.extrapolation_rmse) and poly.extrapolation_status == "undetermined"
    assert poly.undetermined_scores == ["cv_rmse", "cv_rmse_common", "extrapolation_rmse"]
    assert c.ranking == ["thirion", "thesis-poly2"]
    assert poly.rank_basis == "unscored: CV RMSE n/d (fold 3)"
    # the other folds' predictions do not depend on the curvature: they keep a score
    assert [f is None for f in poly.cv.fold_rmse] == [False, False, True, False, False]
    doc = json.loads(c.to_json())
    law = next(x for x in doc["laws"] if x["id"] == "thesis-poly2")
    assert law["cv"]["undetermined"][0]["params"] == ["a3", "a4"]
    assert law["cv_rmse"] is None and law["cv_rmse_common"] is None
    assert law["extrapolation_rmse"] is None and law["cv"]["determined"] is False
    assert law["undetermined_scores"] == ["cv_rmse", "cv_rmse_common", "extrapolation_rmse"]
    hold_v = next(h for h in law["extrapolation"] if h["variable"] == "v")
    assert hold_v["undetermined"] == ["a3", "a4"] and hold_v["status"] == "undetermined"
    assert hold_v["rmse"] is None and hold_v["n_undetermined"] == 1
    lines = c.table().splitlines()
    head = re.split(r"\s{2,}", next(line for line in lines if line.startswith("rank  law")))
    row = re.split(r"\s{2,}", next(line for line in lines if " thesis-poly2 " in line).strip())
    cells = dict(zip(head, row))
    assert cells["CV RMSE"] == "n/d" and cells["extrap.RMSE"] == "n/d"
    assert cells["rank basis"] == "unscored: CV RMSE n/d (fold 3)"
    assert c.to_frame().loc[1, "undetermined"] == "cv_rmse, cv_rmse_common, extrapolation_rmse"
    # every fold determines thirion's two parameters: nothing to say
    assert c["thirion"].cv.undetermined == [] and c["thirion"].undetermined_scores == []
    assert c["thirion"].rank_basis.startswith("CV RMSE 0.33")
    assert not any("cannot determine" in n for n in c["thirion"].extra_notes)


def test_undetermined_rows_follow_the_valley_not_the_names(steel: FitData) -> None:
    """A refit whose rows cannot determine some parameters still predicts the rows its
    valley leaves alone: only predictions that move along the valley are undetermined."""
    from frictionlaws.comparison.cv import refit, undetermined_rows
    from frictionlaws.law.registry import get_law

    law = get_law("nackenhorst")  # b0 + b1 ln v + b2 ln^2 v: 3 terms, 2 velocities > 0
    moving = steel.arrays["v"] > 0
    fd = steel.subset(moving)
    v = fd.arrays["v"]
    for train_mask, expect in ((v < 2, [True]), (v > 0, [False])):
        train = fd.subset(train_mask if expect[0] else np.arange(fd.n) != 0)
        res = refit(law, train, {"seed": 0})
        assert res.non_identifiable  # b0, b1, b2 either way
        test = {k: fd.arrays[k][~train_mask if expect[0] else [0]] for k in law.variables}
        assert undetermined_rows(law, res, train, test, 1).tolist() == expect


def test_implausible_holdout_predictions_are_not_averaged(steel: FitData) -> None:
    """thesis-poly3 fitted below p = 0.18 MPa predicts mu < 0 above it: reported as
    implausible, not folded into an RMSE; with a wider plausible range it is scored."""
    from frictionlaws.comparison.extrapolation import score_holdout
    from frictionlaws.law.registry import get_law

    law = get_law("thesis-poly3")
    split = holdout_splits(steel, {"p": 0.3}, design_of(steel))[0]
    usable = np.ones(steel.n, bool)
    h = score_holdout(law, steel, usable, split)
    assert h.status == "implausible" and math.isnan(h.rmse)
    assert h.implausible is not None and "mu = -0.383 at p = 0.2496 MPa" in h.implausible
    wide = score_holdout(law, steel, usable, split, limits=(-10.0, 10.0))
    assert wide.status == "scored" and wide.rmse > 0.5
    assert np.allclose(wide.predictions, h.predictions)
    c = compare(["thesis-poly3"], steel, holdout="p=0.3", progress=False)
    r = c["thesis-poly3"]
    assert r.extrapolation_status == "implausible" and math.isnan(r.extrapolation_rmse)
    assert any("reported as implausible" in n for n in r.extra_notes)
    assert "implausible" in next(line for line in c.table().splitlines()
                                 if " thesis-poly3 " in line)


# ------------------------------------------------------------- comparison


def test_ranking_and_row_groups(cmp: Comparison) -> None:
    assert sorted(cmp.ranking) == sorted(LAWS)
    sav = cmp["savkoor"]
    assert sav.n_dropped == 8 and "dropped 8 of 19 rows" in sav.notes[0]
    # ranked by the CV RMSE over the rows all laws share (savkoor cannot use v = 0)
    assert cmp.settings["ranking_metric"] == "cv_rmse_common"
    assert cmp.settings["common_rows"] == 11
    # scored laws first: identifiable ones, each group by CV RMSE over the common rows;
    # then the unscored ones (an undetermined CV RMSE) by fewer parameters, then id
    scored = [math.isfinite(r.cv_rmse_common) for r in cmp.results]
    assert scored == sorted(scored, reverse=True)
    head = [r for r in cmp.results if math.isfinite(r.cv_rmse_common)]
    flags = [bool(r.fit.non_identifiable) for r in head]
    assert flags == sorted(flags)
    for flag in (False, True):
        keys = [r.cv_rmse_common for r in head if bool(r.fit.non_identifiable) == flag]
        assert keys == sorted(keys)
    tail = [(r.metrics["k"], r.id) for r in cmp.results if not math.isfinite(r.cv_rmse_common)]
    assert tail == sorted(tail) and all(r.rank_basis.startswith("unscored: CV common n/d")
                                        for r in cmp.results[len(head):])
    # Akaike weights only among laws fitted to the same rows
    groups: dict[int, list[float]] = {}
    for r in cmp.results:
        groups.setdefault(r.aic_group, []).append(r.akaike_weight)
    assert len(groups) == 2
    for ws in groups.values():
        assert sum(ws) == pytest.approx(1.0)
    assert sav.aic_group_size == 1 and sav.akaike_weight == 1.0
    m = cmp["thirion"].metrics
    assert m["k"] == 2 and m["n"] == 19 and 0.9 < m["r2"] < 1.0


def test_thesis_polynomials_flagged_outside_the_pressure_range(cmp: Comparison) -> None:
    for lid in ("thesis-poly2", "thesis-poly3"):
        r = cmp[lid]
        assert not r.plausible
        text = " ".join(r.plausibility.reasons)
        assert "p outside the measured range" in text or "outside the measured p range" in text
    poly2 = " ".join(cmp["thesis-poly2"].plausibility.reasons)
    assert "as p increases beyond the highest measured p (0.2496 MPa)" in poly2
    assert "data show mu falling with p" in poly2
    assert "mu < 0" in " ".join(cmp["thesis-poly3"].plausibility.reasons)
    assert cmp["thirion"].plausible and cmp["coulomb"].plausible
    # its fit below v = 1.94 m/s cannot determine the prediction at 2.77 m/s
    assert cmp["thesis-poly3"].extrapolation_status == "undetermined"


def test_json_holds_every_metric(cmp: Comparison) -> None:
    doc = json.loads(cmp.to_json())
    assert doc["format"] == "frictionlaws-comparison"
    assert doc["dataset"]["name"] == "thesis-steel" and doc["dataset"]["n"] == 19
    assert doc["dataset"]["variables"]["p"]["unit"] == "Pa"
    assert doc["units"]["p"] == "Pa" and doc["units"]["rmse"] == "-"
    keys = {"r2", "adj_r2", "rmse", "mae", "max_abs_residual", "aic", "aicc", "bic", "k", "n",
            "akaike_weight", "cv_rmse", "cv_rmse_common", "cv", "extrapolation_rmse",
            "extrapolation", "plausible", "plausibility_reasons", "warnings",
            "non_identifiable", "residual_tests", "params", "rank"}
    assert [law["id"] for law in doc["laws"]] == cmp.ranking
    for law in doc["laws"]:
        assert keys <= set(law), keys - set(law)
        assert isinstance(law["plausible"], bool)
        assert law["cv"]["seed"] == 3 and law["cv"]["folds"] == 5
    poly3 = next(x for x in doc["laws"] if x["id"] == "thesis-poly3")
    assert poly3["non_identifiable"] and poly3["plausibility_reasons"]
    assert "p" in poly3["residual_tests"]["tests"]


def test_skipped_failed_and_bad_input(steel: FitData) -> None:
    def broken(m, p, a):
        raise ZeroDivisionError("boom")

    bad = Law(id="broken-test-law", title="always fails", family="sliding", variables=("p",),
              params=(Param("a", "", 1.0),), formula=broken)
    c = compare(["thirion", "park", "pacejka", bad], steel, folds=3, holdout=None)
    assert c.ranking == ["thirion"]
    skipped = {s["id"]: s["reason"] for s in c.skipped}
    assert "T (temperature)" in skipped["park"] and "slip ratio" in skipped["pacejka"]
    assert c.failed[0]["id"] == "broken-test-law" and "boom" in c.failed[0]["error"]
    text = c.table()
    assert "park" in text and "broken-test-law" in text
    with pytest.raises(UnknownLawError):
        compare(["no-such-law"], steel)
    with pytest.raises(InputError):
        compare(["park"], steel)  # nothing left to fit: says why
    with pytest.raises(InputError):
        compare(["thirion"], steel, folds=1)
    with pytest.raises(InputError):
        compare(["thirion"], steel, mu_limits=(5, 0))


def test_family_default_and_public_api(steel: FitData) -> None:
    c = frictionlaws.compare("coulomb,thirion", steel, folds=30, holdout="p=0.3")
    assert c.settings["folds"] == 19  # reduced to leave-one-out, with a note
    assert any("leave-one-out" in n for n in c.notes)
    assert [s["variable"] for s in c.settings["splits"]] == ["p"]
    importlib.import_module("frictionlaws.comparison.core")  # the package has its own name
    assert frictionlaws.compare is compare
    assert frictionlaws.compare("coulomb", steel, folds=2, holdout=None).ranking == ["coulomb"]


def test_plausibility_scan_flags_blow_up_and_reversal() -> None:
    p = np.linspace(1e5, 3e5, 9)
    fd = FitData({"mu": 2.0 - 3e-6 * p, "p": p}, "falling", "synthetic")
    design = design_of(fd)
    trends = data_trends(fd, design)
    box = extended_box(fd, design)

    def pole(m, p, a, c):
        return a / (p - c)

    law = Law(id="pole-test", title="pole", family="sliding", variables=("p",),
              params=(Param("a", "", 1.0), Param("c", "Pa", 0.0)), formula=pole)
    res = scan_plausibility(law, {"a": 1e5, "c": 5e5}, fd, design, box, trends)
    kinds = {f.kind for f in res.flags}
    assert not res.plausible and {"below-limit", "above-limit"} <= kinds

    def parabola(m, p, a, b):
        return a + b * (p / 1e5 - 2.0) ** 2

    law2 = Law(id="parabola-test", title="parabola", family="sliding", variables=("p",),
               params=(Param("a", "", 1.0), Param("b", "", 0.1)), formula=parabola)
    res2 = scan_plausibility(law2, {"a": 1.0, "b": 0.05}, fd, design, box, trends)
    assert [f.kind for f in res2.flags] == ["trend"]
    assert "rises by" in res2.reasons[0] and "as p increases beyond" in res2.reasons[0]
    assert "falling with p" in res2.reasons[0]
    assert res2.flags[0].to["p"] == pytest.approx(9e5)
    # the same law, gently falling everywhere in the box: plausible
    res3 = scan_plausibility(law2, {"a": 1.0, "b": 0.0}, fd, design, box, trends)
    assert res3.plausible and res3.mu_min == res3.mu_max == 1.0


def test_progress_bar_only_when_asked(steel: FitData, capsys: pytest.CaptureFixture) -> None:
    compare(["coulomb"], steel, folds=2, holdout=None, progress=True)
    assert "compare" in capsys.readouterr().err
    compare(["coulomb"], steel, folds=2, holdout=None)  # stderr is not a terminal
    assert capsys.readouterr().err == ""


def test_default_family_tells_tyre_slip_from_pin_on_disc_data() -> None:
    from frictionlaws.comparison.core import default_family
    from frictionlaws.fitting import as_fit_data

    s = np.linspace(0.0, 1.0, 12)
    tyre = as_fit_data({"mu": 0.9 * np.sin(1.9 * np.arctan(10 * s)), "s": s})
    assert default_family(tyre) == "slip"
    pin = as_fit_data({"mu": np.ones(6), "p": np.linspace(3e4, 2e5, 6),
                       "v": np.ones(6), "s": np.array([1.0, 1.0, 1.2, 1.5, 2.0, 2.0])})
    assert default_family(pin) == "sliding"
    fixed_pin = as_fit_data({"mu": np.ones(6), "p": np.linspace(3e4, 2e5, 6), "s": np.ones(6)})
    assert default_family(fixed_pin) == "sliding"


@pytest.mark.parametrize("spec", ["T=0.3", "p=0.3,T=0.2", {"T": 0.3}])
def test_a_holdout_naming_a_variable_the_data_lack_is_refused(steel: FitData, spec) -> None:
    with pytest.raises(InputError, match="have no T to hold out; their variables are p, v"):
        compare(["thirion"], steel, holdout=spec)
    # a bare fraction holds out p and v where the data have them: no complaint
    assert [s.variable for s in compare(["coulomb"], steel, holdout=0.3).splits] == ["p", "v"]


def test_jobs_is_a_ceiling_not_a_demand(steel: FitData, monkeypatch: pytest.MonkeyPatch
                                        ) -> None:
    import joblib

    from frictionlaws.parallel import local_workers

    monkeypatch.setattr(joblib, "cpu_count", lambda *a, **k: 8)
    assert [local_workers(j) for j in (1, 2, 8, 9, 1024, -1)] == [1, 2, 8, 8, 8, 8]
    assert local_workers(1024, tasks=3) == 3 and local_workers(-1, tasks=0) == 1
    assert local_workers(1, tasks=50) == 1
    seen: list[int] = []

    class Spy(joblib.Parallel):  # type: ignore[misc]
        def __init__(self, n_jobs: int, **kw: object) -> None:
            seen.append(n_jobs)
            super().__init__(n_jobs=n_jobs, **kw)

    monkeypatch.setattr(joblib, "Parallel", Spy)
    c = compare(["coulomb"], steel, folds=2, holdout=None, jobs=1024)
    assert seen == [3]  # the full fit and two folds: three tasks, three processes
    assert c.ranking == ["coulomb"]


@pytest.mark.parametrize("law_id", ["thirion", "wriggers", "savkoor", "huemer"])
def test_refit_optimum_does_not_depend_on_row_order(steel: FitData, law_id: str) -> None:
    """A comparison's refit reaches the optimum of its rows, not of their order: chi^2
    the same to 1e-9 relative for shuffled rows (the polish ends every path at the
    optimum; Wriggers' optimum sits on a bound, savkoor's and huemer's in a valley)."""
    from frictionlaws.comparison.core import usable_rows
    from frictionlaws.comparison.cv import refit
    from frictionlaws.law.registry import get_law

    law = get_law(law_id)
    rows = np.flatnonzero(usable_rows(law, steel))
    chi2 = refit(law, steel.subset(rows), {"seed": 0}).metrics["chisqr"]
    for seed in range(2):
        perm = np.random.default_rng(seed).permutation(rows)
        again = refit(law, steel.subset(perm), {"seed": 0}).metrics["chisqr"]
        assert again == pytest.approx(chi2, rel=1e-9, abs=0.0)


@settings(max_examples=25, deadline=None)
@given(tenths=st.lists(st.integers(1, 27), min_size=1, max_size=4, unique=True),
       new_tenths=st.integers(1, 27), seed=st.integers(0, 2**16))
def test_undetermined_rows_of_a_quadratic_in_v(tenths: list[int], new_tenths: int,
                                               seed: int) -> None:
    """thesis-poly2 is quadratic in V: trained on fewer than 3 velocities, its prediction
    at another velocity is undetermined and at a trained one determined; trained on 3 or
    more, every prediction is determined."""
    from frictionlaws.comparison.cv import refit, undetermined_rows
    from frictionlaws.law.registry import get_law

    law = get_law("thesis-poly2")
    levels, new = [t / 10 for t in tenths], new_tenths / 10  # 0.1 m/s apart, inside the box
    rng = np.random.default_rng(seed)
    p = np.tile([0.05e6, 0.08e6, 0.1e6, 0.15e6, 0.2e6, 0.25e6], len(levels))
    v = np.repeat(levels, 6)
    mu = 1.5 - 2e-6 * p + 0.1 * v + 0.02 * rng.standard_normal(p.size)
    train = as_fit_data({"mu": mu, "p": p, "v": v})
    res = refit(law, train, {"seed": 0})
    test = {"p": np.array([0.12e6, 0.12e6]), "v": np.array([levels[0], new])}
    got = undetermined_rows(law, res, train, test, 2).tolist()
    far = new_tenths not in tenths
    if len(levels) >= 3:
        assert got == [False, False]
    else:
        assert got == [False, far]


def test_strict_domain_rows_are_left_out_as_a_fit_leaves_them_out():
    """A law that must not be extrapolated is compared on the rows inside its box only."""
    import frictionlaws as fl

    ds = fl.load_dataset("thesis-steel").frame
    extra = ds.iloc[:3].copy()
    extra["p"] = 0.4e6  # beyond the thesis polynomials' box (p up to 0.25 MPa)
    data = {k: np.concatenate([ds[k].to_numpy(float), extra[k].to_numpy(float)])
            for k in ("mu", "p", "v")}
    cmp = fl.compare(["thesis-poly2", "coulomb"], data, folds=3, holdout=None)
    fitted = {row.law.id: row for row in cmp.results}
    assert fitted["thesis-poly2"].fit.metrics["n"] == len(ds)
    assert fitted["coulomb"].fit.metrics["n"] == len(ds) + 3
    assert any("outside p" in note for note in fitted["thesis-poly2"].fit.notes)
