"""``process`` with several manifests, ``--json``, and the campaign runner."""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

import pytest

from frictionlaws.base.errors import InputError
from frictionlaws.base.jsonio import dumps
from frictionlaws.base.jsonio import loads as strict_loads
from frictionlaws.cli import main
from frictionlaws.tribometer.process import manifest_names, process_campaign, process_many
from frictionlaws.tribometer.synthetic import ConditionSpec, make_campaign, synthetic_rig

#: Short records keep the tests fast.
SHORT = {"duration": 15.0, "t_second": 1.0}


@pytest.fixture(scope="module")
def two(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path, Path]:
    """Two synthetic campaigns with one rig: week1/manifest.csv and week2/manifest.csv.

    The second has a row whose record file is missing (an unusable record, mu NaN).
    """
    root = tmp_path_factory.mktemp("many")
    rig = synthetic_rig()
    a = make_campaign(root / "week1", [
        ConditionSpec("steel 2 kg", "steel", 2.0, 1.6, 3, 331.0, -120.0),
        ConditionSpec("steel 3 kg", "steel", 3.0, 1.4, 3, 331.0, -120.0)],
        rig=rig, seed=11, record_kwargs=SHORT)
    b = make_campaign(root / "week2", [
        ConditionSpec("glass 2 kg", "glass", 2.0, 0.9, 3, 331.0, 0.0)],
        rig=rig, seed=12, record_kwargs=SHORT)
    with b.manifest.open("a") as fh:
        fh.write("records/missing.csv,2,glass,glass 2 kg,steady\n")
    return a.manifest, b.manifest, a.rig_file


def _files(directory: Path) -> list[str]:
    return sorted(str(p.relative_to(directory)) for p in directory.rglob("*"))


def test_several_manifests_give_what_each_gives_alone(two, tmp_path, capsys):
    m1, m2, rig = two
    out = tmp_path / "out"
    assert main(["process", str(m1), str(m2), "--rig", str(rig), "-o", str(out),
                 "--jobs", "2"]) == 0
    text = capsys.readouterr().out
    assert f"== {m1}" in text and f"== {m2}" in text
    assert _files(out) == ["week1_manifest.csv", "week1_manifest_records.csv",
                           "week2_manifest.csv", "week2_manifest_records.csv"]
    for manifest, name in ((m1, "week1_manifest"), (m2, "week2_manifest")):
        alone = tmp_path / f"{name}_alone.csv"
        assert main(["process", str(manifest), "--rig", str(rig), "-o", str(alone),
                     "--jobs", "1"]) == 0
        capsys.readouterr()
        assert (out / f"{name}.csv").read_bytes() == alone.read_bytes()
        assert ((out / f"{name}_records.csv").read_bytes()
                == (tmp_path / f"{name}_alone_records.csv").read_bytes())


def test_process_many_equals_process_campaign(two):
    m1, m2, rig = two
    many = process_many([m1, m2], rig, jobs=2, progress=False)
    for manifest, camp in zip((m1, m2), many, strict=True):
        alone = process_campaign(manifest, rig, jobs=1, progress=False)
        assert camp.dataset_text() == alone.dataset_text()
        assert camp.records_text() == alone.records_text()
        assert dumps(camp.to_dict()) == dumps(alone.to_dict())
    assert [c.condition for c in many[1].conditions] == ["glass 2 kg"]
    assert many[1].conditions[0].n == 3 and len(many[1].unusable) == 1


def test_json_output_is_strict_and_carries_units(two, tmp_path, capsys):
    _, m2, rig = two
    out = tmp_path / "glass.csv"
    assert main(["process", str(m2), "--rig", str(rig), "-o", str(out), "--jobs", "1",
                 "--json"]) == 0
    stdout = capsys.readouterr().out

    def refuse(name: str) -> None:
        raise ValueError(f"non-strict JSON constant {name}")

    doc = json.loads(stdout, parse_constant=refuse)  # a strict parser: no NaN/Infinity
    assert strict_loads(stdout) == doc
    assert doc["written"] is True and len(doc["manifests"]) == 1
    camp = doc["manifests"][0]
    assert camp["outputs"] == {"dataset": str(out), "records": str(tmp_path /
                                                                    "glass_records.csv"),
                               "plots": None}
    assert camp["units"]["p"] == "Pa" and camp["units"]["v"] == "m/s"
    assert camp["counts"] == {"records": 4, "used": 3, "outliers": 0, "unusable": 1,
                              "conditions_written": 1}
    bad = [r for r in camp["records"] if r["status"] == "unusable"]
    assert bad[0]["mu"] is None and "not found" in bad[0]["reason"]  # NaN -> null
    cond = camp["conditions"][0]
    assert cond["mu"] == pytest.approx(0.9, rel=0.03)
    lo, hi = cond["mu_ci95"]
    assert lo < cond["mu"] < hi
    rig_ = synthetic_rig()
    assert cond["p"] == pytest.approx(2 * rig_.g / rig_.contact_area, rel=1e-9)


def test_json_output_on_failure_is_json_too_and_nothing_is_written(tmp_path, capsys):
    rig = synthetic_rig()
    truth = make_campaign(tmp_path / "c", [ConditionSpec("s", "steel", 2.0, 1.5, 2, 331.0,
                                                         0.0)], rig=rig, seed=2,
                          record_kwargs=SHORT)
    out = tmp_path / "out"
    code = main(["process", str(truth.manifest), "--rig", str(truth.rig_file), "-o",
                 str(out), "--jobs", "1", "--json", "--min-repeats", "3"])
    captured = capsys.readouterr()
    assert code == 2 and "no condition has 3 or more usable records" in captured.err
    doc = strict_loads(captured.out)
    assert doc["written"] is False and doc["manifests"][0]["outputs"] is None
    assert not out.exists()


def test_one_manifest_without_a_dataset_stops_them_all(two, tmp_path, capsys):
    m1, _, rig = two
    empty = tmp_path / "empty" / "manifest.csv"
    empty.parent.mkdir()
    empty.write_text("file,load [kg],surface\nnone.csv,2,steel\n", encoding="utf-8")
    out = tmp_path / "out"
    code = main(["process", str(m1), str(empty), "--rig", str(rig), "-o", str(out),
                 "--jobs", "1"])
    captured = capsys.readouterr()
    assert code == 2 and f"file '{empty}'" in captured.err
    assert "record file not found" in captured.out  # the summary says why
    assert not out.exists()


@pytest.mark.parametrize("case, match", [
    ("same twice", "given twice"),
    ("through a link", "given twice"),
    ("file for two", "give -o a directory"),
    ("records-out with a directory", "--records-out names one file"),
    ("colliding outputs", "outputs collide"),
    ("output is an input", "also an input"),
    ("names differ in case only", "same name"),
    ("standard output", "not standard output"),
])
def test_refusals_exit_2_before_any_work(two, tmp_path, capsys, case, match):
    m1, m2, rig = two
    out = tmp_path / "out"
    manifests = [str(m1), str(m2)]
    extra: list[str] = []
    if case == "same twice":
        manifests = [str(m1), str(m1)]
    elif case == "through a link":
        link = tmp_path / "link.csv"
        os.symlink(m1, link)
        manifests = [str(m1), str(link)]
    elif case == "file for two":
        out = tmp_path / "one.csv"
    elif case == "records-out with a directory":
        extra = ["--records-out", str(tmp_path / "r.csv")]
    elif case == "colliding outputs":  # a.csv's records table is a_records.csv's dataset
        for name in ("a.csv", "a_records.csv"):
            (tmp_path / name).write_bytes(m1.read_bytes())
        manifests = [str(tmp_path / "a.csv"), str(tmp_path / "a_records.csv")]
    elif case == "standard output":
        out = Path("-")
        manifests = [str(m1)]
    elif case == "output is an input":
        out = m1.parent  # week1/manifest.csv would be overwritten
        manifests = [str(m1)]
    else:
        for name in ("Run.csv", "run.csv"):
            (tmp_path / name).write_bytes(m1.read_bytes())
        manifests = [str(tmp_path / "Run.csv"), str(tmp_path / "run.csv")]
    before = _files(tmp_path)
    code = main(["process", *manifests, "--rig", str(rig), "-o", str(out), "--jobs", "1",
                 *extra])
    captured = capsys.readouterr()
    assert code == 2, captured.err
    lines = [ln for ln in captured.err.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("error: ") and match in lines[0]
    assert captured.out == ""  # refused before any record was processed
    assert _files(tmp_path) == before


def test_manifest_names():
    assert manifest_names(["a/x.csv", "b/y.csv"]) == ["x", "y"]
    assert manifest_names(["w1/manifest.csv", "w2/manifest.csv"]) == ["w1_manifest",
                                                                      "w2_manifest"]
    with pytest.raises(InputError, match="no manifest"):
        manifest_names([])
    with pytest.raises(InputError, match="given twice"):
        manifest_names(["a/x.csv", "a/../a/x.csv"])


@pytest.mark.slow
def test_plots_go_to_one_folder_per_manifest(two, tmp_path):
    pytest.importorskip("matplotlib")
    m1, m2, rig = two
    many = process_many([m1, m2], rig, jobs=1, progress=False, plots=tmp_path / "plots")
    assert sorted(p.name for p in (tmp_path / "plots").iterdir()) == ["week1_manifest",
                                                                     "week2_manifest"]
    assert (tmp_path / "plots" / "week2_manifest" / "conditions.png").is_file()
    assert len(list((tmp_path / "plots" / "week1_manifest").glob("records_*.png"))) == 6
    assert all(math.isfinite(c.mu) for c in many[0].conditions)


def test_bad_jobs_are_refused_by_the_campaign_runner(two):
    m1, _, rig = two
    with pytest.raises(InputError, match="jobs must be"):
        process_campaign(m1, rig, jobs=-3, progress=False)


@pytest.mark.slow
def test_dask_local_cluster_equals_serial(two):
    distributed = pytest.importorskip("dask.distributed")
    m1, m2, rig = two
    serial = process_many([m1, m2], rig, jobs=1, progress=False)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster:
        remote = process_many([m1, m2], rig, scheduler=cluster.scheduler_address,
                              progress=False)
    for a, b in zip(serial, remote, strict=True):
        assert a.dataset_text() == b.dataset_text()
        assert a.records_text() == b.records_text()
