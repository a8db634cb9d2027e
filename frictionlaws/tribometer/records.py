"""Raw tribometer records: CSV files with units in the headers, read into SI.

A record is one test as the data logger wrote it, one row per sample::

    time [s],torque [N m],disc_speed [rpm],pin_speed [rpm]
    0.000,0.3012,0.0,0.0
    0.001,0.2987,0.0,0.0
    ...

Columns (names case-insensitive, unit in square brackets, any unit pint knows
of the right kind):

* ``time`` (a time: ``s``, ``ms``), strictly increasing, uniformly sampled;
* ``torque`` (a torque: ``N m``, ``N*m``, ``N*cm``, ``N*mm``): the raw
  reading of the torque sensor on the disc shaft;
* ``disc_speed`` (an angular velocity: ``rpm``, ``rad/s``, ``deg/s``,
  ``turn/min``);
* ``pin_speed`` (optional, same units): absent for a fixed pin.

**Sign convention of the speeds.** Both speeds are *signed*, measured about
the common axis of pin and disc with the same positive direction.  Pin and disc
turning in opposite directions (the usual counter-rotating test) have speeds
of opposite sign, so the relative speed ``|w_pin - w_disc|`` is the *sum* of
their magnitudes, as in the thesis.  A logger that records magnitudes only can
state the direction per record in the manifest (``direction`` column:
``counter`` or ``same``, see :mod:`frictionlaws.tribometer.process`).

Angular speeds must carry an angle in their unit: ``Hz`` and ``1/s`` are
refused because pint reads 1 Hz as 1 rad/s while a rotation counter means
1 rev/s; write ``rpm``, ``rad/s`` or ``turn/s``.

Other columns are ignored.  Every problem raises
:class:`~frictionlaws.base.errors.InputError` with the file, column and row (the
header is row 1); :mod:`~frictionlaws.tribometer.process` turns it into an
"unusable record" with that message as the reason.
"""

from __future__ import annotations

import csv
import functools
import io
import os
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..base.errors import InputError
from ..base.limits import read_input
from ..base.outputs import atomic_write, check_input_file
from ..base.sanitize import split_lines
from ..base.units import QUANTITIES, canonical_unit, parse_unit, parse_unit_text, unit_registry
from ..io import Table, column_numbers, decode_text, detect_delimiter
from ..io import split_header as _split_header

__all__ = ["Record", "read_record", "split_header", "angular_unit_factor", "COLUMNS"]

#: Record columns: canonical name -> (quantity kind, required).
COLUMNS: dict[str, tuple[str, bool]] = {
    "time": ("time", True),
    "torque": ("torque", True),
    "disc_speed": ("angular_velocity", True),
    "pin_speed": ("angular_velocity", False),
}

_MISSING = frozenset({"", "nan", "na", "n/a", "null", "none", "-"})
#: Largest relative deviation of a time step from the median step.
SAMPLING_TOLERANCE = 0.25


@dataclass
class Record:
    """One raw record in SI units.

    Attributes
    ----------
    time : numpy.ndarray
        Sample times [s], strictly increasing.
    torque : numpy.ndarray
        Raw torque reading [N m] (offsets not subtracted).
    disc_speed : numpy.ndarray
        Signed disc speed [rad/s].
    pin_speed : numpy.ndarray or None
        Signed pin speed [rad/s]; None for a fixed pin.
    source : str
        File name (or a label for records built in memory).
    units : dict
        Column -> unit as written in the file.
    """

    time: np.ndarray
    torque: np.ndarray
    disc_speed: np.ndarray
    pin_speed: np.ndarray | None = None
    source: str = "<memory>"
    units: dict[str, str] = field(default_factory=dict)
    _fs: Any = field(default=None, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        self.time = np.asarray(self.time, dtype=float)
        self.torque = np.asarray(self.torque, dtype=float)
        self.disc_speed = np.asarray(self.disc_speed, dtype=float)
        if self.pin_speed is not None:
            self.pin_speed = np.asarray(self.pin_speed, dtype=float)

    def __len__(self) -> int:
        return int(self.time.size)

    @property
    def fs(self) -> float:
        """Sampling rate [Hz] from the median time step."""
        if self.time.size < 2:
            return float("nan")
        key = (self.time.size, float(self.time[0]), float(self.time[-1]))
        if self._fs is None or self._fs[0] != key:
            self._fs = (key, float(1.0 / np.median(np.diff(self.time))))
        return self._fs[1]

    @property
    def duration(self) -> float:
        """Length of the record [s]."""
        return float(self.time[-1] - self.time[0]) if self.time.size else 0.0

    def pin(self) -> np.ndarray:
        """The pin speed [rad/s] (zeros for a fixed pin)."""
        return self.pin_speed if self.pin_speed is not None else np.zeros_like(self.disc_speed)

    def check(self, row_of: Any = None) -> None:
        """Validate lengths, finiteness and the time base; raise InputError if bad.

        Parameters
        ----------
        row_of : callable, optional
            Maps a 0-based sample index to the row number named in messages
            (default: index + 2, the header being row 1).
        """
        src = self.source
        row_of = row_of or (lambda i: i + 2)
        n = self.time.size
        arrays = {"time": self.time, "torque": self.torque, "disc_speed": self.disc_speed}
        if self.pin_speed is not None:
            arrays["pin_speed"] = self.pin_speed
        for name, arr in arrays.items():
            if arr.ndim != 1 or arr.size != n:
                raise InputError(f"'{name}' has {arr.size} samples, 'time' has {n}", file=src)
            _refuse_non_finite(arr, src, _label(name, self.units), row_of)
        if n < 3:
            raise InputError(f"too short: {n} samples", file=src)
        dt = np.diff(self.time)
        bad = np.flatnonzero(dt <= 0)
        if bad.size:
            raise InputError(
                f"time is not strictly increasing ({self.time[bad[0]]:g} s then "
                f"{self.time[bad[0] + 1]:g} s)",
                file=src, column=_label("time", self.units), row=row_of(int(bad[0]) + 1))
        mean = (self.time[-1] - self.time[0]) / (n - 1)
        bad = np.flatnonzero(np.abs(dt - mean) > SAMPLING_TOLERANCE * mean)
        if bad.size:  # the mean step may be off because of gaps: judge by the median
            med = float(np.median(dt))
            bad = np.flatnonzero(np.abs(dt - med) > SAMPLING_TOLERANCE * med)
        if bad.size:
            i = int(bad[0])
            raise InputError(
                f"irregular sampling: a time step of {dt[i]:.6g} s (the median step is "
                f"{med:.6g} s; {bad.size} irregular step{'s' if bad.size > 1 else ''}); the "
                "filter needs uniform sampling",
                file=src, column=_label("time", self.units), row=row_of(i + 1))


def _refuse_non_finite(arr: np.ndarray, src: str, column: str, row_of: Any) -> None:
    """Name the first missing (NaN, empty) or infinite value of a column, with its row."""
    bad = np.flatnonzero(~np.isfinite(arr))
    if not bad.size:
        return
    i = int(bad[0])
    if np.isinf(arr[i]):
        what = ("infinite value ('inf', or a number beyond 1.8e308 after unit conversion); "
                "expected a finite number")
    else:
        what = "missing or non-numeric value (NaN or empty cell); expected a number"
    raise InputError(f"{what}; {bad.size} non-finite value{'s' if bad.size > 1 else ''} in "
                     "the column", file=src, column=column, row=row_of(i))


def _label(name: str, units: dict[str, str]) -> str:
    unit = units.get(name)
    return f"{name} [{unit}]" if unit else name


def split_header(text: str) -> tuple[str, str | None]:
    """``"torque [N m]"`` -> ``("torque", "N m")``; ``"torque"`` -> ``("torque", None)``."""
    return _split_header(text, brackets_in_name=False)


def _norm(name: str) -> str:
    return re.sub(r"[\s\-]+", "_", name.strip().lower())


@functools.lru_cache(maxsize=64)
def _angular_factor(unit: str) -> float | str:
    ureg = unit_registry()
    try:
        parsed = parse_unit_text(unit).to_pint()  # the one unit grammar: no expression
    except ValueError:
        return "unknown"
    root = ureg.Quantity(1.0, parsed).to_root_units()
    units = dict(root._units)
    if units.get("radian") != 1 or units.get("second") != -1 or len(units) != 2:
        return "no-angle" if units == {"second": -1} else "dimension"
    return float(root.magnitude)


def angular_unit_factor(unit: str, *, column: str | None = None,
                        file: str | None = None) -> float:
    """Factor from ``unit`` to rad/s for an angular speed (``rpm`` -> 2 pi / 60).

    Raises
    ------
    InputError
        For an unknown unit, a unit that is not an angular velocity, or a bare
        frequency (``Hz``, ``1/s``) whose meaning (rev/s or rad/s) is ambiguous.
    """
    res = _angular_factor(unit.strip())
    if isinstance(res, float):
        return res
    if res == "no-angle":
        raise InputError(
            f"unit '{unit}' is ambiguous for a rotation speed (pint reads 1 Hz as 1 rad/s, "
            "a tachometer means 1 rev/s); write 'rpm', 'turn/s' or 'rad/s'",
            file=file, column=column)
    parse_unit(unit, "angular_velocity", column=column, file=file)  # raises the clear error
    raise InputError(f"unit '{unit}' is not an angular velocity; expected 'rpm' or 'rad/s'",
                     file=file, column=column)


@functools.lru_cache(maxsize=64)
def _si_factor(kind: str, unit: str) -> float:
    parsed = parse_unit(unit, kind)
    si = QUANTITIES[kind].si
    return float(unit_registry().Quantity(1.0, parsed).to(si).magnitude)


def _factor(kind: str, unit: str | None, header: str, src: str) -> float:
    if unit is None or not unit.strip():
        example = {"time": "s", "torque": "N m", "angular_velocity": "rpm"}[kind]
        name = split_header(header)[0]
        raise InputError(f"column has no unit; write it in the header, e.g. "
                         f"'{name} [{example}]'", file=src, column=header)
    if kind == "angular_velocity":
        return angular_unit_factor(unit, column=header, file=src)
    parse_unit(unit, kind, column=header, file=src)  # a clear error for a bad unit
    return _si_factor(kind, unit.strip())


def _refuse_duplicate_headers(text: str, delimiter: str, src: str) -> None:
    """pandas renames a repeated header ('torque [N m].1'): refuse it instead."""
    line = next((ln for ln in split_lines(text) if ln.strip() and not ln.startswith("#")), "")
    seen: set[str] = set()
    try:  # every error of the csv module is the file's (a cell over its field limit...)
        cells = next(csv.reader([line], delimiter=delimiter)) if line else []
    except csv.Error as exc:
        raise InputError(f"the header line cannot be read as CSV ({exc})", file=src,
                         row=split_lines(text).index(line) + 1) from None
    for cell in cells:
        name = cell.strip()
        if name in seen:
            raise InputError("duplicate column (two columns have the same header); keep one",
                             file=src, column=name)
        seen.add(name)


def read_record(path: str | os.PathLike[str], *, source: str | None = None) -> Record:
    """Read one raw record CSV into SI units and validate it.

    The file follows the rules of every table the library reads
    (:func:`frictionlaws.io.read_table`): the encoding rule of
    :func:`~frictionlaws.io.decode_text`, a ``;``, tab or ``,`` delimiter taken
    from the header line, decimal commas with ``;`` or tab (then every decimal
    separator must be a comma), ``#`` comment lines and blank lines.

    Parameters
    ----------
    path : str or path
        The CSV file (header row first; lines starting with ``#`` before the
        header are comments).
    source : str, optional
        Name used in messages (default: the path as given).

    Returns
    -------
    Record

    Raises
    ------
    InputError
        Missing file, unreadable text, missing/duplicate/unit-less columns,
        unknown or wrong-dimension units, non-numeric, empty or infinite cells,
        time not strictly increasing or not uniformly sampled.
    """
    src = source or os.fspath(path)
    text = _record_text(Path(path), src)
    layout = _Layout.of(text)
    frame = _record_frame(text, layout, src)
    headers = [str(c) for c in frame.columns]
    found, units = _record_columns(headers, src)
    rows = _RowNumbers(text)
    arrays: dict[str, np.ndarray] = {}
    for key, j in found.items():
        factor = _factor(COLUMNS[key][0], units[key] or None, headers[j], src)
        values = _column_values(frame.iloc[:, j], layout, headers[j], src, rows)
        arrays[key] = values * factor if factor != 1.0 else values
    rec = Record(arrays["time"], arrays["torque"], arrays["disc_speed"],
                 arrays.get("pin_speed"), source=src, units=units)
    rec.check(row_of=rows)
    return rec


def _record_text(p: Path, src: str) -> str:
    """The decoded text of a record file (the one encoding rule); refuses empty files."""
    if not p.exists():
        raise InputError("record file not found", file=src)
    if p.is_dir():
        raise InputError("is a directory; expected a record CSV file", file=src)

    check_input_file(p, "record file")
    raw = read_input(p, "record file", src)  # bounded in size
    text, _ = decode_text(raw, src, "record CSV file")
    if not text.strip():
        raise InputError("file is empty; expected a header such as "
                         "'time [s],torque [N m],disc_speed [rpm]' and data rows", file=src)
    return text


@dataclass(frozen=True)
class _Layout:
    """Delimiter and decimal separator of a record, read from its text."""

    delimiter: str
    decimal_comma: bool

    @classmethod
    def of(cls, text: str) -> _Layout:
        """The delimiter of the header line (as for datasets) and whether commas are decimal."""
        header = next((ln for ln in split_lines(text)
                       if ln.strip() and not ln.lstrip().startswith("#")), "")
        delimiter = detect_delimiter(header) or ","
        body = text[text.find(header) + len(header):]
        return cls(delimiter, delimiter in (";", "\t") and "," in body)


def _record_frame(text: str, layout: _Layout, src: str) -> Any:
    """Parse the text with pandas (fast path: numbers stay numbers, the rest stays text)."""
    import pandas as pd

    opts: dict[str, Any] = {"na_filter": False, "low_memory": False,
                            "sep": layout.delimiter, "skipinitialspace": True,
                            "decimal": "," if layout.decimal_comma else "."}
    if "#" in text:
        opts["comment"] = "#"
    try:
        frame = pd.read_csv(io.StringIO(text), **opts)
    except pd.errors.EmptyDataError:
        raise InputError("file has no header row", file=src) from None
    except (pd.errors.ParserError, ValueError) as exc:
        raise InputError(f"cannot be read as CSV: {' '.join(str(exc).split())}",
                         file=src) from None
    _refuse_duplicate_headers(text, layout.delimiter, src)
    if frame.shape[0] == 0:
        raise InputError("file has a header but no data rows", file=src)
    return frame


def _record_columns(headers: list[str], src: str) -> tuple[dict[str, int], dict[str, str]]:
    """Canonical column -> position, and the unit written for it; refuses missing columns."""
    found: dict[str, int] = {}
    units: dict[str, str] = {}
    for j, h in enumerate(headers):
        name, unit = split_header(h)
        key = _norm(name)
        if key not in COLUMNS:
            continue
        if key in found:
            raise InputError(f"two columns give '{key}' ('{headers[found[key]]}' and '{h}')",
                             file=src, column=h)
        found[key] = j
        units[key] = unit or ""
    missing = [k for k, (_, req) in COLUMNS.items() if req and k not in found]
    if missing:
        listed = ", ".join(f"'{h}'" for h in headers) or "none"
        raise InputError(
            f"missing column{'s' if len(missing) > 1 else ''} {', '.join(missing)}; expected "
            f"'time [s]', 'torque [N m]', 'disc_speed [rpm]' and optionally 'pin_speed [rpm]' "
            f"(columns found: {listed}"
            + ("; the header has one column: separate the columns with ',', ';' or a tab)"
               if len(headers) == 1 else ")"), file=src)
    return found, units


def _column_values(col: Any, layout: _Layout, header: str, src: str,
                   rows: _RowNumbers) -> np.ndarray:
    """A column as floats (NaN where empty): the datasets' number rule, messages and all."""
    if col.dtype.kind in "fiu":
        return np.asarray(col.to_numpy(dtype=float))

    table = Table([header], [col.astype(str).tolist()], rows.all(len(col)), src,
                   decimal_comma=layout.decimal_comma, delimiter=layout.delimiter)
    return column_numbers(table, 0, commas=layout.decimal_comma)


class _RowNumbers:
    """Maps a 0-based data row to its line in the file (comment and blank lines counted)."""

    def __init__(self, text: str) -> None:
        self._text = text
        self._lines: list[int] | None = None

    def all(self, n: int) -> list[int]:
        """The lines of the first ``n`` data rows."""
        if self._lines is None:
            lines = [k for k, ln in enumerate(split_lines(self._text), start=1)
                     if ln.strip() and not ln.lstrip().startswith("#")]
            self._lines = lines[1:]  # the first is the header
        return [self._lines[i] if i < len(self._lines) else i + 2 for i in range(n)]

    def __call__(self, i: int) -> int:
        return self.all(i + 1)[i]


def write_record(path: str | os.PathLike[str], record: Record, *,
                 torque_unit: str = "N m", speed_unit: str = "rpm",
                 decimals: tuple[int, int, int] = (4, 5, 2)) -> Path:
    """Write a record as CSV with units in the headers (fast, fixed decimals).

    Parameters
    ----------
    path : str or path
        Output file.
    record : Record
        Signals in SI.
    torque_unit, speed_unit : str
        Units written (values converted from SI with pint).
    decimals : tuple of int
        Decimals of time [s], torque and speeds.
    """
    ureg = unit_registry()
    tq_f = float(ureg.Quantity(1.0, "N*m").to(parse_unit(torque_unit, "torque")).magnitude)
    sp_f = 1.0 / angular_unit_factor(speed_unit)
    torque_unit = canonical_unit(torque_unit, "torque")  # written as read, never as typed
    speed_unit = parse_unit_text(speed_unit).canonical()
    cols: list[Any] = [record.time, record.torque * tq_f, record.disc_speed * sp_f]
    heads = ["time [s]", f"torque [{torque_unit}]", f"disc_speed [{speed_unit}]"]
    fmts = [f"%.{decimals[0]}f", f"%.{decimals[1]}f", f"%.{decimals[2]}f"]
    if record.pin_speed is not None:
        cols.append(record.pin_speed * sp_f)
        heads.append(f"pin_speed [{speed_unit}]")
        fmts.append(f"%.{decimals[2]}f")
    n = len(record)
    line = ",".join(fmts) + "\n"
    flat = np.column_stack(cols).ravel().tolist()
    body = (line * n) % tuple(flat)
    out = Path(path)
    with atomic_write(out, newline="") as fh:  # never over a file read in this process
        fh.write(",".join(heads) + "\n")
        fh.write(body)
    return out
