"""The example files of the README and the guide: contents, reproducibility, no overwrite."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

import frictionlaws as fl
from frictionlaws.base.errors import InputError
from frictionlaws.cli import main
from frictionlaws.example_files import EXAMPLE_FILES, write_example_files


@pytest.fixture(scope="module")
def examples(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("examples")
    write_example_files(root)
    return root


def test_every_listed_file_is_written(examples: Path) -> None:
    for name in EXAMPLE_FILES:
        assert (examples / name).exists(), name
    assert len(list((examples / "records").glob("*.csv"))) == 18
    assert sorted(p.name for p in (examples / "data").iterdir()) == [
        "day1_glass.csv", "day1_steel.csv", "day2_glass.csv", "day2_steel.csv"]
    for table in examples.rglob("*.csv"):
        if table.parent.name != "records" and table.name != "manifest.csv":
            assert table.read_text().startswith("# synthetic: "), table


def test_the_tables_recover_the_values_they_state(examples: Path) -> None:
    table = fl.load_dataset(examples / "campaign.csv").to_frame()
    steel = table[table["surface"] == "steel"]
    res = fl.fit("thirion", {"mu": steel["mu"].to_numpy(), "p": steel["p [Pa]"].to_numpy()})
    a, b = res.params["a"], res.params["b"]
    assert abs(a.value - 0.25) < 3 * a.stderr + 0.02
    assert abs(b.value - 3.5e-6) < 3 * b.stderr + 0.2e-6
    own = fl.fit("thirion", examples / "my.csv", mapping={"mu": "FC", "p": "CP", "v": "DV"},
                 units={"p": "MPa", "v": "m/s"})
    assert own.metrics["n"] == 21


def test_the_same_seed_writes_the_same_files(examples: Path, tmp_path: Path) -> None:
    write_example_files(tmp_path / "again")
    for name in ("my.csv", "campaign.csv", "temps.csv", "runs.csv", "tyre_data.csv",
                 "manifest.csv", "data/day2_glass.csv"):
        assert (tmp_path / "again" / name).read_bytes() == (examples / name).read_bytes()
    other = tmp_path / "other"
    write_example_files(other, seed=5)
    assert (other / "campaign.csv").read_bytes() != (examples / "campaign.csv").read_bytes()


@pytest.mark.parametrize("name", ["my.csv", "data", "records", "EXAMPLES.txt"])
def test_an_existing_file_is_never_written_over(tmp_path: Path, name: str) -> None:
    target = tmp_path / name
    if "." in name:
        target.write_text("mine\n")
    else:
        target.mkdir()
    before = sorted(os.listdir(tmp_path))
    with pytest.raises(InputError, match=name.replace(".", r"\.")):
        write_example_files(tmp_path)
    assert sorted(os.listdir(tmp_path)) == before
    if "." in name:
        assert target.read_text() == "mine\n"


def test_the_command_writes_and_then_refuses(tmp_path: Path, capsys) -> None:
    assert main(["examples", str(tmp_path / "ex")]) == 0
    out = capsys.readouterr().out
    assert "my.csv" in out and "records/" in out
    assert main(["examples", str(tmp_path / "ex")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "already exist" in err


@pytest.mark.parametrize("seed", [-1, 2**32, 1.5, "1", True, None])
def test_a_seed_that_is_not_a_whole_number_in_range_is_refused(tmp_path: Path, seed) -> None:
    with pytest.raises(InputError, match="seed must be a whole number"):
        write_example_files(tmp_path, seed=seed)
    assert list(tmp_path.iterdir()) == []
