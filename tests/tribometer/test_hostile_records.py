"""Hostile-input harness for raw tribometer records.

A record follows the table rules of every other input (datasets, manifests): the one
encoding rule, a ``;``, tab or ``,`` delimiter read from the header line, decimal commas
with ``;`` or tab.  Whatever the layout, the values read are the values written; every
refusal names the file, the column and the row, and says what was expected.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hostile import hostile
from hypothesis import example, given
from hypothesis import strategies as st

from frictionlaws.base.errors import InputError
from frictionlaws.tribometer.records import read_record

#: The fast cases belong to the hostile harness (CI budget 60 s); the ones that process a
#: campaign run with the ordinary suite.
HOSTILE = pytest.mark.hostile

HEADER = ["time [s]", "torque [N m]", "disc_speed [rpm]"]
TIME = [0.0, 0.01, 0.02, 0.03, 0.04, 0.05]
TORQUE = [0.3012, 0.2987, 1.25, -0.5, 12.0, 0.0]
SPEED = [0.0, 331.5, 331.0, 330.25, 331.0, 331.75]
RPM = 2 * np.pi / 60


def _text(delimiter: str, decimal_comma: bool, comments: bool, quoted: bool,
          cells: dict[tuple[int, int], str] | None = None) -> str:
    rows = []
    for i in range(len(TIME)):
        row = [repr(TIME[i]), repr(TORQUE[i]), repr(SPEED[i])]
        if decimal_comma:
            row = [c.replace(".", ",") for c in row]
        for (r, j), cell in (cells or {}).items():
            if r == i:
                row[j] = cell
        if quoted:
            row = [f'"{c}"' for c in row]
        rows.append(delimiter.join(row))
    head = delimiter.join(f'"{h}"' if quoted else h for h in HEADER)
    lines = (["# logger v2", ""] if comments else []) + [head] + rows
    return "\n".join(lines) + "\n"


LAYOUTS = st.sampled_from([(",", False), (";", False), (";", True), ("\t", False),
                           ("\t", True)])
ENCODINGS = st.sampled_from(["utf-8", "utf-8-sig", "utf-16", "cp1252"])


@HOSTILE
@hostile(40)
@example(layout=(";", False), encoding="utf-8", newline="\n", comments=False, quoted=False)
@example(layout=(";", True), encoding="utf-16", newline="\r\n", comments=True, quoted=False)
@given(layout=LAYOUTS, encoding=ENCODINGS, newline=st.sampled_from(["\n", "\r\n"]),
       comments=st.booleans(), quoted=st.booleans())
def test_every_layout_reads_the_values_written(tmp_path: Path, layout: tuple[str, bool],
                                               encoding: str, newline: str, comments: bool,
                                               quoted: bool) -> None:
    """A ';' record used to read as one column ('missing columns'); now every layout reads."""
    delimiter, comma = layout
    text = _text(delimiter, comma, comments, quoted).replace("\n", newline)
    path = tmp_path / "r.csv"
    path.write_bytes(text.encode(encoding))
    rec = read_record(path)
    np.testing.assert_allclose(rec.time, TIME)
    np.testing.assert_allclose(rec.torque, TORQUE)
    np.testing.assert_allclose(rec.disc_speed, np.array(SPEED) * RPM)


CELLS = [
    # (cell, layout, words the message must contain)
    ("inf", (",", False), ["infinite", "expected a finite number"]),
    ("-Infinity", (",", False), ["infinite"]),
    # pandas reads 1e400 as inf or leaves it to the number parser, by version
    ("1e400", (",", False), ["infinite|overflows a double"]),
    ("1e400", (";", True), ["infinite|overflows a double"]),
    ("-inf", (";", True), ["infinite"]),
    ("nan", (",", False), ["missing", "expected a number"]),
    ("", (";", False), ["missing"]),
    ("ERR", (",", False), ["non-numeric value 'ERR'", "expected a number"]),
    ("1_0", (",", False), ["non-numeric value '1_0'"]),
    ("\uff10.\uff13", (",", False), ["non-numeric value"]),
    ("1.200", (";", True), ["ambiguous", "decimal comma"]),
    ("1.000,5", (";", True), ["non-numeric value '1.000,5'"]),
]


@HOSTILE
@pytest.mark.parametrize("cell,layout,words", CELLS)
def test_a_bad_torque_cell_is_named_with_file_column_row(tmp_path: Path, cell: str,
                                                         layout: tuple[str, bool],
                                                         words: list[str]) -> None:
    """An 'inf' torque was described as 'NaN or empty'; every message now says what it saw."""
    delimiter, comma = layout
    path = tmp_path / "bad.csv"
    path.write_text(_text(delimiter, comma, True, False, {(3, 1): cell}), encoding="utf-8")
    with pytest.raises(InputError) as err:
        read_record(path)
    msg = str(err.value)
    assert "bad.csv" in msg and "torque [N m]" in msg
    assert "row 7" in msg  # two comment/blank lines, the header, then the fourth data row
    for word in words:
        assert any(w in msg for w in word.split("|")), msg
    assert "\n" not in msg


@HOSTILE
def test_a_one_column_header_says_how_to_separate_columns(tmp_path: Path) -> None:
    path = tmp_path / "pipe.csv"
    path.write_text("time [s]|torque [N m]|disc_speed [rpm]\n0|1|2\n0.1|1|2\n0.2|1|2\n")
    with pytest.raises(InputError, match="header has one column.*';' or a tab"):
        read_record(path)


def test_process_uses_a_semicolon_record(tmp_path: Path) -> None:
    """End to end: a campaign whose records use ';' and decimal commas is processed."""
    from frictionlaws.tribometer import process_campaign
    from frictionlaws.tribometer.synthetic import ConditionSpec, make_campaign

    truth = make_campaign(tmp_path, [ConditionSpec("c", "steel", 3.0, 1.1, repeats=2)],
                          record_kwargs={"duration": 12.0, "fs": 100.0})
    for rec in (tmp_path / "records").glob("*.csv"):
        text = rec.read_text()
        rec.write_text(text.replace(",", ";").replace(".", ","), encoding="utf-8")
    assert truth.manifest is not None and truth.rig_file is not None
    campaign = process_campaign(truth.manifest, truth.rig_file, jobs=1)
    data = campaign.dataset()
    assert len(data) == 1
    assert abs(float(data.frame["mu"].iloc[0]) - 1.1) < 0.05


def test_a_name_with_a_comma_keeps_the_manifest_columns(tmp_path: Path) -> None:
    """A condition or surface name holding the separator is quoted, not split across columns."""
    from frictionlaws.tribometer import load_rig, read_manifest
    from frictionlaws.tribometer.synthetic import ConditionSpec, make_campaign

    spec = ConditionSpec('steel, wet "A"', "sandpaper, 120", 3.0, 1.1, repeats=2)
    truth = make_campaign(tmp_path, [spec], record_kwargs={"duration": 12.0, "fs": 100.0})
    assert truth.manifest is not None and truth.rig_file is not None
    entries, _ = read_manifest(truth.manifest, load_rig(truth.rig_file))
    assert [(e.condition, e.surface, e.error) for e in entries] == \
        [('steel, wet "A"', "sandpaper, 120", None)] * 2
