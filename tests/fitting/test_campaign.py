"""Campaigns: groups, many datasets, shared parameters, parallel and Dask."""

from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd
import pytest

import frictionlaws as fl
from frictionlaws.base.errors import InputError
from frictionlaws.fitting.campaign import fit_many, group_keys, run_parallel
from frictionlaws.fitting.shared import fit_shared
from frictionlaws.io import load_dataset

THIRION = fl.get_law("thirion")


def _two_surfaces(tmp_path):
    rng = np.random.default_rng(5)
    p = np.linspace(0.02, 1.0, 20)
    rows = []
    for surface, a in (("steel", 0.3), ("ice", 2.0)):
        mu = THIRION(p=p * 1e6, a=a, b=3e-6) * (1 + 0.01 * rng.standard_normal(p.size))
        rows.append(pd.DataFrame({"mu": mu, "p [MPa]": p, "surface": surface}))
    path = tmp_path / "two.csv"
    pd.concat(rows).to_csv(path, index=False)
    return path


def _temperatures(seed=1, b=3e-6):
    rng = np.random.default_rng(seed)
    frames, truth = [], {}
    for i, T in enumerate((0, 10, 20, 30, 40)):
        a = 0.2 + 0.05 * i
        p = np.linspace(2e4, 1e6, 30)
        mu = THIRION(p=p, a=a, b=b) + 0.02 * rng.standard_normal(p.size)
        frames.append(pd.DataFrame({"mu": mu, "p [Pa]": p, "T [degC]": T}))
        truth[T + 273.15] = a
    return pd.concat(frames, ignore_index=True), truth


def test_a_pooled_fit_over_surfaces_is_refused(tmp_path):
    from frictionlaws.base.errors import GroupingError

    with pytest.raises(GroupingError, match="2 values of 'surface'") as exc:
        fl.fit("thirion", _two_surfaces(tmp_path))
    assert "by='surface'" in str(exc.value)
    code = __import__("frictionlaws.cli", fromlist=["main"]).main(
        ["fit", "--law", "thirion", str(tmp_path / "two.csv")])
    assert code == 2


def test_groups_are_fitted_separately(tmp_path):
    camp = fit_many("thirion", _two_surfaces(tmp_path), by="surface")
    assert [r["group"]["surface"] for r in camp.records] == ["steel", "ice"]
    a = {r["group"]["surface"]: r["result"]["params"]["a"]["value"] for r in camp.records}
    assert a["steel"] == pytest.approx(0.3, rel=0.05)
    assert a["ice"] == pytest.approx(2.0, rel=0.05)
    frame = camp.to_frame()
    assert set(frame.columns) >= {"dataset", "surface", "law", "param", "value", "stderr",
                                  "unit", "r2"}
    assert len(frame) == 4 and set(frame["unit"]) == {"-", "1/Pa"}


def test_missing_group_column_is_named(tmp_path):
    with pytest.raises(InputError, match="no column compound to group by"):
        group_keys(load_dataset(_two_surfaces(tmp_path)), ["compound"])


def test_many_files_and_a_directory_give_the_same_records(tmp_path):
    df, _ = _temperatures()
    folder = tmp_path / "many"
    folder.mkdir()
    for T, part in df.groupby("T [degC]"):
        part.to_csv(folder / f"T{int(T):03d}.csv", index=False)
    from_dir = fit_many(["thirion", "coulomb"], folder)
    from_list = fit_many(["thirion", "coulomb"], sorted(folder.glob("*.csv")))
    assert len(from_dir) == 10
    assert from_dir.to_frame().equals(from_list.to_frame())
    assert not from_dir.errors


def test_an_unreadable_dataset_refuses_the_campaign_before_any_fit(tmp_path):
    """A campaign half done looks complete: every dataset is read first."""
    from frictionlaws.fitting.campaign import UnreadableDatasets

    good = _two_surfaces(tmp_path)
    bad = tmp_path / "bad.csv"
    bad.write_text("mu,p [MPa]\n0.5,abc\n")
    with pytest.raises(UnreadableDatasets, match="1 of 2 datasets") as info:
        fit_many("thirion", [good, bad], by="surface")
    assert [p.file for p in info.value.problems] == [str(bad)]


def test_results_save_as_csv_and_strict_json(tmp_path):
    camp = fit_many("thirion", _two_surfaces(tmp_path), by="surface")
    csv_path = camp.save(tmp_path / "out.csv")
    assert pd.read_csv(csv_path).shape[0] == 4
    doc = json.loads(camp.save(tmp_path / "out.json").read_text(),
                     parse_constant=lambda c: (_ for _ in ()).throw(ValueError(c)))
    assert doc["by"] == ["surface"] and len(doc["records"]) == 2
    with pytest.raises(InputError, match=".csv or .json"):
        camp.save(tmp_path / "out.txt")


def test_parallel_jobs_give_identical_results(tmp_path):
    df, _ = _temperatures()
    folder = tmp_path / "many"
    folder.mkdir()
    for T, part in df.groupby("T [degC]"):
        part.to_csv(folder / f"T{int(T):03d}.csv", index=False)
    serial = fit_many("thirion", folder).to_frame()
    parallel = fit_many("thirion", folder, jobs=2).to_frame()
    pd.testing.assert_frame_equal(serial, parallel)


@pytest.mark.parametrize("jobs", [0, -2, 1.5, True, "2"])
def test_bad_jobs_are_refused(jobs):
    with pytest.raises(InputError, match="jobs must be"):
        run_parallel(abs, [1], jobs=jobs)


@pytest.mark.slow
def test_dask_local_cluster_equals_serial(tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    df, _ = _temperatures()
    folder = tmp_path / "many"
    folder.mkdir()
    for T, part in df.groupby("T [degC]"):
        part.to_csv(folder / f"T{int(T):03d}.csv", index=False)
    serial = fit_many("thirion", folder).to_frame()
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        remote = fit_many("thirion", folder, scheduler=cluster.scheduler_address).to_frame()
    pd.testing.assert_frame_equal(serial, remote)


def test_unreachable_scheduler_is_an_input_error():
    pytest.importorskip("dask.distributed")
    with pytest.raises(InputError, match="cannot reach the Dask scheduler"):
        run_parallel(abs, [1], scheduler="tcp://127.0.0.1:9")


def test_shared_parameter_recovered_across_five_temperatures():
    df, truth = _temperatures(seed=3)
    res = fit_shared("thirion", df, "T", ["b"])
    shared = res.shared_values()["b"]
    assert abs(shared["value"] - 3e-6) < 3 * shared["stderr"]
    for g in res.groups:
        est = g["params"]["a"]
        assert abs(est["value"] - truth[g["key"]["T"]]) < 3 * est["stderr"]
        assert g["params"]["b"]["shared"] and not est["shared"]
    c = res.comparison
    assert c["k_shared"] == 6 and c["k_separate"] == 10 and c["n"] == 150
    assert c["p_value"] > 0.01 and math.isfinite(c["delta_aic"])
    assert "shared vs separate" in res.report()


def test_shared_fit_detects_groups_that_do_not_share():
    frames = []
    rng = np.random.default_rng(4)
    for i, b in enumerate((1e-6, 3e-6, 9e-6)):
        p = np.linspace(2e4, 1e6, 30)
        mu = THIRION(p=p, a=0.3, b=b) * (1 + 0.005 * rng.standard_normal(p.size))
        frames.append(pd.DataFrame({"mu": mu, "p [Pa]": p, "T [degC]": 10 * i}))
    res = fit_shared("thirion", pd.concat(frames, ignore_index=True), "T", ["b"])
    assert res.comparison["p_value"] < 1e-6 and res.comparison["delta_aic"] > 0
    assert "differ" in res.comparison["verdict"]


@pytest.mark.parametrize(("shared", "fix", "match"), [
    ([], None, "name the parameters"),
    (["zz"], None, "has no parameter 'zz'"),
    (["b"], {"b": 1e-6}, "both fixed and shared"),
    (["a", "b"], None, "every free parameter is shared"),
])
def test_shared_fit_refuses_bad_requests(shared, fix, match):
    df, _ = _temperatures()
    with pytest.raises(InputError, match=match):
        fit_shared("thirion", df, "T", shared, fix=fix)


def test_streamed_output_equals_the_in_memory_table(tmp_path):
    df, _ = _temperatures()
    folder = tmp_path / "many"
    folder.mkdir()
    for T, part in df.groupby("T [degC]"):
        part.to_csv(folder / f"T{int(T):03d}.csv", index=False)
    (folder / "broken.csv").write_text("mu,p [MPa]\n0.5,0.1\n")  # one row: thirion fails
    held = fit_many(["thirion", "coulomb"], folder)
    streamed = fit_many(["thirion", "coulomb"], folder, output=tmp_path / "out.csv")
    assert streamed.records == [] and len(streamed) == len(held) == 12
    assert len(streamed.errors) == 1 and "broken" in streamed.errors[0]["dataset"]
    pd.testing.assert_frame_equal(held.to_frame(), streamed.to_frame(), check_dtype=False)
    lines = fit_many("thirion", folder, output=tmp_path / "out.jsonl")
    assert len((tmp_path / "out.jsonl").read_text().splitlines()) == len(lines) == 6


def test_streamed_output_is_checked_before_work(tmp_path):
    src = _two_surfaces(tmp_path)
    with pytest.raises(InputError, match="also an input"):
        fit_many("thirion", src, output=src)
    with pytest.raises(InputError, match=".csv or .jsonl"):
        fit_many("thirion", src, output=tmp_path / "x.txt")
    with pytest.raises(InputError, match="does not exist"):
        fit_many("thirion", src, output=tmp_path / "nope" / "x.csv")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["two.csv"]


def test_compare_many_and_the_cli_compare_by_group(tmp_path, capsys):
    from frictionlaws.cli import main
    from frictionlaws.fitting.campaign import compare_many

    path = _two_surfaces(tmp_path)
    frame = compare_many(path, ["thirion", "coulomb"], by="surface", folds=3)
    assert list(frame["surface"]) == ["steel", "steel", "ice", "ice"]
    assert list(frame["law"][:2]) == ["thirion", "coulomb"]
    assert main(["compare", str(path)]) == 2
    assert "--by surface" in capsys.readouterr().err
    out = tmp_path / "ranking.csv"
    assert main(["compare", str(path), "--by", "surface", "--laws", "thirion,coulomb",
                 "--folds", "3", "--out", str(out)]) == 0
    assert pd.read_csv(out).shape[0] == 4


def test_cli_fit_campaign_and_shared(tmp_path, capsys):
    from frictionlaws.cli import main

    df, _ = _temperatures()
    data = tmp_path / "t.csv"
    df.to_csv(data, index=False)
    assert main(["fit", "--law", "thirion", str(data), "--by", "T", "--shared", "b",
                 "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["shared"] == ["b"] and len(doc["groups"]) == 5
    out = tmp_path / "fits.csv"
    assert main(["fit", "--law", "thirion", str(data), "--by", "T", "--jobs", "2",
                 "--out", str(out)]) == 0
    assert pd.read_csv(out)["T [K]"].nunique() == 5
    assert main(["fit", "--law", "thirion", str(data), "--shared", "b"]) == 2
    assert main(["fit", "--law", "thirion", str(data), "--by", "T", "--save",
                 str(tmp_path / "x.json")]) == 2


def test_campaign_of_only_bad_input_exits_2(capsys):
    """A grouping column no dataset has is bad input (exit 2), not failed fits (exit 1)."""
    from frictionlaws.cli import main

    assert main(["fit", "--law", "thirion", "thesis-steel", "--by", "nosuchcol"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "no column nosuchcol" in err[0]
    assert main(["fit", "--law", "thirion", "-", "-"]) == 2
    assert "more than once" in capsys.readouterr().err


def test_campaign_datasets_of_one_name_are_told_apart(tmp_path):
    from frictionlaws.fitting.campaign import compare_many, dataset_labels

    frame = pd.DataFrame({"mu": [0.8, 0.7, 0.6, 0.55], "p [MPa]": [0.1, 0.2, 0.4, 0.6]})
    camp = fit_many("thirion", [frame, frame.copy()])
    assert list(dict.fromkeys(camp.to_frame()["dataset"])) == ["dataframe #1", "dataframe #2"]
    for folder in ("a", "b"):
        (tmp_path / folder).mkdir()
        frame.to_csv(tmp_path / folder / "data.csv", index=False)
    a, b = tmp_path / "a" / "data.csv", tmp_path / "b" / "data.csv"
    assert dataset_labels([a, b, "thesis-steel"]) == [str(a), str(b), None]
    ranked = compare_many([a, b], ["thirion", "coulomb"])
    assert set(ranked["dataset"]) == {str(a), str(b)}
    with pytest.raises(InputError, match="given twice"):
        fit_many("thirion", [a, tmp_path / "a" / ".." / "a" / "data.csv"])
