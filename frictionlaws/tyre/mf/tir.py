"""Magic Formula property files: the ADAMS ``.tir`` text format and its JSON variant.

A property file is a set of named sections, each a set of ``KEY = value``
entries.  Two spellings of the same content are read here:

* **ADAMS .tir** (text)::

      $------------------------------------------------ comment line
      ! another comment line
      [LONGITUDINAL_COEFFICIENTS]
      PCX1                     = 1.6      $Shape factor Cfx
      PDX1                     = 1.1      $Longitudinal friction Mux at Fznom
      [UNITS]
      LENGTH                   = 'meter'

  ``$`` starts a comment anywhere outside quotes, ``!`` and ``$`` at the start
  of a line make it a comment, values are numbers (Fortran ``1.0D+00`` too) or
  quoted strings, and a few sections hold tables: a ``{col1 col2}`` header
  followed by rows of numbers.
* **JSON** (the layout used by the example files in ``datasets/mf-examples``):
  one object whose members that are objects are the sections (``"MODEL"``,
  ``"LONGITUDINAL_COEFFICIENTS"``...); other members (``"Name"``, ``"Mass"``)
  are kept as metadata.

Both give a :class:`~frictionlaws.tyre.mf.property_file.PropertyFile`, and
:func:`format_tir` / :func:`write_tir` write one as ``.tir`` text.  Anything malformed raises
:class:`~frictionlaws.base.errors.InputError` naming the file and line.  The packaged example
files (``datasets/mf-examples``) are found by name here too
(:func:`packaged_example`, :func:`open_property_file`).
"""


from __future__ import annotations

import json
import math
import re
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from ...base import jsonio
from ...base.errors import InputError
from ...base.limits import read_input
from ...base.numbers import NUMBER_HELP, looks_numeric, parse_number
from ...base.outputs import check_input_file, write_text_atomic
from ...base.sanitize import ascii_line, split_lines, tir_string
from ...io import datasets_dir, decode_text
from .property_file import PropertyFile, Value, format_number

__all__ = ["read_property_file", "read_tir", "read_json", "write_tir", "format_tir",
           "json_to_tir", "converted_header", "CHRONO_PROVENANCE", "EXAMPLES",
           "packaged_example", "open_property_file", "read_packaged"]

CHRONO_PROVENANCE = ("Project Chrono, data/vehicle/generic/tire/ (commit 7689fbc0), "
                     "BSD-3-Clause, Copyright (c) Chrono Development Team; example data, "
                     "not measured")

_SECTION = re.compile(r"^\[\s*([A-Za-z0-9_]+)\s*\]\s*(?:\$.*)?$")
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_KEY = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)\s*=\s*(.*)$")
_TABLE_HEADER = re.compile(r"^\{(.*)\}\s*(?:\$.*)?$")
#: A number with a decimal comma (refused, naming the fix); ASCII digits only.
_DECIMAL_COMMA = re.compile(r"^[-+]?[0-9]*,[0-9]+([eEdD][-+]?[0-9]+)?$", re.ASCII)

# ------------------------------------------------------------------- reading


def read_property_file(path: str | Path) -> PropertyFile:
    """Read a ``.tir`` or ``.json`` property file (chosen by content, then suffix).

    Raises
    ------
    InputError
        File missing, unreadable or malformed (with the line number).
    """
    if not isinstance(path, (str, Path)):
        raise InputError(f"expected the path of a property file, got {type(path).__name__}")
    path = Path(path)
    check_input_file(path, "property file")
    raw = read_input(path, "property file")  # bounded in size
    text, _ = decode_text(raw, str(path), "property file")  # the one encoding rule
    if text.lstrip().startswith("{") or path.suffix.lower() == ".json":
        return read_json(text, source=str(path))
    return read_tir(text, source=str(path))


def read_json(text: str | Mapping[str, Any], *, source: str = "<memory>") -> PropertyFile:
    """Read the JSON variant (a text or an already decoded mapping)."""
    doc = _json_document(text, source) if isinstance(text, str) else text
    if not isinstance(doc, Mapping):
        raise InputError("expected a JSON object whose members are the sections", file=source)
    sections: dict[str, dict[str, Value]] = {}
    metadata: dict[str, Any] = {}
    for name, body in doc.items():
        if isinstance(body, Mapping):
            sec = _tir_name(str(name), "section", source)
            if sec in sections:
                raise InputError(f"section '{name}' appears twice (case-insensitive)",
                                 file=source)
            sections[sec] = _json_section(sec, body, source)
        else:
            metadata[str(name)] = body
    if not sections:
        raise InputError("no sections found (expected members such as "
                         "\"LONGITUDINAL_COEFFICIENTS\": {...})", file=source)
    return PropertyFile(sections, metadata=metadata, path=source, format="json")


def _json_document(text: str, source: str) -> Any:
    """The decoded JSON text (strict JSON: the project's one reader)."""
    try:
        return jsonio.loads(text)
    except json.JSONDecodeError as exc:
        raise InputError(f"not valid JSON: {exc.msg}", file=source, row=exc.lineno) from None
    except ValueError as exc:
        raise InputError(str(exc), file=source) from None


def _tir_name(name: str, what: str, source: str) -> str:
    """A JSON member's name as a ``.tir`` name (upper case), refused unless it is one.

    A ``.tir`` file can only hold names made of letters, digits and ``_``: anything else
    (``=``, ``$``, a bracket, a line break) would change the file written from it.
    """
    if not _NAME.fullmatch(name):
        shown = ascii_line(name)[:40]
        raise InputError(f"{what} '{shown}' is not a property-file name (letters, digits "
                         "and '_', not starting with a digit)", file=source)
    return name.upper()


def _json_section(sec: str, body: Mapping[str, Any], source: str) -> dict[str, Value]:
    """One JSON section: keys upper-cased (unique), values finite numbers or strings;
    ``null`` is an absent entry (the declared default; a required one is then missing)."""
    entries: dict[str, Value] = {}
    seen: set[str] = set()
    for key, value in body.items():
        k = _tir_name(str(key), f"[{sec}] key", source)
        if k in seen:
            raise InputError(f"[{sec}] {key} appears twice (case-insensitive)",
                             file=source)
        seen.add(k)
        if value is None:
            continue
        if isinstance(value, bool) or not isinstance(value, (int, float, str)):
            raise InputError(
                f"[{sec}] {key}: expected a number, a string or null (absent), got "
                f"{type(value).__name__}", file=source)
        if isinstance(value, float) and not math.isfinite(value):
            raise InputError(f"[{sec}] {key} is not finite", file=source)
        entries[k] = float(value) if isinstance(value, (int, float)) else value
    return entries


def _strip_comment(text: str) -> tuple[str, str]:
    """Split ``value $comment`` at the first ``$`` outside single quotes."""
    quoted = False
    for i, ch in enumerate(text):
        if ch == "'":
            quoted = not quoted
        elif ch == "$" and not quoted:
            return text[:i].rstrip(), text[i + 1:].strip()
    return text.rstrip(), ""


def _parse_value(raw: str, source: str, lineno: int, key: str) -> Value:
    raw = raw.strip()
    if not raw:
        raise InputError(f"{key} has no value", file=source, row=lineno)
    if raw[0] in "'\"":
        quote = raw[0]
        end = raw.find(quote, 1)
        if end < 0:
            raise InputError(f"{key}: unterminated string {raw}", file=source, row=lineno)
        if raw[end + 1:].strip():
            raise InputError(f"{key}: unexpected text after the string: {raw[end + 1:]!r}",
                             file=source, row=lineno)
        return raw[1:end]
    try:  # the one number parser (Fortran's D exponent too): no 1_0, no non-ASCII digits
        value = parse_number(raw, fortran=True, finite=False)
    except ValueError:
        pass
    else:
        if not math.isfinite(value):
            raise InputError(f"{key} = {raw} is not finite", file=source, row=lineno)
        return value
    if _DECIMAL_COMMA.match(raw):
        raise InputError(f"{key} = {raw}: a decimal comma; write {raw.replace(',', '.')} "
                         "(property files use a decimal point)", file=source, row=lineno)
    if " " in raw or "\t" in raw:
        raise InputError(f"{key} = {raw!r}: expected one number or a quoted string",
                         file=source, row=lineno)
    if looks_numeric(raw):  # nan, inf, 1_000, non-ASCII digits: no number, and no word
        raise InputError(f"{key} = {ascii_line(raw)[:40]} is not a number a property file "
                         f"holds (expected {NUMBER_HELP}, with the digits 0-9)",
                         file=source, row=lineno)
    return raw  # a bare word (e.g. TRUE): kept as text


def read_tir(text: str, *, source: str = "<memory>") -> PropertyFile:
    """Parse the text of an ADAMS ``.tir`` property file."""
    reader = _TirReader(source)
    for lineno, raw in enumerate(split_lines(text), start=1):
        line = raw.strip().lstrip("\ufeff")
        if line and line[0] not in "$!":
            reader.line(line, lineno)
    if not reader.sections:
        raise InputError("no [SECTION] found: not a .tir property file", file=source)
    return PropertyFile(reader.sections, reader.tables, path=source, format="tir",
                        lines=reader.lines, comments=reader.comments)


class _TirReader:
    """The state of a ``.tir`` parse: sections, tables, where each key was and comments."""

    def __init__(self, source: str) -> None:
        self.source = source
        self.sections: dict[str, dict[str, Value]] = {}
        self.tables: dict[str, tuple[list[str], list[list[float]]]] = {}
        self.lines: dict[tuple[str, str], int] = {}
        self.comments: dict[tuple[str, str], str] = {}
        self.current: str | None = None
        self.table: tuple[list[str], list[list[float]]] | None = None

    def line(self, line: str, lineno: int) -> None:
        """Read one non-blank, non-comment line."""
        m = _SECTION.match(line)
        if m:
            self._section(m.group(1).upper(), lineno)
            return
        if self.current is None:
            raise InputError(f"entry before the first [SECTION]: {line!r}", file=self.source,
                             row=lineno)
        m = _TABLE_HEADER.match(line)
        if m:
            self._table_header(self.current, m.group(1).split(), lineno)
            return
        m = _KEY.match(line)
        if m:
            self._entry(self.current, m.group(1).upper(), m.group(2), lineno)
            return
        if self.table is not None:
            self._table_row(self.current, self.table, line, lineno)
            return
        raise InputError(f"cannot read line {line!r}: expected KEY = value, [SECTION], "
                         "a $comment or a table row", file=self.source, row=lineno)

    def _section(self, name: str, lineno: int) -> None:
        if name in self.sections:
            raise InputError(f"section [{name}] appears twice", file=self.source, row=lineno)
        self.current = name
        self.sections[name] = {}
        self.table = None

    def _table_header(self, current: str, cols: list[str], lineno: int) -> None:
        if not cols:
            raise InputError("empty table header {}", file=self.source, row=lineno)
        if current in self.tables:
            raise InputError(f"section [{current}] has two tables", file=self.source,
                             row=lineno)
        self.table = (cols, [])
        self.tables[current] = self.table

    def _entry(self, current: str, key: str, rest: str, lineno: int) -> None:
        value_text, comment = _strip_comment(rest)
        if (current, key) in self.lines:
            raise InputError(
                f"[{current}] {key} is given twice (lines {self.lines[(current, key)]} and "
                f"{lineno}); remove one", file=self.source, row=lineno)
        self.sections[current][key] = _parse_value(value_text, self.source, lineno,
                                                     f"[{current}] {key}")
        self.lines[(current, key)] = lineno
        if comment:
            self.comments[(current, key)] = comment
        self.table = None

    def _table_row(self, current: str, table: tuple[list[str], list[list[float]]],
                   line: str, lineno: int) -> None:
        body, _ = _strip_comment(line)
        try:  # the one number parser: finite, the digits 0-9, Fortran's D exponent too
            row = [parse_number(p, fortran=True) for p in body.split()]
        except ValueError:
            raise InputError(f"[{current}] table row is not numeric: {line!r}",
                             file=self.source, row=lineno) from None
        if len(row) != len(table[0]):
            raise InputError(
                f"[{current}] table row has {len(row)} values, the header "
                f"{{{' '.join(table[0])}}} names {len(table[0])}", file=self.source,
                row=lineno)
        table[1].append(row)


# ------------------------------------------------------------------- writing


def format_tir(pf: PropertyFile, *, header: Iterable[str] = ()) -> str:
    """The ``.tir`` text of ``pf`` (sections in their order, tables included).

    ``header`` lines are written first as ``!`` comments (e.g. provenance).
    """
    out = [f"! {ascii_line(h)}" if h else "!" for h in header]
    for sec, entries in pf.sections.items():
        sec = ascii_line(sec)
        out.append("$" + "-" * (78 - len(sec)) + sec.lower())
        out.append(f"[{sec}]")
        for key, value in entries.items():
            text = f"'{tir_string(value)}'" if isinstance(value, str) else format_number(value)
            comment = pf.comments.get((sec, key))
            line = f"{ascii_line(key):<26} = {text}"
            if comment:
                line = f"{line:<50} ${ascii_line(comment)}"
            out.append(line)
        if sec in pf.tables:
            cols, rows = pf.tables[sec]
            out.append("{" + " ".join(ascii_line(c) for c in cols) + "}")
            out.extend(" ".join(format_number(x) for x in row) for row in rows)
    return "\n".join(out) + "\n"


def write_tir(pf: PropertyFile, path: str | Path, *, header: Iterable[str] = ()) -> Path:
    """Write ``pf`` as an ADAMS ``.tir`` file (see :func:`format_tir`)."""
    return write_text_atomic(Path(path), format_tir(pf, header=header))


def converted_header(source: str, provenance: str) -> list[str]:
    """Header lines that label a ``.tir`` written from another file as a conversion."""
    return [
        f"CONVERTED by frictionlaws from {source}: not an original ADAMS property file.",
        "Same sections, keys and values as the source; its non-section members follow.",
        f"Source: {provenance}",
    ]


def json_to_tir(src: str | Path, dst: str | Path, *, provenance: str) -> Path:
    """Write the JSON property file ``src`` as a ``.tir`` file ``dst``, labelled as converted.

    Top-level JSON members that are not sections (``Name``, ``Mass``...) are
    written as header comments so that nothing is lost.
    """
    src = Path(src)
    pf = read_property_file(src)
    header = converted_header(src.name, provenance)
    for k, v in pf.metadata.items():
        header.append(f"JSON member {k}: {json.dumps(v)}")
    return write_tir(pf, dst, header=header)


# ----------------------------------------------------------- the packaged examples

#: Packaged example property files (``datasets/mf-examples``), by short name.
EXAMPLES = {
    "magicformula52": "MagicFormula52_Parameters.json",
    "magicformula61": "MagicFormula61_Parameters.json",
    "magicformula62": "MagicFormula62_Parameters.json",
}


def packaged_example(name: str) -> Path | None:
    """Path of a packaged example property file named ``name`` (with or without suffix)."""
    key = Path(name).name.lower()
    for suffix in (".json", ".tir"):
        key = key.removesuffix(suffix)
    key = key.removesuffix("_parameters")
    fname = EXAMPLES.get(key)
    candidates = [fname] if fname else []
    if Path(name).name != name:
        return None
    candidates.append(Path(name).name)
    try:
        root = datasets_dir() / "mf-examples"
        for cand in candidates:
            p = root / cand
            if p.is_file():
                return Path(str(p))
    except (ModuleNotFoundError, FileNotFoundError):
        return None
    return None


def open_property_file(path: str | Path | PropertyFile) -> PropertyFile:
    """A property file read from ``path``, or the packaged example of that name.

    A packaged example is named by its file name (``packaged:NAME``), not where pip
    installed it; a :class:`~frictionlaws.tyre.mf.property_file.PropertyFile` is returned
    as it is.
    """
    if isinstance(path, PropertyFile):
        return path
    if not isinstance(path, (str, Path)):
        raise InputError(f"expected the path of a property file (or a packaged example "
                         f"name), got {type(path).__name__}")
    if not Path(path).exists():
        packaged = read_packaged(str(path))
        if packaged is not None:
            return packaged
    return read_property_file(path)


def read_packaged(name: str) -> PropertyFile | None:
    """The packaged example ``name`` read, named ``packaged:FILE`` (not where pip
    installed it); None when there is none of that name."""
    path = packaged_example(name)
    if path is None:
        return None
    pf = read_property_file(path)
    pf.path = f"packaged:{path.name}"
    return pf
