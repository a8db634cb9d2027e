"""TYDEX files: the tyre test rigs' exchange format, read into and written from tyre data.

A TYDEX file (TYDEX-Format, Description and Reference Manual, Release 1.3, 1997) is text in
sections, each opened by a keyword line in column 1::

    **HEADER          RELEASE, MEASID, SUPPLIER, DATE ...: name, description, value
    **COMMENTS        free text
    **CONSTANTS       conditions of the measurement: name, description, unit, value
    **MEASURCHANNELS  the channels: name, description, unit, conversion factor
    **MEASURDATA      one row per sample, a value per channel, separated by blanks
    **END

Lines are fixed width: the name in columns 1-10, the description in 11-40, the unit in
41-50 and the value (a constant) or the conversion factor (a channel) from column 51; a
value of a channel in its unit is the number in ``**MEASURDATA`` times the factor.  Lines
that start with ``!`` are comments.  Forces and moments are in the W axes (the ISO-W axes
of a Magic Formula property file: x forward, y left, z up, F_z > 0 for a loaded tyre).  One
file holds one sweep type (a slip-angle sweep at one load, say), so a test is several files.

:func:`read_tydex` gives the rows as :class:`~frictionlaws.tyre.data.table.TyreData` (SI,
ISO-W): ``FZW`` the load, ``LONGSLIP`` the slip ratio (``-`` or ``%``), ``SLIPANGL`` the slip
angle, ``INCLANGL`` the camber, ``INFLPRES`` the pressure, ``FX`` (``FXW``, ``FXH``: the same
force) ``FYW``, ``MZW`` the forces and aligning moment.  A quantity without a channel takes
the file's constant of that name (a longitudinal sweep's ``SLIPANGL`` = 0, the ``INFLPRES``
of the test), else its default (slips and camber 0, pressure not measured).  Refused, naming
the file, the line and the channel: a file without ``**HEADER`` first or without ``**END``
(truncated), a section given twice or unknown, a channel given twice (or two channels of one
quantity), a channel name close to a TYDEX name (``SLIPANG``: a misspelling would lose the
channel), a force in hub or centre axes or without its axis (``FYH``, ``FZ``: give W axes), a
channel without a unit or a conversion factor, a factor of 0, offsets (their convention
differs between tools: subtract them first), a data row with another number of values than
channels.  Other channels (``RUNTIME``, temperatures, a rig's own) are named as not used.

:func:`tydex_text` and :func:`write_tydex` write tyre data (the rows of a fit, a property
file's evaluation) as a TYDEX file for other tools; read back, it gives the same data.
"""

from __future__ import annotations

import difflib
import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ... import __version__
from ...base.errors import InputError
from ...base.numbers import parse_number
from ...base.outputs import atomic_write, check_outputs
from ...base.sanitize import ascii_line
from ...base.units import from_si
from .channels import (
    KINDS,
    MEANINGS,
    TYDEX_CHANNELS,
    TYDEX_OTHER_AXES,
    convert,
    read_lines,
    unit_text,
)
from .table import COLUMNS, TyreData, check_sign_convention, to_iso_axes

__all__ = ["TydexChannel", "TydexConstant", "TydexFile", "load_tydex", "read_tydex",
           "tydex_text", "write_tydex", "is_tydex", "SECTIONS", "TYDEX_NAMES", "TYDEX_UNITS"]

#: The keywords of a TYDEX 1.3 file, in their order.
SECTIONS = ("HEADER", "COMMENTS", "CONSTANTS", "MEASURCHANNELS", "MEASURDATA",
            "MODELDEFINITION", "MODELPARAMETERS", "MODELCOEFFICIENTS", "MODELCHANNELS",
            "MODELOUTPUTS", "MODELEND", "END")

#: Quantity -> the TYDEX channel written for it.
TYDEX_NAMES = {"fz": "FZW", "kappa": "LONGSLIP", "alpha": "SLIPANGL", "gamma": "INCLANGL",
               "pressure": "INFLPRES", "fx": "FX", "fy": "FYW", "mz": "MZW"}
#: Quantity -> the unit written by default.
TYDEX_UNITS = {"fz": "N", "kappa": "-", "alpha": "deg", "gamma": "deg", "pressure": "kPa",
               "fx": "N", "fy": "N", "mz": "Nm"}
_DESCRIPTIONS = {"fz": "Vertical force, W axes", "kappa": "Longitudinal slip",
                 "alpha": "Slip angle", "gamma": "Inclination angle",
                 "pressure": "Inflation pressure", "fx": "Longitudinal force",
                 "fy": "Lateral force, W axes", "mz": "Aligning moment, W axes"}
#: A TYDEX name: ASCII letters, digits and underscores.
_NAME = re.compile(r"[A-Za-z0-9_]{1,10}")
#: Text that stands for a missing value in the data of other tools.
_NOT_AVAILABLE = "NOTAVAIL"
_FIXED = ("TYDEX lines are fixed width: name in columns 1-10, description 11-40, unit "
          "41-50, value or conversion factor from 51")


@dataclass
class TydexChannel:
    """One line of ``**MEASURCHANNELS``: the channel's name, description, unit and factor."""

    name: str
    description: str
    unit: str
    factor: float
    line: int


@dataclass
class TydexConstant:
    """One line of ``**CONSTANTS``: name, description, unit and the value as written."""

    name: str
    description: str
    unit: str
    text: str
    line: int


@dataclass
class TydexFile:
    """The content of a TYDEX file: header, comments, constants, channels and data.

    ``values`` holds one column per channel in the channel's unit (the numbers of
    ``**MEASURDATA`` times the conversion factors); ``lines`` the file line of each row.
    """

    source: str
    header: dict[str, str] = field(default_factory=dict)
    comments: list[str] = field(default_factory=list)
    constants: dict[str, TydexConstant] = field(default_factory=dict)
    channels: list[TydexChannel] = field(default_factory=list)
    values: np.ndarray = field(default_factory=lambda: np.empty((0, 0)))
    lines: np.ndarray = field(default_factory=lambda: np.empty(0, dtype=int))
    notes: list[str] = field(default_factory=list)

    def to_tyre_data(self, sign_convention: str = "iso") -> TyreData:
        """The rows as tyre data in SI and ISO-W axes (module documentation).

        Parameters
        ----------
        sign_convention : {"iso", "sae"}
            The axes of the forces: TYDEX W axes are ISO-W; ``"sae"`` for a file written in
            SAE axes (F_z < 0 for a loaded tyre).

        Returns
        -------
        TyreData
        """
        check_sign_convention(sign_convention)
        by_quantity = self._quantities()
        n = self.values.shape[0]
        arrays: dict[str, np.ndarray] = {}
        said: list[str] = []
        for q in COLUMNS:
            arrays[q], how = self._quantity(q, by_quantity.get(q), n)
            if how:
                said.append(how)
        if not any(q in by_quantity for q in ("fx", "fy", "mz")):
            raise InputError("no FX, FYW or MZW channel: nothing to fit", file=self.source)
        unused = [c.name for c in self.channels if TYDEX_CHANNELS.get(c.name) not in COLUMNS]
        notes = list(self.notes) + [f"TYDEX: {'; '.join(said)}"]
        if unused:
            notes.append(f"channels not used: {', '.join(unused)}")
        notes.extend(self._nominal())
        notes.append(to_iso_axes(arrays, sign_convention))
        missing = tuple(q for q in ("kappa", "alpha", "gamma", "pressure")
                        if q not in by_quantity and TYDEX_NAMES[q] not in self.constants)
        units = {q: by_quantity[q].unit for q in by_quantity if q in COLUMNS}
        extra = {"time": convert(self.values[:, self._index(by_quantity["time"])],
                                 by_quantity["time"].unit, "time", file=self.source,
                                 column="RUNTIME")} if "time" in by_quantity else {}
        data = TyreData(arrays["fz"], arrays["kappa"], arrays["alpha"], arrays["gamma"],
                        arrays["pressure"], arrays["fx"], arrays["fy"], self.lines.copy(),
                        self.source, notes, arrays["mz"], tuple(unused), missing,
                        sign_convention, units, extra)
        data.validate()
        return data

    def _index(self, channel: TydexChannel) -> int:
        return self.channels.index(channel)

    def _quantities(self) -> dict[str, TydexChannel]:
        """Quantity -> its channel; two channels of one quantity refused."""
        out: dict[str, TydexChannel] = {}
        for c in self.channels:
            q = TYDEX_CHANNELS.get(c.name)
            if q is None:
                continue
            if q in out:
                raise InputError(f"two channels give the {MEANINGS[q]}: {out[q].name} (line "
                                 f"{out[q].line}) and {c.name}", file=self.source,
                                 column=c.name, row=c.line)
            out[q] = c
        return out

    def _quantity(self, q: str, channel: TydexChannel | None, n: int
                  ) -> tuple[np.ndarray, str]:
        """The SI values of quantity ``q`` and how they were found."""
        if channel is not None:
            values = convert(self.values[:, self._index(channel)], channel.unit, q,
                             file=self.source, column=channel.name, row=channel.line)
            bad = ~np.isfinite(values) & np.isfinite(self.values[:, self._index(channel)])
            if bad.any():
                raise InputError("value is not finite in SI", file=self.source,
                                 column=channel.name, row=int(self.lines[np.argmax(bad)]))
            factor = "" if channel.factor == 1 else f" x {channel.factor:g}"
            return values, f"{q} from {channel.name} [{channel.unit}{factor}]"
        constant = self.constants.get(TYDEX_NAMES[q])
        if constant is not None:
            value = self.constant(constant.name, q)
            return np.full(n, value), (f"{q} = {constant.text} {constant.unit} (constant "
                                       f"{constant.name})")
        if q == "fz":
            raise InputError("no FZW channel or constant (the vertical load)",
                             file=self.source)
        return np.full(n, math.nan if q in ("pressure", "fx", "fy", "mz") else 0.0), ""

    def constant(self, name: str, quantity: str) -> float:
        """The SI value of the constant ``name`` as ``quantity`` (refused when not a number).

        Parameters
        ----------
        name : str
            A constant of the file.
        quantity : str
            A key of :data:`~frictionlaws.tyre.data.channels.KINDS`.

        Returns
        -------
        float
        """
        c = self.constants[name]
        try:
            number = parse_number(c.text)
        except ValueError as exc:
            raise InputError(f"constant {name}: {exc}", file=self.source, column=name,
                             row=c.line) from None
        return float(convert(number, c.unit, quantity, file=self.source, column=name,
                             row=c.line))

    def _nominal(self) -> list[str]:
        """Notes on the nominal conditions the file states (not used by the fit)."""
        out = []
        for name, q in (("NOMPRES", "pressure"), ("FNOMIN", "fz")):
            if name in self.constants:
                value = self.constant(name, q)
                out.append(f"the file states {name} {value:g} {'Pa' if q == 'pressure' else 'N'}"
                           " (the fitted file takes its own from the template or the data)")
        return out


def is_tydex(lines: Sequence[str]) -> bool:
    """True when the first line that is not blank or a ``!`` comment is ``**HEADER``."""
    for line in lines[:1000]:
        s = line.strip()
        if s and not s.startswith("!"):
            return s.upper().startswith("**HEADER")
    return False


def _keyword(line: str) -> str | None:
    """The keyword of a section line (``**NAME``), else None."""
    s = line.strip()
    if not s.startswith("**"):
        return None
    return s[2:].split()[0].upper() if s[2:].strip() else ""


def _sections(lines: Sequence[str], source: str) -> dict[str, list[tuple[int, str]]]:
    """Section -> its (line number, line) pairs; the order and the end checked."""
    out: dict[str, list[tuple[int, str]]] = {}
    current: str | None = None
    end = 0
    for number, line in enumerate(lines, start=1):
        key = _keyword(line)
        if key is not None:
            if key not in SECTIONS:
                raise InputError(f"unknown keyword '**{key[:20]}'; TYDEX 1.3 has "
                                 + ", ".join(f"**{s}" for s in SECTIONS), file=source,
                                 row=number)
            if key in out:
                raise InputError(f"section **{key} is given twice (lines "
                                 f"{out[key][0][0] - 1} and {number})", file=source,
                                 row=number)
            current = key
            out[key] = [(number + 1, "")]  # where it starts, for messages
            if key == "END":
                end = number
                break
            continue
        if current is None:
            if line.strip() and not line.strip().startswith("!"):
                raise InputError("a TYDEX file starts with **HEADER", file=source, row=number)
            continue
        if current != "COMMENTS" and line.strip().startswith("!"):
            continue
        out[current].append((number, line))
    _check_sections(out, lines, end, source)
    return {k: v[1:] for k, v in out.items()}


def _check_sections(out: dict[str, list[tuple[int, str]]], lines: Sequence[str], end: int,
                    source: str) -> None:
    if not end:
        raise InputError(f"the file ends at line {len(lines)} without **END: it is truncated "
                         "(or not a whole TYDEX file)", file=source, row=len(lines) or None)
    after = [i for i in range(end, len(lines)) if lines[i].strip()]
    if after:
        raise InputError("text after **END", file=source, row=after[0] + 1)
    for key in ("HEADER", "MEASURCHANNELS", "MEASURDATA"):
        if key not in out:
            raise InputError(f"no **{key} section", file=source)


def _fields(line: str, number: int, source: str, what: str) -> tuple[str, str, str, str]:
    """Name, description, unit and the rest of a fixed-width line."""
    if "\t" in line:
        raise InputError(f"a tab in a {what} line: {_FIXED}", file=source, row=number)
    name = line[:10].strip()
    if not _NAME.fullmatch(name):
        raise InputError(f"the name field (columns 1-10) of this {what} line holds "
                         f"{ascii(line[:10].strip()[:20])}, not a name of letters, digits and "
                         f"_: {_FIXED}", file=source, row=number)
    return name.upper(), line[10:40].strip(), line[40:50].strip(), line[50:].strip()


def _channel(line: str, number: int, source: str) -> TydexChannel:
    name, description, unit, rest = _fields(line, number, source, "channel")
    if not unit:
        raise InputError(f"channel {name} has no unit (columns 41-50; '-' for a "
                         f"dimensionless channel): {_FIXED}", file=source, column=name,
                         row=number)
    tokens = rest.split()
    if not tokens:
        raise InputError(f"channel {name} has no conversion factor (from column 51; 1 when "
                         "the data are in the unit)", file=source, column=name, row=number)
    if len(tokens) > 3:
        raise InputError(f"channel {name}: {len(tokens)} numbers after the unit; expected a "
                         f"conversion factor and at most two offsets: {_FIXED}", file=source,
                         column=name, row=number)
    try:
        numbers = [parse_number(t) for t in tokens]
    except ValueError as exc:
        raise InputError(f"channel {name}: {exc}", file=source, column=name,
                         row=number) from None
    if numbers[0] == 0:
        raise InputError(f"channel {name} has a conversion factor of 0: every value would be "
                         "0", file=source, column=name, row=number)
    if any(v != 0 for v in numbers[1:]):
        raise InputError(f"channel {name} gives offsets ({', '.join(tokens[1:])}): tools "
                         "apply them differently; subtract them from the data and write 0",
                         file=source, column=name, row=number)
    return TydexChannel(name, description, unit, numbers[0], number)


def _check_names(channels: list[TydexChannel], source: str, notes: list[str]) -> None:
    """Duplicates, misspellings and forces in other axes refused; unknown names noted."""
    seen: dict[str, TydexChannel] = {}
    unknown = []
    used = [n for n, q in TYDEX_CHANNELS.items() if q is not None]
    for c in channels:
        if c.name in seen:
            raise InputError(f"channel {c.name} is given twice (lines {seen[c.name].line} and "
                             f"{c.line})", file=source, column=c.name, row=c.line)
        seen[c.name] = c
        if c.name in TYDEX_OTHER_AXES:
            raise InputError(f"channel {c.name} is not in W axes (TYDEX names the axes: "
                             f"{TYDEX_OTHER_AXES[c.name]} in W axes, those of a property "
                             "file); give the forces and moments in W axes", file=source,
                             column=c.name, row=c.line)
        if c.name not in TYDEX_CHANNELS:
            close = difflib.get_close_matches(c.name, used, n=1, cutoff=0.8)
            if close:
                raise InputError(f"unknown channel {c.name}: did you mean {close[0]} (the "
                                 f"{MEANINGS[TYDEX_CHANNELS[close[0]] or 'fz']})?",
                                 file=source, column=c.name, row=c.line)
            unknown.append(c.name)
    if unknown:
        notes.append(f"channels not in TYDEX 1.3's list (a rig's own): {', '.join(unknown)}")


def _data(rows: list[tuple[int, str]], channels: list[TydexChannel], source: str
          ) -> tuple[np.ndarray, np.ndarray]:
    """The data rows times the factors, and their line numbers."""
    rows = [(n, line) for n, line in rows if line.strip()]
    if not rows:
        raise InputError("**MEASURDATA holds no row", file=source)
    values = np.empty((len(rows), len(channels)))
    lines = np.empty(len(rows), dtype=int)
    for i, (number, line) in enumerate(rows):
        tokens = line.split()
        if len(tokens) != len(channels):
            short = len(tokens) < len(channels)
            raise InputError(f"{len(tokens)} values on this row, {len(channels)} channels "
                             "declared (a truncated or broken row?): "
                             + (f"no value of {channels[len(tokens)].name}" if short
                                else f"a value past {channels[-1].name}, the last channel"),
                             file=source, row=number,
                             column=channels[min(len(tokens), len(channels) - 1)].name)
        for j, token in enumerate(tokens):
            if token.upper() == _NOT_AVAILABLE:
                values[i, j] = math.nan
                continue
            try:
                values[i, j] = parse_number(token)
            except ValueError as exc:
                raise InputError(str(exc), file=source, column=channels[j].name,
                                 row=number) from None
        lines[i] = number
    with np.errstate(over="ignore"):
        values *= np.array([c.factor for c in channels])
    return values, lines


def _named(rows: list[tuple[int, str]], source: str, with_unit: bool
           ) -> dict[str, TydexConstant]:
    """The header or constant lines by name (a name given twice refused)."""
    out: dict[str, TydexConstant] = {}
    for number, line in rows:
        if not line.strip():
            continue
        name, description, unit, rest = _fields(line, number, source,
                                                "constant" if with_unit else "header")
        if name in out:
            raise InputError(f"{name} is given twice (lines {out[name].line} and {number})",
                             file=source, column=name, row=number)
        if not with_unit:
            unit, rest = "", line[40:].strip()
        out[name] = TydexConstant(name, description, unit, rest, number)
    return out


def load_tydex(path: str | Path) -> TydexFile:
    """Read a TYDEX file's sections (module documentation); the numbers checked.

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    TydexFile

    Raises
    ------
    InputError
        Naming the file, line and channel of what cannot be read.
    """
    source = str(path)
    lines, notes = read_lines(path, "TYDEX file")
    sections = _sections(lines, source)
    channels = [_channel(line, n, source) for n, line in sections["MEASURCHANNELS"]
                if line.strip()]
    if not channels:
        raise InputError("**MEASURCHANNELS declares no channel", file=source)
    _check_names(channels, source, notes)
    values, rows = _data(sections["MEASURDATA"], channels, source)
    header = {k: c.text for k, c in _named(sections["HEADER"], source, False).items()}
    return TydexFile(source, header, [line.rstrip() for _, line in sections.get("COMMENTS", [])],
                     _named(sections.get("CONSTANTS", []), source, True), channels, values,
                     rows, notes)


def read_tydex(path: str | Path, *, sign_convention: str = "iso") -> TyreData:
    """Read a TYDEX file as tyre data in SI and ISO-W axes (module documentation).

    Parameters
    ----------
    path : str or Path
        The file.
    sign_convention : {"iso", "sae"}
        The axes of its forces (TYDEX W axes are ISO-W, the default).

    Returns
    -------
    TyreData
    """
    check_sign_convention(sign_convention)
    return load_tydex(path).to_tyre_data(sign_convention)


def _comment(text: str) -> str:
    """A comment line that cannot open a section: one ASCII line, not starting with ``*``."""
    line = ascii_line(text).rstrip()
    return f"- {line}" if line.lstrip().startswith(("*", "!")) else line


def _line(name: str, description: str, unit: str, value: str) -> str:

    return (f"{name:<10}{ascii_line(description)[:29]:<30}{ascii_line(unit)[:9]:<10}"
            f"{value}").rstrip()


def tydex_text(data: TyreData, *, measid: str | None = None, comments: Sequence[str] = (),
               units: Mapping[str, str] | None = None,
               factors: Mapping[str, float] | None = None,
               constants: Mapping[str, tuple[float, str]] | None = None) -> str:
    """The TYDEX text of ``data`` (every measured quantity a channel, full precision).

    Parameters
    ----------
    data : TyreData
        Rows in SI and ISO-W axes (written in W axes).
    measid : str, optional
        The measurement's name (default: the data's source).
    comments : sequence of str
        Lines of ``**COMMENTS`` (provenance); each kept on one ASCII line.
    units : mapping, optional
        Quantity -> unit written (default :data:`TYDEX_UNITS`).
    factors : mapping, optional
        Quantity -> conversion factor written (the numbers written are the values in the
        unit divided by it; default 1).
    constants : mapping, optional
        Extra ``**CONSTANTS``: name -> (value in SI, unit written), e.g. ``{"NOMPRES":
        (2.5e5, "kPa")}``; quantities constant on every row are written as constants too.

    Returns
    -------
    str
    """
    units = {**TYDEX_UNITS, **(units or {})}
    factors = dict(factors or {})
    for q, f in factors.items():
        if not (math.isfinite(f) and f != 0):
            raise InputError(f"the conversion factor of {q} must be finite and not 0, got {f}")
    qs = [q for q in COLUMNS if q in ("fz", "kappa", "alpha", "gamma")
          or np.isfinite(getattr(data, q)).any()]
    out = ["**HEADER", _line("RELEASE", "Release of TYDEX-Format", "", "1.3"),
           _line("MEASID", "Measurement", "", _comment(measid or Path(data.source).name)[:30]),
           _line("SUPPLIER", "Data supplier", "", f"frictionlaws {__version__}"),
           "**COMMENTS", *(_comment(c) for c in comments), "**CONSTANTS"]
    for q in ("gamma", "pressure"):
        v = getattr(data, q)
        if np.isfinite(v).all() and np.ptp(v) == 0:
            out.append(_line(TYDEX_NAMES[q], _DESCRIPTIONS[q], units[q],
                             repr(float(from_si(v[0], _grammar(units[q], q), KINDS[q])))))
    for name, (value, unit) in (constants or {}).items():
        q = TYDEX_CHANNELS.get(name) or ("pressure" if name == "NOMPRES" else "fz")
        out.append(_line(name, "Nominal condition", unit,
                         repr(float(from_si(value, _grammar(unit, q), KINDS[q])))))
    out.append("**MEASURCHANNELS")
    for q in qs:
        out.append(_line(TYDEX_NAMES[q], _DESCRIPTIONS[q], units[q], repr(factors.get(q, 1.0))))
    columns = [from_si(getattr(data, q), _grammar(units[q], q), KINDS[q]) / factors.get(q, 1.0)
               for q in qs]
    out.append("**MEASURDATA")
    for row in zip(*columns, strict=True):
        out.append(" ".join(f"{_number(v):>10}" for v in row))
    out.append("**END")
    return "\n".join(out) + "\n"


def _grammar(unit: str, q: str) -> str:

    return unit_text(unit, KINDS[q])


def _number(v: float) -> str:
    return _NOT_AVAILABLE if not math.isfinite(v) else repr(float(v))


def write_tydex(data: TyreData, path: str | Path, **options: object) -> Path:
    """Write ``data`` as a TYDEX file (atomically; never over an input).

    Parameters
    ----------
    data : TyreData
    path : str or Path
    **options
        As :func:`tydex_text` (``measid``, ``comments``, ``units``, ``factors``,
        ``constants``).

    Returns
    -------
    Path
    """
    check_outputs([path], inputs=list(data.files) or [data.source])
    text = tydex_text(data, **options)  # type: ignore[arg-type]
    with atomic_write(path) as fh:
        fh.write(text)
    return Path(path)
