"""Security of files in and files out: one rule per class, each with generated cases.

* writers: every string from a user or a file reaches a generated file only through the
  sanitiser of its format (no added line, section, key, formula or markup);
* readers split lines only at ``\\n``, ``\\r\\n`` and ``\\r``;
* units and numbers are read by one grammar, with no arithmetic: hostile ones are refused
  within a second;
* every input is bounded (size, standard input too, nesting depth, message length);
* regular expressions on user text run in linear time;
* connecting to a Dask scheduler has one overall deadline, and its error names the cause;
* outputs keep the permissions of the file they replace, and a failed command leaves none.
"""

from __future__ import annotations

import contextlib
import csv
import functools
import io
import math
import os
import re
import socket
import threading
import time
import unicodedata
from collections.abc import Iterator
from pathlib import Path

import pytest
from hostile import (
    MF52_TIR,
    NASTY_NUMBERS,
    Snapshot,
    check_outcome,
    hostile,
    run_cli,
    tcp_peer,
    time_limit,
)
from hypothesis import example, given
from hypothesis import strategies as st

pytestmark = pytest.mark.hostile

#: Every character another tool may read as the end of a line, and other controls.
BREAKS = ["\n", "\r", "\r\n", "\v", "\f", "\x1c", "\x1d", "\x1e", "\x85", "\u2028",
          "\u2029", "\t", "\x1b", "\u202e", "\u200b", "\x7f"]
#: What an attacker would put on the next line of each format.
PAYLOADS = ["*KEYWORD", "*END", "$ x", "[MODEL]", "FNOMIN = 1", "# x", "=1+1", "+A1", "-2+3",
            "@SUM(A1)", "<script>x</script>", "## heading", "1,2,3", "'", '"', "|", "`",
            "[a](javascript:x)", "C", "      stop", "0.5,0.1"]
text_piece = st.one_of(st.sampled_from(BREAKS), st.sampled_from(PAYLOADS),
                       st.text(max_size=4))
hostile_text = st.lists(text_piece, min_size=1, max_size=8).map("".join)
#: Hostile text that can be a file name (no '/', no NUL, not too long).
hostile_name = hostile_text.map(
    lambda s: s.replace("/", "_").replace("\x00", "_").replace(".", "_")[:60] or "x")

GOOD_CSV = "mu,p [MPa]\n0.62,0.03\n0.55,0.06\n0.5,0.09\n0.46,0.12\n0.43,0.15\n"
PARAMS = '{"law": "thirion", "params": {"a": 1.2, "b": 3.5e-6}}'


def _one_line(text: str) -> bool:
    """No character any reader could take as a line end or a control."""
    return not any(unicodedata.category(ch) in ("Cc", "Cf", "Zl", "Zp") for ch in text)


# ------------------------------------------------------------------ writers


@hostile(120)
@given(text=hostile_text)
def test_every_sanitiser_keeps_text_on_one_line_and_inert(text: str) -> None:
    from frictionlaws.base.numbers import is_number
    from frictionlaws.base.sanitize import (
        ascii_line,
        comment_lines,
        csv_cell,
        csv_cell_text,
        html_text,
        markdown_text,
        one_line,
        tir_string,
    )

    for out in (one_line(text), ascii_line(text), csv_cell(text), markdown_text(text),
                html_text(text), tir_string(text)):
        assert _one_line(out), repr(out)
    assert ascii_line(text).isascii() and tir_string(text).isascii()
    assert "'" not in tir_string(text)
    cell = csv_cell(text)
    assert csv_cell_text(cell) == one_line(text)
    assert not (cell.lstrip()[:1] in ("=", "+", "-", "@") and len(cell.strip()) > 1
                and not is_number(cell)), repr(cell)
    md = markdown_text(text)
    assert "<" not in md and ">" not in md
    assert not re.search(r"(?<!\\)[|`\[\]]", md.replace("\\\\", "")), repr(md)
    assert all(line.startswith("#") for line in comment_lines(text.split("\n")))


def _code_lines(text: str, comment: tuple[str, ...]) -> list[str]:
    return [ln for ln in text.split("\n") if not ln.startswith(comment)]


DECKS = [("abaqus", ("**",)), ("lsdyna", ("$",)), ("ansys", ("!",)), ("radioss", ("#",)),
         ("csv", ("#",)), ("abaqus-vfric", ("C", "!"))]


@pytest.fixture(scope="module")
def baseline_decks(tmp_path_factory: pytest.TempPathFactory) -> dict[str, str]:
    tmp = tmp_path_factory.mktemp("decks")
    (tmp / "params.json").write_text(PARAMS, encoding="utf-8")
    out = {}
    for fmt, _ in DECKS:
        res = run_cli(["export", "--params", str(tmp / "params.json"), "--format", fmt,
                       "--p", "0.01:0.5:4", "--units", "mm-N-s", "-o", str(tmp / f"o.{fmt}")])
        assert res.code == 0, res.describe()
        out[fmt] = (tmp / f"o.{fmt}").read_text(encoding="utf-8")
    return out


@hostile(4)
@given(name=hostile_name)
@pytest.mark.parametrize(("fmt", "comment"), DECKS)
def test_a_hostile_source_name_adds_no_line_to_a_deck(
        tmp_path_factory: pytest.TempPathFactory, baseline_decks: dict[str, str], fmt: str,
        comment: tuple[str, ...], name: str) -> None:
    tmp = tmp_path_factory.mktemp("deck")
    params = tmp / f"{name}.json"
    params.write_text(PARAMS, encoding="utf-8")
    out = tmp / f"o.{fmt}"
    res = run_cli(["export", "--params", str(params), "--format", fmt, "--p", "0.01:0.5:4",
                   "--units", "mm-N-s", "-o", str(out)])
    check_outcome(res, codes=[0])
    text = out.read_text(encoding="utf-8")
    assert text.isascii() and _one_line(text.replace("\n", ""))
    assert _code_lines(text, comment) == _code_lines(baseline_decks[fmt], comment)


@hostile(10)
@given(comment=hostile_text, header=hostile_text, value=hostile_text)
def test_a_tir_file_written_from_hostile_text_reads_back_with_the_same_keys(
        comment: str, header: str, value: str) -> None:
    from frictionlaws.tyre.tir import format_tir, read_property_file, read_tir

    pf = read_property_file(MF52_TIR)
    pf.comments[("MODEL", "FITTYP")] = comment
    pf.sections["MODEL"]["TYRESIDE"] = value
    text = format_tir(pf, header=[header, "second"])
    assert text.isascii()
    back = read_tir(text)
    assert {s: set(e) for s, e in back.sections.items()} == \
        {s: set(e) for s, e in pf.sections.items()}
    assert back.sections["MODEL"]["FITTYP"] == pf.sections["MODEL"]["FITTYP"]
    assert all(ln.startswith("!") for ln in text.split("\n")[:2])


@hostile(15)
@given(name=st.sampled_from(["FNOMIN = 1 $", "A]\n[MODEL", "x y", "1ABC", "K\u2028FNOMIN", ""]),
       where=st.sampled_from(["section", "key"]))
def test_a_json_property_file_with_a_name_a_tir_cannot_hold_is_refused(
        tmp_path_factory: pytest.TempPathFactory, name: str, where: str) -> None:
    import json

    from frictionlaws.base.errors import InputError
    from frictionlaws.tyre.tir import read_property_file

    doc = {"MODEL": {"FITTYP": 6}, "VERTICAL": {"FNOMIN": 4000.0}}
    if where == "section":
        doc[name] = {"A": 1.0}
    else:
        doc["VERTICAL"][name] = 1.0
    path = tmp_path_factory.mktemp("json") / "p.json"
    path.write_text(json.dumps(doc), encoding="utf-8")
    with pytest.raises(InputError, match="not a property-file name"):
        read_property_file(path)


@hostile(15)
@given(provenance=hostile_text, surfaces=st.lists(hostile_text, min_size=2, max_size=4))
def test_a_dataset_written_with_hostile_provenance_and_cells_reads_back_row_for_row(
        tmp_path_factory: pytest.TempPathFactory, provenance: str, surfaces: list[str]) -> None:
    import numpy as np

    from frictionlaws.io import Dataset

    n = len(surfaces)
    ds = Dataset({"mu": np.linspace(0.3, 0.6, n), "p": np.linspace(1e5, 2e5, n),
                  "surface": np.array(surfaces, dtype=object)}, "x", "<test>",
                 provenance=provenance)
    path = ds.to_csv(tmp_path_factory.mktemp("ds") / "ds.csv")
    text = path.read_text(encoding="utf-8")
    body = [ln for ln in text.split("\n") if ln and not ln.startswith("#")]
    rows = list(csv.reader(io.StringIO("\n".join(body))))
    assert len(rows) == n + 1, text
    for row in rows[1:]:
        cell = row[-1]
        assert _one_line(cell) and not cell.startswith(("=", "+", "@")), repr(cell)


@hostile(10)
@given(comments=st.lists(hostile_text, min_size=1, max_size=3),
       groups=st.lists(hostile_text, min_size=1, max_size=3))
def test_a_processed_table_keeps_hostile_comments_and_groups_inert(
        comments: list[str], groups: list[str]) -> None:
    import pandas as pd

    from frictionlaws.io import read_table
    from frictionlaws.tribometer.process.results import _csv_text

    frame = pd.DataFrame({"surface": groups, "mu": [0.5] * len(groups)})
    text = _csv_text(frame, comments)
    table = read_table("t.csv", raw=text.encode("utf-8"), source="t.csv")
    assert len(table.rows) == len(groups)
    assert len(table.comments) == len(comments)
    assert not any(str(c).startswith(("=", "+", "@")) for c in table.columns[0])


@pytest.mark.slow
def test_a_hostile_dataset_name_adds_no_markup_or_heading_to_the_markdown_report(
        tmp_path: Path) -> None:
    data = tmp_path / "a<b>\u2028## heading\n<img src=x>|x.csv"
    data.write_text(GOOD_CSV, encoding="utf-8")
    res = run_cli(["compare", "--laws", "thirion,coulomb", str(data), "--report",
                   str(tmp_path / "rep")], timeout=60)
    check_outcome(res, codes=[0, 1])
    md = (tmp_path / "rep" / "report.md").read_text(encoding="utf-8")
    assert "<img" not in md and "<b>" not in md
    assert not [ln for ln in md.split("\n") if ln.startswith("## heading")]
    assert _one_line(md.replace("\n", ""))


def test_a_unit_is_written_in_canonical_form_not_as_typed(tmp_path: Path) -> None:
    (tmp_path / "p.json").write_text(PARAMS, encoding="utf-8")
    out = tmp_path / "o.csv"
    res = run_cli(["export", "--params", str(tmp_path / "p.json"), "--format", "csv",
                   "--p", "0.01:0.5:3", "--units", "p=N / mm**2", "-o", str(out)])
    check_outcome(res, codes=[0])
    assert "p [N/mm^2]" in out.read_text(encoding="utf-8")


@hostile(12)
@given(unit=st.lists(st.sampled_from(["MPa", " ", "\u2028", "\n", "*KEYWORD", "/", "mm^2", "N",
                                      "\r", "# x", "=1", "kPa", "\x85", "**2"]),
                     min_size=1, max_size=5).map("".join))
def test_a_unit_option_reaches_a_deck_only_in_canonical_form(
        tmp_path_factory: pytest.TempPathFactory, unit: str) -> None:
    tmp = tmp_path_factory.mktemp("units")
    (tmp / "p.json").write_text(PARAMS, encoding="utf-8")
    out = tmp / "o.csv"
    res = run_cli(["export", "--params", str(tmp / "p.json"), "--format", "csv", "--p",
                   "0.01:0.5:3", "--units", f"mm-N-s,p={unit}", "-o", str(out)])
    check_outcome(res, codes=[0, 2])
    if res.code == 0:
        lines = out.read_text(encoding="utf-8").split("\n")
        header = next(ln for ln in lines if ln and not ln.startswith("#"))
        assert re.fullmatch(r"p \[[A-Za-z]+(\^\d)?(/[A-Za-z]+(\^\d)?)*\],mu \[-\]", header), header
        assert all(_one_line(ln) for ln in lines)


# ------------------------------------------------------------------ readers


@hostile(25)
@given(sep=st.sampled_from([b for b in BREAKS if b not in ("\n", "\r", "\r\n", "\t")]),
       n=st.integers(2, 6))
def test_a_line_separator_inside_a_cell_does_not_split_the_row(sep: str, n: int) -> None:
    from frictionlaws.io import load_dataset

    rows = "".join(f"0.{5 + i},{0.1 * (i + 1):g},steel{sep if i == 1 else ''}x\n"
                   for i in range(n))
    text = "mu,p [MPa],surface\n" + rows
    ds = load_dataset(_tmp_csv(text))
    assert len(ds) == n == len(list(csv.reader(io.StringIO(text, newline="")))) - 1


@functools.lru_cache(maxsize=1)
def _tmp_dir() -> Path:
    """One folder for the generated files of this module, removed when the run ends
    (hypothesis' examples cannot use the function-scoped ``tmp_path``)."""
    import atexit
    import shutil
    import tempfile

    path = Path(tempfile.mkdtemp(prefix="frictionlaws-hostile-"))
    atexit.register(shutil.rmtree, path, ignore_errors=True)
    return path


def _tmp_csv(text: str) -> Path:
    import tempfile

    fd, name = tempfile.mkstemp(suffix=".csv", dir=_tmp_dir())
    with os.fdopen(fd, "w", encoding="utf-8", newline="") as fh:
        fh.write(text)
    return Path(name)


@hostile(15)
@given(sep=st.sampled_from(["\u2028", "\u2029", "\x85", "\v", "\f", "\x1c", "\x1e"]))
def test_a_tir_comment_holding_a_line_separator_stays_a_comment(sep: str) -> None:
    from frictionlaws.tyre.tir import read_tir

    original = MF52_TIR.read_text(encoding="utf-8")
    text = original.replace("[MODEL]", f"$ note{sep}FNOMIN = 1\n[MODEL]", 1)
    text = text.replace("[VERTICAL]", f"[VERTICAL]\n$ x{sep}[MODEL]", 1)
    pf = read_tir(text)
    assert pf.sections["VERTICAL"]["FNOMIN"] == read_tir(original).sections["VERTICAL"]["FNOMIN"]


# ------------------------------------------------------------------ units and numbers

unit_name = st.sampled_from(["m", "MPa", "N", "mm", "s", "degC", "kg", "h", "%", "x", "1", "2"])
huge = st.sampled_from(["99999999", "9**9**9", "2**99999999", "1e999", "10**10**10",
                        "-99999", "0.5", "(2)", "9" * 40])


def _power(draw: st.DrawFn) -> str:
    base = draw(unit_name)
    op = draw(st.sampled_from(["**", "^", " ** ", "*", "/"]))
    return f"{base}{op}{draw(huge)}"


@st.composite
def hostile_unit(draw: st.DrawFn) -> str:
    kind = draw(st.integers(0, 3))
    if kind == 0:
        return _power(draw)
    if kind == 1:
        depth = draw(st.integers(1, 400))
        return "(" * depth + draw(unit_name) + ")" * depth
    if kind == 2:
        return draw(st.sampled_from(["1e999 m", "2**9**9 m", "m" * 100000, "N/" * 5000 + "m"]))
    return "*".join(_power(draw) for _ in range(draw(st.integers(1, 30))))


@hostile(40)
@given(unit=hostile_unit())
def test_a_hostile_unit_is_refused_within_a_second(unit: str) -> None:
    from frictionlaws.base.errors import InputError
    from frictionlaws.base.units import parse_quantity, to_si, unit_registry

    unit_registry()
    t0 = time.perf_counter()
    with time_limit(2.0):
        for call in (lambda: to_si(1.0, unit, "p"), lambda: parse_quantity(f"1 {unit}", "p"),
                     lambda: parse_quantity(unit, "length")):
            try:
                call()
            except InputError as exc:
                assert len(str(exc)) < 2100
    assert time.perf_counter() - t0 < 1.0


@hostile(60)
@given(text=st.text(alphabet="mNs()*/^ 0123456789-²", max_size=20))
def test_the_unit_grammar_reads_or_refuses_every_text_it_is_given(text: str) -> None:
    from frictionlaws.base.units import MAX_UNIT_EXPONENT, UnitSyntaxError, parse_unit_text

    try:
        parsed = parse_unit_text(text)
    except UnitSyntaxError:
        return
    assert all(abs(e) <= MAX_UNIT_EXPONENT for _, e in parsed.factors)
    assert parse_unit_text(parsed.canonical()) == parsed


unit_text = st.lists(st.one_of(st.sampled_from(["MPa", "N", "mm", "km", "h", "s", "degC", "kgf",
                                                 "psi", "bar", "%", "m", "kg"]),
                                st.sampled_from(["*", "/", " ", "^2", "**-1", "²", "(", ")",
                                                 "1/", "**3", "·"])),
                     min_size=1, max_size=7).map("".join)


@contextlib.contextmanager
def _pint_inputs() -> Iterator[list[str]]:
    """Every text handed to pint's parsers while the block runs."""
    from frictionlaws.base.units import unit_registry

    ureg = unit_registry()
    seen: list[str] = []
    names = [n for n in ("parse_units", "parse_expression", "parse_units_as_container",
                         "parse_pattern") if hasattr(type(ureg), n)]  # pint 0.22 has fewer
    originals = {n: getattr(ureg, n) for n in names}

    def spy(name: str) -> object:
        def call(text: object, *args: object, **kwargs: object) -> object:
            seen.append(str(text))
            return originals[name](text, *args, **kwargs)
        return call

    for n in names:
        setattr(ureg, n, spy(n))
    try:
        yield seen
    finally:
        for n in names:
            delattr(ureg, n)


@hostile(40)
@given(unit=unit_text, kind=st.sampled_from(["p", "v", "T", "F_N", "length", "area"]))
def test_pint_sees_only_single_unit_names_never_an_expression(unit: str, kind: str) -> None:
    from frictionlaws.base import units
    from frictionlaws.base.errors import InputError
    from frictionlaws.base.units import QUANTITIES, parse_quantity, to_si

    # the library's own units: the table's, and the representative unit of each dimension
    # that names what a wrong unit is (``m**2`` for "an area"), never text from the input
    constants = ({q.si for q in QUANTITIES.values()} | {q.display for q in QUANTITIES.values()}
                 | {u for u, _ in units._DIMENSION_NAMES})
    with _pint_inputs() as seen:
        for call in (lambda: to_si(2.0, unit, kind), lambda: parse_quantity(f"2 {unit}", kind)):
            with contextlib.suppress(InputError):
                call()
    names = re.compile(r"[^\W\d][\w\u00b0]*|%|dimensionless")
    assert all(names.fullmatch(t) or t in constants for t in seen), (unit, seen)


def test_a_dataset_keeps_its_units_in_canonical_form() -> None:
    from frictionlaws.io import load_dataset

    ds = load_dataset(_tmp_csv("mu,p [N / mm**2],v [km / h]\n0.5,1,2\n0.4,2,3\n"))
    assert (ds.units["p"], ds.units["v"]) == ("N/mm^2", "km/h")


@hostile(60)
@given(bound=st.sampled_from(NASTY_NUMBERS + ["2**9**9", "1e5**9", "(1)", "1_0 MPa"]),
       count=st.sampled_from(["3", "\uff13", "1_0", "9" * 30, "-2", "3.0"]),
       where=st.integers(0, 2))
def test_every_number_of_a_range_goes_through_the_one_number_parser(
        bound: str, count: str, where: int) -> None:
    from frictionlaws.base.errors import InputError
    from frictionlaws.base.numbers import parse_number
    from frictionlaws.fe_export.api import parse_range

    parts = ["0.01", "0.5", "3"]
    parts[where] = bound if where < 2 else count
    try:
        spec = parse_range("p", ":".join(parts), "mm-N-s")
    except InputError:
        return
    assert all(map(math.isfinite, (spec.lo, spec.hi)))
    if where < 2:
        assert [spec.lo, spec.hi][where] == pytest.approx(parse_number(bound) * 1e6)
    else:
        assert count.isascii() and count.isdigit() and spec.n == int(count)


@pytest.mark.parametrize(("value", "fragment"), [("1e999", "overflows"),
                                                 ("1" + "0" * 5000, "limit of 40")])
def test_a_json_number_beyond_the_limits_is_refused(tmp_path: Path, value: str,
                                                    fragment: str) -> None:
    params = tmp_path / "p.json"
    params.write_text(PARAMS.replace("1.2", value), encoding="utf-8")
    res = run_cli(["export", "--params", str(params), "--format", "csv", "--p", "0.01:0.5:3",
                   "-o", str(tmp_path / "o.csv")])
    check_outcome(res, codes=[2])
    assert fragment in res.err


@hostile(80)
@given(unit=st.text(max_size=16) | st.text(alphabet="mNsPak\u00b0\u00b5_()*/^ 019-\u00b2%.e",
                                             max_size=16),
       kind=st.sampled_from(["p", "v", "T", "F_N", "s", "angle", "mu"]))
@example(unit="_", kind="p")
@example(unit="N_", kind="F_N")
def test_any_unit_text_is_read_or_refused_as_bad_input(unit: str, kind: str) -> None:
    from frictionlaws.base.errors import InputError
    from frictionlaws.base.units import canonical_unit, parse_quantity, to_si

    for call in (lambda: to_si(1.0, unit, kind), lambda: parse_quantity(f"1 {unit}", kind),
                 lambda: canonical_unit(unit, kind)):
        with contextlib.suppress(InputError):
            call()


BAD_UNIT = "m**99999999"


def _unit_cases() -> list[tuple[str, list[str], str]]:
    return [
        ("header", ["fit", "--law", "thirion", "{tmp}/bad.csv"], "column"),
        ("units", ["fit", "--law", "thirion", "{tmp}/plain.csv", "--units", f"p={BAD_UNIT}"],
         "power"),
        ("export-units", ["export", "--params", "{tmp}/p.json", "--format", "csv", "--p",
                          "0.01:0.5:3", "--units", "p=N/(mm^2)^99", "-o", "{tmp}/o.csv"],
         "power"),
        ("range", ["export", "--params", "{tmp}/p.json", "--format", "csv", "--p",
                   "0.01:2**9**9 MPa:3", "-o", "{tmp}/o.csv"], "--p"),
        ("load-unit", ["tyre", "cornering", "--law", "coulomb", "--set", "mu0=0.9",
                       "--load-unit", BAD_UNIT], "--load-unit"),
        ("c-py", ["tyre", "cornering", "--law", "coulomb", "--set", "mu0=0.9", "--c-py",
                  "1 N/m**99999999"], "--c-py"),
        ("tir", ["tyre", "mf", "{tmp}/bad.tir"], "UNITS"),
    ]


@pytest.mark.parametrize(("case", "argv", "fragment"), _unit_cases(),
                         ids=[c[0] for c in _unit_cases()])
def test_a_hostile_unit_from_any_source_is_refused_quickly(
        tmp_path: Path, case: str, argv: list[str], fragment: str) -> None:
    (tmp_path / "plain.csv").write_text(GOOD_CSV.replace(" [MPa]", ""), encoding="utf-8")
    (tmp_path / "bad.csv").write_text(GOOD_CSV.replace("[MPa]", f"[{BAD_UNIT}]"),
                                      encoding="utf-8")
    (tmp_path / "p.json").write_text(PARAMS, encoding="utf-8")
    tir = MF52_TIR.read_text(encoding="utf-8")
    (tmp_path / "bad.tir").write_text(tir.replace("FORCE                      = 'newton'",
                                                  "FORCE = 'N**99999999'", 1),
                                      encoding="utf-8")
    res = run_cli([a.replace("{tmp}", str(tmp_path)) for a in argv], timeout=10)
    check_outcome(res, codes=[2])
    assert fragment in res.err and res.seconds < 5, res.describe()


def test_a_hostile_unit_in_a_rig_file_is_refused(small_campaign: Path, tmp_path: Path) -> None:
    rig = (small_campaign / "rig.toml").read_text(encoding="utf-8")
    for bad in ('g = "2**9**9 m/s^2"', 'g = "9.8 m/s**99999999"'):
        path = tmp_path / "rig.toml"
        path.write_text(rig.replace('g = "9.8 m/s^2"', bad), encoding="utf-8")
        res = run_cli(["process", str(small_campaign / "manifest.csv"), "--rig", str(path),
                       "-o", str(tmp_path / "ds.csv"), "--jobs", "1"], timeout=10)
        check_outcome(res, codes=[2])
        assert "'g'" in res.err and res.seconds < 5


# ------------------------------------------------------------------ bounds


@pytest.mark.parametrize("deep", [
    'x = ' + "[" * 5000 + "]" * 5000 + "\n",
    'x = ' + "{a = " * 3000 + "1" + "}" * 3000 + "\n",
    'x = ' + "[" * 40 + "]" * 40 + "\n",
], ids=["arrays", "inline-tables", "past-the-limit"])
def test_a_deeply_nested_rig_file_is_refused_naming_the_limit(
        small_campaign: Path, tmp_path: Path, deep: str) -> None:
    rig = tmp_path / "rig.toml"
    rig.write_text(deep, encoding="utf-8")
    res = run_cli(["process", str(small_campaign / "manifest.csv"), "--rig", str(rig),
                   "-o", str(tmp_path / "ds.csv")])
    check_outcome(res, codes=[2])
    assert "nested deeper than the limit of 32" in res.err


@pytest.fixture
def small_limit(monkeypatch: pytest.MonkeyPatch) -> int:
    from frictionlaws.base import limits

    monkeypatch.setattr(limits, "MAX_INPUT_BYTES", 200)
    return 200


def test_an_input_file_larger_than_the_limit_is_refused(tmp_path: Path,
                                                       small_limit: int) -> None:
    data = tmp_path / "big.csv"
    data.write_text(GOOD_CSV * 4, encoding="utf-8")
    res = run_cli(["fit", "--law", "thirion", str(data)])
    check_outcome(res, codes=[2])
    assert f"limit of {small_limit} bytes" in res.err


def test_standard_input_larger_than_the_limit_is_refused(small_limit: int) -> None:
    res = run_cli(["fit", "--law", "thirion", "-"], stdin=(GOOD_CSV * 40).encode())
    check_outcome(res, codes=[2])
    assert f"limit of {small_limit} bytes" in res.err and "stdin" in res.err


@hostile(3)
@given(ncols=st.sampled_from([20000, 100000]))
def test_a_table_with_very_many_columns_gives_a_short_message(
        tmp_path_factory: pytest.TempPathFactory, ncols: int) -> None:
    path = tmp_path_factory.mktemp("wide") / "wide.csv"
    path.write_text(",".join(f"column{j}" for j in range(ncols)) + "\n"
                    + ",".join("1" for _ in range(ncols)) + "\n", encoding="utf-8")
    res = run_cli(["fit", "--law", "thirion", str(path)], timeout=20)
    check_outcome(res, codes=[2])
    assert max(len(ln) for ln in res.err.split("\n")) <= 2100


# ------------------------------------------------------------------ regular expressions


_OLD_HEADER = re.compile(r"^(?P<name>.*?)\s*\[(?P<unit>[^\[\]]*)\]\s*$")


@hostile(200)
@given(h=st.text(alphabet="p []x\t", max_size=12))
def test_the_linear_header_rule_reads_headers_as_the_pattern_did(h: str) -> None:
    from frictionlaws.io import split_header

    m = _OLD_HEADER.match(h)
    expected = (m.group("name").strip(), m.group("unit").strip()) if m else (h.strip(), None)
    assert split_header(h) == expected


@hostile(4)
@given(pad=st.sampled_from([" ", " \u00a0", "\u3000"]), n=st.sampled_from([30000, 60000]))
def test_a_header_cell_padded_with_spaces_is_read_in_linear_time(pad: str, n: int) -> None:
    from frictionlaws.io import load_dataset

    path = _tmp_csv(f"mu,p{pad * n}x,v{pad * n}[m/s,T{pad * n}[degC]\n0.5,1,2,3\n0.4,2,3,4\n")
    with time_limit(2.0):
        ds = load_dataset(path)
    assert list(ds.column("T", float)) == pytest.approx([276.15, 277.15])


def test_a_long_number_option_is_read_in_linear_time(tmp_path: Path) -> None:
    (tmp_path / "p.json").write_text(PARAMS, encoding="utf-8")
    res = run_cli(["export", "--params", str(tmp_path / "p.json"), "--format", "csv",
                   "--p", "0.01:" + "1" * 20000 + "x:3", "-o", str(tmp_path / "o.csv")],
                  timeout=5)
    check_outcome(res, codes=[2])
    assert res.seconds < 2


@pytest.mark.parametrize("line", ["FNOMIN = " + "1" * 40000 + "x",
                                  "FNOMIN = '" + "1" * 40000,
                                  "{" + "} " * 40000 + "x"])
def test_a_long_tir_line_is_read_in_linear_time(line: str) -> None:
    from frictionlaws.base.errors import InputError
    from frictionlaws.tyre.tir import read_tir

    with time_limit(2.0), contextlib.suppress(InputError):
        read_tir(f"[VERTICAL]\n{line}\n")


@hostile(6)
@given(word=st.sampled_from(["/", "a/", "site-packages/", "C:\\", "'"]),
       n=st.sampled_from([20000, 100000]))
def test_a_long_message_is_cleaned_in_linear_time(word: str, n: int) -> None:
    from frictionlaws.cli import _clean

    with time_limit(1.0):
        text = _clean(word * n)
    assert len(text) <= 2100


# ------------------------------------------------------------------ network


@pytest.fixture
def silent_peer() -> Iterator[str]:
    """A TCP server on 127.0.0.1 that accepts and never says a word."""
    yield from tcp_peer([])


@pytest.mark.slow
def test_a_peer_that_accepts_and_never_answers_fails_within_the_deadline(
        tmp_path: Path, silent_peer: str, monkeypatch: pytest.MonkeyPatch) -> None:
    pytest.importorskip("distributed")
    from frictionlaws.parallel import _network

    monkeypatch.setattr(_network, "CONNECT_TIMEOUT", 2.0)
    data = tmp_path / "d.csv"
    data.write_text("mu,p [MPa],surface\n" + "".join(
        f"0.{6 - i},0.0{i + 3},{s}\n" for s in ("a", "b") for i in range(4)), encoding="utf-8")
    snap = Snapshot.take([tmp_path])
    res = run_cli(["fit", "--law", "thirion", str(data), "--by", "surface", "--scheduler",
                   silent_peer], timeout=15)
    check_outcome(res, snapshot=snap, codes=[2])
    assert "no Dask handshake within 2 s" in res.err and res.seconds < 6


def test_a_peer_that_answers_garbage_is_named_not_dask() -> None:
    pytest.importorskip("distributed")
    from frictionlaws.base.errors import InputError
    from frictionlaws.parallel._network import connect_scheduler

    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(4)
    held: list[socket.socket] = []

    def reply() -> None:
        for _ in range(2):  # the plain TCP check, then the Dask handshake
            conn, _ = server.accept()
            conn.sendall(b"HTTP/1.1 400 Bad Request\r\n\r\n" * 4)
            held.append(conn)

    threading.Thread(target=reply, daemon=True).start()
    t0 = time.perf_counter()
    with time_limit(6.0), pytest.raises(InputError, match="not answer in the Dask protocol"):
        connect_scheduler(f"tcp://127.0.0.1:{server.getsockname()[1]}", timeout=2.0)
    assert time.perf_counter() - t0 < 1.5
    for conn in held:
        conn.close()
    server.close()


# ------------------------------------------------------------------ outputs


def test_an_output_keeps_the_permissions_of_the_file_it_replaces(tmp_path: Path) -> None:
    data = tmp_path / "d.csv"
    data.write_text(GOOD_CSV, encoding="utf-8")
    saved = tmp_path / "fit.json"
    saved.write_text("{}", encoding="utf-8")
    saved.chmod(0o600)
    res = run_cli(["fit", "--law", "thirion", str(data), "--save", str(saved)])
    check_outcome(res, codes=[0])
    assert saved.stat().st_mode & 0o777 == 0o600 and saved.read_text() != "{}"


@pytest.mark.parametrize("plots", ["ds.csv", "ds.csv/sub", "plots"])
def test_a_failing_process_leaves_no_dataset_behind(small_campaign: Path, plots: str) -> None:
    (small_campaign / "plots" / "conditions.png").mkdir(parents=True, exist_ok=True)
    snap = Snapshot.take([small_campaign])
    res = run_cli(["process", str(small_campaign / "manifest.csv"), "--rig",
                   str(small_campaign / "rig.toml"), "-o", str(small_campaign / "ds.csv"),
                   "--plots", str(small_campaign / plots), "--jobs", "1"], timeout=60)
    check_outcome(res, snapshot=snap, codes=[2])
    assert not (small_campaign / "ds.csv").exists()
