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

Both give a :class:`PropertyFile`.  Keys and section names are case-insensitive
(stored in upper case).  Anything malformed raises
:class:`~frictionlaws.base.errors.InputError` naming the file and line.  The
``[UNITS]`` section is honoured: :meth:`PropertyFile.si` converts the
dimensional entries (loads, lengths, pressures, stiffnesses) to SI with pint.
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..base.errors import InputError
from ..base.numbers import NUMBER_HELP, looks_numeric, parse_number
from ..base.sanitize import ascii_line, split_lines, tir_string
from .mf_coefficients import DECLARED, STRUCTURE_SECTIONS, outside_fit, section_keys

__all__ = ["PropertyFile", "read_property_file", "read_tir", "read_json", "write_tir",
           "format_tir", "json_to_tir", "converted_header", "CHRONO_PROVENANCE"]

#: Provenance of the packaged example property files (datasets/mf-examples).
CHRONO_PROVENANCE = ("Project Chrono, data/vehicle/generic/tire/ (commit 7689fbc0), "
                     "BSD-3-Clause, Copyright (c) Chrono Development Team; example data, "
                     "not measured")

Value = float | str

_SECTION = re.compile(r"^\[\s*([A-Za-z0-9_]+)\s*\]\s*(?:\$.*)?$")
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_KEY = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)\s*=\s*(.*)$")
_TABLE_HEADER = re.compile(r"^\{(.*)\}\s*(?:\$.*)?$")
#: A number with a decimal comma (refused, naming the fix); ASCII digits only.
_DECIMAL_COMMA = re.compile(r"^[-+]?[0-9]*,[0-9]+([eEdD][-+]?[0-9]+)?$", re.ASCII)

#: The SI symbols of the declarations' units and the file's ``[UNITS]`` entry each is
#: converted from (a unit per radian is per radian in every file: angles must be radians).
_UNIT_KINDS = {"N": "force", "m": "length", "s": "time", "kg": "mass", "Pa": "pressure"}


def _unit_kind(unit: str) -> str | None:
    """The kind of a declared SI unit (``"N/m"`` -> ``"force/length"``), None if none."""
    kind = re.sub(r"/rad(\*\*[0-9])?|\brad(\*\*[0-9])?\b", "", unit)
    kind = re.sub(r"\b(N|m|s|kg|Pa)\b", lambda m: _UNIT_KINDS[m.group(1)], kind)
    return kind if re.search(r"force|length|time|mass|pressure", kind) else None


#: Dimensional entries and the kind of unit they carry, for :meth:`PropertyFile.si`,
#: from the declarations' units (:mod:`frictionlaws.tyre.mf_coefficients`).  Everything
#: else a Magic Formula uses is dimensionless or an angle (radians).
DIMENSIONAL = {(c.section, c.name): kind for c in DECLARED.values()
               if (kind := _unit_kind(c.unit)) is not None}


#: The coefficient names of the Magic Formula 5.2 (PAC2002), 6.1 and 6.2 property
#: files, per section (from the declarations, :mod:`frictionlaws.tyre.mf_coefficients`):
#: a key of a coefficient section outside this list is unknown (listed to the user, or
#: refused when it is a near miss of an absent name).
MF_KEYS: dict[str, frozenset[str]] = section_keys()


@dataclass
class PropertyFile:
    """The content of a Magic Formula property file.

    Attributes
    ----------
    sections : dict
        Section name (upper case) -> {key (upper case) -> float or str}.
    tables : dict
        Section name -> (column names, list of rows) for table sections.
    metadata : dict
        Top-level JSON members that are not sections (``Name``, ``Mass``...).
    path : str
        Where it was read from (``"<memory>"`` when built in code).
    format : str
        ``"tir"`` or ``"json"``.
    lines : dict
        (section, key) -> line number in a ``.tir`` file, for messages.
    comments : dict
        (section, key) -> the trailing ``$comment`` of a ``.tir`` entry.
    """

    sections: dict[str, dict[str, Value]]
    tables: dict[str, tuple[list[str], list[list[float]]]] = field(default_factory=dict)
    metadata: dict[str, Any] = field(default_factory=dict)
    path: str = "<memory>"
    format: str = "tir"
    lines: dict[tuple[str, str], int] = field(default_factory=dict)
    comments: dict[tuple[str, str], str] = field(default_factory=dict)

    # ----------------------------------------------------------------- access
    def has(self, section: str, key: str) -> bool:
        """True when ``[section] key`` is present."""
        return key.upper() in self.sections.get(section.upper(), {})

    def get(self, section: str, key: str, default: Any = None) -> Any:
        """The raw value of ``[section] key`` (float or str), or ``default``."""
        return self.sections.get(section.upper(), {}).get(key.upper(), default)

    def number(self, section: str, key: str, default: float | None = None) -> float:
        """``[section] key`` as a float (file units); ``default`` when absent.

        Raises
        ------
        InputError
            When the entry is absent and no default is given, or is not a number.
        """
        section, key = section.upper(), key.upper()
        value = self.sections.get(section, {}).get(key)
        if value is None:
            if default is None:
                raise InputError(f"[{section}] {key} is missing", file=self.path)
            return float(default)
        if isinstance(value, str):
            raise InputError(f"[{section}] {key} = '{value}' is text, expected a number",
                             file=self.path, row=self.lines.get((section, key)))
        return float(value)

    def text(self, section: str, key: str, default: str | None = None) -> str | None:
        """``[section] key`` as text (numbers are formatted), or ``default``."""
        value = self.get(section, key)
        if value is None:
            return default
        return value if isinstance(value, str) else _format_number(value)

    def coefficients(self, *sections: str) -> dict[str, float]:
        """All numeric entries of ``sections`` merged into one dict (upper-case keys)."""
        out: dict[str, float] = {}
        for sec in sections:
            for k, v in self.sections.get(sec.upper(), {}).items():
                if not isinstance(v, str):
                    out[k] = float(v)
        return out

    def check_coefficients(self) -> list[str]:
        """Check the coefficient sections against :data:`MF_KEYS`.

        Returns
        -------
        list of str
            A note listing unknown keys (kept, not used), when there are any.

        Raises
        ------
        InputError
            A coefficient that is text instead of a number, or an unknown key that
            is a near miss of a standard name the file lacks (a misspelling that
            would silently leave the coefficient at its default).
        """
        import difflib

        unknown: list[str] = []
        for sec, known in MF_KEYS.items():
            entries = self.sections.get(sec, {})
            for key, value in entries.items():
                row = self.lines.get((sec, key))
                if isinstance(value, str):
                    raise InputError(f"[{sec}] {key} = '{value}' is text, expected a number",
                                     file=self.path, row=row)
                if key in known:
                    continue
                home = next((other for other, names in MF_KEYS.items() if key in names), None)
                if home is not None:
                    raise InputError(
                        f"[{sec}] {key} belongs to [{home}]: is the [{home}] header missing "
                        "above it?", file=self.path, row=row)
                near = [k for k in difflib.get_close_matches(key, known, n=3, cutoff=0.75)
                        if k not in entries]
                if near:
                    raise InputError(
                        f"[{sec}] unknown key {key}: did you mean {' or '.join(near)}? "
                        f"({near[0]} is absent, so it would take its default)",
                        file=self.path, row=row)
                unknown.append(f"[{sec}] {key}")
        notes = self.check_bounds()
        if unknown:
            notes.append("unknown keys kept but not used by the Magic Formula: "
                         + ", ".join(unknown))
        return notes

    def check_bounds(self) -> list[str]:
        """Check every declared entry against its bounds (in SI, with ``[UNITS]``).

        Returns
        -------
        list of str
            Notes of values outside the range fit-mf searches (possible, but unusual).

        Raises
        ------
        InputError
            A value outside the physically possible ones, naming section, key, value,
            the bounds and the line.
        """
        notes: list[str] = []
        for sec, entries in self.sections.items():
            for key, value in entries.items():
                c = DECLARED.get(key)
                if c is None or isinstance(value, str) or not (
                        c.section == sec or (sec in STRUCTURE_SECTIONS
                                             and c.section in STRUCTURE_SECTIONS)):
                    continue
                si = self.si(sec, key)
                if not c.allows(si):
                    shown = f"{value:g}" + (f" ({si:g} SI)" if si != value else "")
                    raise InputError(c.refusal(shown, sec), file=self.path,
                                     row=self.lines.get((sec, key)))
                note = outside_fit(key, si)
                if note:
                    notes.append(note)
        return notes

    # ------------------------------------------------------------------ units
    def unit(self, kind: str) -> str:
        """The unit the file declares for ``kind`` (LENGTH, FORCE, ANGLE, MASS, TIME, PRESSURE).

        Missing entries mean SI (meter, newton, radian, kg, second, pascal).
        """
        defaults = {"LENGTH": "meter", "FORCE": "newton", "ANGLE": "radian", "MASS": "kg",
                    "TIME": "second", "PRESSURE": ""}
        value = self.text("UNITS", kind, defaults[kind.upper()])
        return (value or "").strip()

    def si(self, section: str, key: str, default: float | None = None) -> float:
        """``[section] key`` converted to SI with the file's ``[UNITS]`` (pint).

        Dimensionless entries are returned unchanged.  ``default`` is taken as
        already SI.
        """
        section, key = section.upper(), key.upper()
        if not self.has(section, key):
            if default is None:
                raise InputError(f"[{section}] {key} is missing", file=self.path)
            return float(default)
        value = self.number(section, key)
        kind = DIMENSIONAL.get((section, key))
        if kind is None:
            return value
        return value * self.si_factor(kind)

    def si_factor(self, kind: str) -> float:
        """Factor from the file's unit of ``kind`` (e.g. ``"force/length"``) to SI.

        The file's units are read by the one unit grammar
        (:func:`~frictionlaws.base.units.parse_unit_text`), never evaluated by pint.
        """
        from ..base.units import parse_unit_text, unit_registry

        ureg = unit_registry()
        pieces = {"force": self.unit("FORCE"), "length": self.unit("LENGTH"),
                  "time": self.unit("TIME"), "mass": self.unit("MASS")}
        if kind == "pressure" and self.unit("PRESSURE"):
            expr, target = _pint_name(self.unit("PRESSURE")), "pascal"
        else:
            formula = "force/length**2" if kind == "pressure" else kind
            expr = re.sub(r"\b(force|length|time|mass)\b",
                          lambda m: f"({_pint_name(pieces[m.group(1)])})", formula)
            target = re.sub(r"\b(force|length|time|mass)\b",
                            lambda m: {"force": "newton", "length": "meter", "time": "second",
                                       "mass": "kilogram"}[m.group(1)], formula)
        try:
            unit = parse_unit_text(expr).to_pint()
            return float(ureg.Quantity(1.0, unit).to(target).magnitude)
        except Exception as exc:  # noqa: BLE001 - pint raises several types
            raise InputError(f"[UNITS] cannot convert '{ascii_line(expr)[:80]}' to {target} "
                             f"({ascii_line(exc)[:120]})", file=self.path) from None

    def check_angle_unit(self) -> None:
        """Raise when the file's angles are not in radians (coefficients assume radians)."""
        unit = self.unit("ANGLE").lower()
        if unit not in ("radian", "radians", "rad"):
            from ..base.units import parse_unit_text, unit_registry

            ureg = unit_registry()
            try:
                angle = parse_unit_text(_pint_name(unit)).to_pint()
                factor = float(ureg.Quantity(1.0, angle).to("radian").magnitude)
            except Exception:  # noqa: BLE001
                factor = math.nan
            if factor != 1.0:
                raise InputError(
                    f"[UNITS] ANGLE = '{unit}': only property files with angles in radians "
                    "are supported (slip-angle and camber coefficients are defined per "
                    "radian); convert the file", file=self.path,
                    row=self.lines.get(("UNITS", "ANGLE")))

    def __repr__(self) -> str:
        return (f"<PropertyFile {self.path!r} ({self.format}): "
                f"{len(self.sections)} sections>")


def _pint_name(unit: str) -> str:
    """Unit names as ADAMS writes them -> names pint knows."""
    u = unit.strip().strip("'").strip()
    aliases = {"METER": "meter", "MM": "millimeter", "CM": "centimeter", "KM": "kilometer",
               "NEWTON": "newton", "KN": "kilonewton", "N": "newton", "KGF": "kilogram_force",
               "POUND_FORCE": "pound_force", "LBF": "pound_force", "SECOND": "second",
               "SEC": "second", "MILLI": "millisecond", "PASCAL": "pascal", "KPA": "kilopascal",
               "MPA": "megapascal", "BAR": "bar", "PSI": "psi", "RADIAN": "radian",
               "RADIANS": "radian", "DEGREE": "degree", "DEGREES": "degree", "DEG": "degree"}
    return aliases.get(u.upper(), u)


def _format_number(x: float) -> str:
    if float(x).is_integer() and abs(x) < 1e15:
        return str(int(x))
    return repr(float(x))


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
    from ..base.limits import read_input
    from ..base.outputs import check_input_file
    from ..io import decode_text

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
    from ..base import jsonio

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
            text = f"'{tir_string(value)}'" if isinstance(value, str) else _format_number(value)
            comment = pf.comments.get((sec, key))
            line = f"{ascii_line(key):<26} = {text}"
            if comment:
                line = f"{line:<50} ${ascii_line(comment)}"
            out.append(line)
        if sec in pf.tables:
            cols, rows = pf.tables[sec]
            out.append("{" + " ".join(ascii_line(c) for c in cols) + "}")
            out.extend(" ".join(_format_number(x) for x in row) for row in rows)
    return "\n".join(out) + "\n"


def write_tir(pf: PropertyFile, path: str | Path, *, header: Iterable[str] = ()) -> Path:
    """Write ``pf`` as an ADAMS ``.tir`` file (see :func:`format_tir`)."""
    from ..base.outputs import write_text_atomic  # atomic, never over a file read

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
