"""TYDEX files: read into tyre data, written back, refused when broken (file, line, channel)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from frictionlaws.base.errors import InputError
from frictionlaws.tyre.data import (
    load_tydex,
    read_tydex,
    read_tyre_data,
    read_tyre_files,
    tydex_text,
    write_tydex,
    write_tyre_csv,
)
from frictionlaws.tyre.data.synthetic import sweep_data
from frictionlaws.tyre.magic_formula import MagicFormula

TRUTH = MagicFormula.from_file("MagicFormula61")
QUANTITIES = ("fz", "kappa", "alpha", "gamma", "pressure", "fx", "fy", "mz")


def _sweeps(kind: str = "lateral", **kw) -> object:
    options = dict(loads=(0.5, 1.0), cambers_deg=(0.0, 2.0), pressures=(1.0,), n=9)
    options.update(kw)
    return sweep_data(TRUTH, kind, **options)


def _same(a, b, rtol: float = 1e-13) -> None:
    for q in QUANTITIES:
        x, y = getattr(a, q), getattr(b, q)
        assert np.array_equal(np.isnan(x), np.isnan(y)), q
        ok = ~np.isnan(x)
        np.testing.assert_allclose(y[ok], x[ok], rtol=rtol, atol=1e-300, err_msg=q)


@pytest.mark.parametrize("kind", ["lateral", "longitudinal", "combined"])
@pytest.mark.parametrize("units,factors", [
    ({}, {}),
    ({"pressure": "bar", "fx": "N", "fy": "daN", "kappa": "%", "alpha": "rad", "mz": "N-m"},
     {"fx": 10.0, "mz": 0.001}),
])
def test_a_written_file_reads_back_to_the_same_data(tmp_path: Path, kind, units,
                                                     factors) -> None:
    data = _sweeps(kind)
    path = write_tydex(data, tmp_path / f"{kind}.tdx", units=units, factors=factors,
                       comments=["made by a test", "**END in a comment is no keyword"])
    back = read_tydex(path)
    _same(data, back)
    assert back.rows.tolist() == sorted(back.rows.tolist()) and back.rows[0] > 10
    if factors:
        assert "mz from MZW [N-m x 0.001]" in back.notes[0] or kind == "longitudinal"


def test_the_sections_are_read_as_written(tmp_path: Path) -> None:
    path = write_tydex(_sweeps(), tmp_path / "a.tdx", measid="LAT 4 kN",
                       comments=["first line", "second line"],
                       constants={"NOMPRES": (2.5e5, "bar")})
    f = load_tydex(path)
    assert f.header["RELEASE"] == "1.3" and f.header["MEASID"] == "LAT 4 kN"
    assert f.comments == ["first line", "second line"]
    assert f.constant("NOMPRES", "pressure") == pytest.approx(2.5e5)
    assert [c.name for c in f.channels] == ["FZW", "LONGSLIP", "SLIPANGL", "INCLANGL",
                                            "INFLPRES", "FYW", "MZW"]
    assert "INCLANGL" not in f.constants  # two cambers: a channel, not a constant
    assert any("NOMPRES 250000 Pa" in n for n in read_tydex(path).notes)


def _file(channels: list[str], rows: list[str], constants: list[str] = (),
          end: bool = True) -> str:
    out = ["**HEADER", "RELEASE   Release                       1.3", "**COMMENTS",
           "hand made", "**CONSTANTS", *constants, "**MEASURCHANNELS", *channels,
           "**MEASURDATA", *rows]
    return "\n".join(out + (["**END"] if end else [])) + "\n"


def _ch(name: str, unit: str, factor: str = "1", desc: str = "a channel") -> str:
    return f"{name:<10}{desc:<30}{unit:<10}{factor}"


LAT = [_ch("FZW", "N"), _ch("SLIPANGL", "deg"), _ch("FYW", "N")]
LAT_ROWS = ["4000 -4 3000", "4000 -2 1700", "4000 0 0", "4000 2 -1700", "4000 4 -3000"]


def test_a_quantity_without_a_channel_takes_the_constant(tmp_path: Path) -> None:
    path = tmp_path / "c.tdx"
    path.write_text(_file(LAT, LAT_ROWS, [_ch("INFLPRES", "bar", "2.4"),
                                          _ch("INCLANGL", "deg", "-1.5"),
                                          _ch("LONGSLIP", "%", "0"), _ch("TRCKSURF", "", "")]))
    d = read_tydex(path)
    assert np.all(d.pressure == pytest.approx(2.4e5)) and np.all(d.kappa == 0)
    assert np.all(d.gamma == pytest.approx(math.radians(-1.5)))
    assert d.missing == () and "pressure = 2.4 bar (constant INFLPRES)" in d.notes[0]


def test_percent_slips_and_factors(tmp_path: Path) -> None:
    path = tmp_path / "p.tdx"
    path.write_text(_file([_ch("FZW", "kN", "0.001"), _ch("LONGSLIP", "%"),
                           _ch("FX", "daN", "10")],
                          ["4000 -10 -300", "4000 0 0", "4000 10 300"]))
    d = read_tydex(path)
    assert d.fz == pytest.approx([4000, 4000, 4000])
    assert d.kappa == pytest.approx([-0.1, 0, 0.1]) and d.fx == pytest.approx([-3e4, 0, 3e4])


BROKEN_FILES = [
    ([_ch("FZW", "N", "0"), *LAT[1:]], LAT_ROWS, "FZW", "conversion factor of 0"),
    ([_ch("FZW", ""), *LAT[1:]], LAT_ROWS, "FZW", "has no unit"),
    ([_ch("FZW", "N", ""), *LAT[1:]], LAT_ROWS, "FZW", "no conversion factor"),
    ([_ch("FZW", "N", "1 5"), *LAT[1:]], LAT_ROWS, "FZW", "offsets"),
    ([_ch("FZW", "N", "abc"), *LAT[1:]], LAT_ROWS, "FZW", "not a number"),
    ([*LAT, _ch("FYW", "N")], [r + " 1" for r in LAT_ROWS], "FYW", "given twice"),
    ([*LAT, _ch("FX", "N"), _ch("FXW", "N")], [r + " 1 1" for r in LAT_ROWS], "FXW",
     "two channels give the longitudinal force"),
    ([_ch("FZW", "N"), _ch("SLIPANG", "deg"), _ch("FYW", "N")], LAT_ROWS, "SLIPANG",
     "did you mean SLIPANGL"),
    ([_ch("FZW", "N"), _ch("SLIPANGL", "deg"), _ch("FYH", "N")], LAT_ROWS, "FYH",
     "not in W axes"),
    ([_ch("FZ", "N"), *LAT[1:]], LAT_ROWS, "FZ", "FZW in W axes"),
    ([_ch("FZW", "N"), _ch("SLIPANGL", "%"), _ch("FYW", "N")], LAT_ROWS, "SLIPANGL",
     "not an angle"),
    ([_ch("FZW", "m"), *LAT[1:]], LAT_ROWS, "FZW", "force"),
    ([_ch("FZW", "N"), _ch("SLIPANGL", "rad"), _ch("FYW", "N")], LAT_ROWS, "alpha",
     "beyond 90 degrees"),
    (LAT, [*LAT_ROWS[:2], "4000 0", *LAT_ROWS[3:]], "FYW",
     "2 values on this row.*no value of FYW"),
    (LAT, [*LAT_ROWS[:2], "4000 0 1 2", *LAT_ROWS[3:]], "FYW", "a value past FYW"),
    (LAT, [*LAT_ROWS[:2], "4000 \uff10 0", *LAT_ROWS[3:]], "SLIPANGL", "is not a number"),
    (LAT, [*LAT_ROWS[:2], "4000 1_0 0", *LAT_ROWS[3:]], "SLIPANGL", "is not a number"),
    (LAT, [*LAT_ROWS[:2], "4000 nan 0", *LAT_ROWS[3:]], "SLIPANGL", "is not a number"),
    (LAT, [*LAT_ROWS[:2], "4000 1e999 0", *LAT_ROWS[3:]], "SLIPANGL", "overflows"),
    ([_ch("FZ\u2028W", "N"), *LAT[1:]], LAT_ROWS, None, "not a name of letters"),
    ([_ch("F\u00c4W", "N"), *LAT[1:]], LAT_ROWS, None, "not a name of letters"),
    ([_ch("FZW", "N").replace("  ", "\t", 1), *LAT[1:]], LAT_ROWS, None, "a tab"),
    ([_ch("FZW", "N"), _ch("SLIPANGL", "deg")], ["4000 1", "4000 2"], None,
     "no FX, FYW or MZW channel"),
    ([_ch("SLIPANGL", "deg"), _ch("FYW", "N")], ["1 2", "2 3"], None, "no FZW channel"),
]


@pytest.mark.parametrize("channels,rows,column,match", BROKEN_FILES)
def test_broken_files_are_refused_naming_file_line_and_channel(tmp_path: Path, channels, rows,
                                                                column, match) -> None:
    path = tmp_path / "bad.tdx"
    path.write_text(_file(channels, rows))
    with pytest.raises(InputError, match=match) as exc:
        read_tydex(path)
    assert exc.value.file == str(path)
    assert column is None or exc.value.column == column
    text = path.read_text().splitlines()
    if exc.value.row is not None:
        assert 1 <= exc.value.row <= len(text)


CLI_REFUSALS = {  # what the issue names: truncated, unknown, duplicate, no unit, no factor
    "truncated": (_file(LAT, LAT_ROWS[:3], end=False), None, 13, "truncated"),
    "truncated row": (_file(LAT, [*LAT_ROWS[:2], "4000 -2"]), "FYW", 13, "no value of FYW"),
    "unknown": (_file([LAT[0], _ch("SLIPANG", "deg"), LAT[2]], LAT_ROWS), "SLIPANG", 8,
                "unknown channel SLIPANG"),
    "duplicate": (_file([*LAT, _ch("FYW", "N")], [r + " 1" for r in LAT_ROWS]), "FYW", 10,
                  "FYW is given twice"),
    "no unit": (_file([_ch("FZW", ""), *LAT[1:]], LAT_ROWS), "FZW", 7, "has no unit"),
    "no factor": (_file([_ch("FZW", "N", ""), *LAT[1:]], LAT_ROWS), "FZW", 7,
                  "no conversion factor"),
}


@pytest.mark.parametrize("case", list(CLI_REFUSALS))
def test_the_cli_refuses_a_broken_file_in_one_line_naming_file_line_and_channel(
        tmp_path: Path, capsys, case: str) -> None:
    from frictionlaws.cli import main

    text, channel, line, match = CLI_REFUSALS[case]
    path = _write(tmp_path / "broken.tdx", text.rstrip("\n"))
    assert main(["tyre", "fit-mf", str(path), "-o", str(tmp_path / "never.tir")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and match in err, err
    assert "broken.tdx" in err and f"row {line}" in err, err
    assert channel is None or f"column '{channel}'" in err, err
    assert list(tmp_path.iterdir()) == [path]


def test_prepare_says_a_tydex_file_is_no_raw_run(tmp_path: Path, capsys) -> None:
    from frictionlaws.cli import main

    path = write_tydex(_sweeps(n=3), tmp_path / "lateral.tdx")
    assert main(["tyre", "prepare", str(path), "-o", str(tmp_path / "never.csv")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "a TYDEX file" in err and "fit-mf" in err, err
    assert list(tmp_path.iterdir()) == [path]


def test_every_truncation_is_refused_or_whole(tmp_path: Path) -> None:
    """A file cut after any line: refused (naming the file) unless the cut keeps all of it."""
    text = tydex_text(_sweeps(n=3)).splitlines()
    whole = read_tydex(_write(tmp_path / "whole.tdx", "\n".join(text)))
    for cut in range(len(text)):
        path = _write(tmp_path / f"cut{cut}.tdx", "\n".join(text[:cut]))
        with pytest.raises(InputError) as exc:
            read_tydex(path)
        assert exc.value.file == str(path)
    assert len(whole) == 24


def _write(path: Path, text: str) -> Path:
    path.write_text(text + "\n" if text else "")
    return path


@pytest.mark.parametrize("tail", ["\n**END\n", "\n1 2 3\n", "\n**MODELS\n"])
def test_text_after_the_end_is_refused(tmp_path: Path, tail) -> None:
    path = tmp_path / "t.tdx"
    path.write_text(_file(LAT, LAT_ROWS) + tail)
    with pytest.raises(InputError, match="text after \\*\\*END") as exc:
        read_tydex(path)
    assert exc.value.row == len(path.read_text().splitlines())


@pytest.mark.parametrize("text,match", [
    (_file(LAT, LAT_ROWS).replace("**COMMENTS", "**MODELS"), "unknown keyword '\\*\\*MODELS'"),
    (_file(LAT, LAT_ROWS).replace("**COMMENTS", "**CONSTANTS"), "CONSTANTS is given twice"),
    ("RELEASE 1.3\n" + _file(LAT, LAT_ROWS), "starts with \\*\\*HEADER"),
    (_file(LAT, []), "holds no row"),
    (_file(LAT, LAT_ROWS).replace("**MEASURCHANNELS", "**MODELCHANNELS"),
     "no \\*\\*MEASURCHANNELS"),
])
def test_sections_out_of_place_are_refused(tmp_path: Path, text, match) -> None:
    path = tmp_path / "s.tdx"
    path.write_text(text)
    with pytest.raises(InputError, match=match):
        read_tydex(path)


def test_a_rigs_own_channel_is_named_not_refused(tmp_path: Path) -> None:
    path = tmp_path / "own.tdx"
    path.write_text(_file([*LAT, _ch("TEMP1", "degC"), _ch("RUNTIME", "s")],
                          [r + " 30 0.1" for r in LAT_ROWS]))
    d = read_tydex(path)
    assert "channels not in TYDEX 1.3's list (a rig's own): TEMP1" in d.notes
    assert "channels not used: TEMP1, RUNTIME" in d.notes and "time" in d.extra


def test_sae_loads_in_a_file_read_as_w_axes_name_the_other_convention(tmp_path: Path) -> None:
    data = _sweeps()
    path = write_tydex(data, tmp_path / "w.tdx")
    text = path.read_text().splitlines()
    start = text.index("**MEASURDATA") + 1
    flipped = [" ".join(str(-float(v)) if j in (0, 5, 6) else v
                        for j, v in enumerate(line.split()))
               for line in text[start:-1]]  # FZW, FYW, MZW negated: SAE axes, alpha kept
    sae = _write(tmp_path / "sae.tdx", "\n".join(text[:start] + flipped + ["**END"]))
    with pytest.raises(InputError, match="sign_convention='sae'"):
        read_tydex(sae)
    back = read_tydex(sae, sign_convention="sae")
    np.testing.assert_allclose(back.fy, data.fy, rtol=1e-13)
    np.testing.assert_allclose(back.alpha, -data.alpha, rtol=1e-13)


def test_writing_refuses_a_factor_of_zero_and_an_input_as_output(tmp_path: Path) -> None:
    data = _sweeps()
    with pytest.raises(InputError, match="not 0"):
        tydex_text(data, factors={"fy": 0.0})
    path = write_tydex(data, tmp_path / "in.tdx")
    d = read_tydex(path)
    with pytest.raises(InputError, match="also an input"):
        write_tydex(d, path)


def test_several_files_are_read_together_and_mixed_units_refused(tmp_path: Path) -> None:
    lat = write_tydex(_sweeps("lateral"), tmp_path / "lat.tdx")
    lon = write_tydex(_sweeps("longitudinal"), tmp_path / "lon.tdx",
                      units={"pressure": "bar", "fx": "N"}, factors={"fx": 10.0})
    data, files = read_tyre_files([lat, lon])
    assert [f.format for f in files] == ["tydex", "tydex"] and len(data) == 144
    assert data.where(80) == (str(lon), int(files[1].data.rows[8]))
    bad = write_tydex(_sweeps("longitudinal"), tmp_path / "kpa_as_bar.tdx",
                      units={"pressure": "bar"})
    text = bad.read_text().replace("bar", "kPa")
    bad.write_text(text)
    with pytest.raises(InputError, match="pressure of .*kpa_as_bar.tdx.* a unit is wrong"):
        read_tyre_files([lat, bad])
    with pytest.raises(InputError, match="given twice"):
        read_tyre_files([lat, tmp_path / "." / "lat.tdx"])


def test_csv_and_tydex_of_the_same_rows_give_the_same_data(tmp_path: Path) -> None:
    data = _sweeps("combined")
    csv = write_tyre_csv(data, tmp_path / "rows.csv")
    tdx = write_tydex(data, tmp_path / "rows.tdx")
    a, b = read_tyre_data(csv), read_tydex(tdx)
    for q in QUANTITIES:
        assert np.array_equal(getattr(a, q), getattr(b, q), equal_nan=True), q


@pytest.mark.slow
def test_a_tir_fitted_from_a_written_tydex_file_equals_the_one_from_its_csv(tmp_path: Path
                                                                             ) -> None:
    import warnings

    from frictionlaws.base.errors import ExtrapolationWarning
    from frictionlaws.tyre import fit_mf
    from frictionlaws.tyre.tir import format_tir

    kw = dict(loads=(0.6, 1.2), cambers_deg=(0.0,), n=9)
    data, _ = read_tyre_files([write_tydex(_sweeps(k, **kw), tmp_path / f"{k}.tdx")
                               for k in ("lateral", "longitudinal")])
    tdx = write_tydex(data, tmp_path / "all.tdx")
    csv = write_tyre_csv(data, tmp_path / "all.csv")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        fits = [fit_mf(read(p)) for read, p in ((read_tydex, tdx), (read_tyre_data, csv))]
    assert format_tir(fits[0].property_file) == format_tir(fits[1].property_file)
    assert fits[0].values == fits[1].values


BAD_TOKENS = ["1_000", "\uff11\uff12", "nan", "inf", "1e999", "1,5", "0x10", "--1", "1.2.3",
              "\u0661\u0662", "NOTAVAILABLE"]
TEXT = tydex_text(_sweeps(n=5))


@settings(max_examples=40, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(row=st.integers(0, 39), column=st.integers(0, 6), token=st.sampled_from(BAD_TOKENS))
def test_any_bad_number_is_refused_with_its_line_and_channel(tmp_path: Path, row, column,
                                                             token) -> None:
    lines = TEXT.splitlines()
    first = lines.index("**MEASURDATA") + 1
    cells = lines[first + row].split()
    cells[column] = token
    lines[first + row] = " ".join(cells)
    path = _write(tmp_path / "bad.tdx", "\n".join(lines))
    with pytest.raises(InputError) as exc:
        read_tydex(path)
    assert exc.value.file == str(path) and exc.value.row == first + row + 1
    assert exc.value.column == ["FZW", "LONGSLIP", "SLIPANGL", "INCLANGL", "INFLPRES", "FYW",
                                "MZW"][column]


def test_a_property_files_evaluation_is_written_for_other_tools(tmp_path: Path) -> None:
    grid = sweep_data(TRUTH, "combined", loads=(0.8,), cambers_deg=(0.0,), n=5, noise=0.0,
                      jitter=False)
    back = read_tydex(write_tydex(grid, tmp_path / "eval.tdx", measid="MF 6.1 example"))
    out = TRUTH.steady_state(back.kappa, back.alpha, back.fz, back.gamma,
                             pressure=back.pressure)
    np.testing.assert_allclose(back.fx, out["Fx"], rtol=1e-12)
    np.testing.assert_allclose(back.mz, out["Mz"], rtol=1e-12)
    assert np.ptp(np.degrees(back.alpha)) == pytest.approx(16.0)
