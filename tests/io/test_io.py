"""The dataset loader (frictionlaws.io), packaged datasets and ``frictionlaws datasets``."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import frictionlaws
from frictionlaws import io
from frictionlaws.base.errors import InputError
from frictionlaws.cli import main

DATA = Path(__file__).resolve().parents[1] / "data"
FORMATS = DATA / "formats"
MALFORMED = DATA / "malformed"
ORIGINAL_MAP = {"mu": "FC", "p": "CP", "v": "DV"}
ORIGINAL_UNITS = {"p": "MPa", "v": "m/s"}


def write(tmp_path: Path, text: str, name: str = "data.csv") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


# --------------------------------------------------------------------------- public API
def test_public_api_names() -> None:
    assert frictionlaws.load_dataset is io.load_dataset
    assert frictionlaws.Dataset is io.Dataset
    assert frictionlaws.list_datasets is io.list_datasets


# --------------------------------------------------------------------------- packaged data
def test_thesis_steel_packaged() -> None:
    ds = io.load_dataset("thesis-steel")
    assert len(ds) == 19
    assert ds.name == "thesis-steel"
    assert ds.source == "packaged:thesis-steel"
    assert list(ds.frame.columns) == ["mu", "p", "v", "F_N", "surface"]
    assert ds.variables == {"p", "v", "F_N"}
    assert ds.varying == {"p", "v", "F_N"}
    assert ds.units == {"mu": "", "p": "MPa", "v": "m/s", "F_N": "N"}
    f = ds.frame
    # first and last published rows (thesis Figure 5-16a)
    assert f["mu"].iloc[0] == 3.005 and f["p"].iloc[0] == pytest.approx(31190.0)
    assert f["mu"].iloc[-1] == 3.716 and f["v"].iloc[-1] == 2.77
    assert sorted(set(f["v"])) == [0.0, 1.38, 2.77]
    assert set(f["surface"]) == {"steel"}
    # p as published is F_N / 314.16 mm^2 to 4 significant figures
    np.testing.assert_allclose(f["p"], f["F_N"] / 314.16e-6, rtol=5e-4)
    assert ds.provenance and "Figure 5-16a" in ds.provenance
    assert ds.weights() is None
    assert ds.notes == []
    assert ds.rows is not None and ds.row_of(0) == ds.rows[0] > 1


def test_thesis_original_loads_through_map_and_units() -> None:
    ds = io.load_dataset("thesis-steel-original", mapping=ORIGINAL_MAP, units=ORIGINAL_UNITS)
    ref = io.load_dataset("thesis-steel")
    assert len(ds) == 19
    for col in ("mu", "p", "v"):
        np.testing.assert_array_equal(ds.frame[col], ref.frame[col])
    # NL [kg] x 9.8 is the F_N of thesis-steel
    raw = pd.read_csv(io.datasets_dir() / "thesis-steel-original.csv", comment="#")
    np.testing.assert_allclose(raw["NL"] * 9.8, ref.frame["F_N"], rtol=1e-12)
    assert raw["PV"].isna().all()
    assert any("NL, PV" in n and "ignored" in n for n in ds.notes)
    # the string forms of the CLI are accepted too
    ds2 = io.load_dataset("thesis-steel-original", mapping="mu=FC,p=CP,v=DV",
                          units="p=MPa,v=m/s")
    np.testing.assert_array_equal(ds2.frame["p"], ds.frame["p"])


def test_thesis_original_with_load_in_kg_and_area() -> None:
    ds = io.load_dataset("thesis-steel-original", mapping={"mu": "FC", "F_N": "NL"},
                         units={"F_N": "kg"}, area="314.16 mm^2")
    ref = io.load_dataset("thesis-steel")
    np.testing.assert_allclose(ds.frame["F_N"], ref.frame["F_N"], rtol=1e-12)
    np.testing.assert_allclose(ds.frame["p"], ref.frame["p"], rtol=5e-4)
    assert any("g = 9.8" in n for n in ds.notes)
    assert any("p derived" in n for n in ds.notes)


def test_thesis_original_without_map_fails_clearly() -> None:
    with pytest.raises(InputError) as exc:
        io.load_dataset("thesis-steel-original")
    # the library names its own argument; the CLI renders the same setting as a flag
    assert "mapping='mu=COLUMN'" in str(exc.value)
    assert "FC, NL, CP, PV, DV" in str(exc.value)
    from frictionlaws.base.errors import Argument

    assert Argument("mapping", "mu=COLUMN") in exc.value.parts
    assert "or --map mu=COLUMN (columns" in exc.value.compose(label={"mapping": "--map"}.get)


def test_list_datasets() -> None:
    items = {d["name"]: d for d in io.list_datasets()}
    assert {"thesis-steel", "thesis-steel-original"} <= set(items)
    for d in items.values():
        assert d["rows"] > 0
        assert d["title"]
        assert "thesis" in d["provenance"].lower() or len(d["provenance"]) > 40
    assert items["thesis-steel"]["rows"] == 19


def test_every_packaged_dataset_loads_and_is_documented() -> None:
    readme = (Path(__file__).resolve().parents[2] / "datasets" / "README.md").read_text(
        "utf-8")
    needs = {"thesis-steel-original": {"mapping": ORIGINAL_MAP, "units": ORIGINAL_UNITS}}
    for d in io.list_datasets():
        ds = io.load_dataset(d["name"], **needs.get(d["name"], {}))
        assert len(ds) == d["rows"]
        assert ds.provenance
        assert f"### `{d['name']}`" in readme


def test_packaged_prefix_and_unknown_name() -> None:
    assert len(io.load_dataset("packaged:thesis-steel")) == 19
    with pytest.raises(InputError, match="no packaged dataset 'nope'"):
        io.load_dataset("packaged:nope")
    with pytest.raises(InputError) as exc:
        io.load_dataset("thesis-stel")
    assert "file not found" in str(exc.value) and "thesis-steel" in str(exc.value)
    assert exc.value.file == "thesis-stel"


def test_a_file_wins_over_a_packaged_name(tmp_path: Path, monkeypatch: pytest.MonkeyPatch
                                          ) -> None:
    monkeypatch.chdir(tmp_path)
    write(tmp_path, "mu\n0.5\n", "thesis-steel")
    ds = io.load_dataset("thesis-steel")
    assert len(ds) == 1 and ds.source == "thesis-steel"


# --------------------------------------------------------------------------- formats
def test_semicolon_decimal_comma_aliases_and_units() -> None:
    ds = io.load_dataset(FORMATS / "semicolon_decimal_comma.csv")
    f = ds.frame
    assert list(f.columns) == ["mu", "p", "v", "T"]
    np.testing.assert_allclose(f["mu"], [1.2, 1.1, 1.05])
    np.testing.assert_allclose(f["p"], [1e5, 2e5, 3e5])
    np.testing.assert_allclose(f["v"], [1.0, 2.0, 3.0])
    np.testing.assert_allclose(f["T"], [293.15, 298.65, 303.15])
    assert ds.units == {"mu": "", "p": "kPa", "v": "km/h", "T": "°C"}
    assert ds.provenance == "exported by a European spreadsheet"
    # rows are file line numbers: comment line 1, header line 2, blank line 5
    assert list(ds.rows) == [3, 4, 6]


def test_bom_tab_and_kgf() -> None:
    ds = io.load_dataset(FORMATS / "bom_tab.csv")
    f = ds.frame
    assert list(f.columns) == ["mu", "p", "v", "F_N"]
    np.testing.assert_allclose(f["p"], [1e5, 2e5])
    np.testing.assert_allclose(f["v"], [0.1, 0.2])
    np.testing.assert_allclose(f["F_N"], [9.80665, 2 * 9.80665])
    assert not any("9.8 m/s" in n for n in ds.notes)  # kgf is standard gravity, no note


def test_comments_blank_lines_quotes_and_replicates() -> None:
    ds = io.load_dataset(FORMATS / "comments_blank.csv")
    assert len(ds) == 3
    assert ds.provenance == "rig: pin on disc\noperator: test\nfirst condition"
    assert list(ds.frame["surface"]) == ["steel", "steel", "sandpaper, 120"]
    assert list(ds.rows) == [6, 8, 9]
    w = ds.weights()
    np.testing.assert_allclose(w, np.sqrt([4, 5, 3]) / np.array([0.05, 0.04, 0.06]))


def test_nan_rows_are_dropped_and_reported() -> None:
    ds = io.load_dataset(FORMATS / "nan_rows.csv")
    assert len(ds) == 3
    np.testing.assert_allclose(ds.frame["mu"], [1.2, 1.0, 0.8])
    assert "dropped 2 rows (rows 3, 6): empty or NaN in column 'mu'" in ds.notes
    assert "dropped 1 row (row 5): empty or NaN in column 'p [MPa]'" in ds.notes
    assert list(ds.rows) == [2, 4, 7]


def test_load_given_as_mass_uses_g_9_8_and_says_so() -> None:
    ds = io.load_dataset(FORMATS / "thesis_kg.csv")
    np.testing.assert_allclose(ds.frame["F_N"], [9.8, 19.6, 29.4])
    assert ds.units["F_N"] == "kg"
    assert any("g = 9.8 m/s^2" in n and "load [kg]" in n for n in ds.notes)


def test_utf16_and_cp1252_files() -> None:
    ds = io.load_dataset(FORMATS / "utf16.csv")
    np.testing.assert_allclose(ds.frame["p"], [1e5, 2e5])
    ds = io.load_dataset(FORMATS / "cp1252.csv")
    np.testing.assert_allclose(ds.frame["T"], [293.15, 298.15])
    np.testing.assert_allclose(ds.frame["mu"], [1.2, 1.1])
    assert any("cp1252" in n for n in ds.notes)


@pytest.mark.parametrize("delimiter", [",", ";", "\t"])
@pytest.mark.parametrize("line_end", ["\n", "\r\n"])
def test_delimiters_and_line_endings(tmp_path: Path, delimiter: str, line_end: str) -> None:
    dec = "," if delimiter != "," else "."
    rows = [["mu", "p [MPa]", "v [m/s]"], [f"1{dec}5", f"0{dec}1", "2"], ["1", "0.2", "3"]]
    text = line_end.join(delimiter.join(r) for r in rows) + line_end
    path = tmp_path / "d.csv"
    path.write_bytes(text.encode("utf-8"))
    ds = io.load_dataset(path)
    np.testing.assert_allclose(ds.frame["mu"], [1.5, 1.0])
    np.testing.assert_allclose(ds.frame["p"], [1e5, 2e5])


def test_quoted_cells_and_spaces_after_delimiter(tmp_path: Path) -> None:
    p = write(tmp_path, '"mu", "p [MPa]"\n"1.2", 0.1\n 1.1 , "0.2"\n')
    ds = io.load_dataset(p)
    np.testing.assert_allclose(ds.frame["p"], [1e5, 2e5])


def test_trailing_delimiters_and_short_rows(tmp_path: Path) -> None:
    p = write(tmp_path, "mu,p [MPa],T [degC],\n1.2,0.1,20,\n1.1,0.2\n1.0,0.3,25,,\n")
    ds = io.load_dataset(p)
    assert len(ds) == 2  # the short row has no T: dropped and reported
    assert any("row 3" in n and "T [degC]" in n for n in ds.notes)


@pytest.mark.parametrize(
    ("canon", "unit", "value", "si"),
    [("mu", None, "0.5", 0.5), ("p", "MPa", "0.1", 1e5), ("v", "m/s", "2", 2.0),
     ("T", "degC", "20", 293.15), ("F_N", "N", "10", 10.0), ("s", None, "0.1", 0.1),
     ("mu_std", None, "0.05", 0.05), ("n", None, "4", 4.0), ("surface", None, "glass", "glass")],
)
def test_every_alias(tmp_path: Path, canon: str, unit: str | None, value: str,
                     si: float | str) -> None:
    for alias in io.ALIASES[canon]:
        for spelling in {alias, alias.upper(), alias.title(), alias.replace(" ", "_")}:
            header = f"{spelling} [{unit}]" if unit else spelling
            cols = [header] if canon == "mu" else ["mu", header]
            vals = [value] if canon == "mu" else ["0.5", value]
            p = write(tmp_path, ";".join(cols) + "\n" + ";".join(vals) + "\n")
            ds = io.load_dataset(p)
            got = ds.frame[canon].iloc[0]
            assert got == (pytest.approx(si) if canon != "surface" else si), spelling


def test_single_letter_names_are_not_confused(tmp_path: Path) -> None:
    # 't' is a time and 'N' an rpm here, not T or n: ignored and reported
    p = write(tmp_path, "mu,t [s],N [rpm],p [MPa]\n0.5,1,331,0.1\n0.6,2,331,0.2\n")
    ds = io.load_dataset(p)
    assert list(ds.frame.columns) == ["mu", "p"]
    assert any("t [s], N [rpm]" in n for n in ds.notes)


# --------------------------------------------------------------------------- mapping / units
def test_mapping_by_name_with_or_without_unit(tmp_path: Path) -> None:
    p = write(tmp_path, "FC,CP [MPa],DV [km/h]\n1.2,0.1,3.6\n1.1,0.2,7.2\n")
    for mapping in ({"mu": "FC", "p": "CP", "v": "DV"},
                    {"mu": "FC", "p": "CP [MPa]", "v": "dv"}, "MU=FC, p=CP, V=DV"):
        ds = io.load_dataset(p, mapping=mapping)
        np.testing.assert_allclose(ds.frame["v"], [1.0, 2.0])
        assert ds.units["v"] == "km/h"


def test_mapping_overrides_an_aliased_column(tmp_path: Path) -> None:
    p = write(tmp_path, "mu,p [MPa],CP [bar]\n1.2,0.1,2\n1.1,0.2,3\n")
    ds = io.load_dataset(p, mapping={"p": "CP"})
    np.testing.assert_allclose(ds.frame["p"], [2e5, 3e5])
    assert any("'p [MPa]' ignored" in n for n in ds.notes)


def test_units_by_canonical_or_column_name(tmp_path: Path) -> None:
    p = write(tmp_path, "FC,CP,DV\n1.2,0.1,1\n1.1,0.2,2\n")
    m = {"mu": "FC", "p": "CP", "v": "DV"}
    a = io.load_dataset(p, mapping=m, units={"p": "MPa", "v": "m/s"})
    b = io.load_dataset(p, mapping=m, units={"CP": "MPa", "DV": "m/s"})
    np.testing.assert_array_equal(a.frame["p"], b.frame["p"])
    np.testing.assert_allclose(a.frame["p"], [1e5, 2e5])


def test_units_agreeing_with_header_are_fine_conflicts_are_not(tmp_path: Path) -> None:
    p = write(tmp_path, "mu,p [MPa]\n1.2,0.1\n")
    assert io.load_dataset(p, units={"p": "MPa"}).frame["p"].iloc[0] == 1e5
    with pytest.raises(InputError, match="the header gives unit 'MPa' but units='p=kPa'"):
        io.load_dataset(p, units={"p": "kPa"})


@pytest.mark.parametrize(
    ("text", "fragment"),
    [("mu", "is not NAME=VALUE"), ("mu=", "empty name or value"), ("=FC", "empty name"),
     ("x=FC", "'x' is not a dataset column"), ("mu=FC,mu=CP", "given twice"),
     ("mu=FC,p=FC", "mapped to both"), ("", "is empty")],
)
def test_parse_mapping_errors(text: str, fragment: str) -> None:
    with pytest.raises(InputError, match=fragment):
        io.parse_mapping(text)


def test_parse_mapping_and_units() -> None:
    assert io.parse_mapping("mu=FC, p=CP,v=DV") == {"mu": "FC", "p": "CP", "v": "DV"}
    assert io.parse_mapping(["mu=FC", "f_n=NL"]) == {"mu": "FC", "F_N": "NL"}
    assert io.parse_mapping({"T": "temp"}) == {"T": "temp"}
    assert io.parse_mapping(None) == {}
    assert io.parse_units("p=MPa,v=km/h,t=degC") == {"p": "MPa", "v": "km/h", "T": "degC"}
    with pytest.raises(InputError, match="argument 'units'") as exc:
        io.parse_units("p:MPa")
    assert exc.value.option == "units"
    assert io.canonical_name("f_n") == "F_N"


# --------------------------------------------------------------------------- errors
@pytest.mark.parametrize(
    ("name", "kwargs", "column", "row", "fragment"),
    [
        ("missing_mu.csv", {}, None, None, "no friction coefficient column"),
        ("non_numeric.csv", {}, "p [MPa]", 3, "non-numeric value 'abc'"),
        ("empty.csv", {}, None, None, "file is empty"),
        ("comments_only.csv", {}, None, None, "file is empty"),
        ("header_only.csv", {}, None, None, "no data rows"),
        ("nan_mu.csv", {}, "mu", None, "column is empty"),
        ("negative_pressure.csv", {}, "p [MPa]", 4, "a contact pressure must be >= 0"),
        ("negative_mu.csv", {}, "mu", 3, "a friction coefficient must be >= 0"),
        ("duplicate_column.csv", {}, "mu", None, "duplicate column (columns 1 and 3"),
        ("two_pressures.csv", {}, "pressure [bar]", None, "both give 'p'"),
        ("unknown_unit.csv", {}, "p [Mpa]", None, "did you mean 'MPa'"),
        ("wrong_dimension.csv", {}, "p [m/s]", None, "is a velocity, expected a pressure"),
        ("pipe_delimiter.csv", {}, None, None, "delimiter is not recognised"),
        ("mixed_delimiter.csv", {}, "p [MPa]", 3, "another delimiter"),
        ("binary.csv", {}, None, None, "not a text CSV file"),
        ("no_unit.csv", {"mapping": {"mu": "FC", "p": "CP", "v": "DV"}}, "CP", None,
         "give it in the header as 'CP [MPa]' or with units='p=MPa'"),
        ("no_unit.csv", {"mapping": {"mu": "FC", "p": "XX"}}, "XX", None,
         "no such column in the file (columns: FC, CP, DV)"),
        ("no_unit.csv", {"mapping": {"mu": "FC"}, "units": {"T": "degC"}}, None, None,
         "the file has no 'T' column"),
        ("no_unit.csv", {"mapping": {"mu": "FC", "p": "CP"}, "units": {"CP": "furlong"}},
         "CP", None, "unit 'furlong' is a length, expected a pressure"),
        ("no_unit.csv", {"mapping": {"mu": "FC", "p": "CP"}, "units": {"p": "bananas"}},
         "CP", None, "unknown unit 'bananas'"),
        ("no_unit.csv", {"mapping": {"mu": "FC"}, "units": {"CP": "MPa"}}, "CP",
         None, "the column is not used; map it first"),
        ("no_unit.csv", {"mapping": {"mu": "FC"}, "units": {"QQ": "MPa"}}, None,
         None, "'QQ' is neither a dataset column"),
        ("temperature_coulomb.csv", {}, "T [C]", None, "did you mean 'degC'"),
        ("below_absolute_zero.csv", {}, "T [K]", 3, "below absolute zero"),
        ("load_only.csv", {"area": "314 mm"}, None, None, "is a length, expected an area"),
        ("load_only.csv", {"area": "0.0003"}, None, None, "has no unit"),
        ("load_only.csv", {"area": -1e-4}, None, None, "must be > 0"),
        ("missing_mu.csv", {"area": "1 mm^2"}, None, None, "no friction coefficient"),
    ],
)
def test_malformed_files(name: str, kwargs: dict, column: str | None, row: int | None,
                         fragment: str) -> None:
    path = MALFORMED / name
    with pytest.raises(InputError) as exc:
        io.load_dataset(path, **kwargs)
    err = exc.value
    assert fragment in str(err)
    assert err.file == str(path)
    assert err.column == column
    assert err.row == row
    assert "\n" not in str(err)


def test_missing_file_and_directory(tmp_path: Path) -> None:
    with pytest.raises(InputError, match="file not found") as exc:
        io.load_dataset(tmp_path / "nope.csv")
    assert exc.value.file == str(tmp_path / "nope.csv")
    with pytest.raises(InputError, match="is a directory"):
        io.load_dataset(tmp_path)


@pytest.mark.parametrize(
    ("text", "column", "row", "fragment"),
    [
        ("mu,p [MPa]\n0.5,0.1\n0.6,inf\n", "p [MPa]", 3, "not finite"),
        ("mu,p [MPa]\n0.5,1,5\n", None, 2, "decimal comma needs ';'"),
        ('mu,p [MPa]\n0.5,"1,5"\n', "p [MPa]", 2, "decimal comma needs ';'"),
        ("mu,p [MPa]\n0.5,0.1\n#DIV/0!,0.2\n", "mu", 3, "non-numeric value '#DIV/0!'"),
        ("mu;p [MPa]\n0,5;1.000,5\n", "p [MPa]", 2, "non-numeric value '1.000,5'"),
        ("mu,p [MPa]\n0.5,0.1,7\n", None, 2, "has 3 fields but the header has 2"),
        ("mu\n0.5;0.1\n", None, 2, "different delimiters"),
        ("mu,F_N [N]\n0.5,-3\n", "F_N [N]", 2, "a normal load must be >= 0"),
        ("mu,mu_std\n0.5,-0.1\n", "mu_std", 2, "standard deviation must be >= 0"),
        ("mu,n\n0.5,2.5\n", "n", 2, "whole number >= 1"),
        ("mu,n\n0.5,0\n", "n", 2, "whole number >= 1"),
        ("mu,,p [MPa]\n0.5,3,0.1\n", None, None, "column 2 has no name"),
        ("mu,p [MPa]\n,0.1\nnan,0.2\n", "mu", None, "column is empty"),
        ("mu,p [MPa]\n,0.1\n0.5,\n", None, None, "no usable rows"),
        ("FC;p [MPa]\n0.5;0.1\n", None, None, "no friction coefficient column"),
        ("mu p v\n0.5 0.1 1\n", None, None, "delimiter is not recognised"),
        ("mu,p [MPa],v [m/s]\n0.5,0.1,1\n", None, None, "area='1 mm^2' needs"),
    ],
)
def test_malformed_text(tmp_path: Path, text: str, column: str | None, row: int | None,
                        fragment: str) -> None:
    path = write(tmp_path, text)
    kwargs = {"area": "1 mm^2", "mapping": None} if "area=" in fragment else {}
    if "area=" in fragment:  # area without F_N needs a file without p
        path = write(tmp_path, "mu,v [m/s]\n0.5,1\n")
    with pytest.raises(InputError) as exc:
        io.load_dataset(path, **kwargs)
    assert fragment in str(exc.value)
    assert exc.value.column == column
    assert exc.value.row == row


def test_mapped_empty_column_is_an_error_unmapped_is_a_note(tmp_path: Path) -> None:
    p = write(tmp_path, "mu,T [degC],PV [m/s]\n0.5,,\n0.6,,\n")
    ds = io.load_dataset(p)
    assert list(ds.frame.columns) == ["mu"]
    assert any("'T [degC]' (T) is empty: ignored" in n for n in ds.notes)
    with pytest.raises(InputError, match="column is empty") as exc:
        io.load_dataset(p, mapping={"v": "PV"})
    assert exc.value.column == "PV [m/s]"


def test_zero_velocity_is_kept_and_negative_velocity_noted(tmp_path: Path) -> None:
    p = write(tmp_path, "mu,v [m/s],s [%]\n0.5,0,10\n0.6,-1,150\n")
    ds = io.load_dataset(p)
    assert list(ds.frame["v"]) == [0.0, -1.0]
    assert any("negative v" in n for n in ds.notes)
    assert any("outside 0..1" in n for n in ds.notes)
    np.testing.assert_allclose(ds.frame["s"], [0.1, 1.5])


# --------------------------------------------------------------------------- area
def test_area_derives_pressure(tmp_path: Path) -> None:
    p = MALFORMED / "load_only.csv"
    for area in ("314.16 mm^2", "3.1416 cm^2", 314.16e-6):
        ds = io.load_dataset(p, area=area)
        np.testing.assert_allclose(ds.frame["p"], ds.frame["F_N"] / 314.16e-6, rtol=1e-12)
        assert list(ds.frame.columns) == ["mu", "p", "F_N"]
        assert any("p derived as F_N / area" in n for n in ds.notes)
        assert ds.units["p"].startswith("F_N / area")
    ds = io.load_dataset("thesis-steel", area="314.16 mm^2")
    assert any("not used" in n for n in ds.notes)


# --------------------------------------------------------------------------- in memory
def test_dataframe_and_dict_inputs_are_si() -> None:
    df = pd.DataFrame({"mu": [0.5, 0.6, np.nan], "p [Pa]": [1e5, 2e5, 3e5],
                       "speed [m/s]": [1, 2, 3]})
    ds = io.load_dataset(df)
    assert len(ds) == 2 and ds.source == "<DataFrame>"
    np.testing.assert_allclose(ds.frame["p"], [1e5, 2e5])
    np.testing.assert_allclose(ds.frame["v"], [1, 2])
    assert any("positions 2" in n for n in ds.notes)
    assert ds.rows is None
    ds = io.load_dataset(pd.DataFrame({"mu": [0.5], "p [MPa]": [0.1],
                                       "T [K]": pd.array([None], "Float64")}))
    assert ds.frame["p"].iloc[0] == 1e5 and "T" not in ds.frame.columns
    ds = io.load_dataset({"mu": [0.5, 0.4], "p": [1e5, 2e5]})
    assert ds.source == "<dict>" and len(ds) == 2
    with pytest.raises(InputError, match="a friction coefficient must be >= 0"):
        io.load_dataset(pd.DataFrame({"mu": [0.5, -0.1]}))
    with pytest.raises(InputError, match="non-numeric value 'x'"):
        io.load_dataset(pd.DataFrame({"mu": [0.5, "x"]}))
    with pytest.raises(InputError, match="no rows"):
        io.load_dataset(pd.DataFrame({"mu": []}))


def test_dataset_passthrough_and_bad_types() -> None:
    ds = io.load_dataset("thesis-steel")
    assert io.load_dataset(ds) is ds
    with pytest.raises(InputError, match="already loaded"):
        io.load_dataset(ds, mapping={"mu": "x"})
    with pytest.raises(InputError, match="cannot load a dataset from a int"):
        io.load_dataset(3)  # type: ignore[arg-type]


# --------------------------------------------------------------------------- Dataset
def test_dataset_methods(tmp_path: Path) -> None:
    ds = io.load_dataset(FORMATS / "comments_blank.csv")
    arrays = ds.arrays()
    assert set(arrays) == {"mu", "p", "v"}
    assert all(a.dtype == float for a in arrays.values())
    assert ds.variables == {"p", "v"} and ds.varying == {"p"}
    sub = ds.subset(ds.frame["p"] > 1.5e5)
    assert len(sub) == 2 and list(sub.rows) == [8, 9]
    assert "subset: kept 2 of 3 rows" in sub.notes
    with pytest.raises(InputError, match="shape"):
        ds.subset([True])
    text = ds.describe()
    assert "3 rows" in text and "p [MPa]" in text and "0.1 .. 0.3" in text
    assert "sandpaper, 120" in text
    summary = json.loads(json.dumps(ds.summary()))
    assert summary["rows"] == 3 and summary["columns"]["p"]["unit"] == "Pa"
    assert "3 rows" in repr(ds)


def test_weights_rules() -> None:
    base = {"mu": [0.5, 0.6], "p": [1e5, 2e5]}
    assert io.load_dataset(base).weights() is None
    np.testing.assert_allclose(io.load_dataset({**base, "n": [4, 9]}).weights(), [2, 3])
    np.testing.assert_allclose(io.load_dataset({**base, "mu_std": [0.1, 0.2]}).weights(),
                               [10, 5])
    np.testing.assert_allclose(
        io.load_dataset({**base, "mu_std": [0.1, 0.2], "n": [4, 9]}).weights(), [20, 15])
    ds = io.load_dataset({**base, "mu_std": [0.0, 0.2], "n": [4, 9]})
    np.testing.assert_allclose(ds.weights(), [2, 3])
    assert any("weights used: sqrt(n)" in n for n in ds.notes)
    ds = io.load_dataset({**base, "mu_std": [0.0, 0.2]})
    assert ds.weights() is None
    assert any("unweighted" in n for n in ds.notes)


def test_to_csv_writes_units_and_provenance(tmp_path: Path) -> None:
    ds = io.load_dataset(FORMATS / "semicolon_decimal_comma.csv")
    out = ds.to_csv(tmp_path / "out.csv")
    lines = out.read_text("utf-8").splitlines()
    assert lines[0] == "# exported by a European spreadsheet"
    assert lines[1] == "mu,p [MPa],v [m/s],T [degC]"
    assert lines[2] == "1.2,0.1,1,20"
    back = io.load_dataset(out)
    pd.testing.assert_frame_equal(back.frame, ds.frame, rtol=1e-12)


finite = {"allow_nan": False, "allow_infinity": False, "allow_subnormal": False}


@st.composite
def frames(draw: st.DrawFn) -> pd.DataFrame:
    n = draw(st.integers(min_value=1, max_value=12))
    cols = draw(st.sets(st.sampled_from(["p", "v", "T", "F_N", "s", "mu_std", "n",
                                         "surface"])))
    ranges = {"mu": (0, 10), "p": (0, 1e9), "v": (-100, 100), "T": (1, 2000),
              "F_N": (0, 1e6), "s": (-1, 2), "mu_std": (1e-6, 1)}
    data: dict[str, list] = {}
    for c in ["mu", *sorted(cols, key=io.CANONICAL.index)]:
        if c == "n":
            data[c] = draw(st.lists(st.integers(1, 50), min_size=n, max_size=n))
        elif c == "surface":
            text = st.text(alphabet="abc XYZ,;\"'0123456789-_", max_size=12).map(str.strip)
            data[c] = draw(st.lists(text.filter(lambda s: s.lower() not in
                                                io.MISSING_TOKENS),
                                    min_size=n, max_size=n))
        else:
            lo, hi = ranges[c]
            data[c] = draw(st.lists(st.floats(lo, hi, **finite), min_size=n, max_size=n))
    return pd.DataFrame(data)


@settings(max_examples=40, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(frames(), st.one_of(st.none(), st.text(alphabet="abc :;,#", max_size=30)))
def test_round_trip_to_csv_and_load(tmp_path: Path, frame: pd.DataFrame,
                                    provenance: str | None) -> None:
    ds = io.load_dataset(frame.to_dict("list"))  # SI columns: the dict's contract
    ds.provenance = provenance.strip() or None if provenance else None
    back = io.load_dataset(ds.to_csv(tmp_path / "rt.csv"))
    assert list(back.frame.columns) == list(ds.frame.columns)
    for c in ds.frame.columns:
        if c == "surface":
            assert list(back.frame[c]) == list(ds.frame[c])
        else:
            np.testing.assert_allclose(back.frame[c], ds.frame[c], rtol=1e-12, atol=1e-9)
    assert back.provenance == ds.provenance
    if ds.weights() is None:
        assert back.weights() is None
    else:
        np.testing.assert_allclose(back.weights(), ds.weights(), rtol=1e-9)


# --------------------------------------------------------------------------- CLI
def test_cli_datasets_list(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["datasets"]) == 0
    out = capsys.readouterr().out
    assert "thesis-steel " in out and "19" in out
    assert main(["datasets", "--json"]) == 0
    items = json.loads(capsys.readouterr().out)
    assert {d["name"] for d in items} >= {"thesis-steel", "thesis-steel-original"}


def test_cli_datasets_describe(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["datasets", "thesis-steel"]) == 0
    out = capsys.readouterr().out
    assert "19 rows" in out and "p [MPa]" in out and "0.03119 .. 0.2496" in out
    assert "provenance:" in out and "Figure 5-16a" in out
    assert main(["datasets", "thesis-steel-original", "--map", "mu=FC,p=CP,v=DV",
                 "--units", "p=MPa,v=m/s", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["rows"] == 19 and doc["columns"]["p"]["given_unit"] == "MPa"
    assert any("NL, PV" in n for n in doc["notes"])


def test_cli_datasets_file_errors(capsys: pytest.CaptureFixture[str]) -> None:
    path = MALFORMED / "non_numeric.csv"
    assert main(["datasets", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "non_numeric.csv" in err and "row 3" in err
    assert main(["datasets", "--map", "mu=FC"]) == 2
    assert "need a dataset NAME" in capsys.readouterr().err


def test_nothing_is_lost_when_cells_are_nan_strings(tmp_path: Path) -> None:
    # every missing-value spelling is a reported drop, never a silent one
    tokens = sorted(t for t in io.MISSING_TOKENS if t)
    body = "".join(f"{t},0.1\n" for t in tokens) + "0.5,0.2\n"
    ds = io.load_dataset(write(tmp_path, "mu,p [MPa]\n" + body))
    assert len(ds) == 1
    dropped = sum(int(n.split()[1]) for n in ds.notes if n.startswith("dropped"))
    assert dropped == len(tokens)
    assert math.isclose(ds.frame["mu"].iloc[0], 0.5)


@pytest.mark.parametrize("reader", ["dataset", "record", "manifest"])
def test_nul_byte_past_the_first_block_is_refused_with_its_row(tmp_path, reader):
    """A NUL deep in a file (after the binary sniffing window) is refused, row named.

    pandas reads such a cell as text and the csv module stops with an internal
    message; every table reader refuses it instead.
    """
    from frictionlaws.tribometer.process import read_manifest
    from frictionlaws.tribometer.records import read_record
    from frictionlaws.tribometer.rig import Rig

    header, row, read = {
        "dataset": (b"mu,p [MPa]\n", b"0.5,0.1\n", io.load_dataset),
        "record": (b"time [s],torque [N m],disc_speed [rpm]\n", b"0.1,2,3\n", read_record),
        "manifest": (b"record,F_N [N]\n", b"r.csv,100\n",
                     lambda path: read_manifest(path, Rig())),
    }[reader]
    path = tmp_path / "nul.csv"
    path.write_bytes(header + row * 2000 + row.replace(b",", b",\x00", 1) + row)
    with pytest.raises(InputError, match="NUL byte") as info:
        read(path)
    assert info.value.row == 2002
    assert str(path) in str(info.value)


@pytest.mark.parametrize("reader", ["dataset", "manifest"])
@pytest.mark.parametrize(("line", "message"), [
    (b'0.5,0.1,"a\nb"\n', "a quoted field is not closed on its line"),
    (b'0.5,0.1,"a"b\n', "malformed quoting"),
])
def test_one_table_reader_refuses_broken_quoting_with_its_row(tmp_path, reader, line,
                                                              message):
    """Datasets and manifests share one reader: same quoting rule, same message."""
    from frictionlaws.tribometer.process import read_manifest
    from frictionlaws.tribometer.rig import Rig

    header, read = {
        "dataset": (b"mu,p [MPa],note\n0.5,0.1,x\n", io.load_dataset),
        "manifest": (b"file,load [kg],surface\nr.csv,2,steel\n",
                     lambda path: read_manifest(path, Rig())),
    }[reader]
    path = tmp_path / "quoted.csv"
    path.write_bytes(header + line)
    with pytest.raises(InputError, match=message) as info:
        read(path)
    assert info.value.row == 3


def test_overflow_in_unit_conversion_is_refused_with_its_row(tmp_path):
    """1e300 GPa is finite as written and infinite in Pa: refused, no NumPy warning."""
    import warnings

    path = tmp_path / "overflow.csv"
    path.write_text("mu,p [GPa]\n0.5,0.2\n0.5,1e300\n0.6,0.3\n")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(InputError, match="overflows when converted to SI") as info:
            io.load_dataset(path)
    assert info.value.row == 3 and info.value.column == "p [GPa]"


@pytest.mark.parametrize("delimiter", [";", "\t"])
def test_a_thousands_point_in_a_decimal_comma_file_is_refused(tmp_path, delimiter):
    """'1.200' beside '0,5' could be 1200 or 1.2: refused with its row, never guessed."""
    path = tmp_path / "mixed.csv"
    rows = ["mu", "p [kPa]"], ["0,5", "100"], ["0,4", "1.200"], ["0,3", "300"]
    path.write_text("\n".join(delimiter.join(r) for r in rows) + "\n")
    with pytest.raises(InputError, match="ambiguous in a file with decimal commas") as info:
        io.load_dataset(path)
    assert info.value.row == 3
    # points only: one convention, read as written
    path.write_text(path.read_text().replace(",", "."))
    assert io.load_dataset(path).frame["p"].tolist() == [1e5, 1.2e3, 3e5]


def test_the_micro_sign_header_reads_as_mu(tmp_path):
    path = tmp_path / "micro.csv"
    path.write_text("\u00b5,p [MPa]\n0.5,0.1\n0.4,0.2\n", encoding="utf-8")
    assert io.load_dataset(path).frame["mu"].tolist() == [0.5, 0.4]


@pytest.mark.parametrize(("cell", "message"), [
    ("1e400", "overflows a double"),
    ("9" * 5000, "(5000 characters)' overflows a double"),
    ("abc" + "x" * 100, "(103 characters)'; expected a number"),
])
def test_overflowing_and_long_cells_are_named_shortly(tmp_path, cell, message):
    path = tmp_path / "cells.csv"
    path.write_text(f"mu,p [MPa]\n0.5,{cell}\n0.4,0.2\n")
    with pytest.raises(InputError, match=re.escape(message)) as info:
        io.load_dataset(path)
    assert len(str(info.value)) < 300


@pytest.mark.parametrize("encode", [lambda t: t.encode("utf-32"),
                                    lambda t: t.encode("utf-16"),
                                    lambda t: t.encode() + b"\x1a"],
                         ids=["utf-32", "utf-16", "ctrl-z"])
def test_encodings_by_byte_order_mark_and_a_dos_end_mark(tmp_path, encode):
    path = tmp_path / "enc.csv"
    path.write_bytes(encode("mu,p [MPa]\n0.5,0.1\n0.4,0.2\n"))
    assert io.load_dataset(path).frame["mu"].tolist() == [0.5, 0.4]


def test_library_messages_name_arguments_not_flags(tmp_path: Path) -> None:
    """The library speaks of its arguments (mapping=, units=, area=); only the CLI of flags."""
    path = write(tmp_path, "mu,FC2,p [MPa]\n0.5,0.4,0.1\n")
    with pytest.raises(InputError) as exc:
        io.load_dataset(path, mapping="p=NOPE")
    assert "--" not in str(exc.value) and "mapping='p=NOPE'" in str(exc.value)
    flags = {"mapping": "--map", "units": "--units", "area": "--area"}.get
    assert exc.value.compose(label=flags).startswith(
        f"file '{path}', column 'NOPE': --map p=NOPE: no such column")
    ds = io.load_dataset(path)
    assert any("(map them to use them)" in n for n in ds.notes)
    with pytest.raises(InputError) as exc:
        io.load_dataset(write(tmp_path, "mu,F_N [N]\n0.5,3\n"), area="3 mm")
    assert "area '3 mm' is a length" in str(exc.value)
    assert "--area '3 mm' is a length" in exc.value.compose(label=flags)


def test_dataframe_column_without_a_unit_is_refused_as_in_a_csv(tmp_path) -> None:
    from frictionlaws import fit as io_fit

    frame = pd.DataFrame({"mu": [0.5, 0.4], "p": [0.1, 0.2]})
    path = tmp_path / "nounit.csv"
    frame.to_csv(path, index=False)
    for data in (frame, str(path)):
        with pytest.raises(InputError, match="column has no unit") as err:
            io.load_dataset(data)
        assert err.value.column == "p"
    with pytest.raises(InputError, match="column has no unit"):
        io_fit("thirion", frame)
    ds = io.load_dataset(frame, units={"p": "MPa"})
    np.testing.assert_allclose(ds.frame["p"], [1e5, 2e5])
    # the API's dict of arrays keeps its contract: SI
    assert io.load_dataset({"mu": [0.5, 0.4], "p": [1e5, 2e5]}).frame["p"].iloc[0] == 1e5
