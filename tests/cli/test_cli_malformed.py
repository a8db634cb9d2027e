"""Malformed input through ``frictionlaws fit``: exit code 2, one line, no traceback.

Each case runs ``frictionlaws.cli.main(["fit", "--law", LAW, DATA, ...])`` and checks
that the command fails with exit code 2 and exactly one line on stderr that names
the file and, where it applies, the column and row, and says what was expected.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from frictionlaws.base.errors import UnknownLawError
from frictionlaws.cli import main
from frictionlaws.law.registry import get_law

DATA = Path(__file__).resolve().parents[1] / "data"
MALFORMED = DATA / "malformed"


def _has_law(name: str) -> bool:
    try:
        get_law(name)
    except UnknownLawError:
        return False
    return True


# (id, law, data, extra args, fragments that must all be in the message)
# data: a file in tests/data/malformed, a packaged dataset name, or a path that does not exist.
CASES = [
    ("missing-mu-column", "thirion", "missing_mu.csv", [],
     ["missing_mu.csv", "no friction coefficient column", "--map mu="]),
    ("non-numeric-cell", "thirion", "non_numeric.csv", [],
     ["non_numeric.csv", "column 'p [MPa]'", "row 3", "non-numeric value 'abc'"]),
    ("empty-file", "thirion", "empty.csv", [], ["empty.csv", "file is empty"]),
    ("comments-only", "thirion", "comments_only.csv", [],
     ["comments_only.csv", "file is empty"]),
    ("header-only", "thirion", "header_only.csv", [], ["header_only.csv", "no data rows"]),
    ("nan-everywhere-in-mu", "thirion", "nan_mu.csv", [],
     ["nan_mu.csv", "column 'mu'", "empty or NaN"]),
    ("negative-pressure", "thirion", "negative_pressure.csv", [],
     ["negative_pressure.csv", "column 'p [MPa]'", "row 4", "pressure must be >= 0"]),
    ("negative-mu", "thirion", "negative_mu.csv", [],
     ["negative_mu.csv", "column 'mu'", "row 3", "friction coefficient must be >= 0"]),
    ("duplicate-column", "thirion", "duplicate_column.csv", [],
     ["duplicate_column.csv", "column 'mu'", "duplicate column"]),
    ("two-columns-same-quantity", "thirion", "two_pressures.csv", [],
     ["two_pressures.csv", "pressure [bar]", "both give 'p'"]),
    ("unknown-unit", "thirion", "unknown_unit.csv", [],
     ["unknown_unit.csv", "column 'p [Mpa]'", "unknown unit 'Mpa'", "did you mean 'MPa'"]),
    ("wrong-dimension-unit", "thirion", "wrong_dimension.csv", [],
     ["wrong_dimension.csv", "column 'p [m/s]'", "expected a pressure"]),
    ("temperature-in-coulomb", "thirion", "temperature_coulomb.csv", [],
     ["temperature_coulomb.csv", "column 'T [C]'", "did you mean 'degC'"]),
    ("unknown-law", "no-such-law", "thesis-steel", [], ["unknown law 'no-such-law'"]),
    ("wrong-delimiter-pipe", "thirion", "pipe_delimiter.csv", [],
     ["pipe_delimiter.csv", "delimiter is not recognised", "';'"]),
    ("wrong-delimiter-in-row", "thirion", "mixed_delimiter.csv", [],
     ["mixed_delimiter.csv", "row 3", "another delimiter"]),
    ("binary-file", "thirion", "binary.csv", [], ["binary.csv", "not a text CSV file"]),
    ("missing-file", "thirion", "does_not_exist.csv", [],
     ["does_not_exist.csv", "file not found", "thesis-steel"]),
    ("mismatched-map", "thirion", "thesis-steel-original",
     ["--map", "mu=FC,p=PRESSURE", "--units", "p=MPa"],
     ["thesis-steel-original", "column 'PRESSURE'", "no such column",
      "FC, NL, CP, PV, DV"]),
    ("malformed-map-text", "thirion", "thesis-steel-original", ["--map", "mu"],
     ["--map", "NAME=VALUE"]),
    ("map-to-unknown-canonical", "thirion", "thesis-steel-original",
     ["--map", "friction_thing=FC"], ["friction_thing", "mu, p, v"]),
    ("column-without-unit", "thirion", "thesis-steel-original",
     ["--map", "mu=FC,p=CP,v=DV"],
     ["thesis-steel-original", "column 'CP'", "has no unit", "--units p=MPa"]),
    ("unknown-unit-option", "thirion", "thesis-steel-original",
     ["--map", "mu=FC,p=CP,v=DV", "--units", "p=MPa,v=furlongs/fortnight/x"],
     ["thesis-steel-original", "column 'DV'", "expected a velocity"]),
    ("bad-area-dimension", "thirion", "load_only.csv", ["--area", "314 mm"],
     ["load_only.csv", "--area '314 mm' is a length, expected an area"]),
    ("bad-area-no-unit", "thirion", "load_only.csv", ["--area", "0.000314"],
     ["load_only.csv", "has no unit"]),
    ("bad-area-text", "thirion", "load_only.csv", ["--area", "big"],
     ["load_only.csv", "--area 'big' is not a number with a unit"]),
    ("area-without-load", "thirion", "no_load.csv", ["--area", "314.16 mm^2"],
     ["no_load.csv", "needs a normal-load column F_N"]),
    ("below-absolute-zero", "thirion", "below_absolute_zero.csv", [],
     ["below_absolute_zero.csv", "column 'T [K]'", "row 3", "below absolute zero"]),
    ("law-needs-missing-variable", "thirion", "load_only.csv", [],
     ["load_only", "needs p"]),
]

SLIP_CASE = ("slip-law-on-sliding-data", "pacejka", "thesis-steel", [],
             ["pacejka", "thesis-steel", "slip ratio s"])


def _run(law: str, data: str, extra: list[str], tmp_path: Path,
         capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    if data == "no_load.csv":
        path = tmp_path / data
        path.write_text("mu,v [m/s]\n0.5,1\n0.6,2\n0.7,3\n", encoding="utf-8")
        target = str(path)
    elif data.endswith(".csv"):
        target = str(MALFORMED / data)
    else:
        target = data
    code = main(["fit", "--law", law, target, *extra])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def _check(code: int, out: str, err: str, fragments: list[str]) -> None:
    assert code == 2, (code, out, err)
    assert "Traceback" not in err and "Traceback" not in out
    assert err.endswith("\n") and err.count("\n") == 1, f"not one line: {err!r}"
    assert err.startswith("error: ")
    for frag in fragments:
        assert frag in err, f"{frag!r} not in {err!r}"


@pytest.mark.parametrize(("case", "law", "data", "extra", "fragments"), CASES,
                         ids=[c[0] for c in CASES])
def test_malformed_input_gives_exit_2_and_one_line(
    case: str, law: str, data: str, extra: list[str], fragments: list[str],
    tmp_path: Path, capsys: pytest.CaptureFixture[str],
) -> None:
    code, out, err = _run(law, data, extra, tmp_path, capsys)
    _check(code, out, err, fragments)


def test_slip_law_on_sliding_data(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    case, law, data, extra, fragments = SLIP_CASE
    if not _has_law(law):
        pytest.skip("law 'pacejka' is not registered yet")
    code, out, err = _run(law, data, extra, tmp_path, capsys)
    _check(code, out, err, fragments)


def test_at_least_fifteen_malformed_cases() -> None:
    assert len(CASES) >= 15


def test_thesis_original_columns_fit_like_the_packaged_dataset(
    capsys: pytest.CaptureFixture[str],
) -> None:
    """Done-when: the same fit works on the thesis' own column names via --map/--units."""
    import json

    assert main(["fit", "--law", "thirion", "thesis-steel", "--json"]) == 0
    ref = json.loads(capsys.readouterr().out)
    assert main(["fit", "--law", "thirion", "thesis-steel-original", "--map",
                 "mu=FC,p=CP,v=DV", "--units", "p=MPa,v=m/s", "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    for name in ("a", "b"):
        np.testing.assert_allclose(got["params"][name]["value"], ref["params"][name]["value"],
                                   rtol=1e-9)
        assert got["params"][name]["unit"] == ref["params"][name]["unit"]
    assert got["metrics"]["n"] == ref["metrics"]["n"] == 19
    np.testing.assert_allclose(got["metrics"]["r2"], ref["metrics"]["r2"], rtol=1e-9)


def test_dropped_rows_are_reported_by_fit(tmp_path: Path,
                                          capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "gaps.csv"
    lines = ["mu,p [MPa]"] + [f"{1 / (0.15 + 4.7 * p):.5f},{p}" for p in
                              (0.03, 0.06, 0.09, 0.12, 0.15, 0.18)]
    lines.insert(3, ",0.07")
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    assert main(["fit", "--law", "thirion", str(path)]) == 0
    out = capsys.readouterr().out
    assert "dropped 1 row (row 4): empty or NaN in column 'mu'" in out


@pytest.mark.parametrize(("extra", "fragments"), [
    (["--fix", "a=1_000"], ["--fix", "'a=1_000'", "not a number"]),
    (["--fix", "a=1", "--fix", "a=2"], ["--fix", "'a' is given twice"]),
    (["--units", "p=MPa", "--units", "p=kPa"], ["--units", "'p' is given twice"]),
    (["--seed", "-3"], ["--seed", "from 0 to"]),
    (["--starts", "-1"], ["--starts", "from 0 to 1000"]),
])
def test_malformed_options_give_exit_2_and_one_line(
    extra: list[str], fragments: list[str], capsys: pytest.CaptureFixture[str],
) -> None:
    code = main(["fit", "--law", "thirion", "thesis-steel", *extra])
    captured = capsys.readouterr()
    _check(code, captured.out, captured.err, fragments)


def test_malformed_stdin_is_named_stdin(monkeypatch: pytest.MonkeyPatch,
                                        capsys: pytest.CaptureFixture[str]) -> None:
    """``-`` as DATA: the message names <stdin>, not the private copy."""
    import io
    import sys

    raw = (MALFORMED / "non_numeric.csv").read_bytes()
    monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(raw), encoding="utf-8"))
    code = main(["fit", "--law", "thirion", "-"])
    captured = capsys.readouterr()
    _check(code, captured.out, captured.err,
           ["file '<stdin>'", "column 'p [MPa]'", "row 3", "non-numeric value 'abc'"])
