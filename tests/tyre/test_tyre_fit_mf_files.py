"""``tyre fit-mf FILE...``: one or several files of any tyre test format fitted together."""

from __future__ import annotations

import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from frictionlaws.base.errors import ExtrapolationWarning, InputError
from frictionlaws.cli import main
from frictionlaws.tyre.data import join, write_tydex
from frictionlaws.tyre.data.synthetic import RawRunSpec, sweep_data, synthetic_raw_run
from frictionlaws.tyre.magic_formula import MagicFormula
from frictionlaws.tyre.synthetic_rig import moved_tyre, truth_errors

TRUTH = moved_tyre()
CONDITIONS = dict(loads=(0.5, 1.0, 1.5), cambers_deg=(0.0, 3.0), pressures=(1.0,))


def _tydex(tmp_path: Path) -> list[Path]:
    kw = dict(CONDITIONS, n=25)
    return [write_tydex(sweep_data(TRUTH, "lateral", **kw), tmp_path / "lateral.tdx"),
            write_tydex(sweep_data(TRUTH, "longitudinal", **kw), tmp_path / "longitudinal.tdx",
                        units={"pressure": "bar", "fx": "N"}, factors={"fx": 10.0}),
            write_tydex(sweep_data(TRUTH, "combined", **kw), tmp_path / "combined.tdx")]


def _errors(tir: Path) -> dict[str, float]:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        return truth_errors(TRUTH, MagicFormula.from_file(tir), **CONDITIONS)


@pytest.mark.slow
def test_three_tydex_files_are_fitted_in_one_command(tmp_path: Path, capsys) -> None:
    files = _tydex(tmp_path)
    tir = tmp_path / "fitted.tir"
    assert main(["tyre", "fit-mf", *map(str, files), "-o", str(tir)]) == 0
    out = capsys.readouterr().out
    assert "3 files read together (tydex)" in out and "fx from FX [N x 10]" in out
    header = tir.read_text().splitlines()[0]
    assert all(str(f) in header for f in files)
    e = _errors(tir)
    assert e["Fx0"] < 0.01 and e["Fy0"] < 0.01 and e["Fx"] < 0.02 and e["Fy"] < 0.02, e
    assert e["Mz"] < 0.03, e


@pytest.mark.slow
def test_a_raw_run_from_standard_input_beside_a_tydex_file(tmp_path: Path, capsys,
                                                          monkeypatch) -> None:
    import io
    import sys

    spec = RawRunSpec(loads=(0.5, 1.0), cambers_deg=(0.0,), pressures=(1.0,), rate=50.0,
                      combined_deg=(), cycles=1, warmup_s=10.0)
    run = synthetic_raw_run(TRUTH, spec).write(tmp_path / "run.dat")
    lat = _tydex(tmp_path)[0]
    monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(run.read_bytes())))
    tir = tmp_path / "mixed.tir"
    assert main(["tyre", "fit-mf", "-", str(lat), "-o", str(tir)]) == 0
    text = tir.read_text()
    assert "<stdin> + " in text.splitlines()[0] and "frictionlaws-stdin" not in text
    assert "note: 2 files read together (raw, tydex)" in text
    assert "note: <stdin>: kappa is SL" in text
    capsys.readouterr()


@pytest.mark.parametrize("make,match", [
    (lambda t, f: [f[0], t / "." / f[0].name], "given twice"),
    (lambda t, f: ["-", "-"], "standard input ('-') can be given once"),
    (lambda t, f: [f[0], _kpa_as_bar(f[1])], "a unit is wrong in one of them"),
    (lambda t, f: [f[0], _copied(f[0], t / "copy.tdx")], "hold the same data"),
    (lambda t, f: [f[0], _broken(f[2])], "did you mean FYW"),
    (lambda t, f: [f[0], t / "missing.tdx"], "not found"),
])
def test_files_that_cannot_be_fitted_together_are_refused(tmp_path: Path, capsys, make,
                                                          match) -> None:
    files = _tydex(tmp_path)
    argv = [str(p) for p in make(tmp_path, files)]
    tir = tmp_path / "never.tir"
    assert main(["tyre", "fit-mf", *argv, "-o", str(tir)]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and match in err, err
    assert not tir.exists()


SMALL = sweep_data(TRUTH, "lateral", loads=(1.0,), cambers_deg=(0.0,), pressures=(1.0,), n=5)


@settings(max_examples=10, deadline=None)
@given(row=st.integers(0, len(SMALL) - 1),
       column=st.sampled_from(["fz", "kappa", "alpha", "gamma", "pressure", "fy", "mz"]))
def test_the_same_data_under_another_name_is_refused_and_one_cell_apart_is_not(
        row: int, column: str) -> None:
    """A copy of a file under another name counts its rows twice: refused naming both;
    one cell changed in the last digit is another measurement."""
    copy = replace(SMALL.subset(np.ones(len(SMALL), bool)), source="copy.tdx")
    with pytest.raises(InputError, match="'<synthetic lateral sweeps>' and 'copy.tdx' hold "
                                         "the same data") as err:
        join([SMALL, copy])
    assert err.value.file == "copy.tdx"
    values = getattr(copy, column).copy()
    values[row] = np.nextafter(values[row], np.inf)
    setattr(copy, column, values)
    assert len(join([SMALL, copy])) == 2 * len(SMALL)


def _copied(path: Path, to: Path) -> Path:
    to.write_bytes(path.read_bytes())
    return to


@pytest.mark.parametrize("order", [1, -1])
def test_of_two_files_the_one_whose_pressure_is_no_tyre_s_is_named(tmp_path: Path, capsys,
                                                                    order: int) -> None:
    """bar numbers under a kPa unit in one file of two: the file named is that one (its
    pressure is outside the range tyres run at), in either order."""
    files = _tydex(tmp_path)[:2]
    bad = files[1]
    bad.write_text(bad.read_text().replace("INFLPRES  Inflation pressure            bar",
                                           "INFLPRES  Inflation pressure            kPa"))
    assert main(["tyre", "fit-mf", *map(str, files[::order]), "-o",
                 str(tmp_path / "o.tir")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: file '{bad}', column 'pressure', row ") and (
        "only this one's is outside the range tyres run at" in err), err


def _kpa_as_bar(path: Path) -> Path:
    path.write_text(path.read_text().replace("bar", "kPa"))
    return path


def _broken(path: Path) -> Path:
    path.write_text(path.read_text().replace("FYW      ", "FYWW     ", 1))
    return path


def test_the_output_may_not_be_one_of_the_inputs(tmp_path: Path, capsys) -> None:
    files = _tydex(tmp_path)
    twin = tmp_path / "twin.tir"
    twin.write_text("!")
    assert main(["tyre", "fit-mf", str(files[0]), str(twin), "-o", str(twin)]) == 2
    assert "also an input" in capsys.readouterr().err
    assert twin.read_text() == "!"
