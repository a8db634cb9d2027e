"""The boundary walk: every reader, writer and option, from the code's own lists, meets
every hostile class of ``shared/reference/hostile-checklist.md`` that applies to it.

Nothing here names a reader, an option or a format by hand:

* **readers** come from :data:`frictionlaws.io.readers.READERS` (each with a valid example
  of its input): numbers spelled past the one number parser (non-ASCII and full-width
  digits, ``_`` separators, ``nan``, ``inf``, ``1e999``; checklist 10) are refused naming
  the file and place unless the format itself allows them, and malformed input
  (binary bytes, an empty file, a NUL, a truncated file, UTF-16, a line past the csv
  field limit, deep nesting, a file past the size limit, a line separator inside the
  text; checklists 4, 11, 12 and "every parse error is an input error") gives an
  :class:`~frictionlaws.base.errors.InputError` naming the file or a result, never another
  exception;
* **options** come from the argparse parsers (:func:`frictionlaws.cli.build_parser`):
  every option that takes a number refuses each hostile spelling of it (an option with
  a converter is tried on the converter; the others on the command line, where the
  refusal must quote the value); every option and positional that takes a value gets an
  over-long value and control characters (checklists 11, 12); every input file
  argument gets binary bytes, an empty file, a directory and a missing file; every
  output argument gets an input's name, a missing directory and a directory (no file
  is ever written by a refused command);
* **writers** come from the export formats table (:data:`frictionlaws.fe_export.FORMATS`):
  hostile text in the source adds no line to any format, a parameter past the number
  parser or not finite writes nothing.

A value option whose metavar or destination is not classified below fails the walk,
naming it: classify it (once) and it is walked from then on.  Every run is bounded in
time (the harness's guard) and checked by the harness's invariants.
"""

from __future__ import annotations

import argparse
import ast
import re
import shutil
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest
from hostile import Snapshot, check_outcome, run_cli

from frictionlaws.base.errors import InputError
from frictionlaws.io.readers import FORMATS, READERS, Reader

pytestmark = pytest.mark.hostile

ROOT = Path(__file__).resolve().parents[2]
MF61 = ROOT / "datasets" / "mf-examples" / "MagicFormula61_Parameters.converted.tir"

# ------------------------------------------------------------------ hostile spellings

_ARABIC = str.maketrans("0123456789", "\u0660\u0661\u0662\u0663\u0664\u0665\u0666\u0667"
                                      "\u0668\u0669")
_WIDE = str.maketrans("0123456789.", "\uff10\uff11\uff12\uff13\uff14\uff15\uff16\uff17"
                                     "\uff18\uff19\uff0e")


def _underscored(number: str) -> str:
    """The same number with a ``_`` separator, as Python's float() and int() read it."""
    m = re.search(r"[0-9][0-9]", number)
    return number[:m.start() + 1] + "_" + number[m.start() + 1:] if m else "0_" + number


#: Checklist 10: spellings Python's float()/int() read that the one number parser
#: refuses.  The first three are the same number (a lenient reader would accept them
#: and go on); the others are no measured value.
NUMBER_CLASSES: dict[str, Callable[[str], str]] = {
    "non-ASCII digits": lambda n: n.translate(_ARABIC),
    "full-width digits": lambda n: n.translate(_WIDE),
    "_ separators": _underscored,
    "nan": lambda n: "nan",
    "inf": lambda n: "inf",
    "overflow": lambda n: "1e999",
}
#: What a file format allows of them (its own grammar, or a missing cell).
FORMAT_ALLOWS = {"_ separators": "underscore", "nan": "missing"}

#: A number in a value or a file: not part of a word, a name or a longer number.
_NUMBER = re.compile(r"(?<![\w.\-+])[0-9]+(?:\.[0-9]+)?(?![\w.])", re.ASCII)


def _shown(token: str) -> tuple[str, ...]:
    """How a message may show ``token``: as typed, or escaped for one ASCII line."""
    return (token, token.encode("unicode_escape").decode("ascii"), ascii(token)[1:-1])


# ------------------------------------------------------------------------- readers


@pytest.fixture(scope="module")
def examples(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """A valid example of every reader's input, all in one folder (manifests name their
    records relative to it)."""
    root = tmp_path_factory.mktemp("readers")
    return {r.name: r.write_example(root) for r in READERS}


def _data_numbers(text: str, fmt: str) -> list[re.Match[str]]:
    """Numbers in the data of a file: not in comments, not in a CSV header."""
    out = []
    offset = 0
    seen_header = False
    for line in text.splitlines(keepends=True):
        body = line.strip()
        comment = body.startswith(("#", "$", "!")) or not body
        header = fmt == "csv" and not comment and not seen_header
        seen_header = seen_header or header
        if not comment and not header:
            out += [m for m in _NUMBER.finditer(text, offset, offset + len(line))
                    if _opens_a_value(text, m.start())]
        offset += len(line)
    return out


def _opens_a_value(text: str, start: int) -> bool:
    """A number that starts a value (after a delimiter, ``=``, ``:``, ``[`` or a quote),
    not one inside a text such as ``glass 6 kg``."""
    i = start - 1
    while i >= 0 and text[i] in " \t" and text[i] != "\t":
        i -= 1
    return i < 0 or text[i] in ",;\t=:[\"\n"


def _reader_cases() -> Iterator[tuple[Reader, str]]:
    for r in READERS:
        for cls in NUMBER_CLASSES:
            yield r, cls


@pytest.mark.parametrize(("reader", "cls"), list(_reader_cases()),
                         ids=lambda x: x.name if isinstance(x, Reader) else x)
def test_every_reader_refuses_every_number_past_the_parser(
        reader: Reader, cls: str, examples: dict[str, Path], tmp_path: Path) -> None:
    source = examples[reader.name]
    text = source.read_text(encoding="utf-8-sig")
    numbers = _data_numbers(text, reader.format)
    assert numbers, f"no number found in the example of {reader.name}"
    for m in (numbers[0], numbers[-1]):  # the first value read, and the last
        spelled = NUMBER_CLASSES[cls](m.group())
        hostile = source.with_name(f"hostile{source.suffix}")
        hostile.write_text(text[:m.start()] + spelled + text[m.end():], encoding="utf-8")
        try:
            result = reader.read(hostile)
        except InputError as exc:
            assert str(hostile) in str(exc) or hostile.name in str(exc), str(exc)
            if reader.format in ("csv", "tir"):
                assert exc.row is not None or "row" in str(exc) or "line" in str(exc), \
                    f"{reader.name}: no place named: {exc}"
            continue
        refused = [r for r in reader.refusals(result) if any(s in r for s in _shown(spelled))]
        if refused:  # the row is refused, named and not used; the others are read
            continue
        allowed = FORMAT_ALLOWS.get(cls) in FORMATS[reader.format]
        assert allowed, (f"{reader.name} read {spelled!r} ({cls}) where "
                         f"{m.group()!r} stood, at offset {m.start()}")


def _byte_readers() -> set[str]:
    """Modules of the package that read a file's bytes (through the bounded reader)."""
    package = ROOT / "frictionlaws"
    out = set()
    for path in package.rglob("*.py"):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        if any(isinstance(n, ast.Call) and getattr(n.func, "id", None) == "read_input"
               for n in ast.walk(tree)):
            out.add(".".join(path.relative_to(ROOT).with_suffix("").parts))
    return out


def test_the_list_of_readers_reaches_every_module_that_reads_a_file(
        examples: dict[str, Path]) -> None:
    """A new reader is walked once it is in READERS: every module that reads a file's
    bytes is reached by some reader of the list (traced while each reads its example)."""
    import sys

    from frictionlaws.base.limits import read_input

    reached: set[str] = set()

    def trace(frame, event, arg):  # noqa: ANN001, ANN202 - sys.setprofile's signature
        if event == "call" and frame.f_code is read_input.__code__:
            reached.add(frame.f_back.f_globals.get("__name__", ""))

    for r in READERS:
        sys.setprofile(trace)
        try:
            r.read(examples[r.name])
        finally:
            sys.setprofile(None)
    missing = _byte_readers() - reached
    assert "frictionlaws.tyre.mf.tir" in _byte_readers()
    assert not missing, f"modules that read files but no entry of READERS reaches: {missing}"


def _malformed(text: bytes, cls: str) -> bytes:
    if cls == "binary bytes":
        return b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\xff\xfe\xfd" + bytes(range(256))
    if cls == "empty":
        return b""
    if cls == "NUL byte":
        return text[:len(text) // 2] + b"\x00" + text[len(text) // 2:]
    if cls == "truncated":
        return text[:len(text) * 2 // 3]
    if cls == "UTF-16":
        return text.decode("utf-8-sig").encode("utf-16")
    if cls == "line past the field limit":
        first, _, rest = text.partition(b"\n")
        return first + b"," + b"x" * 140_000 + b"\n" + rest
    if cls == "deep nesting":
        return b"a = " + b"[" * 5000 + b"]" * 5000 + b"\n" if text.lstrip()[:1] != b"{" \
            else b'{"a": ' + b"[" * 5000 + b"]" * 5000 + b"}"
    if cls == "line separator":
        return text.replace(b"\n", "\u2028".encode(), 2)
    raise AssertionError(cls)


MALFORMED = ["binary bytes", "empty", "NUL byte", "truncated", "UTF-16",
             "line past the field limit", "deep nesting", "line separator", "past the size limit"]
#: Classes no input of any format survives.
ALWAYS_REFUSED = {"binary bytes", "empty", "past the size limit"}


@pytest.mark.parametrize("cls", MALFORMED)
@pytest.mark.parametrize("reader", READERS, ids=lambda r: r.name)
def test_every_parse_error_of_every_reader_is_an_input_error(
        reader: Reader, cls: str, examples: dict[str, Path],
        monkeypatch: pytest.MonkeyPatch) -> None:
    source = examples[reader.name]
    raw = source.read_bytes()
    hostile = source.with_name(f"malformed{source.suffix}")
    if cls == "past the size limit":
        from frictionlaws.base import limits

        monkeypatch.setattr(limits, "MAX_INPUT_BYTES", max(len(raw) // 2, 16))
        hostile.write_bytes(raw)
    else:
        hostile.write_bytes(_malformed(raw, cls))
    try:
        reader.read(hostile)
    except InputError as exc:
        assert str(hostile) in str(exc) or hostile.name in str(exc), str(exc)
        assert "\n" not in str(exc).strip(), str(exc)
        return
    assert cls not in ALWAYS_REFUSED, f"{reader.name} read {cls} without a word"


# ------------------------------------------------------------------------- options


def _value_actions(parser: argparse.ArgumentParser, path: tuple[str, ...] = ()
                   ) -> Iterator[tuple[tuple[str, ...], argparse.Action]]:
    """(command path, action) of every argument that takes a value, in every parser."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                yield from _value_actions(sub, (*path, name))
        elif action.nargs != 0 and not isinstance(action, (
                argparse._HelpAction, argparse._VersionAction, argparse._StoreConstAction)):
            yield path, action


def _label(path: tuple[str, ...], action: argparse.Action) -> str:
    return " ".join(path) + " " + (action.option_strings[-1] if action.option_strings
                                   else action.dest)


#: Options that take numbers without a converter of their own (read by the command),
#: by metavar: a valid value with a number in it.
NUMERIC = {
    "AREA": "314 mm^2", "NAME=VALUE,...": "a=0.25", "MIN:MAX:N|A,B,C": "2:6.5:10",
    "DEG,...": "1,2,3", "LEN": "150 mm", "LOAD": "3 kN", "STIFF": "8.49e6 N/m^2",
    "SPEED": "10 m/s", "MIN:MAX[:N]": None, "FRACTION|VAR=F,...": "0.3",
    "SSID,MSID[,SSTYP,MSTYP]": "10,2", "TIME": "60 s",
}
#: Values that are text (names, units, choices of words, addresses), by metavar or dest.
TEXT = {"NAME", "LAW", "LAW,...", "A,B,...", "COL=NAME,...", "COL=UNIT,...", "SETTING,...",
        "COLUMN[,COLUMN]", "NAME[,NAME]", "UNIT", "SYSTEM", "VAR=lin|log,...", "ADDRESS",
        "SHELL", "law", "family", "weights", "uncertainty", "boot_interval", "progress",
        "format", "sign_convention", "slip_angle", "friction_scaling", "loads_above_fzmax",
        "equations", "side", "case", "pressure_shape", "outputs"}
#: Files read, and files or folders written, by destination.
INPUTS = {"params", "fit", "data", "template", "rig", "manifest", "file", "name", "raw"}
OUTPUTS = {"out", "save", "plot", "output", "records_out"}
OUTPUT_DIRS = {"report", "plots", "directory"}


def _kind(action: argparse.Action) -> str:
    meta = action.metavar if isinstance(action.metavar, str) else None
    if action.dest in INPUTS:
        return "input"
    if action.dest in OUTPUTS:
        return "output"
    if action.dest in OUTPUT_DIRS:
        return "output-dir"
    if action.type is not None:
        return "converter"
    if meta in NUMERIC:
        return "numeric"
    if meta in TEXT or action.dest in TEXT or (action.choices and not meta):
        return "text"
    return "unclassified"


@pytest.fixture(scope="module")
def parser() -> argparse.ArgumentParser:
    from frictionlaws.cli import build_parser

    return build_parser()


def test_every_value_option_is_classified_for_the_walk(parser: argparse.ArgumentParser
                                                       ) -> None:
    left = [f"{_label(p, a)} (metavar {a.metavar!r}, dest {a.dest!r})"
            for p, a in _value_actions(parser) if _kind(a) == "unclassified"]
    assert not left, "classify these for the boundary walk: " + "; ".join(left)


def _template(action: argparse.Action) -> str | None:
    """A value the converter accepts, with a number in it (None: it takes none)."""
    candidates = [str(action.default), *(str(c) for c in action.choices or ()),
                  "1", "3", "20", "200", "0.5", "0"]
    for text in candidates:
        if not _NUMBER.search(text):
            continue
        try:
            value = action.type(text)  # type: ignore[misc]
        except (argparse.ArgumentTypeError, ValueError, TypeError):
            continue
        if not action.choices or value in action.choices:
            return text
    return None


def _converter_cases() -> list[tuple[str, argparse.Action, str]]:
    from frictionlaws.cli import build_parser

    return [(_label(p, a), a, cls) for p, a in _value_actions(build_parser())
            if _kind(a) == "converter" for cls in NUMBER_CLASSES]


@pytest.mark.parametrize(("label", "action", "cls"), _converter_cases(),
                         ids=lambda x: x if isinstance(x, str) else "")
def test_every_option_converter_refuses_every_number_past_the_parser(
        label: str, action: argparse.Action, cls: str) -> None:
    template = _template(action)
    assert template is not None, f"{label}: no valid numeric value found for the walk"
    m = _NUMBER.search(template)
    assert m is not None
    spelled = template[:m.start()] + NUMBER_CLASSES[cls](m.group()) + template[m.end():]
    with pytest.raises((argparse.ArgumentTypeError, ValueError, TypeError)):
        value = action.type(spelled)  # type: ignore[misc]
        if action.choices and value not in action.choices:
            raise ValueError("not a choice")  # argparse refuses it after converting


#: The command line each command's options are walked on (inputs made by the fixture).
def _bases(files: dict[str, Path]) -> dict[tuple[str, ...], list[str]]:
    out = files["out"]
    return {
        ("laws",): ["laws"],
        ("show",): ["show", "thirion"],
        ("fit",): ["fit", str(files["data"]), "--law", "thirion"],
        ("compare",): ["compare", str(files["data"]), "--laws", "thirion,coulomb"],
        ("datasets",): ["datasets", str(files["loads"])],
        ("tyre", "cornering"): ["tyre", "cornering", "--law", "thirion", "--params",
                                str(files["params"])],
        ("tyre", "thesis"): ["tyre", "thesis"],
        ("tyre", "mf"): ["tyre", "mf", str(files["tir"])],
        ("tyre", "reduce"): ["tyre", "reduce", str(files["tir"]), "--load", "4kN"],
        ("tyre", "fit-mf"): ["tyre", "fit-mf", str(files["tyre"]), "-o",
                             str(out.with_suffix(".tir"))],
        ("tyre", "prepare"): ["tyre", "prepare", str(files["raw"]), "-o", str(out)],
        ("process",): ["process", str(files["manifest"]), "--rig", str(files["rig"]), "-o",
                       str(out), "--jobs", "1"],
        ("validate",): ["validate", "--case", "nope"],
        ("export",): ["export", "--params", str(files["params"]), "--format", "csv",
                      "--p", "0.01MPa:0.5MPa:4", "-o", str(out)],
        ("examples",): ["examples", str(out.parent / "ex")],
    }


#: Where an option needs more than its command's base line to be read at all.
CONTEXT = {
    ("fit", "area"): ["fit", "LOADS", "--law", "thirion"],
    ("compare", "area"): ["compare", "LOADS", "--laws", "thirion,coulomb"],
    ("tyre", "cornering", "area"): ["tyre", "cornering", "--law", "thirion", "--fit", "LOADS"],
    ("tyre", "cornering", "fix"): ["tyre", "cornering", "--law", "thirion", "--fit", "DATA"],
    ("tyre", "cornering", "set"): ["tyre", "cornering", "--law", "thirion"],
    ("tyre", "cornering", "fit"): ["tyre", "cornering", "--law", "thirion"],
    ("export", "fit"): ["export", "--law", "thirion", "--format", "csv",
                        "--p", "0.01MPa:0.5MPa:4", "-o", "OUT"],
    ("export", "area"): ["export", "--law", "thirion", "--fit", "LOADS", "--format", "csv",
                         "--p", "0.01MPa:0.5MPa:4", "-o", "OUT"],
    ("export", "fix"): ["export", "--law", "thirion", "--fit", "DATA", "--format", "csv",
                        "--p", "0.01MPa:0.5MPa:4", "-o", "OUT"],
    ("export", "set"): ["export", "--law", "thirion", "--format", "csv",
                        "--p", "0.01MPa:0.5MPa:4", "-o", "OUT"],
    ("export", "lsdyna_contact"): ["export", "--law", "exponential-decay", "--preset",
                                   "rubber-steel", "--format", "lsdyna", "-o", "OUT"],
    ("export", "range_p"): ["export", "--law", "park", "--format", "csv", "-o", "OUT"],
    ("export", "range_v"): ["export", "--law", "park", "--format", "csv", "-o", "OUT"],
    ("export", "range_T"): ["export", "--law", "park", "--format", "csv", "-o", "OUT"],
    ("export", "range_F_N"): ["export", "--law", "schallamach", "--preset", "hertz",
                              "--format", "csv", "-o", "OUT"],
    ("export", "range_s"): ["export", "--law", "pacejka", "--preset", "dry", "--format", "csv",
                            "-o", "OUT"],
}
#: Valid numeric values that depend on the option, not only on its metavar.
RANGES = {"range_p": "0.01MPa:0.5MPa:4", "range_v": "0.01:2:4", "range_T": "20degC:80degC:3",
          "range_F_N": "10:500:3", "range_s": "0:1:5"}


@pytest.fixture(scope="module")
def files(tmp_path_factory: pytest.TempPathFactory, examples: dict[str, Path]
          ) -> dict[str, Path]:
    root = tmp_path_factory.mktemp("walk")
    data = root / "data.csv"
    data.write_text("p [MPa],mu\n" + "".join(
        f"{p},{1 / (0.25 + 3.5 * p):.4f}\n" for p in (0.03, 0.06, 0.09, 0.12, 0.15, 0.2)),
        encoding="utf-8")
    loads = root / "loads.csv"
    loads.write_text("F_N [N],mu\n" + "".join(
        f"{f},{1 / (0.25 + 3.5 * f / 314):.4f}\n" for f in (10, 20, 30, 40, 50, 60)),
        encoding="utf-8")
    params = root / "params.json"
    params.write_text('{"law": "thirion", "params": {"a": 0.25, "b": 3.5e-06}}\n',
                      encoding="utf-8")
    (root / "out").mkdir()
    tir = root / "tyre.tir"
    shutil.copyfile(MF61, tir)
    return {"data": data, "loads": loads, "params": params, "out": root / "out" / "o.csv",
            "tyre": examples["tyre data"], "manifest": examples["manifest"],
            "rig": examples["rig"], "tir": tir, "root": root, "raw": examples["raw rig run"]}


def _argv_for(path: tuple[str, ...], dest: str, files: dict[str, Path]) -> list[str]:
    names = {"LOADS": str(files["loads"]), "DATA": str(files["data"]), "OUT": str(files["out"])}
    base = CONTEXT.get((*path, dest)) or _bases(files)[path]
    return [names.get(t, t) for t in base]


def _numeric_cases() -> list[tuple[tuple[str, ...], str, str, str]]:
    from frictionlaws.cli import build_parser

    out = []
    for path, a in _value_actions(build_parser()):
        if _kind(a) != "numeric":
            continue
        template = RANGES.get(a.dest) or NUMERIC[str(a.metavar)]
        for cls in NUMBER_CLASSES:
            out.append((path, a.option_strings[-1], a.dest, f"{template}|{cls}"))
    return out


@pytest.mark.parametrize(("path", "flag", "dest", "case"), _numeric_cases())
def test_every_numeric_option_refuses_every_number_past_the_parser(
        path: tuple[str, ...], flag: str, dest: str, case: str,
        files: dict[str, Path]) -> None:
    template, cls = case.split("|")
    m = _NUMBER.search(template)
    assert m is not None
    token = NUMBER_CLASSES[cls](m.group())
    value = template[:m.start()] + token + template[m.end():]
    argv = [*_argv_for(path, dest, files), flag, value]
    snap = Snapshot.take([files["root"]])
    res = run_cli(argv)
    check_outcome(res, snapshot=snap, codes=[2])
    assert any(s in res.err for s in _shown(token)), \
        f"refused, but not for the value {token!r}: {res.err.strip()}"


def _any_value_cases() -> list[tuple[tuple[str, ...], str, str]]:
    from frictionlaws.cli import build_parser

    return [(p, a.option_strings[-1] if a.option_strings else "", a.dest)
            for p, a in _value_actions(build_parser()) if p]


@pytest.mark.parametrize(("path", "flag", "dest"), _any_value_cases())
def test_every_value_takes_an_overlong_or_controlled_value_in_one_line(
        path: tuple[str, ...], flag: str, dest: str, files: dict[str, Path]) -> None:
    """Checklists 11 and 12: a value of 100000 characters, and one holding line breaks and
    control characters, are refused (or read) within the time bound in one line; nothing
    is written by a refusal."""
    base = _argv_for(path, dest, files)
    for value in ("9" * 100_000, "x\n*KEYWORD\r\u2028$ y\x1b[2J\x00z"):
        argv = [*base, flag, value] if flag else [*base[:len(path)], value,
                                                  *base[len(path) + 1:]]
        snap = Snapshot.take([files["root"]])
        res = run_cli(argv, timeout=10)
        check_outcome(res, snapshot=snap, codes=[0, 1, 2])
        assert res.seconds < 5, f"{res.seconds:.1f} s"
        if res.code == 2:
            assert len(res.err) < 2600, "a message longer than its bound"


def _file_cases(kinds: set[str]) -> list[tuple[tuple[str, ...], str, str]]:
    from frictionlaws.cli import build_parser

    return [(p, a.option_strings[-1] if a.option_strings else "", a.dest)
            for p, a in _value_actions(build_parser()) if _kind(a) in kinds and p]


def _with(base: list[str], path: tuple[str, ...], flag: str, dest: str, value: str
          ) -> list[str]:
    """``base`` with the argument ``flag`` (a positional when empty) set to ``value``."""
    if flag:
        out = list(base)
        for i, token in enumerate(out[:-1]):
            if token == flag:
                out[i + 1] = value
                return out
        return [*out, flag, value]
    out = list(base)
    out[len(path)] = value  # the first positional follows the command path
    return out


@pytest.mark.parametrize("cls", ["binary bytes", "empty", "a directory", "missing"])
@pytest.mark.parametrize(("path", "flag", "dest"), _file_cases({"input"}))
def test_every_input_argument_refuses_a_hostile_file_in_one_line(
        path: tuple[str, ...], flag: str, dest: str, cls: str, files: dict[str, Path],
        tmp_path: Path) -> None:
    target = tmp_path / "in.dat"
    if cls == "binary bytes":
        target.write_bytes(b"\x89PNG\r\n\x1a\n\x00\xff\xfe" + bytes(range(256)))
    elif cls == "empty":
        target.write_bytes(b"")
    elif cls == "a directory":
        target.mkdir()
    argv = _with(_argv_for(path, dest, files), path, flag, dest, str(target))
    snap = Snapshot.take([files["root"], tmp_path])
    res = run_cli(argv)
    check_outcome(res, snapshot=snap, codes=[2])
    assert "in.dat" in res.err, res.err


@pytest.mark.parametrize("cls", ["an input", "a missing folder", "a directory"])
@pytest.mark.parametrize(("path", "flag", "dest"), _file_cases({"output", "output-dir"}))
def test_every_output_argument_refuses_a_bad_target_and_writes_nothing(
        path: tuple[str, ...], flag: str, dest: str, cls: str, files: dict[str, Path],
        tmp_path: Path) -> None:
    base = _argv_for(path, dest, files)
    is_dir = dest in OUTPUT_DIRS
    if cls == "an input":  # an input of this very command line
        inputs = [t for t in base if Path(t).is_file()]
        if not inputs:
            pytest.skip("the command reads no file of the user's")
        target = inputs[0]
    elif cls == "a missing folder":
        target = str(tmp_path / "missing" / "deeper" / ("d" if is_dir else "o.csv"))
        if is_dir:
            pytest.skip("an output folder is created with its parents")
    else:
        (tmp_path / "taken").mkdir()
        (tmp_path / "taken" / "file").write_text("x", encoding="utf-8")
        target = str(tmp_path / "taken" / "file") if is_dir else str(tmp_path / "taken")
    argv = _with(base, path, flag, dest, target)
    snap = Snapshot.take([files["root"], tmp_path])
    res = run_cli(argv)
    check_outcome(res, snapshot=snap, codes=[2])


# -------------------------------------------------------------------------- writers


def _format_cases() -> list[str]:
    from frictionlaws.fe_export import FORMATS as EXPORT_FORMATS

    return list(EXPORT_FORMATS)


#: Laws to export with, tried in order until one suits the format (the formats table
#: says what a format takes; the walk finds a law it takes).
_LAWS = [("exponential-decay", {"mu_s": 1.0, "mu_d": 0.6, "v_c": 1.0, "delta": 1.0},
          {"v": (0.01, 2.0, 5)}),
         ("thirion", {"a": 0.25, "b": 3.5e-6}, {"p": (1e4, 5e5, 5)}),
         ("coulomb", {"mu0": 0.5}, {})]


@dataclass
class _Export:
    law: str
    params: dict[str, float]
    box: dict[str, tuple[float, float, int]]


def _exporting(fmt: str) -> _Export:
    from frictionlaws.fe_export import export

    for law, params, box in _LAWS:
        try:
            export(law, params, fmt, box, source="walk")
        except InputError:
            continue
        return _Export(law, params, box)
    raise AssertionError(f"no law of the walk exports as {fmt}")


@pytest.mark.parametrize("fmt", _format_cases())
def test_every_export_format_keeps_hostile_text_in_its_line(fmt: str) -> None:
    """Checklist 11: a source holding every line separator and a payload adds no line:
    the file has the lines of one written from a plain source of the same length, and
    each line that differs starts as the plain one does (the comment it belongs to)."""
    from frictionlaws.fe_export import export

    job = _exporting(fmt)
    seps = ["\n", "\r", "\r\n", "\v", "\f", "\x1c", "\x85", "\u2028", "\u2029"]
    hostile = "SRC" + "".join(f"{s}*KEYWORD $ x" for s in seps)
    plain = "SRC" + "".join(f"{' ' * len(s)}*KEYWORD $ x" for s in seps)
    got = export(job.law, job.params, fmt, job.box, source=hostile).text.splitlines()
    ref = export(job.law, job.params, fmt, job.box, source=plain).text.splitlines()
    assert any("SRC" in ln for ln in got), "the source is not written"
    assert len(got) == len(ref), "hostile text changed the number of lines"
    for a, b in zip(got, ref):
        assert a.isascii(), a
        if a != b:
            assert a[:2] == b[:2], f"a line changed its kind: {a!r} (plain: {b!r})"


@pytest.mark.parametrize("cls", list(NUMBER_CLASSES))
@pytest.mark.parametrize("fmt", _format_cases())
def test_every_export_format_writes_no_number_past_the_parser(
        fmt: str, cls: str, tmp_path: Path) -> None:
    """Checklist 10: a parameter value spelled past the one number parser, from the
    command line, writes no file in any format."""
    job = _exporting(fmt)
    name, value = next(iter(job.params.items()))
    m = _NUMBER.search(repr(value))
    assert m is not None
    token = NUMBER_CLASSES[cls](m.group())
    sets = ",".join(f"{k}={token if k == name else v!r}" for k, v in job.params.items())
    ranges = [x for var, (lo, hi, n) in job.box.items()
              for x in (f"--{var}", f"{lo!r}:{hi!r}:{n}")]
    out = tmp_path / f"deck.{fmt}"
    snap = Snapshot.take([tmp_path])
    res = run_cli(["export", "--law", job.law, "--set", sets, "--format", fmt, "--units",
                   "SI", *ranges, "-o", str(out)])
    check_outcome(res, snapshot=snap, codes=[2])
    assert not out.exists()


@pytest.mark.parametrize("fmt", _format_cases())
def test_every_export_format_refuses_a_value_that_is_not_finite(fmt: str,
                                                               tmp_path: Path) -> None:
    from frictionlaws.fe_export import export

    job = _exporting(fmt)
    name = next(iter(job.params))
    for bad in (float("nan"), float("inf")):
        with pytest.raises(InputError):
            export(job.law, {**job.params, name: bad}, fmt, job.box,
                   path=tmp_path / f"x.{fmt}")
    assert not list(tmp_path.iterdir())


# ---------------------------------------------------------------- the code's patterns


def _patterns(package: Path = ROOT / "frictionlaws") -> Iterator[tuple[str, int, str]]:
    """Regular expressions of the package that say ``\\d`` without ``re.ASCII``."""
    for path in sorted(package.rglob("*.py")):
        source = path.read_text(encoding="utf-8")
        if "\\d" not in source:
            continue
        for node in ast.walk(ast.parse(source)):
            if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                    and isinstance(node.func.value, ast.Name) and node.func.value.id == "re"):
                continue
            pattern = node.args[0] if node.args else None
            if not (isinstance(pattern, ast.Constant) and isinstance(pattern.value, str)
                    and "\\d" in pattern.value and "(?a)" not in pattern.value):
                continue
            if "ASCII" not in (ast.get_source_segment(source, node) or ""):
                yield str(path.relative_to(package.parent)), node.lineno, pattern.value


def test_no_pattern_reads_digits_of_every_script() -> None:
    """``\\d`` matches any Unicode digit (``\u0663``, ``\uff13``): a pattern meant for numbers says
    ``[0-9]`` or is compiled with ``re.ASCII``."""
    found = [f"{f}:{n}: {p}" for f, n, p in _patterns()]
    assert not found, found


def test_the_pattern_check_sees_a_pattern(tmp_path: Path) -> None:
    (tmp_path / "pkg").mkdir()
    (tmp_path / "pkg" / "m.py").write_text(
        'import re\nA = re.compile(r"\\d+")\nB = re.compile(r"\\d", re.ASCII)\n'
        'C = re.sub(r"[0-9]", "", "x")\n', encoding="utf-8")
    assert [n for _, n, _ in _patterns(tmp_path / "pkg")] == [2]
