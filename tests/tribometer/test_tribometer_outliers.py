"""The pooled outlier rule: Monte-Carlo power and false alarms, campaign use, CLI report."""

from __future__ import annotations

import math
import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from frictionlaws.base.errors import InputError
from frictionlaws.cli import main
from frictionlaws.tribometer import load_rig, process_records, write_record
from frictionlaws.tribometer.outliers import (
    MIN_POOL,
    inner_count,
    outlier_power,
    pooled_outliers,
    pooled_thresholds,
)
from frictionlaws.tribometer.process import RecordResult, summarise
from frictionlaws.tribometer.synthetic import (
    ConditionSpec,
    RecordSpec,
    campaign_records,
    generate_record,
    make_campaign,
    synthetic_rig,
)

DOC = Path(__file__).resolve().parents[2] / "docs" / "user-guide" / "tribometer.rst"
SHORT = {"duration": 15.0, "t_second": 1.0}
COLUMNS = ["pooled +20%", "pooled +30%", "pooled +50%", "pooled false alarms",
           "grubbs +20%", "grubbs +30%", "grubbs +50%", "grubbs false alarms"]


def _doc_table(title: str = "Outlier power table\n") -> dict[int, list[float]]:
    text = DOC.read_text(encoding="utf-8")
    block = text[text.index(f".. list-table:: {title}"):]
    block = block[:block.index("\n\n", block.index("   * - 3"))]
    rows: dict[int, list[float]] = {}
    for chunk in block.split("   * - ")[2:]:
        cells = [c.strip() for c in re.split(r"\n\s+- ", chunk.strip())]
        rows[int(cells[0])] = [float(c) for c in cells[1:]]
    return rows


def test_power_table_in_docs_is_the_seeded_monte_carlo():
    table = _doc_table()
    assert sorted(table) == [3, 4, 5, 6, 7]
    for n, documented in table.items():
        measured = outlier_power(n, trials=4000, seed=14)
        got = [measured[c] for c in COLUMNS]
        assert got == pytest.approx(documented, abs=0.0015), n
        # the requirements: false alarms <= 1 % per condition at every n
        assert measured["pooled false alarms"] <= 0.01
    assert table[4][COLUMNS.index("pooled +30%")] >= 0.9
    # and the pooled rule is far better than Grubbs at few repeats
    assert table[4][COLUMNS.index("grubbs +30%")] < 0.5
    assert table[3][COLUMNS.index("pooled +30%")] > 0.9


def test_power_table_with_an_outlier_in_every_condition():
    table = _doc_table("Outlier power table, an outlier in every condition\n")
    cols = [c for c in COLUMNS if "false" not in c]
    assert sorted(table) == [3, 4, 5, 6, 7]
    for n, documented in table.items():
        measured = outlier_power(n, trials=1000, seed=14, every_condition=True)
        assert [measured[c] for c in cols] == pytest.approx(documented, abs=0.0015), n
    assert table[4][cols.index("pooled +30%")] >= 0.9  # a bad pin throughout is caught
    assert table[3][cols.index("pooled +30%")] < 0.9  # the documented weakness is real


def test_false_alarms_hold_for_other_layouts_and_seeds():
    # an independent seed and layouts the docs do not show: 3, 5 and 12 conditions
    for n, k in ((3, 3), (4, 5), (6, 12)):
        r = outlier_power(n, (0.3,), conditions=k, trials=3000, seed=99)
        se = math.sqrt(0.01 * 0.99 / (3000 * k))
        assert r["pooled false alarms"] <= 0.01 + 2 * se, (n, k, r)


def test_power_needs_a_pool_and_grows_with_the_campaign():
    small = outlier_power(4, (0.3,), conditions=2, trials=2000, seed=5)["pooled +30%"]
    large = outlier_power(4, (0.3,), conditions=8, trials=2000, seed=5)["pooled +30%"]
    assert small < 0.7 < 0.9 < large


def test_pooled_rule_flags_the_outlier_and_is_scale_free():
    rng = np.random.default_rng(3)
    levels = [0.4, 0.8, 1.2, 1.6, 2.0]
    conds = [lv * (1 + 0.02 * rng.standard_normal(4)) for lv in levels]
    conds[2][1] *= 1.3
    res = pooled_outliers(conds)
    assert res.pooled and res.pool == 5 * inner_count(4)
    assert res.flagged == [[], [], [1], [], []]
    assert 0.005 < res.sigma < 0.04  # the 2 % scatter, not inflated by the outlier
    assert res.z[2][1] > res.threshold[2] > 3
    scaled = pooled_outliers([10 * c for c in conds])
    assert scaled.flagged == res.flagged and scaled.sigma == pytest.approx(res.sigma)
    # a pair is not tested and does not enter the pool
    with_pair = pooled_outliers([*conds, np.array([1.0, 1.5])])
    assert with_pair.flagged[-1] == [] and math.isnan(with_pair.threshold[-1])
    assert with_pair.pool == res.pool


def test_pooled_rule_keeps_the_majority_and_refuses_bad_input():
    conds = [np.array([1.0, 1.001, 0.999, 1.0005]) * lv for lv in (0.5, 1.0, 1.5, 2.0)]
    conds.append(np.array([1.0, 1.0, 2.0, 2.0]))  # two pairs: at most one may go
    res = pooled_outliers(conds)
    assert len(res.flagged[-1]) == 1
    flat = pooled_outliers([np.array([1.0, 1.0, 1.0, 1.3])] * 3)
    assert not flat.pooled and flat.flagged == [[], [], []]  # no scatter: nothing to pool
    few = pooled_outliers([np.array([1.0, 1.01, 1.5])])
    assert not few.pooled and few.pool < MIN_POOL and few.flagged == [[]]
    with pytest.raises(InputError, match="positive"):
        pooled_outliers([np.array([1.0, -1.0, 1.0])] * 3)
    with pytest.raises(InputError, match="alpha"):
        pooled_outliers([np.ones(4)] * 3, alpha=0.7)
    with pytest.raises(InputError, match="n >= 3"):
        outlier_power(2)


def test_thresholds_depend_on_the_layout():
    big = pooled_thresholds(((4, 20),), 0.01)[4]
    small = pooled_thresholds(((4, 3),), 0.01)[4]
    assert small > big > 3  # a small pool is noisier: a higher threshold
    assert pooled_thresholds(((4, 20),), 0.05)[4] < big


def _result(name: str, mu: float, i: int) -> RecordResult:
    return RecordResult(file=f"{name}_{i}.csv", row=i + 2, surface="steel", mode="steady",
                        load=20.0, load_text="2 kg", condition=name, status="used", mu=mu,
                        p=1e5, v=1.0, s=1.0, disc_speed=30.0, pin_speed=0.0,
                        explicit_condition=True)


def test_summarise_uses_the_pooled_rule_and_says_so():
    rng = np.random.default_rng(7)
    results = []
    for k, lv in enumerate((0.5, 0.9, 1.3, 1.7)):
        mus = lv * (1 + 0.02 * rng.standard_normal(4))
        if k == 1:
            mus[3] *= 1.3
        results += [_result(f"c{k}", m, i) for i, m in enumerate(mus)]
    rig = synthetic_rig()
    conds, rule = summarise(results, rig)
    assert rule.startswith("pooled") and "t_4 = " in rule and "0.01" in rule
    assert [len(c.outliers) for c in conds] == [0, 1, 0, 0]
    (bad,) = [r for r in results if r.status == "outlier"]
    assert bad.file == "c1_3.csv" and "pooled scatter" in bad.reason and "+3" in bad.reason
    assert all(math.isfinite(r.outlier_z) for r in results)
    _, grubbs_rule = summarise(results, replace(rig, outliers=replace(rig.outliers,
                                                                      rule="grubbs")))
    assert grubbs_rule.startswith("grubbs")
    # a single condition cannot pool a scatter: Grubbs, said so
    alone = [_result("only", m, i) for i, m in enumerate([1.0, 1.01, 0.99, 1.0, 1.4])]
    conds, rule = summarise(alone, rig)
    assert "fallback" in rule and conds[0].n == 4 and "Grubbs" in conds[0].outliers[0][1]


def test_rig_default_and_rule_names(tmp_path):
    assert synthetic_rig().outliers.rule == "pooled"
    f = tmp_path / "rig.toml"
    f.write_text('track_radius = "40 mm"\npin_diameter = "20 mm"\n[outliers]\nrule = "x"\n')
    with pytest.raises(InputError, match="pooled, grubbs, none"):
        load_rig(f)
    f.write_text(synthetic_rig().to_toml())
    assert load_rig(f).outliers.rule == "pooled"


def test_campaign_with_one_bad_record_cli_prints_and_records_the_rule(tmp_path, capsys):
    rig = synthetic_rig()
    conds = [ConditionSpec(f"steel {m} kg", "steel", m, mu, 4, 331.0, 0.0, repeat_sd=0.01)
             for m, mu in ((1.0, 1.9), (2.0, 1.6), (3.0, 1.4), (4.0, 1.2))]
    truth = make_campaign(tmp_path / "camp", conds, rig=rig, seed=11, record_kwargs=SHORT)
    bad = generate_record(RecordSpec(mu=1.4 * 1.3, load=3 * 9.8, duration=15.0, t_start=2.0,
                                     t_stop=13.0), rig, 5, source="odd.csv")
    write_record(truth.directory / "records" / "odd.csv", bad)
    with truth.manifest.open("a") as fh:
        fh.write("records/odd.csv,3,steel,steel 3.0 kg,steady\n")
    manifest = pd.read_csv(truth.manifest)
    assert (manifest["condition"] == "steel 3.0 kg").sum() == 5
    out = tmp_path / "dataset.csv"
    code = main(["process", str(truth.manifest), "--rig", str(truth.rig_file), "-o", str(out),
                 "--jobs", "1"])
    printed = capsys.readouterr().out
    assert code == 0
    assert "17 records: 16 used, 1 dropped as outliers" in printed
    assert "outlier rule: pooled" in printed and "records/odd.csv" in printed
    assert "# outlier rule: pooled" in out.read_text()
    records = pd.read_csv(tmp_path / "dataset_records.csv", comment="#")
    assert records.loc[records["status"] == "outlier", "file"].tolist() == ["records/odd.csv"]
    assert records["outlier_z"].notna().all()
    # the same records in memory, by the API: the same decision
    recs, rows, _ = campaign_records(conds, rig, seed=11, record_kwargs=SHORT)
    camp = process_records([*recs, bad], [*rows, {**rows[8], "file": "odd.csv"}], rig)
    assert [r.file for r in camp.outliers] == ["odd.csv"]
    assert camp.outlier_rule.startswith("pooled")
