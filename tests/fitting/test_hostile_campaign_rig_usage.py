"""Hostile usage, campaigns, rigs and Magic Formula fits: rules found by a hostile corpus.

Each test states a general rule and checks it on generated or hand-built inputs (the
corpus itself stays outside the project):

* a command line that cannot run shows the usage of the (sub-)command concerned on
  stdout and one ``error:`` line on stderr, exit 2; a missing command names the
  commands there are, as the parser knows them;
* a campaign is read whole before any fit: every dataset that cannot be read is named
  on its own ``error:`` line, the last one also summing up, exit 2 and nothing fitted;
* a grouping column (``by=``, ``--by``) groups rows: a measured quantity (a law
  variable, ``mu``, ``mu_std``, ``n``), a column that is not there, or one that leaves
  fewer than two rows a group on average is refused;
* a rig quantity outside its plausible range is refused naming ``rig.toml``, the key,
  the value with its unit and the range; a filter cutoff must lie below the Nyquist
  frequency of every record;
* a Magic Formula fit keeps the peak friction within physical bounds while it fits, and
  says so when the data stop before the peak instead of refusing the fit.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import pytest
from hostile import Snapshot, check_outcome, hostile, run_cli, stderr_lines
from hypothesis import given
from hypothesis import strategies as st

import frictionlaws as fl
from frictionlaws.base.errors import InputError
from frictionlaws.fitting.campaign import (
    MIN_ROWS_PER_GROUP,
    NEVER_GROUPING,
    UnreadableDatasets,
    fit_many,
)

HOSTILE = pytest.mark.hostile


# ------------------------------------------------------------------ usage


def _commands() -> list[str]:
    from frictionlaws.cli import build_parser, command_names

    return command_names(build_parser())


@HOSTILE
@pytest.mark.parametrize("argv,words", [
    ([], "no command given; choose one of: "),
    (["--bogus"], "unrecognized arguments: --bogus"),
    (["fit"], "the following arguments are required"),
    (["tyre"], "frictionlaws tyre: no command given; choose one of: cornering"),
    (["-q"], "no command given"),
])
def test_a_command_line_that_cannot_run_shows_usage_and_one_error(argv: list[str],
                                                                  words: str) -> None:
    res = run_cli(argv)
    check_outcome(res, codes=[2])
    assert words in res.err
    assert res.out.startswith("usage: frictionlaws"), res.out
    if not argv or argv == ["-q"]:
        listed = res.err.split("choose one of: ", 1)[1].strip().split(", ")
        assert listed == _commands() and "fit" in listed and "export" in listed


@HOSTILE
def test_with_json_a_usage_error_leaves_stdout_empty() -> None:
    res = run_cli(["fit", "--json"])
    check_outcome(res, codes=[2])
    assert res.out == ""


# ------------------------------------------------------------------ campaigns

GOOD = ("mu,p [MPa],v [m/s],surface\n1.2,0.05,1,steel\n1.1,0.1,1,steel\n1.0,0.15,2,glass\n"
        "0.95,0.2,2,glass\n0.9,0.25,3,glass\n0.85,0.3,3,steel\n")
#: Files no loader can read: empty, a header and nothing, text in a number, no mu column.
UNREADABLE = (b"", b"mu,p [MPa]\n", b"mu,p [MPa]\n0.5,abc\n0.4,0.2\n", b"x,y\n1,2\n3,4\n",
              b"\x00\x01\x02\xff")


@HOSTILE
@hostile(6)
@given(good=st.integers(0, 3), bad=st.lists(st.sampled_from(UNREADABLE), min_size=1,
                                            max_size=3))
def test_a_campaign_with_an_unreadable_dataset_names_each_and_fits_none(good: int,
                                                                       bad: list[bytes]) -> None:
    """Every unreadable file on its own error line, the last one summing up; exit 2,
    nothing written."""
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp) / "campaign"
        folder.mkdir()
        for i in range(good):
            (folder / f"good{i}.csv").write_text(GOOD)
        names = [f"bad{i}.csv" for i in range(len(bad))]
        for name, content in zip(names, bad):
            (folder / name).write_bytes(content)
        snap = Snapshot.take([Path(tmp)], list(folder.iterdir()))
        res = run_cli(["fit", "--law", "thirion", str(folder), "--out",
                       str(Path(tmp) / "fits.csv")])
        assert res.code == 2 and "Traceback" not in res.err, res.describe()
        lines = [ln for ln in stderr_lines(res.err) if not ln.startswith("warning:")]
        assert all(ln.startswith("error: ") for ln in lines), lines
        total = good + len(bad)
        if total == 1:  # one dataset: its own error, one line
            assert len(lines) == 1 and names[0] in lines[0]
        else:
            assert len(lines) == len(bad), lines  # one line per problem
            for name, line in zip(names, lines):
                assert name in line
            assert f"{len(bad)} of {total} datasets" in lines[-1]
            assert "gives no results" in lines[-1]
        assert not snap.check(failed=True)


@HOSTILE
def test_the_api_refuses_the_campaign_listing_every_unreadable_dataset(tmp_path: Path) -> None:
    (tmp_path / "a.csv").write_text(GOOD)
    (tmp_path / "b.csv").write_bytes(b"")
    (tmp_path / "c.csv").write_bytes(b"mu,p [MPa]\n0.5,abc\n")
    with pytest.raises(UnreadableDatasets) as info:
        fit_many("thirion", tmp_path)
    assert [Path(str(p.file)).name for p in info.value.problems] == ["b.csv", "c.csv"]
    assert "2 of 3 datasets" in str(info.value) and "b.csv" in str(info.value)


# ------------------------------------------------------------------ grouping

MEASURED = sorted(set(NEVER_GROUPING) | {"p"})  # p: thirion's variable


@HOSTILE
@hostile(10)
@given(column=st.sampled_from(MEASURED), other=st.sampled_from([[], ["surface"]]))
def test_grouping_by_a_measured_quantity_is_refused(column: str, other: list[str]) -> None:
    by = other + [column]
    with pytest.raises(InputError, match="not a measured quantity") as info:
        fit_many("thirion", "thesis-steel", by=by)
    assert info.value.option == "by"
    with tempfile.TemporaryDirectory() as tmp:
        data = Path(tmp) / "d.csv"
        data.write_text(GOOD)
        res = run_cli(["fit", "--law", "thirion", str(data), "--by", ",".join(by)])
        check_outcome(res, codes=[2])
        assert "--by" in res.err and "grouping column such as surface" in res.err


@HOSTILE
def test_a_condition_the_law_does_not_use_may_group() -> None:
    """T groups an isothermal law's fits (the shared-parameter workflow); v groups thirion."""
    from frictionlaws.fitting.campaign import check_grouping

    assert check_grouping(["T"], ["thirion"]) == ("T",)
    with pytest.raises(InputError, match="law 'thirion' is fitted on it"):
        check_grouping(["surface", "p"], ["coulomb", "thirion"])
    with pytest.raises(InputError, match="given twice"):
        check_grouping(["surface", "surface"])


@HOSTILE
@hostile(12)
@given(rows=st.integers(2, 40), data=st.data())
def test_a_column_that_leaves_under_two_rows_a_group_is_no_grouping(rows: int,
                                                                   data: st.DataObject) -> None:
    """Groups of fewer than MIN_ROWS_PER_GROUP rows on average: refused, naming the column."""
    groups = data.draw(st.integers(1, rows))
    labels = [f"s{i % groups}" for i in range(rows)]
    body = "".join(f"{1.0 - 0.01 * i:.3f},{0.05 + 0.01 * i:.3f},{lab}\n"
                   for i, lab in enumerate(labels))
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "d.csv"
        path.write_text("mu,p [MPa],surface\n" + body)
        ds = fl.load_dataset(path)
        from frictionlaws.fitting.campaign import group_keys

        if groups > 1 and rows < MIN_ROWS_PER_GROUP * groups:
            with pytest.raises(InputError, match="column 'surface' splits"):
                group_keys(ds, ["surface"])
        else:
            assert len(group_keys(ds, ["surface"])) == groups


@HOSTILE
def test_a_missing_grouping_column_is_named_with_the_columns_there_are(tmp_path: Path) -> None:
    data = tmp_path / "d.csv"
    data.write_text(GOOD)
    res = run_cli(["fit", "--law", "thirion", str(data), "--by", "compound"])
    check_outcome(res, codes=[2])
    assert "no column compound" in res.err and "surface" in res.err


# ------------------------------------------------------------------ Magic Formula fit


def _below_the_peak_csv(path: Path) -> Path:
    """Pure-slip forces of a tyre whose lateral data stop before the peak.

    Longitudinal: F_x = F_z 1.1 sin(1.6 arctan(12 kappa)), kappa in -0.2..0.2 (peak
    reached); lateral: F_y = -F_z sin(1.3 arctan(0.2 alpha/deg)), alpha in -10..10 deg,
    whose peak (C arctan(B alpha) = pi/2) lies at about 13 deg, beyond the data.
    """
    import numpy as np

    rows = ["Fz [kN],kappa [-],alpha [deg],gamma [deg],pressure [bar],Fx [N],Fy [N]"]
    for fz in (2.0, 4.0, 6.0):  # kN
        for kappa in np.linspace(-0.2, 0.2, 21):
            fx = 1e3 * fz * 1.1 * np.sin(1.6 * np.arctan(12 * kappa))
            rows.append(f"{fz},{kappa:.4f},0,0,2.2,{fx:.4f},")
        for alpha in np.linspace(-10, 10, 21):
            fy = -1e3 * fz * np.sin(1.3 * np.arctan(0.2 * alpha))
            rows.append(f"{fz},0,{alpha:.3f},0,2.2,,{fy:.4f}")
    path.write_text("\n".join(rows) + "\n")
    return path


@pytest.mark.slow
def test_data_that_stop_before_the_peak_give_a_plausible_tyre_and_a_warning(
        tmp_path: Path) -> None:
    """Was refused: 'the peak friction mu_y = 149.7 ... check the inflation pressure'."""
    import json

    import numpy as np

    from frictionlaws.tyre import MagicFormula
    from frictionlaws.tyre.mf.fit.peak import PEAK_MU

    data = _below_the_peak_csv(tmp_path / "forces.csv")
    out = tmp_path / "fitted.tir"
    res = run_cli(["tyre", "fit-mf", str(data), "--json", "-o", str(out)], timeout=240)
    check_outcome(res, codes=[0], json_out=True)
    doc = json.loads(res.out)
    warned = [w for w in doc["warnings"] if "stop before the peak" in w]
    assert len(warned) == 1 and warned[0].startswith("Fy0") and "PDY1" in warned[0]
    assert any("stop before the peak" in ln for ln in stderr_lines(res.err)
               if ln.startswith("warning:"))
    assert not any(w.startswith("Fx0") for w in doc["warnings"])  # that peak is measured
    model = MagicFormula.from_file(out)
    alpha = np.radians(np.linspace(-10, 10, 41))
    for fz in (2000.0, 4000.0, 6000.0):  # at the measured 2.2 bar (the file's NOMPRES differs)
        mu = float(model.lateral(fz, 0.0, 2.2e5).mu)
        assert PEAK_MU[0] <= mu <= PEAK_MU[1], mu
        measured = -fz * np.sin(1.3 * np.arctan(0.2 * np.degrees(alpha)))
        assert np.abs(model.fy0(alpha, fz, 0.0, 2.2e5) - measured).max() < 0.01 * fz
    assert doc["errors"]["y"]["rmse"] < 1.0  # newtons, on forces up to 6 kN


@HOSTILE
@hostile(20)
@given(mu=st.one_of(st.floats(-1e6, 1e6), st.sampled_from([float("nan"), float("inf")])),
       fz=st.floats(1.0, 1e5))
def test_the_peak_penalty_is_zero_inside_the_physical_range_only(mu: float, fz: float) -> None:
    import numpy as np

    from frictionlaws.tyre.mf.fit.peak import PEAK_MU, peak_penalty

    pen = float(peak_penalty(np.array([mu]), np.array([fz]))[0])
    assert np.isfinite(pen) and pen >= 0
    assert (pen == 0) == (PEAK_MU[0] <= mu <= PEAK_MU[1])


# ------------------------------------------------------------------ rig ranges


def _rig_with(key: str, text: str) -> dict:
    """A valid rig mapping with ``key`` (``"table.key"`` for a table entry) set to ``text``."""
    rig: dict = {"track_radius": "40 mm", "contact_area": "314 mm^2"}
    table, _, name = key.rpartition(".")
    if key == "pin_diameter":
        del rig["contact_area"]
    (rig.setdefault(table, {}) if table else rig)[name] = text
    return rig


def _outside(key: str, factor: float, above: bool) -> float:
    """A value of rig key ``key`` (in its range's display unit) outside its range."""
    from frictionlaws.tribometer.rig import RANGES

    rng = RANGES[key]
    lo, hi = rng.lo / rng.scale, rng.hi / rng.scale
    if above or lo == 0:  # below 0 the sign check refuses first (its own message)
        return hi * factor if hi > 0 else hi / factor
    return lo / factor if lo > 0 else lo * factor


def _ranged_keys() -> list[str]:
    from frictionlaws.tribometer.rig import RANGES

    return sorted(RANGES)


@HOSTILE
@pytest.mark.parametrize("key", _ranged_keys())
@hostile(3)
@given(factor=st.floats(1.01, 1e6), above=st.booleans())
def test_a_rig_value_outside_its_plausible_range_is_refused(key: str, factor: float,
                                                            above: bool) -> None:
    """Every ranged key: names the rig file, the key, the value with its unit and the range."""
    from frictionlaws.tribometer.rig import RANGES, rig_from_dict

    unit = RANGES[key].unit
    text = f"{_outside(key, factor, above):.10g} {unit}"
    with pytest.raises(InputError) as info:
        rig_from_dict(_rig_with(key, text), source="rig.toml")
    message = str(info.value)
    assert info.value.file == "rig.toml"
    assert f"'{key}' = '{text}'" in message and "plausible range" in message, message
    assert f" {unit} (" in message  # the range, in the unit of the key


@HOSTILE
def test_every_ranged_rig_value_accepts_its_range_ends() -> None:
    """The ranges are inclusive and every ranged key is read through them."""
    from frictionlaws.tribometer.rig import RANGES, rig_from_dict

    for key, rng in RANGES.items():
        for end in (rng.lo, rng.hi):
            if end == 0 and key != "filter.auto_max" and not key.startswith("window."):
                continue
            rig_from_dict(_rig_with(key, f"{end / rng.scale!r} {rng.unit}"), source="rig.toml")


@HOSTILE
@pytest.mark.parametrize("old,new,words", [
    ('"40 mm"', '"40 km"', "'track_radius' = '40 km'"),
    ('"9.8 m/s^2"', '"98000 m/s^2"', "9.7..9.9 m/s^2"),
    ('cutoff = "auto"', 'cutoff = "1e9 Hz"', "'filter.cutoff' = '1e9 Hz'"),
])
def test_process_refuses_an_absurd_rig_naming_the_rig(small_campaign: Path, tmp_path: Path,
                                                      old: str, new: str, words: str) -> None:
    """These passed the unit checks and ended as 'no condition has 2 usable records'."""
    text = (small_campaign / "rig.toml").read_text()
    assert text.count(old) == 1
    rig = tmp_path / "rig.toml"
    rig.write_text(text.replace(old, new))
    snap = Snapshot.take([tmp_path])
    res = run_cli(["process", str(small_campaign / "manifest.csv"), "--rig", str(rig),
                   "-o", str(tmp_path / "ds.csv"), "--jobs", "1"])
    check_outcome(res, snapshot=snap, codes=[2])
    assert "rig.toml" in res.err and words in res.err and "plausible range" in res.err


@HOSTILE
@hostile(4)
@given(cutoff=st.floats(50.5, 1e6))  # records at 100 Hz
def test_a_cutoff_at_or_above_a_records_nyquist_frequency_refuses_the_rig(
        small_campaign: Path, cutoff: float) -> None:
    """Checked when each record is read: the rig is wrong, not the record (exit 2)."""
    with tempfile.TemporaryDirectory() as tmp:
        text = (small_campaign / "rig.toml").read_text()
        rig = Path(tmp) / "rig.toml"
        rig.write_text(text.replace('cutoff = "auto"', f'cutoff = "{cutoff!r} Hz"'))
        assert f'cutoff = "{cutoff!r} Hz"' in rig.read_text()
        res = run_cli(["process", str(small_campaign / "manifest.csv"), "--rig", str(rig),
                       "-o", str(Path(tmp) / "ds.csv"), "--jobs", "1"])
        check_outcome(res, codes=[2])
        assert "rig.toml" in res.err and "'filter.cutoff'" in res.err
        assert "Nyquist frequency 50 Hz" in res.err and "100 Hz" in res.err
        assert not (Path(tmp) / "ds.csv").exists()


@HOSTILE
@pytest.mark.parametrize("figure", ["fit.xyz", "fit.docx"])
def test_fit_mf_refuses_a_figure_format_before_fitting(tmp_path: Path, figure: str) -> None:
    """Once the fit succeeded, '--plot x.xyz' failed after writing the .tir (exit 3)."""
    data = _below_the_peak_csv(tmp_path / "forces.csv")
    snap = Snapshot.take([tmp_path], [data])
    res = run_cli(["tyre", "fit-mf", str(data), "-o", str(tmp_path / "out.tir"), "--plot",
                   str(tmp_path / figure)])
    check_outcome(res, snapshot=snap, codes=[2])
    assert figure in res.err and ".png" in res.err
