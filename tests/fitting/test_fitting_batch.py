"""Stacked fits (one law, many datasets at once) give the numbers and warnings of one fit each.

The datasets are generated: clean, weighted, noisy, with an outlier, of varying size and
columns, and hostile ones (a parameter driven to its bound, a variable with one value, a
constant mu, exact data, as many rows as parameters plus one, too many rows for a stack).
Every member a stack fits must equal :func:`frictionlaws.fit` of that dataset: values,
standard errors, intervals, metrics, derived quantities, the residual structure and the
warnings, to 1e-6 relative (a value or interval bound far below its standard error: to
1e-6 of that error, the precision both reach the optimum with); every member it hands
back is fitted by :func:`fit` itself.  The tests also hold that the stacks do fit the
plain members (so they cannot pass by handing everything back) and hand back the
hostile ones.
"""

from __future__ import annotations

import pickle

import numpy as np
import pandas as pd
import pytest

import frictionlaws as fl
from frictionlaws.fitting import as_fit_data
from frictionlaws.fitting.batch import POLISH_ROWS, Problems, solve
from frictionlaws.fitting.campaign import _compact, fit_many
from frictionlaws.fitting.campaign_results import Block
from frictionlaws.fitting.stacked import fit_stacked, stack_fits, stackable

RANGES = {"p": (2e4, 5e5), "v": (0.01, 3.0), "F_N": (10.0, 1000.0), "s": (0.01, 0.3)}
KINDS = ("clean", "clean", "weighted", "noisy", "outlier", "ragged", "extra-T", "bound",
         "one-value", "constant", "exact", "minimal", "large")
#: Kinds a stack must hand back to the one-fit path (a non-linear law of two parameters).
HANDED_BACK = {"bound", "one-value", "constant", "exact", "minimal", "large"}


def _variables(law, n, rng, kind):
    out = {}
    for var in law.variables:
        lo, hi = RANGES[var]
        levels = np.linspace(lo, hi, max(2, min(6, n // 3)))
        x = rng.uniform(lo, hi, n) if kind == "ragged" or var == "s" else rng.choice(levels, n)
        if kind == "one-value" and var == law.variables[0]:
            x = np.full(n, levels[1])
        out[var] = x
    return out


def _parameters(law, rng):
    out = {}
    for p in law.params:
        typical = p.default or 0.1
        lo, hi = p.bounds
        value = typical * rng.uniform(0.7, 1.3)
        out[p.name] = min(max(value, lo + 1e-6 * abs(typical)), hi - 1e-6 * abs(typical))
    return out


def generated(law, kind, rng):
    """One dataset of ``kind`` for ``law`` (SI arrays, as fit takes them)."""
    n = {"minimal": len(law.params) + 1, "ragged": int(rng.integers(8, 60)),
         "large": POLISH_ROWS + 10}.get(kind, 24)
    x = _variables(law, n, rng, kind)
    with np.errstate(all="ignore"):
        mu = np.broadcast_to(np.asarray(law.evaluate(
            x, {**law.setting_values, **_parameters(law, rng)}), float), (n,)).copy()
    if not np.all(np.isfinite(mu)) or np.any(np.abs(mu) > 5):  # a law the data miss
        z = sum((v - v.mean()) / (np.ptp(v) + 1e-12) for v in x.values()) if x else 0.0
        mu = 0.6 + 0.2 * np.tanh(z) + np.zeros(n)
    scale = float(np.abs(mu).mean()) + 1e-3
    mu = mu + {"exact": 0.0, "noisy": 0.5, "constant": 0.0}.get(kind, 0.03) \
        * scale * rng.standard_normal(n)
    if kind == "constant":
        mu = np.full(n, 0.7)
    if kind == "outlier":
        mu[n // 2] += 10 * scale
    if kind == "bound" and "p" in x:  # mu rising with p: Thirion's b wants to be negative
        mu = 0.3 + 1e-7 * x["p"] + 0.01 * rng.standard_normal(n)
    data = {"mu": np.abs(mu) if law.family == "sliding" else mu, **x}
    if kind == "weighted":
        data["weights"] = rng.uniform(0.5, 2.0, n)
    if kind == "extra-T":
        data["T"] = rng.choice([280.0, 300.0, 320.0], n)
    return data


def assert_same(stacked, alone, path="result"):
    """Equal records: numbers to 1e-6 relative (of the standard error for a parameter's
    value or interval bound far below it; of 1 - R^2 for R^2), all else exactly."""
    if isinstance(alone, dict):
        assert stacked.keys() == alone.keys(), path
        for key in alone:
            if key == "params":
                for name, est in alone[key].items():
                    _same_estimate(stacked[key][name], est, f"{path}/params/{name}")
            else:
                assert_same(stacked[key], alone[key], f"{path}/{key}")
    elif isinstance(alone, list):
        assert len(stacked) == len(alone), path
        for a, b in zip(stacked, alone):
            assert_same(a, b, path)
    elif isinstance(alone, float) and isinstance(stacked, float):
        if path.endswith(("/r2", "/adj_r2")):
            stacked, alone = 1 - stacked, 1 - alone
        assert stacked == pytest.approx(alone, rel=1e-6, abs=0), path
    else:
        assert stacked == alone, path


def _same_estimate(stacked, alone, path):
    se = alone["stderr"] or 0.0
    for key, value in alone.items():
        if key in ("value", "ci95") and value is not None:
            for a, b in zip(np.atleast_1d(stacked[key]), np.atleast_1d(value)):
                assert abs(a - b) <= 1e-6 * max(abs(a), abs(b), se), (path, key, a, b)
        else:
            assert_same(stacked[key], value, f"{path}/{key}")


def _compare(law_id, kinds, count, seed):
    """Stack ``count`` generated datasets; compare each stacked member with fit alone."""
    law = fl.get_law(law_id)
    rng = np.random.default_rng(seed)
    kind_of = [kinds[i % len(kinds)] for i in range(count)]
    datasets = [generated(law, kind, rng) for kind in kind_of]
    results = fit_stacked(law, [as_fit_data(d) for d in datasets])
    for data, result in zip(datasets, results):
        if result is not None:
            assert_same(result, _compact(fl.fit(law, data).to_dict()))
    return {kind: [r is not None for k, r in zip(kind_of, results) if k == kind]
            for kind in kinds}


@pytest.mark.parametrize("law_id", ["thirion", "coulomb", "quadratic-pv"])
def test_stacked_fits_equal_one_fit_each_and_hand_back_the_hostile_members(law_id):
    stacked = _compare(law_id, KINDS, 2 * len(KINDS), seed=7)
    assert all(stacked["clean"])
    # Coulomb's weighted mean is worse than the plain mean (R^2 < 0): fit warns, alone
    assert all(stacked["weighted"]) if law_id != "coulomb" else not any(stacked["weighted"])
    assert all(stacked["ragged"]) and all(stacked["extra-T"])
    assert not any(stacked["large"]) and not any(stacked["constant"])
    if law_id == "thirion":  # a non-linear law: every hostile kind is handed back
        assert not any(v for kind in HANDED_BACK for v in stacked[kind])


@pytest.mark.slow
@pytest.mark.parametrize("law_id", ["denny", "schallamach", "kiencke-daiss", "burckhardt-sqrt",
                                    "exponential-decay", "wriggers", "nackenhorst", "germann"])
def test_stacked_fits_of_other_laws_equal_one_fit_each(law_id):
    stacked = _compare(law_id, KINDS, 2 * len(KINDS), seed=11)
    assert not any(stacked["large"])


def test_a_law_without_analytic_jacobian_or_other_options_fits_alone():
    persson = fl.get_law("persson")
    assert fit_stacked(persson, [as_fit_data(generated(fl.get_law("thirion"), "clean",
                                                       np.random.default_rng(0)))]) == [None]
    assert stackable({"weights": None, "seed": 3}) and stackable({})
    for options in ({"uncertainty": "sandwich"}, {"fix": {"b": 1e-6}}, {"starts": 4},
                    {"global_stage": "on"}, {"lean": True}, {"weights": np.ones(3)},
                    {"method": "nelder"}, {"initial": {"a": 1.0}}):
        assert not stackable(options), options


def test_the_solver_reaches_the_least_squares_optimum_of_a_linear_law():
    law = fl.get_law("quadratic-pv")
    rng = np.random.default_rng(3)
    p, v = rng.uniform(2e4, 5e5, (40, 24)), rng.uniform(0.01, 3, (40, 24))
    y = 0.8 + 1e-6 * p - 0.05 * v + 0.02 * rng.standard_normal((40, 24))
    names = list(law.param_names)
    from frictionlaws.fitting.derivatives import jacobian_function

    prob = Problems(law, names, {}, law.prepare_variables({"p": p, "v": v}), y, None,
                    np.full(6, -np.inf), np.full(6, np.inf), jacobian_function(law))
    sol = solve(prob, np.tile([1.0, 0, 0, 0, 0, 0], (40, 1)))
    assert sol.converged.all() and sol.iterations.max() <= 10
    for i in range(40):
        cols = np.column_stack([np.ones(24), p[i], v[i], p[i] * v[i], p[i] ** 2, v[i] ** 2])
        scale = np.linalg.norm(cols, axis=0)
        coef = np.linalg.lstsq(cols / scale, y[i], rcond=None)[0] / scale
        r_best, r_got = y[i] - cols @ coef, y[i] - cols @ sol.theta[i]
        assert r_got @ r_got <= (r_best @ r_best) * (1 + 1e-12)


def test_the_solver_stops_on_a_bound_and_says_it_did_not_converge():
    law = fl.get_law("thirion")
    p = np.tile(np.linspace(2e4, 5e5, 24), (3, 1))
    y = 0.3 + 1e-7 * p  # rising with p: b would be negative
    from frictionlaws.fitting.derivatives import jacobian_function

    prob = Problems(law, ["a", "b"], {}, law.prepare_variables({"p": p}), y, None,
                    np.array([1e-9, 0.0]), np.array([np.inf, np.inf]), jacobian_function(law))
    sol = solve(prob, np.tile([2.0, 1e-6], (3, 1)))
    assert not sol.converged.any()
    assert np.all(sol.theta[:, 1] >= 0.0) and np.all(sol.theta[:, 1] < 1e-8)


@pytest.mark.parametrize("law_id", ["thirion", "schallamach"])
def test_a_single_fit_ends_at_the_optimum_whatever_its_start(law_id):
    """fit continues every small fit to its optimum: the start does not show."""
    law = fl.get_law(law_id)
    data = generated(law, "clean", np.random.default_rng(5))
    first = fl.fit(law, data)
    for factor in (0.5, 2.0):
        other = fl.fit(law, data, initial={k: e.value * factor for k, e in first.params.items()
                                           if k != "n"})
        for name, est in first.params.items():
            assert other.params[name].value == pytest.approx(est.value, rel=1e-8)
            assert other.params[name].stderr == pytest.approx(est.stderr, rel=1e-6)


LAWS = ("thirion", "coulomb", "quadratic-pv")


def _campaign_folder(tmp_path, count, seed=0):
    """``count`` files as the campaign benchmark writes them (p in MPa, v in m/s)."""
    law = fl.get_law("thirion")
    rng = np.random.default_rng(seed)
    p = np.repeat([0.03, 0.06, 0.12, 0.25], 6)
    v = np.tile([0.1, 0.3, 0.7, 1.4, 2.0, 2.8], 4)
    folder = tmp_path / "campaign"
    folder.mkdir()
    for i in range(count):
        mu = law(p=p * 1e6, a=rng.uniform(0.2, 0.5), b=rng.uniform(2e-6, 6e-6)) \
            + 0.02 * rng.standard_normal(p.size)
        pd.DataFrame({"mu": mu, "p [MPa]": p, "v [m/s]": v}).to_csv(
            folder / f"ds{i:05d}.csv", index=False)
    return folder


def test_a_campaign_of_30_datasets_gives_the_values_of_one_fit_each(tmp_path, monkeypatch):
    """The issue's measure: 30 datasets x 3 laws, every record that of fit alone."""
    import frictionlaws.fitting.campaign as campaign

    folder = _campaign_folder(tmp_path, 30)
    alone_calls = []
    one = campaign._fit_one
    monkeypatch.setattr(campaign, "_fit_one",
                        lambda *a: alone_calls.append(a[0]) or one(*a))
    camp = fit_many(LAWS, folder)
    assert len(camp) == 90 and alone_calls == []  # every fit made in a stack
    for rec in camp.records:
        alone = fl.fit(rec["law"], folder / f"{rec['dataset']}.csv")
        assert_same(rec["result"], _compact(alone.to_dict()))


def test_options_a_stack_does_not_take_give_one_fit_each(tmp_path):
    folder = _campaign_folder(tmp_path, 3)
    camp = fit_many("thirion", folder, uncertainty="sandwich")
    for rec in camp.records:
        alone = fl.fit("thirion", folder / f"{rec['dataset']}.csv", uncertainty="sandwich")
        assert rec["result"] == _compact(alone.to_dict())


def test_an_unreadable_dataset_stops_the_fits_of_its_chunk(tmp_path, monkeypatch):
    import frictionlaws.fitting.stacked as stacked
    from frictionlaws.fitting.campaign import UnreadableDatasets

    folder = _campaign_folder(tmp_path, 6)
    (folder / "ds00002.csv").write_text("mu,p [MPa]\n0.5,abc\n")
    made = []
    monkeypatch.setattr(stacked, "stack_fits", lambda *a, **k: made.append(a))
    with pytest.raises(UnreadableDatasets, match="1 of 6 datasets") as info:
        fit_many(LAWS, folder)
    assert "ds00002.csv" in str(info.value) and made == []


def test_a_block_travels_as_columns_and_gives_its_records_back():
    law = fl.get_law("thirion")
    rng = np.random.default_rng(2)
    data = [generated(law, kind, rng) for kind in ("clean", "weighted", "bound")]
    fits = stack_fits(law, [as_fit_data(d) for d in data])
    assert fits.row.tolist() == [0, 1, -1]  # the bound-hitting member handed back
    heads = [(f"d{i}", f"d{i}.csv", {}, "thirion", 24) for i in range(3)]
    parts = [(0, 0), (0, 1), {"error": "no start gave a finite result"}]
    block = Block(heads, parts, [fits])
    moved = pickle.loads(pickle.dumps(block))
    assert len(moved) == 3 and moved.problems == []
    assert moved.records == block.records
    assert_same(moved.records[1]["result"], _compact(fl.fit(law, data[1]).to_dict()))
    assert list(moved.tidy(())) == list(block.tidy(()))
    assert len(list(block.tidy(()))) == 2 + 2 + 1


def test_the_table_of_blocks_equals_the_table_of_their_records(tmp_path):
    """Stacked, alone and failed fits, groups: the columns written at once give the
    frame the records' rows give."""
    from frictionlaws.fitting.campaign import tidy_columns

    rng = np.random.default_rng(1)
    p = np.tile(np.repeat([0.05, 0.1, 0.2, 0.3], 3), 2)
    for i in range(4):
        mu = np.full(24, 0.5) if i == 1 else \
            1 / (0.3 + 3e-6 * p * 1e6) + 0.02 * rng.standard_normal(24)
        pd.DataFrame({"mu": mu, "p [MPa]": p, "surface": np.repeat(["steel", "ice"], 12)}
                     ).to_csv(tmp_path / f"x{i}.csv", index=False)
    (tmp_path / "x9.csv").write_text(  # two rows a group: exponential-decay cannot fit
        "mu,p [MPa],surface\n0.5,0.1,steel\n0.6,0.2,steel\n0.5,0.1,ice\n0.7,0.2,ice\n")
    camp = fit_many(["thirion", "coulomb", "exponential-decay"], tmp_path, by="surface")
    fast = camp.to_frame()
    rows = pd.DataFrame(list(camp.rows()), columns=tidy_columns(camp.by))
    for col in rows.columns:
        if rows[col].dtype == object:
            rows[col] = rows[col].where(rows[col].notna(), np.nan)
    pd.testing.assert_frame_equal(fast, rows)
    assert fast["error"].notna().sum() >= 6 and fast["warnings"].max() >= 1


def _spoil(folder, rng, count):
    """Blank, NaN or negate a cell of ``count`` of the files at random (the reader drops
    such a row or notes it); the spoiled datasets' names."""
    files = sorted(folder.glob("*.csv"))
    spoiled = set()
    for i in rng.choice(len(files), count, replace=False):
        lines = files[i].read_text().splitlines()
        row = int(rng.integers(1, len(lines)))
        cells = lines[row].split(",")
        col = int(rng.integers(0, 3))
        cells[col] = str(rng.choice(["", "nan", "NaN"])) if col < 2 else "-" + cells[col]
        lines[row] = ",".join(cells)
        files[i].write_text("\n".join(lines) + "\n")
        spoiled.add(files[i].stem)
    return spoiled


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_rows_the_reader_drops_are_noted_in_every_record_and_table(tmp_path, seed,
                                                                   monkeypatch):
    """Nothing dropped silently: a dataset's notes (rows dropped, negative speeds) are in
    its records, as fit alone gives them, and in the table, stacked or alone, held or
    streamed."""
    import frictionlaws.fitting.campaign as campaign

    rng = np.random.default_rng(seed)
    folder = _campaign_folder(tmp_path, 8, seed)
    spoiled = _spoil(folder, rng, 4)
    alone_calls = []
    one = campaign._fit_one
    monkeypatch.setattr(campaign, "_fit_one", lambda *a: alone_calls.append(a[0]) or one(*a))
    camp = fit_many(LAWS, folder)
    noted = [rec for rec in camp.records if rec["result"]["notes"]]
    assert {rec["dataset"] for rec in noted} == spoiled
    assert len(alone_calls) < len(noted)  # some noted fits were made in a stack
    for rec in camp.records:
        alone = fl.fit(rec["law"], folder / f"{rec['dataset']}.csv")
        assert_same(rec["result"], _compact(alone.to_dict()))
    streamed = fit_many(LAWS, folder, output=tmp_path / "out.csv").to_frame()
    for frame in (camp.to_frame(), streamed):
        for rec in camp.records:
            cells = frame.loc[(frame["dataset"] == rec["dataset"])
                              & (frame["law"] == rec["law"]), "notes"]
            notes = rec["result"]["notes"]
            if notes:
                assert (cells == " | ".join(notes)).all(), rec["dataset"]
            else:
                assert cells.isna().all(), rec["dataset"]
