"""The notes and header lines of a fitted property file are true of the file written.

Each case fits, writes the ``.tir``, reads it back and checks every note and header line
against it: an entry a line names is in the file (or, where the line says it is not
written, absent), the values a line states are the file's, the version and row count of the
first line are the file's and the data's, and the JSON holds the same notes.  Before, an
MF 5.2 fit noted that the median measured pressure was "taken as NOMPRES" while the file
written has no NOMPRES, and the template was said to give FNOMIN after FNOMIN had been set
to the median measured load.
"""

from __future__ import annotations

import json
import re
import warnings
from pathlib import Path
from typing import Any

import pytest

from frictionlaws.tyre import MagicFormula, fit_mf
from frictionlaws.tyre.mf.declarations import DECLARED
from frictionlaws.tyre.mf.property_file import FITTYP_VERSIONS
from frictionlaws.tyre.mf.tir import format_tir, read_packaged, read_property_file
from frictionlaws.tyre.synthetic_rig import rig_data

#: "NAME is set to the median measured 6750 N", "taken as NOMPRES" and the like: the
#: entry, the value and its unit stated by a line.
_STATED = re.compile(r"\b([A-Z][A-Z0-9_]{2,})\b (?:is set to (?:the median measured )?"
                     r"([-+0-9.eE]+) (N|Pa))")
_TAKEN = re.compile(r"([-+0-9.eE]+) (N|Pa) is taken as ([A-Z][A-Z0-9_]+)")


def _fitted(tmp_path: Path, truth: str, fittyp: int, template: Any = None,
            pressures: tuple[float, ...] = (1.0,), loads: tuple[float, ...] = (0.7, 1.0, 1.3)
            ) -> tuple[Any, Path]:
    data = rig_data(MagicFormula.from_file(truth), n=7, loads=loads, pressures=pressures,
                    cambers_deg=(0.0,), combined=False)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        res = fit_mf(data, fittyp=fittyp, template=template)
    # one warning path: what Python was told is what the result (its file, JSON) holds
    assert list(dict.fromkeys(str(w.message) for w in caught)) == res.warnings
    return res, res.write(tmp_path / "fitted.tir")


def _check_lines_against_the_file(res: Any, path: Path) -> None:
    """Every header and note line of the written file is true of it."""
    text = path.read_text()
    header = [line[2:] for line in text.splitlines() if line.startswith("! ")]
    pf = read_property_file(path)
    entries = {k: (sec, v) for sec, body in pf.sections.items() for k, v in body.items()}
    first = header[0]
    version = FITTYP_VERSIONS[int(pf.number("MODEL", "FITTYP"))]
    assert f"Magic Formula {version}" in first and f"({len(res.data)} rows)" in first
    for line in header:
        named = set(re.findall(r"\b[A-Z][A-Z0-9_]{2,}\b", line)) & (set(DECLARED) | {"FITTYP"})
        absent = "not written" in line
        for name in named:
            assert (name in entries) != absent, (name, line)
        for name, value, _unit in _STATED.findall(line):
            sec, _ = entries[name]
            assert pf.si(sec, name) == pytest.approx(float(value), rel=1e-9), line
        for value, _unit, name in _TAKEN.findall(line):
            sec, _ = entries[name]
            assert pf.si(sec, name) == pytest.approx(float(value), rel=1e-9), line
    notes = [line.removeprefix("note: ") for line in header if line.startswith("note: ")]
    assert notes == res.notes and json.loads(json.dumps(res.to_dict()))["notes"] == notes
    said = [line.removeprefix("warning: ") for line in header if line.startswith("warning: ")]
    assert said == res.warnings and json.loads(json.dumps(res.to_dict()))["warnings"] == said
    assert [line.removeprefix("warning: ") for line in res.report().splitlines()
            if line.startswith("warning: ")] == said


@pytest.mark.slow
def test_an_mf52_fit_with_a_pressure_column_notes_no_nominal_pressure(tmp_path: Path) -> None:
    res, path = _fitted(tmp_path, "MagicFormula52", fittyp=5)
    assert not [n for n in res.notes if "NOMPRES" in n]  # none is written
    assert [w for w in res.warnings if "stop before the peak" in w]  # said on every path
    assert "OPERATING_CONDITIONS" not in read_property_file(path).sections
    _check_lines_against_the_file(res, path)


@pytest.mark.slow
def test_a_template_fnomin_far_from_the_data_is_not_said_to_come_from_it(tmp_path) -> None:
    tpl = read_packaged("MagicFormula61")
    assert tpl is not None
    tpl.sections["VERTICAL"]["FNOMIN"] = 60000.0  # a truck's, for a car tyre's loads
    res, path = _fitted(tmp_path, "MagicFormula61", fittyp=61, template=tpl)
    assert [n for n in res.notes if "FNOMIN is set to the median measured" in n]
    assert not [n for n in res.notes if "FNOMIN, the other sections" in n]
    _check_lines_against_the_file(res, path)


@pytest.mark.slow
def test_coefficients_the_template_lacks_are_said_not_to_be_written(tmp_path: Path) -> None:
    tpl = read_packaged("MagicFormula61")
    assert tpl is not None
    for name in ("PPX1", "PPY1", "PDX3"):  # undetermined by one pressure and one camber
        del tpl.sections["LONGITUDINAL_COEFFICIENTS" if "X" in name[2:]
                         else "LATERAL_COEFFICIENTS"][name]
    (tmp_path / "tpl.tir").write_text(format_tir(tpl))
    res, path = _fitted(tmp_path, "MagicFormula61", fittyp=61, template=tmp_path / "tpl.tir")
    note = next(n for n in res.notes if "not in the template" in n)
    assert {"PPX1", "PPY1", "PDX3"} <= set(re.findall(r"[A-Z][A-Z0-9]+", note))
    _check_lines_against_the_file(res, path)


@pytest.mark.parametrize("name", ["MagicFormula52", "MagicFormula61", "MagicFormula62"])
def test_a_converted_file_is_what_its_header_says(tmp_path: Path, name: str) -> None:
    """json_to_tir's header: "same sections, keys and values as the source; its
    non-section members follow", read back."""
    from frictionlaws.tyre.mf.tir import json_to_tir, packaged_example

    src = packaged_example(name)
    dst = json_to_tir(src, tmp_path / "converted.tir", provenance="the packaged example")
    header = [line[2:] for line in dst.read_text().splitlines() if line.startswith("! ")]
    assert "Same sections, keys and values as the source" in header[1]
    before, after = read_property_file(src), read_property_file(dst)
    assert list(after.sections) == list(before.sections)
    for sec, body in before.sections.items():
        assert list(after.sections[sec]) == list(body), sec
        for key, value in body.items():
            got = after.sections[sec][key]
            assert got == (pytest.approx(value, rel=1e-12) if isinstance(value, float)
                           else value), (sec, key)
    members = [line.removeprefix("JSON member ") for line in header
               if line.startswith("JSON member ")]
    assert members == [f"{k}: {json.dumps(v)}" for k, v in before.metadata.items()]
