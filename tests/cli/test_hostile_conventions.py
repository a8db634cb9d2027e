"""The shared CLI machinery in ``frictionlaws/cli/_common.py``: the rules every command adopts."""

from __future__ import annotations

import argparse
import io
import math
import re
import sys
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from frictionlaws.cli._common import (
    MAX_POINTS,
    MergeAssignments,
    MergeNames,
    RangeSpec,
    UsageError,
    add_data_options,
    add_fit_options,
    add_progress_option,
    bounded_int,
    data_source,
    flag_of,
    non_negative_int,
    parse_assignments,
    parse_floats,
    parse_names,
    parse_values,
    positive_int,
    progress_value,
    range_option,
    range_values,
    refuse_unused,
)

DOC = Path(__file__).resolve().parents[2] / "docs" / "user-guide" / "cli.rst"


def test_integer_types_name_the_allowed_range() -> None:
    assert non_negative_int("0") == 0 and positive_int("+7") == 7
    for bad in ("-1", "1.5", "1e3", "\uff11", "", " ", "1_0"):
        with pytest.raises(argparse.ArgumentTypeError):
            non_negative_int(bad)
    with pytest.raises(argparse.ArgumentTypeError, match="from 2 to 5"):
        bounded_int(2, 5)("6")
    with pytest.raises(argparse.ArgumentTypeError, match=">= 1"):
        positive_int("0")


def test_assignments_merge_and_refuse_a_name_twice() -> None:
    assert parse_assignments(["a=1", "b=2,c=3"], "--fix") == {"a": "1", "b": "2", "c": "3"}
    assert parse_assignments("a = 1 ,", "--fix") == {"a": "1"}
    for bad, msg in ((["a=1", "a=2"], "'a' is given twice"), ("a=1,a=1", "given twice"),
                     ("", "is empty"), (" , ", "is empty"), ("a", "NAME=VALUE"),
                     ("=1", "NAME=VALUE"), ("a=", "NAME=VALUE")):
        with pytest.raises(UsageError, match=msg):
            parse_assignments(bad, "--fix")
    assert parse_floats("a=1.5e-3", "--fix") == {"a": 1.5e-3}
    for bad in ("a=1_0", "a=nan", "a=1e999", "a=\uff11"):
        with pytest.raises(UsageError, match="--fix"):
            parse_floats(bad, "--fix")
    assert parse_names(["E_v", "x,y"], "--free") == ["E_v", "x", "y"]
    with pytest.raises(UsageError, match="given twice"):
        parse_names(["E_v", "E_v"], "--free")


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="t", exit_on_error=False)
    add_data_options(p)
    add_fit_options(p)
    add_progress_option(p)
    p.set_defaults(_parser=p)
    return p


def test_merge_actions_keep_one_string_for_the_library() -> None:
    p = _parser()
    args = p.parse_args(["--map", "mu=FC", "--map", "p=CP,v=DV", "--free", "E_v",
                         "--free", "x"])
    assert args.map == "mu=FC,p=CP,v=DV" and args.free == "E_v,x"
    assert args.units is None and args.fix is None
    assert isinstance(p._option_string_actions["--map"], MergeAssignments)
    assert isinstance(p._option_string_actions["--free"], MergeNames)
    with pytest.raises(argparse.ArgumentError, match="'mu' is given twice"):
        p.parse_args(["--map", "mu=FC", "--map", "mu=X"])


def test_refuse_unused_names_the_flags() -> None:
    p = _parser()
    args = p.parse_args(["--fix", "a=1", "--starts", "3"])
    refuse_unused(args, ["map", "units", "seed"], "without --fit")  # defaults: fine
    with pytest.raises(UsageError, match=r"--fix, --starts are not used without --fit"):
        refuse_unused(args, ["fix", "starts", "seed"], "without --fit")
    assert flag_of(args, "drop_invalid") == "--drop-invalid"
    bare = argparse.Namespace(tol=None, spacing=[], json=True)
    with pytest.raises(UsageError, match="--json is not used"):
        refuse_unused(bare, ["tol", "spacing", "json"], "here")


def test_progress_value() -> None:
    assert progress_value(argparse.Namespace(progress="auto")) is None
    assert progress_value(argparse.Namespace(progress="auto", quiet=True)) is False
    assert progress_value(argparse.Namespace(progress="on")) is True
    assert progress_value(argparse.Namespace(progress="off")) is False


def test_range_grammar_with_units_and_points() -> None:
    r = range_option("0.01:0.5:20", "p", option="--p", unit="MPa")
    assert (r.lo, r.hi, r.n) == (pytest.approx(1e4), pytest.approx(5e5), 20)
    r = range_option("10kPa:0.5MPa", "p", option="--p")
    assert (r.lo, r.hi, r.n) == (pytest.approx(1e4), pytest.approx(5e5), None)
    r = range_option("20degC:80degC:7", "T", option="--T")
    assert r.lo == pytest.approx(293.15) and r.hi == pytest.approx(353.15)
    assert range_option("1:2:3", "v", option="--v", unit=lambda x: x / 1000).hi == 0.002
    values = range_values(range_option("2:6:5", "F_N", option="--loads", unit="kN"))
    assert values == pytest.approx([2000, 3000, 4000, 5000, 6000])
    assert range_values(RangeSpec(1.0, 100.0, 3), "log") == pytest.approx([1, 10, 100])


@pytest.mark.parametrize(("text", "msg"), [
    ("1", "MIN:MAX"), ("1:2:3:4", "MIN:MAX"), (":2", "empty bound"), ("2:1", "above MAX"),
    ("1:2:0", "N"), ("1:2:1.5", "N"), (f"1:2:{MAX_POINTS + 1}", "N"), ("1:1:3", "MIN < MAX"),
    ("1e999:2", "bound|finite|overflow"), ("nan:1", "nan"), ("1_0:20", "1_0"),
    ("0.1m/s:1MPa", "m/s"), ("a:b", "'a"),
])
def test_range_grammar_errors_name_the_option(text: str, msg: str) -> None:
    with pytest.raises(UsageError, match=msg) as info:
        range_option(text, "p", option="--p", unit="MPa")
    assert str(info.value).startswith("--p")


@settings(max_examples=60, deadline=None, derandomize=True, database=None)
@given(lo=st.floats(0, 1e6), span=st.floats(0, 1e6), n=st.integers(2, 500))
def test_range_values_are_sorted_and_end_exactly(lo: float, span: float, n: int) -> None:
    hi = lo + span
    if hi == lo:
        return
    vals = range_values(RangeSpec(lo, hi, n))
    assert len(vals) == n and vals[0] == lo and vals[-1] == hi
    assert all(a <= b for a, b in zip(vals, vals[1:]))


def test_values_lists_and_ranges() -> None:
    assert parse_values("2kN,4kN,6500N", "F_N", option="--loads", unit="kN") == \
        pytest.approx([2000, 4000, 6500])
    assert parse_values("2:6:3", "F_N", option="--loads", unit="kN") == \
        pytest.approx([2000, 4000, 6000])
    with pytest.raises(UsageError, match="number of points"):
        parse_values("2:6", "F_N", option="--loads", unit="kN")
    with pytest.raises(UsageError, match="empty"):
        parse_values(" ", "F_N", option="--loads")


def test_the_conventions_page_examples_parse() -> None:
    """Every ``--p/--v/--T`` range written on the conventions page parses."""
    text = DOC.read_text(encoding="utf-8")
    found = re.findall(r"--(p|v|T) ([^`\s]+)", text)
    assert len(found) >= 2
    for var, rng in found:
        spec = range_option(rng, var, option=f"--{var}", unit=None)
        assert math.isfinite(spec.lo) and spec.lo <= spec.hi


def test_stdin_is_spooled_and_named(monkeypatch: pytest.MonkeyPatch) -> None:
    from frictionlaws.base.errors import InputError

    fake = io.TextIOWrapper(io.BytesIO(b"mu,p [MPa]\n0.5,0.1\n"), encoding="utf-8")
    monkeypatch.setattr(sys, "stdin", fake)
    with data_source("-") as path:
        assert Path(path).read_bytes() == b"mu,p [MPa]\n0.5,0.1\n"
        kept = path
    assert not Path(kept).exists()
    monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(b"x"), encoding="utf-8"))
    with pytest.raises(InputError) as info, data_source("-") as path:
        raise InputError(f"bad table in {path}", file=path)
    assert str(info.value) == "file '<stdin>': bad table in <stdin>"
    with data_source("thesis-steel") as name:  # a packaged name passes unchanged
        assert name == "thesis-steel"


def test_stdin_from_a_terminal_is_refused(monkeypatch: pytest.MonkeyPatch) -> None:
    class Terminal(io.StringIO):
        def isatty(self) -> bool:
            return True

    monkeypatch.setattr(sys, "stdin", Terminal())
    with pytest.raises(UsageError, match="terminal"), data_source("-"):
        pass


def _commands(parser: argparse.ArgumentParser, prefix: str = ""):
    """(command name, parser) for every leaf command of the CLI."""
    subs = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    if not subs:
        yield prefix.strip(), parser
        return
    for name, sub in subs[0].choices.items():
        yield from _commands(sub, f"{prefix} {name}")


def test_one_progress_flag_everywhere() -> None:
    """Every command with parallel or long work has the one ``--progress {auto,on,off}``."""
    from frictionlaws.cli import build_parser

    seen = []
    for name, parser in _commands(build_parser()):
        flags = {opt: a for a in parser._actions for opt in a.option_strings}
        assert "--no-progress" not in flags, name
        if "--progress" in flags:
            assert tuple(flags["--progress"].choices) == ("auto", "on", "off"), name
            seen.append(name)
        if "--jobs" in flags:
            assert "--progress" in flags, f"{name} has --jobs but no --progress"
    assert {"fit", "compare", "process"} <= set(seen)


def test_every_option_refuses_an_empty_value(capsys: pytest.CaptureFixture) -> None:
    from frictionlaws.cli import build_parser, main

    cases = [(name.split(), opt) for name, parser in _commands(build_parser())
             for a in parser._actions if a.nargs != 0 for opt in a.option_strings]
    assert len(cases) > 100 and (["compare"], "--report") in cases
    for words, opt in cases:
        for argv in ([*words, opt, ""], [*words, f"{opt}="] if opt.startswith("--") else None):
            if argv is None:
                continue
            assert main(argv) == 2, argv
            err = capsys.readouterr().err.strip().splitlines()
            assert err == [f"error: {opt}: empty value; give one (an empty value means "
                           "neither everything nor nothing)"], (argv, err)
