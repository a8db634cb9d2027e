"""Hostile inputs and outputs: rules found by a hostile corpus kept outside the project.

Each test states the general rule, then checks it on the kinds of input that broke it:

* every file a manifest lists is an input: ``process -o`` may not overwrite a raw record;
* an output directory (``--plots``, ``--report``) is created with its parents only when
  the run succeeds: a failed run leaves nothing, not even the directory;
* options are checked as the library checks the same values (``compare --seed -1`` was an
  internal error, ``--mu-max inf`` and a law named twice were accepted);
* a campaign in which no dataset can be read is bad input (exit 2);
* the number in a quantity goes through the one number parser (``4_0 mm``, ``4,0 mm``);
* a value that does not apply is still checked (``--area 'nan mm^2'`` with a pressure column);
* arrays given to ``fit`` hold real numbers in one dimension; initial values obey bounds;
* a JSON parameter file nested too deeply is bad input, not an internal error.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hostile import Snapshot, check_outcome, hostile, run_cli
from hypothesis import given
from hypothesis import strategies as st

import frictionlaws as fl
from frictionlaws.base.errors import InputError
from frictionlaws.base.numbers import parse_number
from frictionlaws.base.units import parse_quantity

#: The fast cases belong to the hostile harness (CI budget 60 s); the ones that process a
#: campaign run with the ordinary suite.
HOSTILE = pytest.mark.hostile

GOOD = "mu,p [MPa],v [m/s]\n1.2,0.05,1\n1.1,0.1,1\n1.0,0.15,2\n0.95,0.2,2\n0.9,0.25,3\n"


@HOSTILE
@pytest.mark.parametrize("target", ["records/c_01.csv", "records/c_02.csv"])
def test_process_refuses_to_overwrite_a_record_the_manifest_lists(small_campaign: Path,
                                                                   target: str) -> None:
    """The corpus: '-o records/x.csv' replaced a raw record with the dataset (exit 0)."""
    out = small_campaign / target
    snap = Snapshot.take([small_campaign], list((small_campaign / "records").glob("*.csv")))
    res = run_cli(["process", str(small_campaign / "manifest.csv"), "--rig",
                   str(small_campaign / "rig.toml"), "-o", str(out), "--jobs", "1"])
    check_outcome(res, snapshot=snap, codes=[2])
    assert "also an input" in res.err and Path(target).name in res.err


def test_a_failed_process_leaves_no_plots_and_no_directory(small_campaign: Path) -> None:
    """The corpus: a run ending in 'nothing written at all' had written plots/sub/*.png."""
    plots = small_campaign / "new" / "plots"
    snap = Snapshot.take([small_campaign])
    res = run_cli(["process", str(small_campaign / "manifest.csv"), "--rig",
                   str(small_campaign / "rig.toml"), "-o", str(small_campaign / "ds.csv"),
                   "--plots", str(plots), "--min-repeats", "5", "--jobs", "1"],
                  timeout=60)
    check_outcome(res, snapshot=snap, codes=[2])
    assert not (small_campaign / "new").exists()


@HOSTILE
def test_atomic_dir_creates_missing_parents_only_on_success(tmp_path: Path) -> None:
    from frictionlaws.base.outputs import atomic_dir

    target = tmp_path / "a" / "b" / "c"
    with pytest.raises(RuntimeError), atomic_dir(target) as tmp:
        (tmp / "x.txt").write_text("x")
        raise RuntimeError("the work failed")
    assert sorted(p.name for p in tmp_path.iterdir()) == []
    with atomic_dir(target) as tmp:
        (tmp / "x.txt").write_text("x")
    assert (target / "x.txt").read_text() == "x"
    assert not [p for p in tmp_path.rglob("*") if ".part" in p.name]


@HOSTILE
@pytest.mark.parametrize("opts,words", [
    (["--seed", "-1"], "--seed"),
    (["--seed", "4294967296"], "--seed"),
    (["--mu-max", "inf"], "--mu-max"),
    (["--mu-max", "1e999"], "--mu-max"),
    (["--mu-max", "0"], "--mu-max"),
    (["--laws", "thirion,thirion"], "given twice"),
    (["--laws", "pacejka,magic-formula"], "given twice"),  # an alias is its law
])
def test_compare_options_are_checked_before_any_fit(tmp_path: Path, opts: list[str],
                                                    words: str) -> None:
    data = tmp_path / "d.csv"
    data.write_text(GOOD)
    argv = ["compare", str(data)] + (opts if "--laws" in opts else ["--laws", "coulomb"] + opts)
    res = run_cli(argv)
    check_outcome(res, codes=[2])
    assert words in res.err


@HOSTILE
@pytest.mark.parametrize("kwargs", [{"seed": -1}, {"seed": 2.5}, {"starts": -2},
                                    {"mu_limits": (0.0, math.inf)},
                                    {"mu_limits": (math.nan, 5.0)}])
def test_compare_api_refuses_the_same_values(tmp_path: Path, kwargs: dict) -> None:
    data = tmp_path / "d.csv"
    data.write_text(GOOD)
    with pytest.raises(InputError):
        fl.compare(["coulomb"], data, **kwargs)


@HOSTILE
def test_a_campaign_with_no_readable_dataset_is_bad_input(tmp_path: Path) -> None:
    """compare over files that all fail to load exited 1 (a failed comparison)."""
    (tmp_path / "a.csv").write_bytes(b"")
    (tmp_path / "b.csv").write_text("mu\n")
    for argv in (["compare", str(tmp_path / "a.csv"), str(tmp_path / "b.csv")],
                 ["compare", str(tmp_path)]):
        res = run_cli(argv)
        check_outcome(res, codes=[2])
        assert "a.csv" in res.err
    (tmp_path / "good.csv").write_text(GOOD)  # one readable: the rest is reported, exit 1
    res = run_cli(["compare", str(tmp_path), "--laws", "coulomb", "--json"])
    check_outcome(res, codes=[1], json_out=True)


NUMBER_TEXT = st.one_of(
    st.sampled_from(["4_0", "4,0", "1.000,5", "\uff14\uff10", "1e999", "-1e400", "0x10",
                     "1..2", "1e", "+-3", "40", "-0.5", ".5", "1e-3", "2E5"]),
    st.from_regex(r"[-+]?[0-9_.,]{1,6}([eE][-+]?[0-9_]{1,3})?", fullmatch=True))


@HOSTILE
@hostile(60)
@given(number=NUMBER_TEXT, unit=st.sampled_from([" mm", "mm", " km", " m"]))
def test_a_quantity_reads_its_number_with_the_one_number_parser(number: str,
                                                                 unit: str) -> None:
    """pint read '4_0 mm' as 40 mm and '4,0 mm' as 40 mm: now both are refused."""
    try:
        expected = parse_number(number)
    except ValueError:
        with pytest.raises(InputError):
            parse_quantity(number + unit, "length")
        return
    factor = {"mm": 1e-3, "km": 1e3, "m": 1.0}[unit.strip()]
    got = parse_quantity(number + unit, "length")
    assert got == pytest.approx(expected * factor, rel=1e-12)


@HOSTILE
@pytest.mark.parametrize("area", ["nan mm^2", "-314 mm^2", "0 mm^2", "314", "314 mm"])
def test_an_area_is_checked_even_when_the_data_have_a_pressure(tmp_path: Path,
                                                               area: str) -> None:
    data = tmp_path / "d.csv"
    data.write_text(GOOD)
    res = run_cli(["fit", "--law", "coulomb", str(data), "--area", area])
    check_outcome(res, codes=[2])
    assert "--area" in res.err


@HOSTILE
@pytest.mark.parametrize("arrays,words", [
    ({"mu": [True, False, True], "p": [1e5, 2e5, 3e5]}, "booleans"),
    ({"mu": np.array([1.0, 0.9, 0.8]) + 0j, "p": [1e5, 2e5, 3e5]}, "complex"),
    ({"mu": [[1.0, 0.9], [0.8, 0.7]], "p": [[1e5, 2e5], [3e5, 4e5]]}, "one-dimensional"),
])
def test_fit_arrays_hold_real_numbers_in_one_dimension(arrays: dict, words: str) -> None:
    with pytest.raises(InputError, match=words):
        fl.fit("thirion", arrays)


@HOSTILE
@pytest.mark.parametrize("initial", [{"a": -5.0}, {"a": math.nan}, {"a": "x"}, {"b": -1.0}])
def test_initial_values_obey_the_declared_bounds(initial: dict) -> None:
    data = {"mu": [1.2, 1.1, 1.0, 0.95], "p": [5e4, 1e5, 1.5e5, 2e5]}
    with pytest.raises(InputError, match="initial"):
        fl.fit("thirion", data, initial=initial)


@HOSTILE
def test_a_deeply_nested_params_file_is_bad_input(tmp_path: Path) -> None:
    params = tmp_path / "p.json"
    params.write_bytes(b"[" * 100000 + b"]" * 100000)
    res = run_cli(["export", "--params", str(params), "--format", "csv", "--p",
                   "0.01:0.5:5", "--units", "mm-N-s", "-o", str(tmp_path / "o.csv")])
    check_outcome(res, codes=[2])
    assert "nested deeper than the limit" in res.err


@HOSTILE
@pytest.mark.parametrize("jobs", [-7, -2, 2.5, True, "4"])
def test_process_campaign_refuses_a_nonsense_job_count(small_campaign: Path, jobs: object) -> None:
    """jobs=-7 was taken as 'one per CPU' (-1 is that; the CLI and the API refuse the rest)."""
    with pytest.raises(InputError, match="jobs"):
        fl.process_campaign(small_campaign / "manifest.csv", small_campaign / "rig.toml", jobs=jobs)


@HOSTILE
def test_load_rig_names_the_function_for_a_mapping() -> None:
    """load_rig({...}) was a TypeError from os.fspath; it points to rig_from_dict now."""
    with pytest.raises(InputError, match="rig_from_dict"):
        fl.load_rig({"track_radius": "-40 mm"})  # type: ignore[arg-type]
