"""The export formats are one table (``fe_export.formats``): a format is a writer and one
entry, which the API (its options and their defaults), the command line (``--format``
choices, one flag per option, the help) and the docs' table read."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import pytest

from frictionlaws.base.errors import InputError
from frictionlaws.cli import build_parser, main
from frictionlaws.fe_export import export, formats
from frictionlaws.fe_export.api import OPTIONS, check_options
from frictionlaws.fe_export.job import Job, Written

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "docs" / "_ext"))
import fl_docgen  # noqa: E402

THIRION = {"a": 0.3, "b": 3e-6}


def _export_parser() -> argparse.ArgumentParser:
    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    return sub.choices["export"]


def test_every_option_is_of_a_format_and_every_format_option_a_flag() -> None:
    assert set(OPTIONS) == {o.name for f in formats.FORMATS.values() for o in f.options}
    flags = {a.dest: a for a in _export_parser()._actions}
    for name, opt in OPTIONS.items():
        action = flags[name]
        assert action.option_strings == ["--" + name.replace("_", "-")]
        assert action.default is None  # not given: the library's default applies
        assert formats.formats_taking(name) and opt.lo <= opt.default <= opt.hi


def test_the_api_fills_the_defaults_and_refuses_an_option_the_format_does_not_take() -> None:
    assert check_options(None, "ansys") == {"ansys_mat": 1}
    assert check_options({"ansys_mat": 7}, "ansys") == {"ansys_mat": 7}
    assert check_options(None, "csv") == {}
    with pytest.raises(InputError, match="does not apply to format csv.*ansys") as info:
        check_options({"ansys_mat": 7}, "csv")
    assert info.value.option == "options"
    res = export("thirion", THIRION, "lsdyna", box={"p": (1e4, 5e5, 5)},
                 options={"lsdyna_ssid": 7, "lsdyna_table_id": 20})
    assert "*DEFINE_TABLE" in res.text
    assert "         7         2         3         3" in res.text  # SSID given, the rest default
    assert "\n        20" in res.text  # the table id given


def test_the_cli_passes_a_format_flag_and_refuses_one_that_does_not_apply(tmp_path, capsys):
    deck = tmp_path / "deck.inp"
    assert main(["export", "--law", "thirion", "--set", "a=0.3,b=3e-6", "--format", "ansys",
                 "--p", "0.01MPa:0.5MPa:5", "--ansys-mat", "42", "-o", str(deck)]) == 0
    assert "TB,FRIC,42" in deck.read_text().replace(" ", "")
    table = tmp_path / "mu.csv"
    assert main(["export", "--law", "thirion", "--set", "a=0.3,b=3e-6", "--format", "csv",
                 "--p", "0.01MPa:0.5MPa:5", "--ansys-mat", "42", "-o", str(table)]) == 2
    assert "--ansys-mat is not used with --format csv" in capsys.readouterr().err
    assert not table.exists()


def _write_plain(job: Job) -> Written:
    """A throwaway writer: mu at the box's corners, one per line."""
    mu = job.law.evaluate({v: lo for v, (lo, _hi, _n) in
                           ((k, (s.lo, s.hi, s.n)) for k, s in job.specs.items())},
                          job.values)
    return Written(f"plain {job.options['plain_id']}: mu = {float(mu)!r}\n", exact=True,
                   summary=["a throwaway format"])


def test_one_entry_makes_a_format_everywhere(monkeypatch, tmp_path):
    entry = formats.ExportFormat(
        "plain", _write_plain, "a throwaway test format", "mu at the box's lower corner",
        options=(formats.FormatOption("plain_id", 1, 9, 3, "a throwaway id"),))
    monkeypatch.setitem(formats.FORMATS, "plain", entry)
    parser = _export_parser()
    fmt = next(a for a in parser._actions if "--format" in a.option_strings)
    assert "plain" in fmt.choices
    help_text = parser.format_help()
    assert "a throwaway test format" in help_text and "--plain-id" in help_text
    assert "``plain``" in fl_docgen.export_formats_table()
    assert "``plain_id``: a throwaway id, 1..9, default 3" in fl_docgen.export_formats_table()
    assert export("thirion", THIRION, "plain", box={"p": (1e5, 2e5)}).text.startswith("plain 3")
    out = tmp_path / "mu.txt"
    assert main(["export", "--law", "thirion", "--set", "a=0.3,b=3e-6", "--format", "plain",
                 "--p", "0.1MPa:0.2MPa", "--plain-id", "5", "-o", str(out)]) == 0
    assert out.read_text().startswith("plain 5: mu = ")
