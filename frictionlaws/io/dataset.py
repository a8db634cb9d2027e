"""The :class:`Dataset`: friction data in SI with its units, notes and provenance, and its
assembly from a read table (:func:`_build`).
"""

from __future__ import annotations

import csv
import html
import os
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..base import units as _units
from ..base.errors import InputError
from ..base.sanitize import comment_lines, csv_cell, split_lines

if TYPE_CHECKING:  # pandas is imported where a DataFrame is made or asked for
    import pandas as pd

from ..base.display import unit_text
from ..base.outputs import atomic_write
from ..law.interop import table_html
from .building import (
    _assign_columns,
    _check_headers,
    _column_notes,
    _column_units,
    _is_frame,
    _kept_columns,
    _numbers,
    _pressure_from_area,
    _rows_to_keep,
    _to_si_checked,
)
from .columns import CANONICAL, TEXT_COLUMNS, VARIABLE_COLUMNS, parse_mapping, parse_units
from .reading import Table, _table_from_frame, split_header

__all__ = ["Dataset", "dataset_html"]


# --------------------------------------------------------------------------- Dataset
class Dataset:
    """A friction dataset in canonical SI columns.

    The parameters are kept as attributes of the same names.  The columns are
    numpy arrays until :attr:`frame` is first asked for: reading and fitting a
    dataset does not import pandas; from then on the DataFrame holds the data.

    Parameters
    ----------
    frame : pandas.DataFrame or mapping of str to numpy.ndarray
        Canonical columns only, in SI: ``mu`` [-], ``p`` [Pa], ``v`` [m/s],
        ``T`` [K], ``F_N`` [N], ``s`` [-], ``mu_std`` [-], ``n`` [-],
        ``surface`` (text); only those present, one value per row.
    name : str
        Short name (packaged name or file stem).
    source : str
        The path read, ``packaged:NAME``, or ``<DataFrame>``.
    units : dict
        Canonical column -> unit as given by the user (``"MPa"``, ``"kg"``;
        ``""`` for dimensionless).
    notes : list of str
        What the loader did that the user should know: ignored columns,
        dropped rows, unit conventions, derived columns.
    provenance : str or None
        Where the data come from (the file's ``#`` comment block).
    rows : numpy.ndarray or None
        For each row of ``frame``, the row of the source file (line number);
        used to name rows in later messages.
    """

    def __init__(self, frame: pd.DataFrame | Mapping[str, np.ndarray], name: str, source: str,
                 units: dict[str, str] | None = None, notes: list[str] | None = None,
                 provenance: str | None = None, rows: np.ndarray | None = None) -> None:
        self._frame: pd.DataFrame | None = None
        self._columns: dict[str, np.ndarray] | None = None
        if isinstance(frame, Mapping):
            self._columns = {str(k): np.asarray(v) for k, v in frame.items()}
        else:
            self._frame = frame
        self.name = name
        self.source = source
        self.units: dict[str, str] = {} if units is None else units
        self.notes: list[str] = [] if notes is None else notes
        self.provenance = provenance
        self.rows = rows
        #: Per canonical column, the rows dropped for an empty or NaN value in it (row
        #: labels as in the notes): a grouping column's empty cells are refused from it.
        self.dropped: dict[str, list[str]] = {}

    @property
    def frame(self) -> pd.DataFrame:
        """The data as a :class:`pandas.DataFrame` (built on first use, then kept)."""
        if self._frame is None:
            import pandas as pd

            cols = self._columns or {}
            self._frame = pd.DataFrame(
                {c: (pd.Series(v, dtype=object) if v.dtype == object else v)
                 for c, v in cols.items()},
                index=pd.RangeIndex(len(next(iter(cols.values()), ()))))
            self._columns = None  # the frame is the data from now on (it may be edited)
        return self._frame

    @frame.setter
    def frame(self, value: pd.DataFrame) -> None:
        self._frame, self._columns = value, None

    @property
    def column_names(self) -> tuple[str, ...]:
        """The columns present, in order (canonical names)."""
        if self._columns is not None:
            return tuple(self._columns)
        return tuple(str(c) for c in self.frame.columns)

    def column(self, name: str, dtype: Any = None) -> np.ndarray:
        """Return one column as a numpy array.

        Parameters
        ----------
        name : str
            A column of :attr:`column_names`.
        dtype : numpy dtype, optional
            The dtype wanted (e.g. ``float``).

        Returns
        -------
        numpy.ndarray
            The values, one per row (SI for numeric columns).

        Raises
        ------
        KeyError
            When the dataset has no such column.
        """
        if self._columns is not None:
            return np.asarray(self._columns[name], dtype=dtype)
        return self.frame[name].to_numpy(dtype=dtype)

    def __len__(self) -> int:
        if self._columns is not None:
            return len(next(iter(self._columns.values()), ()))
        return len(self.frame)

    def __repr__(self) -> str:
        cols = ", ".join(self.column_names)
        return f"Dataset({self.name!r}, {len(self)} rows, columns: {cols})"

    def _repr_html_(self) -> str:
        return dataset_html(self)

    @property
    def variables(self) -> set[str]:
        """Variable columns present (among ``p``, ``v``, ``T``, ``F_N``, ``s``)."""
        return {c for c in VARIABLE_COLUMNS if c in self.column_names}

    @property
    def varying(self) -> set[str]:
        """Variable columns that take more than one distinct value."""
        out = set()
        for c in self.variables:
            x = self.column(c, float)
            if np.unique(x[~np.isnan(x)]).size > 1:
                out.add(c)
        return out

    @property
    def row_labels(self) -> np.ndarray | None:
        """Source-file row of each dataset row (same as :attr:`rows`)."""
        return self.rows

    def row_of(self, index: int) -> int | None:
        """Return the source-file row of the dataset row at a position.

        Parameters
        ----------
        index : int
            Position of the row in :attr:`frame` (0-based).

        Returns
        -------
        int or None
            The row of the source file (the line number a text editor shows), or
            None when the dataset has no source rows (built from a DataFrame).
        """
        if self.rows is None:
            return None
        return int(self.rows[index])

    def arrays(self) -> dict[str, np.ndarray]:
        """Return mu and each variable column as float arrays in SI.

        Returns
        -------
        dict of str to numpy.ndarray
            ``{"mu": ..., "p": ..., ...}``: ``mu`` [-] and each variable column
            present among ``p`` [Pa], ``v`` [m/s], ``T`` [K], ``F_N`` [N] and
            ``s`` [-].
        """
        names = self.column_names
        return {c: self.column(c, float) for c in ("mu", *VARIABLE_COLUMNS) if c in names}

    def weights(self) -> np.ndarray | None:
        """Return fit weights from the replicate statistics, or None (unweighted).

        * ``mu_std`` present and > 0 in every row: ``1 / mu_std``, multiplied by
          ``sqrt(n)`` when ``n`` is present too (1 / standard error of the mean);
        * otherwise ``n`` present: ``sqrt(n)`` (a mean of n replicates has a
          variance n times smaller);
        * otherwise ``None``.

        Weights multiply the residuals (lmfit's convention), so a weight is
        1 / sigma.  When ``mu_std`` is present but cannot be used (a zero in
        some row), the loader says so in :attr:`notes`.

        Returns
        -------
        numpy.ndarray or None
            One weight (1 / sigma of mu) per row, or None when the dataset has
            neither a usable ``mu_std`` nor an ``n`` column.
        """
        names = self.column_names
        n = self.column("n", float) if "n" in names else None
        if "mu_std" in names:
            std = self.column("mu_std", float)
            if len(std) and np.all(std > 0):
                w = 1.0 / std
                return w * np.sqrt(n) if n is not None else w
        if n is not None:
            return np.sqrt(n)
        return None

    def subset(self, mask: Any) -> Dataset:
        """Return a new dataset with the rows where ``mask`` is true.

        Parameters
        ----------
        mask : array-like of bool
            One boolean per row of the dataset.

        Returns
        -------
        Dataset
            The kept rows (renumbered from 0), with their source-file rows, the
            same units and provenance, and a note of how many rows were kept.

        Raises
        ------
        InputError
            When ``mask`` does not have one value per row.
        """
        m = np.asarray(mask, dtype=bool)
        if m.shape != (len(self),):
            raise InputError(
                f"subset mask has shape {m.shape}, expected ({len(self)},) for dataset "
                f"'{self.name}'"
            )
        frame: pd.DataFrame | dict[str, np.ndarray]
        if self._columns is not None:
            frame = {c: v[m] for c, v in self._columns.items()}
        else:
            frame = self.frame.loc[m].reset_index(drop=True)
        rows = None if self.rows is None else self.rows[m]
        notes = list(self.notes)
        if not m.all():
            notes.append(f"subset: kept {int(m.sum())} of {len(self)} rows")
        return Dataset(frame, self.name, self.source, dict(self.units), notes,
                       self.provenance, rows)

    def describe(self) -> str:
        """Describe the dataset in a short text.

        Returns
        -------
        str
            Name, number of rows and source; the range and number of distinct
            values of each numeric column in display units (p in MPa, T in
            degC...); the surfaces; and the loader's notes.
        """
        lines = [f"{self.name}: {len(self)} rows ({self.source})"]
        for col in ("mu", *VARIABLE_COLUMNS, "mu_std", "n"):
            if col not in self.column_names:
                continue
            unit = _units.display_unit(col)
            vals = _units.from_si(self.column(col, float), unit, col)
            distinct = len(np.unique(vals))
            rng = (f"{vals.min():.4g}" if distinct == 1
                   else f"{vals.min():.4g} .. {vals.max():.4g}")
            label = _units.header(col, unit)
            given = self.units.get(col)
            src = f", given in {given}" if given and given != unit else ""
            lines.append(f"  {label:<12} {rng}  ({distinct} distinct{src})")
        if "surface" in self.column_names:
            surfaces = sorted({str(s) for s in self.column("surface") if str(s)})
            lines.append(f"  {'surface':<12} {', '.join(surfaces) or '-'}")
        for note in self.notes:
            lines.append(f"note: {note}")
        return "\n".join(lines)

    def summary(self) -> dict[str, Any]:
        """Summarise the dataset as a JSON-able dict.

        Returns
        -------
        dict
            ``name``, ``source``, ``rows`` (count), ``columns`` (for each
            numeric column its SI unit, min, max, number of distinct values and
            the unit given by the user; for ``surface`` its values), ``notes``
            and ``provenance``.
        """
        cols: dict[str, dict[str, Any]] = {}
        for col in self.column_names:
            if col in TEXT_COLUMNS:
                cols[col] = {"values": sorted({str(s) for s in self.column(col)})}
                continue
            vals = self.column(col, float)
            cols[col] = {"unit": _units.si_unit(col), "min": float(vals.min()),
                         "max": float(vals.max()), "distinct": int(len(np.unique(vals))),
                         "given_unit": self.units.get(col, "")}
        return {"name": self.name, "source": self.source, "rows": len(self),
                "columns": cols, "notes": list(self.notes), "provenance": self.provenance}

    @classmethod
    def from_frame(cls, frame: pd.DataFrame, *,
                   mapping: Mapping[str, str] | str | None = None,
                   units: Mapping[str, str] | str | None = None,
                   area: str | float | None = None, name: str = "dataframe") -> Dataset:
        """Build a dataset from a :class:`pandas.DataFrame`, checked as a CSV file is.

        Column names follow the CSV schema: canonical names or aliases, with the
        unit in square brackets (``p [MPa]``, ``T [degC]``); a column without a
        unit in its name needs one in ``units``, or is refused as in a CSV file
        (dimensionless columns such as ``mu`` need none).  :meth:`to_frame` writes this form, so
        ``Dataset.from_frame(ds.to_frame())`` gives ``ds`` back.

        Parameters
        ----------
        frame : pandas.DataFrame
            One row per measurement.
        mapping : dict or str, optional
            Canonical column -> the frame's column, e.g. ``{"mu": "FC"}``.
        units : dict or str, optional
            Units of columns whose name carries none, e.g. ``{"p": "MPa"}``.
        area : str or float, optional
            Nominal contact area (``"314.16 mm^2"`` or m^2) to derive ``p`` from
            ``F_N``.
        name : str
            Short name of the dataset (used in reports).

        Returns
        -------
        Dataset
            The data in canonical SI columns; its ``source`` is ``<DataFrame>``.

        Raises
        ------
        InputError
            As :func:`load_dataset` for a file: a non-numeric, negative or
            non-finite value names its column and row (the row's position in the
            frame, from 0); a wrong unit, a missing ``mu`` column, a bad mapping or
            no row left are refused too.
        """
        if not _is_frame(frame):
            raise InputError(f"Dataset.from_frame takes a pandas DataFrame, got "
                             f"{type(frame).__name__}")
        if isinstance(mapping, str):
            mapping = parse_mapping(mapping)
        if isinstance(units, str):
            units = parse_units(units)
        return _build(_table_from_frame(frame, "<DataFrame>"), name, mapping, units, area, None)

    def to_frame(self, units: str = "si") -> pd.DataFrame:
        """Return the data as a DataFrame whose column names carry their units.

        Parameters
        ----------
        units : {"si", "display"}
            ``si`` (default): values in SI with SI units in the names (``p [Pa]``,
            ``v [m/s]``, ``T [K]``, ``F_N [N]``); ``display``: the units
            :meth:`to_csv` writes (``p [MPa]``, ``T [degC]``).  Dimensionless
            columns (``mu``, ``s``, ``mu_std``, ``n``) and ``surface`` carry no
            unit.

        Returns
        -------
        pandas.DataFrame
            The canonical columns present, in the CSV schema's order; a copy.
            ``attrs`` holds ``name``, ``source`` and ``units`` (column -> unit).
            :meth:`from_frame` reads it back.

        Raises
        ------
        InputError
            For ``units`` other than ``"si"`` or ``"display"``.
        """
        import pandas as pd

        if units not in ("si", "display"):
            raise InputError(f"units must be 'si' or 'display', got {units!r}")
        out = pd.DataFrame(index=range(len(self)))
        given: dict[str, str] = {}
        for c in (c for c in CANONICAL if c in self.column_names):
            if c in TEXT_COLUMNS or c not in _units.QUANTITIES:
                out[c] = np.array(self.column(c), copy=True)
                continue
            unit = _units.si_unit(c) if units == "si" else _units.display_unit(c)
            vals = self.column(c, float)
            out[_units.header(c, unit)] = (vals.copy() if units == "si"
                                           else _units.from_si(vals, unit, c))
            given[c] = unit
        out.attrs.update(name=self.name, source=self.source, units=given)
        return out

    def to_csv(self, path: str | os.PathLike[str]) -> Path:
        """Write the dataset to a CSV file in the canonical schema.

        Units go in the headers and the provenance in ``#`` lines.  Numbers are
        written with 15 significant digits in display units (p in MPa, v in m/s,
        T in degC, F_N in N), so that ``load_dataset(path)`` gives back the same
        SI values.

        Parameters
        ----------
        path : str or path-like
            The file to write (replaced atomically if it exists; never a file
            read in this process, see :mod:`frictionlaws.base.outputs`).

        Returns
        -------
        pathlib.Path
            The path written.
        """
        path = Path(path)
        cols = [c for c in CANONICAL if c in self.column_names]
        headers = [_units.header(c) if c in _units.QUANTITIES else c for c in cols]
        columns: list[list[str]] = []
        for c in cols:
            if c in TEXT_COLUMNS:
                columns.append([csv_cell(s) for s in self.column(c)])
                continue
            unit = _units.display_unit(c)
            vals = _units.from_si(self.column(c, float), unit, c)
            columns.append([format(float(x), ".15g") for x in vals])

        with atomic_write(path, newline="") as fh:
            if self.provenance:
                for line in comment_lines(split_lines(self.provenance)):
                    fh.write(line + "\n")
            writer = csv.writer(fh, lineterminator="\n")
            writer.writerow(headers)
            for row in zip(*columns, strict=True):
                writer.writerow(row)
        return path


def _build(table: Table, name: str, mapping: Mapping[str, str] | None,
           units: Mapping[str, str] | None, area: str | float | None,
           provenance: str | None) -> Dataset:
    """The dataset of a table's raw cells: every check of the input layer, in order."""
    notes = list(table.notes)
    _check_headers(table)
    names = [split_header(h)[0] for h in table.headers]
    assigned, explicit = _assign_columns(table, names, mapping, notes)
    unit_of = _column_units(table, names, assigned, units)
    values = _numbers(table, assigned, explicit, unit_of, notes)
    si = _to_si_checked(table, assigned, values, unit_of, notes)
    dropped: dict[str, list[str]] = {}
    keep = _rows_to_keep(table, assigned, si, notes, dropped)
    columns = _kept_columns(table, assigned, si, keep)
    units_given = {c: _written_unit(unit_of.get(c, ""), c) for c in columns
                   if c not in TEXT_COLUMNS}
    if area is not None:
        columns = _pressure_from_area(columns, area, table.source, units_given, notes)
    notes.extend(_column_notes(columns))
    rows = np.asarray(table.rows, dtype=int)[keep] if table.from_file else None
    ds = Dataset(columns, name, table.source, units_given, notes, provenance, rows)
    ds.dropped = dropped
    return ds


def _written_unit(unit: str, column: str) -> str:
    """A unit as a dataset keeps it for its outputs: canonical (``N/mm^2``), never as typed."""
    if _units.is_no_unit(unit):
        return unit
    return _units.canonical_unit(unit, column)


def dataset_html(dataset: Any, head: int = 5) -> str:
    """HTML for a dataset: name, source, each column's range in display units, first rows."""
    rows = []
    for col in dataset.column_names:
        if col not in _units.QUANTITIES:
            values = sorted({str(x) for x in dataset.column(col)})
            rows.append({"column": col, "unit": "", "range": ", ".join(values[:8])
                         + (", ..." if len(values) > 8 else ""), "distinct": len(values),
                         "given in": ""})
            continue
        shown = _units.to_display(dataset.column(col, float), col)
        rows.append({"column": col, "unit": unit_text(_units.display_unit(col)),
                     "range": f"{shown.min():.4g} .. {shown.max():.4g}",
                     "distinct": len(np.unique(shown)),
                     "given in": dataset.units.get(col, "")})
    first = dataset.to_frame("display").head(head)
    notes = "".join(f"<li>{html.escape(n)}</li>" for n in dataset.notes)
    return "\n".join([
        f"<h4>dataset <code>{html.escape(str(dataset.name))}</code>: {len(dataset)} rows</h4>",
        f"<p>source: {html.escape(str(dataset.source))}</p>",
        table_html(rows, caption="columns (display units)"),
        f"<p>first {len(first)} rows</p>",
        first.to_html(index=False, float_format=lambda x: f"{x:.6g}"),
        f"<ul>{notes}</ul>" if notes else ""])
