"""The table reader's column at once: the same numbers and refusals as cell by cell.

:func:`frictionlaws.base.numbers.parse_numbers` reads a column of plain numbers in one go and
the reader splits the rows of a file without quotes or comments at once; both must give
exactly what the cell-by-cell, line-by-line path gives (and leave everything else to it):
checked on generated cells, lines and whole files, hostile ones included.
"""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import frictionlaws.io.building as building
import frictionlaws.io.reading as reading
from frictionlaws.base.errors import InputError
from frictionlaws.base.numbers import parse_number, parse_numbers
from frictionlaws.io import load_dataset
from frictionlaws.io.reading import _split

NUMBERS = st.one_of(
    st.floats(allow_nan=False, allow_infinity=False).map(repr),
    st.integers(-10**30, 10**30).map(str),
    st.from_regex(r"[+-]?[0-9]{0,4}\.?[0-9]{0,4}([eE][+-]?[0-9]{1,3})?", fullmatch=True),
)
CELLS = st.one_of(
    NUMBERS,
    st.tuples(st.sampled_from(["", " ", "\t", "  "]), NUMBERS,
              st.sampled_from(["", " ", "\t"])).map("".join),
    st.sampled_from(["", " ", "nan", "NA", "-", "1_000", "１", "1e999", "0x10", "inf",
                     "1,5", "1.200", ",5", "5,", "\u00a01", "1 2", ".", "e5", "+", "1e"]),
)


def _one_by_one(cells, decimal_comma):
    out = []
    for cell in cells:
        if not cell.strip(" \t"):
            out.append(math.nan)
            continue
        try:
            out.append(parse_number(cell, decimal_comma=decimal_comma))
        except ValueError:
            return None
    return out


@settings(max_examples=300, deadline=None)
@given(st.lists(CELLS, min_size=1, max_size=12), st.booleans())
def test_a_column_at_once_reads_what_the_number_parser_reads(cells, decimal_comma):
    fast = parse_numbers(cells, decimal_comma=decimal_comma)
    if fast is None:  # left to the cell-by-cell path, with its messages
        return
    slow = _one_by_one(cells, decimal_comma)
    assert slow is not None, cells
    np.testing.assert_array_equal(fast, np.array(slow, float))


def test_a_column_of_hostile_cells_is_left_to_the_cell_by_cell_path():
    for cells in (["1", "nan"], ["1_000"], ["1e999"], ["\u00a01"], ["1,5"], ["inf"],
                  ["1\n2"], ["1.5"] * 100 + ["x"]):
        assert parse_numbers(cells) is None, cells
    assert parse_numbers(["1,5", "2"], decimal_comma=True).tolist() == [1.5, 2.0]
    assert parse_numbers(["1.5"], decimal_comma=True) is None  # ambiguous there: slow path


@settings(max_examples=200, deadline=None)
@given(st.text(alphabet='ab1. ,;\t-', max_size=40), st.sampled_from([",", ";", "\t"]))
def test_an_unquoted_line_is_split_as_the_csv_module_splits_it(line, delimiter):
    expected = next(csv.reader([line], delimiter=delimiter, skipinitialspace=True,
                               strict=True))
    assert _split(line, delimiter, "f.csv", 2) == expected


def _files():
    """Files the fast and the cell-by-cell paths must read alike (or refuse alike)."""
    yield "mu,p [MPa],v [m/s]\n0.5,0.1,1\n0.6, 0.2 ,2\n0.7,\t0.3,3\n"
    yield "mu,p [MPa]\n0.5,0.1\n,0.2\n0.7,nan\n0.8,0.4\n"            # dropped rows
    yield "mu;p [MPa]\n0,5;0,1\n0,6;0,2\n0,7;0,3\n"                    # decimal commas
    yield "mu;p [MPa]\n0.5;0.1\n0.6;0.2\n"                             # points with ';'
    yield "mu;p [MPa]\n0,5;1.200\n0,6;0,2\n"                           # ambiguous 1.200
    yield 'mu,p [MPa],surface\n0.5,0.1,"steel, wet"\n0.6,0.2,steel\n'   # quotes
    yield "mu,p [MPa]\n0.5,abc\n0.6,0.2\n"                             # text in a number
    yield "mu,p [MPa]\n0.5,1e999\n0.6,0.2\n"                           # overflow
    yield "mu,p [MPa]\n0.5,1_000\n0.6,0.2\n"                           # no underscores
    yield "mu,p [MPa]\n-0.5,0.1\n0.6,0.2\n"                            # negative mu
    yield "# provenance\nmu,p [MPa],v [m/s]\n\n0.5,0.1,1\n0.6,0.2,2,\n"


def _read(path):
    """What a file reads as (columns, notes, rows) or the message refusing it; then the
    same with the column-at-once and row-at-once paths switched off."""
    def read():
        try:
            ds = load_dataset(path)
        except InputError as exc:
            return str(exc)
        return {c: ds.column(c).tolist() for c in ds.column_names}, ds.notes, \
            ds.rows.tolist()

    fast = read()
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(building, "parse_numbers", lambda *a, **k: None)
        patch.setattr(reading, "_plain_rows", lambda *a: False)
        slow = read()
    return repr(fast), repr(slow)  # NaN included


@pytest.mark.parametrize("text", list(_files()))
def test_a_file_reads_alike_with_and_without_the_column_at_once(tmp_path, text):
    path = tmp_path / "data.csv"
    path.write_text(text)
    fast, slow = _read(path)
    assert fast == slow


@settings(max_examples=150, deadline=None)
@given(st.lists(st.lists(st.sampled_from(["0.5", " 1", "2 ", "", "x", "#3", '"4"', "5,5",
                                          " ", "\t6"]), min_size=1, max_size=4),
                min_size=1, max_size=6),
       st.sampled_from([",", ";", "\t"]))
def test_generated_files_read_alike_row_by_row(tmp_path_factory, rows, delimiter):
    header = delimiter.join(["mu", "p [MPa]", "v [m/s]", "note"])
    path = tmp_path_factory.mktemp("gen") / "data.csv"
    path.write_text("\n".join([header] + [delimiter.join(r) for r in rows]) + "\n")
    fast, slow = _read(path)
    assert fast == slow
