"""Tyre test data (forces against slip, load, camber and pressure) from a tidy CSV file.

One row per measured point, units in the headers as elsewhere in frictionlaws::

    Fz [kN], kappa [-], alpha [deg], gamma [deg], pressure [kPa], Fx [N], Fy [N], Mz [N m]

``Fz`` is required, and at least one of ``Fx`` / ``Fy`` / ``Mz`` (the aligning
moment); ``kappa``, ``alpha``,
``gamma`` default to 0 and ``pressure`` to "not measured".  Angles need an
explicit unit (``deg`` or ``rad``).  Aliases (any case): ``FZ``/``load``,
``SR``/``SL``/``slip_ratio``,
``SA``/``slip_angle``, ``IA``/``camber``/``inclination``, ``P``/``p``.  The file is read
by the one table reader (:func:`frictionlaws.io.read_table`) and converted with
:func:`frictionlaws.base.units.to_si`.  Columns of other names are not used, and the notes
say which.  A pressure column with blank cells among values is refused (a blank would
be taken as the nominal pressure).

Sign conventions
----------------
``sign_convention="iso"`` (default) takes the data as they are, in the ISO-W
(TYDEX W) axes of a Magic Formula property file: x forward, y left, z up, F_z > 0
for a loaded tyre, and a positive slip angle gives a negative F_y.
``"sae"`` converts SAE J670 axes (y right, z down: a 180 degree rotation about x) to
ISO: ``F_z -> -F_z``, ``F_y -> -F_y``, ``M_z -> -M_z``, ``alpha -> -alpha``; ``F_x``,
``kappa`` and
the inclination angle ``gamma`` are unchanged.  The conversion made is recorded
in the notes.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..base.errors import Argument, InputError
from ..base.units import parse_unit, to_si, unit_registry
from ..io import read_table, split_header, to_float

__all__ = ["TyreData", "read_tyre_data", "SIGN_CONVENTIONS", "COLUMNS"]

SIGN_CONVENTIONS = ("iso", "sae")

#: Column -> (quantity kind for :func:`frictionlaws.base.units.to_si`, accepted names).
COLUMNS: dict[str, tuple[str, tuple[str, ...]]] = {
    "fz": ("F_N", ("fz", "load", "normal_load")),
    "kappa": ("s", ("kappa", "sr", "sl", "slip_ratio", "longitudinal_slip")),
    "alpha": ("angle", ("alpha", "sa", "slip_angle")),
    "gamma": ("angle", ("gamma", "ia", "camber", "inclination")),
    "pressure": ("p", ("pressure", "p", "inflation_pressure")),
    "fx": ("F_N", ("fx",)),
    "fy": ("F_N", ("fy",)),
    "mz": ("torque", ("mz",)),
}


@dataclass
class TyreData:
    """Measured tyre forces in SI and ISO-W axes (arrays of one length).

    ``pressure`` is NaN where not measured; ``fx`` / ``fy`` / ``mz`` are NaN where
    the row has no such force or moment.  ``rows`` are the source rows (for messages).
    ``unused`` are the file's headers not read, ``missing`` the slip, camber and pressure
    columns the file lacks (defaulted), ``sign_convention`` the axes the file was read in,
    ``units`` the unit each column's header gives.
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

    def __post_init__(self) -> None:
        if self.mz.size == 0:
            self.mz = np.full(self.fz.size, np.nan)

    def subset(self, keep: np.ndarray) -> TyreData:
        """The rows where ``keep`` is true (source rows and notes kept)."""
        return TyreData(self.fz[keep], self.kappa[keep], self.alpha[keep], self.gamma[keep],
                        self.pressure[keep], self.fx[keep], self.fy[keep], self.rows[keep],
                        self.source, list(self.notes), self.mz[keep], self.unused,
                        self.missing, self.sign_convention, dict(self.units))

    def __len__(self) -> int:
        return int(self.fz.size)

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
                raise InputError(f"{name} is missing or not finite", file=self.source,
                                 column=name, row=int(self.rows[np.argmax(bad)]))
        if np.any(self.fz <= 0):
            i = int(np.argmax(self.fz <= 0))
            raise InputError(_negative_load(self.sign_convention), file=self.source,
                             column="Fz", row=int(self.rows[i]))
        if np.any(np.abs(self.alpha) >= np.pi / 2):
            i = int(np.argmax(np.abs(self.alpha) >= np.pi / 2))
            raise InputError("slip angle beyond 90 degrees (wrong angle unit?)",
                             file=self.source, column="alpha", row=int(self.rows[i]))
        for name in ("pressure", "fx", "fy", "mz"):  # NaN: not measured; inf: broken
            bad = np.isinf(getattr(self, name))
            if bad.any():
                raise InputError(f"{name} is infinite (an empty cell means not measured; "
                                 "infinity is not a measurement)", file=self.source,
                                 column=name, row=int(self.rows[np.argmax(bad)]))
        bad_p = np.isfinite(self.pressure) & ~(self.pressure > 0)
        if bad_p.any():
            raise InputError("the inflation pressure must be positive", file=self.source,
                             column="pressure", row=int(self.rows[np.argmax(bad_p)]))
        if not (np.isfinite(self.fx).any() or np.isfinite(self.fy).any()
                or np.isfinite(self.mz).any()):
            raise InputError("no Fx, Fy or Mz value: nothing to fit", file=self.source)


def _negative_load(convention: str) -> list[str | Argument]:
    """Why a load is not positive in ISO-W axes, and the sign convention to give."""
    if convention == "sae":
        return ["the load Fz must be positive in ISO-W axes; SAE loads are negative and are "
                "negated, so these loads are positive in the file: the data look like ISO-W "
                "axes already (give ", Argument("sign_convention", "iso"), ", the default)"]
    return ["the load Fz must be positive in ISO-W axes (SAE data have negative loads: "
            "give ", Argument("sign_convention", "sae"), ")"]


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


def _column_index(headers: list[str], source: str) -> dict[str, tuple[int, str | None]]:
    found: dict[str, tuple[int, str | None]] = {}
    for j, h in enumerate(headers):
        name, unit = split_header(h)
        key = name.strip().lower().replace(" ", "_")
        for col, (_, aliases) in COLUMNS.items():
            if key in aliases:
                if col in found:
                    raise InputError(f"two columns give {col} ('{headers[found[col][0]]}' "
                                     f"and '{h}')", file=source, column=h)
                found[col] = (j, unit)
    if "fz" not in found:
        raise InputError("no Fz column (the vertical load, e.g. 'Fz [N]'); columns: "
                         + ", ".join(headers), file=source)
    if "fx" not in found and "fy" not in found and "mz" not in found:
        raise InputError("no Fx, Fy or Mz column (e.g. 'Fx [N]', 'Fy [N]', 'Mz [N m]')",
                         file=source)
    return found


def _convert(table: Any, j: int, unit: str | None, col: str) -> np.ndarray:
    kind = COLUMNS[col][0]
    header = table.headers[j]
    if kind == "angle":
        ureg = unit_registry()
        if unit is None or not unit.strip() or unit.strip() in ("-", "1"):
            raise InputError("an angle column needs its unit in the header, e.g. "
                             f"'{col} [deg]' or '{col} [rad]'", file=table.source,
                             column=header)
    values = np.empty(len(table.rows))
    for i, cell in enumerate(table.columns[j]):
        v = to_float(cell, table.decimal_comma)
        if v is None:
            raise InputError(f"'{cell}' is not a number", file=table.source, column=header,
                             row=table.rows[i])
        values[i] = v
    si = np.asarray(to_si(values, unit or "", kind, column=header, file=table.source))
    if kind == "angle" and str(ureg.get_root_units(parse_unit(unit or "", kind))[1]) != "radian":
        raise InputError(f"unit '{unit}' is not an angle (deg or rad)", file=table.source,
                         column=header)
    inf = np.isinf(si)
    if inf.any():
        raise InputError("value is not finite", file=table.source, column=header,
                         row=table.rows[int(np.argmax(inf))])
    return si


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
    if sign_convention not in SIGN_CONVENTIONS:
        raise InputError(f"sign convention must be one of {', '.join(SIGN_CONVENTIONS)}, "
                         f"got {sign_convention!r}")
    source = str(path)
    table = read_table(path, header_hint="'Fz [N],kappa [-],alpha [deg],Fx [N],Fy [N]'",
                       what="tyre data file")
    found = _column_index(table.headers, source)
    n = len(table.rows)
    arrays = {col: (_convert(table, *found[col], col) if col in found
                    else np.full(n, np.nan if col in ("pressure", "fx", "fy", "mz") else 0.0))
              for col in COLUMNS}
    if "pressure" in found:
        _check_blank_pressures(arrays["pressure"], table, found["pressure"][0])
    notes = list(table.notes)
    used = {j for j, _ in found.values()}
    unused = [h for j, h in enumerate(table.headers) if j not in used]
    if unused:
        notes.append(f"columns not used (not a tyre-data column): {', '.join(unused)}")
    if sign_convention == "sae":
        for col in ("fz", "fy", "mz", "alpha"):
            arrays[col] = -arrays[col]
        notes.append("SAE axes converted to ISO-W: Fz, Fy, Mz and alpha negated; Fx, kappa "
                     "and gamma unchanged")
    else:
        notes.append("data taken in ISO-W axes (Fz > 0; a positive slip angle gives a "
                     "negative Fy for a usual tyre)")
    missing = [c for c in ("kappa", "alpha", "gamma", "pressure") if c not in found]
    if missing:
        notes.append(f"no {', '.join(missing)} column: "
                     + ", ".join("not measured" if c == "pressure" else f"{c} = 0"
                                 for c in missing))
    data = TyreData(arrays["fz"], arrays["kappa"], arrays["alpha"], arrays["gamma"],
                    arrays["pressure"], arrays["fx"], arrays["fy"], np.asarray(table.rows),
                    source, notes, arrays["mz"], tuple(unused), tuple(missing),
                    sign_convention, {c: u or "" for c, (_, u) in found.items()})
    data.validate()
    return data
