"""The shared primitives: strict JSON, the number parser and the output guard."""

from __future__ import annotations

import json
import math
import os
import string

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from frictionlaws.base import jsonio, numbers, outputs
from frictionlaws.base.errors import InputError


def _strict(text: str):
    def refuse(name):
        raise ValueError(f"non-standard JSON constant {name}")

    return json.loads(text, parse_constant=refuse)


# ------------------------------------------------------------------ JSON
@given(st.recursive(
    st.none() | st.booleans() | st.floats(allow_nan=True, allow_infinity=True) | st.integers()
    | st.text(max_size=5),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=4), inner,
                                                                max_size=4),
    max_leaves=20))
@settings(max_examples=150, deadline=None, derandomize=True)
def test_dumps_is_always_strict_json(obj):
    _strict(jsonio.dumps(obj))


def test_non_finite_numbers_become_null_and_numpy_is_plain():
    doc = {"a": math.nan, "b": np.float64(np.inf), "c": np.arange(3), "d": np.int64(4),
           "e": (1.5, -math.inf), "f": np.bool_(True)}
    assert _strict(jsonio.dumps(doc)) == {"a": None, "b": None, "c": [0, 1, 2], "d": 4,
                                          "e": [1.5, None], "f": True}


def test_bounds_keep_their_infinity_as_text():
    assert jsonio.bound_to_json(math.inf) == "inf"
    assert jsonio.bound_from_json("-inf") == -math.inf
    assert jsonio.bound_from_json(2) == 2.0
    for bad in (None, True, "1e3", [1]):
        with pytest.raises(ValueError):
            jsonio.bound_from_json(bad)


# --------------------------------------------------------------- numbers
@pytest.mark.parametrize("text", ["1_000", "\uff11\uff12", "nan", "inf", "-Infinity", "1e999",
                                  "0x10", "1,5", "", " ", "1.2.3", "٣", "1e", "--1", "1 000"])
def test_lenient_float_spellings_are_refused(text):
    with pytest.raises(ValueError):
        numbers.parse_number(text)


@pytest.mark.parametrize(("text", "value"), [("0.25", 0.25), (" -3 ", -3.0), ("1.5e-6", 1.5e-6),
                                             (".5", 0.5), ("5.", 5.0), ("+2E3", 2000.0)])
def test_plain_numbers_are_read(text, value):
    assert numbers.parse_number(text) == value


def test_decimal_comma_refuses_a_point():
    assert numbers.parse_number("0,25", decimal_comma=True) == 0.25
    with pytest.raises(ValueError):
        numbers.parse_number("1.000,5", decimal_comma=True)
    with pytest.raises(ValueError):
        numbers.parse_number("0.25", decimal_comma=True)


@given(st.text(alphabet=string.printable + "\uff10\u0663_", max_size=12))
@settings(max_examples=300, deadline=None, derandomize=True)
def test_parse_number_accepts_only_what_float_reads_the_same(text):
    try:
        value = numbers.parse_number(text)
    except ValueError:
        return
    assert math.isfinite(value)
    assert value == float(text.strip())
    assert text.strip().isascii() and "_" not in text


# ---------------------------------------------------------- output guard
def test_output_equal_to_an_input_is_refused(tmp_path):
    src = tmp_path / "data.csv"
    src.write_text("mu\n1\n")
    with pytest.raises(InputError, match="also an input"):
        outputs.check_outputs([src], inputs=[src])
    link = tmp_path / "link.csv"
    link.symlink_to(src)
    with pytest.raises(InputError, match="also an input"):
        outputs.check_outputs([link], inputs=[src])
    with pytest.raises(InputError, match="named twice"):
        outputs.check_outputs([tmp_path / "a", tmp_path / "a"])


def test_bad_output_targets_are_refused_before_work(tmp_path):
    with pytest.raises(InputError, match="is a directory"):
        outputs.check_outputs([tmp_path])
    with pytest.raises(InputError, match="does not exist"):
        outputs.check_outputs([tmp_path / "missing" / "out.csv"])
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    with pytest.raises(InputError, match="not a regular file"):
        outputs.check_outputs([fifo])
    with pytest.raises(InputError, match="not a regular file"):
        outputs.check_input_file(fifo)
    with pytest.raises(InputError, match="not found"):
        outputs.check_input_file(tmp_path / "nope.csv")
    with pytest.raises(InputError, match="exists and is not a directory"):
        (tmp_path / "file").write_text("x")
        outputs.check_outputs(dirs=[tmp_path / "file"])


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes everywhere")
def test_unwritable_directory_is_refused(tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o500)
    with pytest.raises(InputError, match="not writable"):
        outputs.check_outputs([ro / "out.csv"])


def test_atomic_write_leaves_nothing_on_failure(tmp_path):
    target = tmp_path / "out.txt"
    target.write_text("old")
    with pytest.raises(RuntimeError), outputs.atomic_write(target) as fh:
        fh.write("partial")
        raise RuntimeError("boom")
    assert target.read_text() == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.txt"]
    outputs.write_text_atomic(target, "new")
    assert target.read_text() == "new"


def test_registered_inputs_are_never_replaced(tmp_path):
    src = tmp_path / "in.csv"
    src.write_text("keep")
    outputs.check_outputs([tmp_path / "other.csv"], inputs=[src])
    with pytest.raises(InputError, match="overwrite an input"):
        outputs.write_text_atomic(src, "lost")
    assert src.read_text() == "keep"


def test_atomic_dir_moves_in_only_on_success(tmp_path):
    out = tmp_path / "report"
    with pytest.raises(RuntimeError), outputs.atomic_dir(out) as tmp:
        (tmp / "a.html").write_text("x")
        raise RuntimeError("boom")
    assert not out.exists()
    assert list(tmp_path.iterdir()) == []
    with outputs.atomic_dir(out) as tmp:
        (tmp / "a.html").write_text("x")
        (tmp / "fig").mkdir()
        (tmp / "fig" / "b.png").write_bytes(b"png")
    assert (out / "a.html").read_text() == "x" and (out / "fig" / "b.png").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["report"]


@pytest.mark.parametrize("cell", ["1_000", "\uff11", "\u0663", "1e999", "0x10", "1 000"])
def test_dataset_cells_go_through_the_one_number_parser(tmp_path, cell):
    from frictionlaws.io import load_dataset

    path = tmp_path / "d.csv"
    path.write_text(f"mu,p [MPa]\n0.5,{cell}\n0.6,0.2\n0.7,0.3\n", encoding="utf-8")
    with pytest.raises(InputError, match=r"column 'p \[MPa\]', row 2") as exc:
        load_dataset(path)
    assert str(path) in str(exc.value)


@pytest.mark.parametrize("text", [
    '{"law": "thirion", "params": {"a": 0.5, "a": 0.9, "b": 1e-6}}',
    '{"law": "thirion", "params": {"a": 0.5, "b": 1e-6}, "params": {"a": 0.9, "b": 1e-6}}',
])
def test_duplicate_json_keys_are_refused_in_params_and_property_files(tmp_path, text):
    """The one JSON reader refuses a key given twice (Python keeps the last silently)."""
    from frictionlaws.base.errors import InputError
    from frictionlaws.fitting import load_result
    from frictionlaws.tyre.tir import read_json

    path = tmp_path / "params.json"
    path.write_text(text)
    with pytest.raises(InputError, match="given twice"):
        load_result(path)
    with pytest.raises(InputError, match="given twice"):
        read_json('{"MODEL": {"FITTYP": 61, "FITTYP": 62}}')
