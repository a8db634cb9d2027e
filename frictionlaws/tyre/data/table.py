"""Tyre test data (forces against slip, load, camber and pressure): the data every reader
gives, and the tidy CSV file.

One row per measured point, units in the headers as elsewhere in frictionlaws::

    Fz [kN], kappa [-], alpha [deg], gamma [deg], pressure [kPa], Fx [N], Fy [N], Mz [N m]

``Fz`` is required, and at least one of ``Fx`` / ``Fy`` / ``Mz`` (the aligning
moment); ``kappa``, ``alpha``,
``gamma`` default to 0 and ``pressure`` to "not measured".  Angles need an
explicit unit (``deg`` or ``rad``).  Aliases (any case): ``FZ``/``load``,
``SL``/``slip_ratio``, ``SA``/``slip_angle``, ``IA``/``camber``/``inclination``, ``P``/``p``.
``SR``, a rig's slip ratio on the loaded radius, is read as kappa only when no ``SL`` (the
slip ratio on the effective rolling radius, the Magic Formula's kappa) is given, and the
notes say which was read.  The columns ``tyre prepare`` writes beside (``sweep``, a label
per sweep; ``direction``, +1 up and -1 down; ``samples``; ``time``) are kept with the rows.
The file is read by the one table reader (:func:`frictionlaws.io.read_table`) and converted
with :func:`frictionlaws.base.units.to_si`.
Columns of other names are not used, and the notes say which.  A pressure column with
blank cells among values is refused (a blank would be taken as the nominal pressure).
:func:`write_tyre_csv` writes such a file; :func:`join` joins the data of several files.

Sign conventions
----------------
``sign_convention="iso"`` (default) takes the data as they are, in the ISO-W
(TYDEX W) axes of a Magic Formula property file: x forward, y left, z up, F_z > 0
for a loaded tyre, and a positive slip angle gives a negative F_y.
``"sae"`` converts SAE J670 axes (y right, z down: a 180 degree rotation about x) to
ISO: ``F_z -> -F_z``, ``F_y -> -F_y``, ``M_z -> -M_z``, ``alpha -> -alpha``; ``F_x``,
``kappa`` and
the inclination angle ``gamma`` are unchanged (:func:`to_iso_axes`, for every reader).  The
conversion made is recorded in the notes.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ...base.errors import Argument, InputError
from ...base.outputs import atomic_write, check_outputs
from ...base.sanitize import comment_lines
from ...base.units import from_si
from ...io import read_table, split_header, to_float
from .channels import KINDS, convert

__all__ = ["TyreData", "read_tyre_data", "SIGN_CONVENTIONS", "COLUMNS", "to_iso_axes",
           "check_sign_convention", "join", "write_tyre_csv", "tyre_csv_text", "CSV_UNITS",
           "EXTRA_COLUMNS"]

SIGN_CONVENTIONS = ("iso", "sae")

#: Column -> (quantity kind for :func:`frictionlaws.base.units.to_si`, accepted names).
COLUMNS: dict[str, tuple[str, tuple[str, ...]]] = {
    "fz": (KINDS["fz"], ("fz", "load", "normal_load")),
    "kappa": (KINDS["kappa"], ("kappa", "sl", "sr", "slip_ratio", "longitudinal_slip")),
    "alpha": (KINDS["alpha"], ("alpha", "sa", "slip_angle")),
    "gamma": (KINDS["gamma"], ("gamma", "ia", "camber", "inclination")),
    "pressure": (KINDS["pressure"], ("pressure", "p", "inflation_pressure")),
    "fx": (KINDS["fx"], ("fx",)),
    "fy": (KINDS["fy"], ("fy",)),
    "mz": (KINDS["mz"], ("mz",)),
}

#: The unit of each column in a CSV file written by :func:`write_tyre_csv`.
CSV_UNITS = {"fz": "N", "kappa": "-", "alpha": "deg", "gamma": "deg", "pressure": "kPa",
             "fx": "N", "fy": "N", "mz": "N m"}
_CSV_NAMES = {"fz": "Fz", "kappa": "kappa", "alpha": "alpha", "gamma": "gamma",
              "pressure": "pressure", "fx": "Fx", "fy": "Fy", "mz": "Mz"}
#: The quantities the SAE axes have of the other sign than the ISO-W axes.
_SAE_NEGATED = ("fz", "fy", "mz", "alpha")


@dataclass
class TyreData:
    """Measured tyre forces in SI and ISO-W axes (arrays of one length).

    ``pressure`` is NaN where not measured; ``fx`` / ``fy`` / ``mz`` are NaN where
    the row has no such force or moment.  ``rows`` are the source rows (for messages).
    ``unused`` are the file's headers not read, ``missing`` the slip, camber and pressure
    columns the file lacks (defaulted), ``sign_convention`` the axes the file was read in,
    ``units`` the unit each column's header gives.  ``extra`` holds further per-row
    columns a reader keeps (``sweep``: a sweep label; ``direction``: +1 for a slip sweep
    upwards, -1 downwards; ``samples``: how many samples of a raw run a row averages;
    ``time`` [s]; ``file``: the index of the row's file in ``files`` when several files
    are joined).
    """

    fz: np.ndarray
    kappa: np.ndarray
    alpha: np.ndarray
    gamma: np.ndarray
    pressure: np.ndarray
    fx: np.ndarray
    fy: np.ndarray
    rows: np.ndarray
    source: str = "<memory>"
    notes: list[str] = field(default_factory=list)
    mz: np.ndarray = field(default_factory=lambda: np.array([]))
    unused: tuple[str, ...] = ()
    missing: tuple[str, ...] = ()
    sign_convention: str = "iso"
    units: dict[str, str] = field(default_factory=dict)
    extra: dict[str, np.ndarray] = field(default_factory=dict)
    files: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if self.mz.size == 0:
            self.mz = np.full(self.fz.size, np.nan)

    def subset(self, keep: np.ndarray) -> TyreData:
        """The rows where ``keep`` is true (source rows, notes and extra columns kept)."""
        return TyreData(self.fz[keep], self.kappa[keep], self.alpha[keep], self.gamma[keep],
                        self.pressure[keep], self.fx[keep], self.fy[keep], self.rows[keep],
                        self.source, list(self.notes), self.mz[keep], self.unused,
                        self.missing, self.sign_convention, dict(self.units),
                        {k: v[keep] for k, v in self.extra.items()}, self.files)

    def __len__(self) -> int:
        return int(self.fz.size)

    def where(self, i: int) -> tuple[str, int]:
        """The file and source row of row ``i`` (for messages about joined files)."""
        if self.files and "file" in self.extra:
            return self.files[int(self.extra["file"][i])], int(self.rows[i])
        return self.source, int(self.rows[i])

    @classmethod
    def from_arrays(cls, *, fz: Any, kappa: Any = 0.0, alpha: Any = 0.0, gamma: Any = 0.0,
                    pressure: Any = np.nan, fx: Any = np.nan, fy: Any = np.nan,
                    mz: Any = np.nan, source: str = "<memory>") -> TyreData:
        """Build from arrays already in SI and ISO-W axes (broadcast to one length)."""
        arrays = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in
                                       (fz, kappa, alpha, gamma, pressure, fx, fy, mz)))
        fz_, k, a, g, p, x, y, m = (np.array(v, dtype=float).ravel() for v in arrays)
        data = cls(fz_, k, a, g, p, x, y, np.arange(1, fz_.size + 1), source, mz=m)
        data.validate()
        return data

    def validate(self) -> None:
        """Refuse non-finite inputs, non-positive loads and rows without any force."""
        for name in ("fz", "kappa", "alpha", "gamma"):
            bad = ~np.isfinite(getattr(self, name))
            if bad.any():
                self._refuse(f"{name} is missing or not finite", name, bad)
        if np.any(self.fz <= 0):
            self._refuse(_negative_load(self.sign_convention), "Fz", self.fz <= 0)
        if np.any(np.abs(self.alpha) >= np.pi / 2):
            self._refuse("slip angle beyond 90 degrees (wrong angle unit?)", "alpha",
                         np.abs(self.alpha) >= np.pi / 2)
        for name in ("pressure", "fx", "fy", "mz"):  # NaN: not measured; inf: broken
            bad = np.isinf(getattr(self, name))
            if bad.any():
                self._refuse(f"{name} is infinite (an empty cell means not measured; "
                             "infinity is not a measurement)", name, bad)
        bad_p = np.isfinite(self.pressure) & ~(self.pressure > 0)
        if bad_p.any():
            self._refuse("the inflation pressure must be positive", "pressure", bad_p)
        if not (np.isfinite(self.fx).any() or np.isfinite(self.fy).any()
                or np.isfinite(self.mz).any()):
            raise InputError("no Fx, Fy or Mz value: nothing to fit", file=self.source)

    def _refuse(self, message: Any, column: str, bad: np.ndarray) -> None:
        file, row = self.where(int(np.argmax(bad)))
        raise InputError(message, file=file, column=column, row=row)


def _negative_load(convention: str) -> list[str | Argument]:
    """Why a load is not positive in ISO-W axes, and the sign convention to give."""
    if convention == "sae":
        return ["the load Fz must be positive in ISO-W axes; SAE loads are negative and are "
                "negated, so these loads are positive in the file: the data look like ISO-W "
                "axes already (give ", Argument("sign_convention", "iso"), ", the default)"]
    return ["the load Fz must be positive in ISO-W axes (SAE data have negative loads: "
            "give ", Argument("sign_convention", "sae"), ")"]


def check_sign_convention(sign_convention: str) -> None:
    """Refuse a sign convention that is not one of :data:`SIGN_CONVENTIONS`."""
    if sign_convention not in SIGN_CONVENTIONS:
        raise InputError(f"sign convention must be one of {', '.join(SIGN_CONVENTIONS)}, "
                         f"got {sign_convention!r}")


def to_iso_axes(arrays: dict[str, np.ndarray], sign_convention: str) -> str:
    """Turn the arrays of a file in ``sign_convention`` axes into ISO-W axes, in place.

    Parameters
    ----------
    arrays : dict
        Quantity (``fz``, ``fy``, ``mz``, ``alpha``, ...) -> SI values.
    sign_convention : {"iso", "sae"}

    Returns
    -------
    str
        The note saying what was done.
    """
    check_sign_convention(sign_convention)
    if sign_convention == "sae":
        for name in _SAE_NEGATED:
            if name in arrays:
                arrays[name] = -arrays[name]
        return ("SAE axes converted to ISO-W: Fz, Fy, Mz and alpha negated; Fx, kappa "
                "and gamma unchanged")
    return ("data taken in ISO-W axes (Fz > 0; a positive slip angle gives a "
            "negative Fy for a usual tyre)")


def _check_blank_pressures(pressure: np.ndarray, table: Any, j: int) -> None:
    """Refuse blank cells in a pressure column that has values on other rows."""
    blank = np.flatnonzero(np.isnan(pressure))
    if blank.size == 0 or blank.size == pressure.size:
        return
    rows = [int(table.rows[i]) for i in blank]
    shown = ", ".join(map(str, rows[:10])) + (f" and {len(rows) - 10} more" if len(rows) > 10
                                              else "")
    raise InputError(f"{len(rows)} blank pressure cell(s) (rows {shown}) in a column with "
                     "values on the other rows: a blank would be taken as the template's "
                     "nominal pressure; fill in the pressure or remove those rows",
                     file=table.source, column=table.headers[j], row=rows[0])


def _no_force_rows(arrays: dict[str, np.ndarray], table: Any) -> str | None:
    """The note naming rows whose Fx, Fy and Mz are all missing (blank or a missing-value
    token such as ``nan``): such a row has nothing to fit and is left out, said so."""
    none = ~(np.isfinite(arrays["fx"]) | np.isfinite(arrays["fy"]) | np.isfinite(arrays["mz"]))
    if not none.any() or none.all():  # all: refused by TyreData.validate
        return None
    rows = [int(table.rows[i]) for i in np.flatnonzero(none)]
    shown = ", ".join(map(str, rows[:10])) + (f" and {len(rows) - 10} more" if len(rows) > 10
                                              else "")
    which = "row" if len(rows) == 1 else "rows"
    return (f"{len(rows)} row(s) with no Fx, Fy or Mz value (blank or a missing-value token "
            f"such as 'nan'; {which} {shown}): nothing to fit there, left out")


#: The rig's slip ratio on the loaded radius: read as kappa only without another kappa column.
_LOADED_SLIP = "sr"


def _column_index(headers: list[str], source: str, notes: list[str]
                  ) -> dict[str, tuple[int, str | None]]:

    found: dict[str, tuple[int, str | None]] = {}
    loaded: tuple[int, str | None] | None = None
    for j, h in enumerate(headers):
        name, unit = split_header(h)
        key = name.strip().lower().replace(" ", "_")
        if key == _LOADED_SLIP:
            loaded = (j, unit)
            continue
        for col, (_, aliases) in COLUMNS.items():
            if key in aliases:
                if col in found:
                    raise InputError(f"two columns give {col} ('{headers[found[col][0]]}' "
                                     f"and '{h}')", file=source, column=h)
                found[col] = (j, unit)
    if loaded is not None:
        _loaded_slip(found, loaded, headers, notes)
    if "fz" not in found:
        raise InputError("no Fz column (the vertical load, e.g. 'Fz [N]'); columns: "
                         + ", ".join(headers), file=source)
    if "fx" not in found and "fy" not in found and "mz" not in found:
        raise InputError("no Fx, Fy or Mz column (e.g. 'Fx [N]', 'Fy [N]', 'Mz [N m]')",
                         file=source)
    return found


def _loaded_slip(found: dict[str, tuple[int, str | None]], loaded: tuple[int, str | None],
                 headers: list[str], notes: list[str]) -> None:
    """Kappa from ``SR`` only without another kappa column; the choice said either way."""
    sr = headers[loaded[0]]
    if "kappa" in found:
        notes.append(f"kappa is '{headers[found['kappa'][0]]}'; '{sr}' (a rig's slip ratio "
                     "on the loaded radius, offset from the Magic Formula's kappa on the "
                     "effective rolling radius) is not used")
        return
    found["kappa"] = loaded
    notes.append(f"kappa is '{sr}', a rig's slip ratio on the loaded radius: the Magic "
                 "Formula's kappa is on the effective rolling radius (a rig's SL), and the "
                 "two differ by a few percent of slip; give SL when the file has it")


def _cells(table: Any, j: int) -> np.ndarray:
    """The numbers of column ``j`` (NaN for a blank), refusing text with its row."""
    values = np.empty(len(table.rows))
    for i, cell in enumerate(table.columns[j]):
        v = to_float(cell, table.decimal_comma)
        if v is None:
            raise InputError(f"'{cell}' is not a number", file=table.source,
                             column=table.headers[j], row=table.rows[i])
        values[i] = v
    return values


def _convert(table: Any, j: int, unit: str | None, col: str) -> np.ndarray:
    header = table.headers[j]
    if COLUMNS[col][0] == "angle" and (unit is None or unit.strip() in ("", "-", "1")):
        raise InputError("an angle column needs its unit in the header, e.g. "
                         f"'{col} [deg]' or '{col} [rad]'", file=table.source, column=header)
    si = convert(_cells(table, j), unit or "", col, file=table.source, column=header)
    inf = np.isinf(si)
    if inf.any():
        raise InputError("value is not finite", file=table.source, column=header,
                         row=table.rows[int(np.argmax(inf))])
    return si


#: The per-row columns of whole numbers (written as integers).
_WHOLE = ("sweep", "direction", "samples")
#: Per-row columns a file may carry beside the tyre data (as ``tyre prepare`` writes them):
#: name -> what it is.
EXTRA_COLUMNS = {"sweep": "a label per sweep", "direction": "+1 up, -1 down",
                 "samples": "samples a row averages", "time": "time [s]"}


def _extra_columns(table: Any) -> dict[str, np.ndarray]:
    """The :data:`EXTRA_COLUMNS` of the file (``time`` in SI), each complete."""
    out: dict[str, np.ndarray] = {}
    for j, h in enumerate(table.headers):
        name, unit = split_header(h)
        key = name.strip().lower()
        if key not in EXTRA_COLUMNS or key in out:
            continue
        values = _cells(table, j)
        if key == "time":
            values = convert(values, unit or "", "time", file=table.source, column=h)
        if not np.all(np.isfinite(values)):
            i = int(np.argmax(~np.isfinite(values)))
            raise InputError(f"a {key} value is missing ({EXTRA_COLUMNS[key]})",
                             file=table.source, column=h, row=table.rows[i])
        out[key] = values
    return out


def read_tyre_data(path: str | Path, *, sign_convention: str = "iso") -> TyreData:
    """Read tyre test data from a tidy CSV file (see the module documentation).

    Parameters
    ----------
    path : str or Path
        The CSV file.
    sign_convention : {"iso", "sae"}
        Axes of the measurement; SAE data are converted to ISO-W.

    Returns
    -------
    TyreData

    Raises
    ------
    InputError
        Naming the file, column and row of what cannot be used.
    """
    check_sign_convention(sign_convention)
    source = str(path)
    table = read_table(path, header_hint="'Fz [N],kappa [-],alpha [deg],Fx [N],Fy [N]'",
                       what="tyre data file")
    notes = list(table.notes)
    found = _column_index(table.headers, source, notes)
    n = len(table.rows)
    arrays = {col: (_convert(table, *found[col], col) if col in found
                    else np.full(n, np.nan if col in ("pressure", "fx", "fy", "mz") else 0.0))
              for col in COLUMNS}
    if "pressure" in found:
        _check_blank_pressures(arrays["pressure"], table, found["pressure"][0])
    extra = _extra_columns(table)
    used = {j for j, _ in found.values()}
    unused = [h for j, h in enumerate(table.headers) if j not in used
              and split_header(h)[0].strip().lower() not in extra]
    if unused:
        notes.append(f"columns not used (not a tyre-data column): {', '.join(unused)}")
    notes.append(to_iso_axes(arrays, sign_convention))
    notes.extend(filter(None, [_no_force_rows(arrays, table)]))
    missing = [c for c in ("kappa", "alpha", "gamma", "pressure") if c not in found]
    if missing:
        notes.append(f"no {', '.join(missing)} column: "
                     + ", ".join("not measured" if c == "pressure" else f"{c} = 0"
                                 for c in missing))
    data = TyreData(arrays["fz"], arrays["kappa"], arrays["alpha"], arrays["gamma"],
                    arrays["pressure"], arrays["fx"], arrays["fy"], np.asarray(table.rows),
                    source, notes, arrays["mz"], tuple(unused), tuple(missing),
                    sign_convention, {c: u or "" for c, (_, u) in found.items()}, extra)
    data.validate()
    return data


def join(parts: Sequence[TyreData]) -> TyreData:
    """The rows of several files as one data set (each row keeps its file and source row).

    The notes of each file are kept, prefixed with its name; ``extra["file"]`` indexes
    ``files``.  Sweep labels are made unique across the files.  A file given twice is
    refused (its rows would count twice).

    Parameters
    ----------
    parts : sequence of TyreData
        One per file, each in SI and ISO-W axes.

    Returns
    -------
    TyreData
    """
    if len(parts) == 1:
        return parts[0]
    if not parts:
        raise InputError("no tyre data file given")
    sources = [p.source for p in parts]
    twice = sorted({s for s in sources if sources.count(s) > 1})
    if twice:
        raise InputError(f"the same file is given twice ({', '.join(twice)}): its rows "
                         "would count twice")
    _refuse_same_data(parts)
    cat = {name: np.concatenate([getattr(p, name) for p in parts])
           for name in ("fz", "kappa", "alpha", "gamma", "pressure", "fx", "fy", "rows", "mz")}
    extra = _joined_extra(parts)
    notes = [f"{p.source}: {n}" for p in parts for n in p.notes]
    units = {k: ", ".join(sorted({p.units[k] for p in parts if k in p.units}))
             for k in COLUMNS if any(k in p.units for p in parts)}
    missing = tuple(c for c in ("kappa", "alpha", "gamma", "pressure")
                    if all(c in p.missing for p in parts))
    unused = tuple(dict.fromkeys(u for p in parts for u in p.unused))
    data = TyreData(cat["fz"], cat["kappa"], cat["alpha"], cat["gamma"], cat["pressure"],
                    cat["fx"], cat["fy"], cat["rows"], " + ".join(sources), notes, cat["mz"],
                    unused, missing, parts[0].sign_convention, units, extra, tuple(sources))
    data.validate()
    return data


def _refuse_same_data(parts: Sequence[TyreData]) -> None:
    """Refuse two files of the same rows (every value of every column, a copy under
    another name): the measurement would count twice, doubling its weight in a fit."""
    seen: dict[bytes, str] = {}
    for p in parts:
        table = np.stack([getattr(p, k) for k in COLUMNS], axis=1)
        key = np.where(np.isnan(table), np.inf, table).tobytes()  # NaN (not measured) alike
        if key in seen:
            raise InputError(f"'{seen[key]}' and '{p.source}' hold the same data (every "
                             "value of every row): the same measurement given twice would "
                             "count double in a fit; give it once", file=p.source)
        seen[key] = p.source


def _joined_extra(parts: Sequence[TyreData]) -> dict[str, np.ndarray]:
    """The extra columns of joined files: their file index, sweeps numbered apart."""
    extra = {"file": np.concatenate([np.full(len(p), i) for i, p in enumerate(parts)])}
    keys = set.intersection(*(set(p.extra) for p in parts)) - {"file"}
    for key in sorted(keys):
        if key == "sweep":
            offset, labels = 0.0, []
            for p in parts:
                _, codes = np.unique(p.extra["sweep"], return_inverse=True)
                labels.append(codes + offset)
                offset += codes.max() + 1 if codes.size else 0
            extra[key] = np.concatenate(labels)
        else:
            extra[key] = np.concatenate([p.extra[key] for p in parts])
    return extra


def tyre_csv_text(data: TyreData, comments: Sequence[str] = ()) -> str:
    """The tidy CSV text of ``data`` (:data:`CSV_UNITS`; numbers as read back exactly).

    Parameters
    ----------
    data : TyreData
    comments : sequence of str
        Written as ``#`` lines before the header (provenance, notes).

    Returns
    -------
    str
    """
    cols = [c for c in COLUMNS if c in ("fz", "kappa", "alpha", "gamma")
            or np.isfinite(getattr(data, c)).any()]
    header = [f"{_CSV_NAMES[c]} [{CSV_UNITS[c]}]" for c in cols]
    values = [from_si(getattr(data, c), CSV_UNITS[c], KINDS[c]) for c in cols]
    extras = [k for k in ("sweep", "direction", "samples", "time") if k in data.extra]
    header += [f"{k} [s]" if k == "time" else k for k in extras]
    values += [data.extra[k] for k in extras]
    lines = comment_lines(comments)
    lines.append(",".join(header))
    whole = [k in _WHOLE for k in cols] + [k in _WHOLE for k in extras]
    for row in zip(*values, strict=True):
        lines.append(",".join("" if not np.isfinite(v) else str(int(v)) if w and v == int(v)
                              else repr(float(v)) for v, w in zip(row, whole, strict=True)))
    return "\n".join(lines) + "\n"


def write_tyre_csv(data: TyreData, path: str | Path, comments: Sequence[str] = ()) -> Path:
    """Write ``data`` as a tidy CSV file that :func:`read_tyre_data` reads back.

    Parameters
    ----------
    data : TyreData
    path : str or Path
        Written atomically, checked as an output first (never over an input).
    comments : sequence of str
        Provenance lines written as ``#`` comments.

    Returns
    -------
    Path
    """
    check_outputs([path], inputs=list(data.files) or [data.source])
    text = tyre_csv_text(data, comments)
    with atomic_write(path) as fh:
        fh.write(text)
    return Path(path)
