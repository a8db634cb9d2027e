"""Datasets: read tribometer tables in the user's columns and units, into SI.

A dataset is a table with one friction coefficient per row and the conditions
it was measured at.  The canonical columns are

=========== ============================== ======================= =====
column      meaning                        unit in the file        SI
=========== ============================== ======================= =====
``mu``      friction coefficient           none (or ``-``)         ``-``
``p``       contact pressure               required, e.g. ``MPa``  Pa
``v``       sliding velocity               required, e.g. ``m/s``  m/s
``T``       temperature                    required, e.g. ``degC`` K
``F_N``     normal load                    required, e.g. ``N``,   N
                                           ``kgf``, ``kg``
``s``       slip ratio                     none, ``-`` or ``%``    ``-``
``mu_std``  std. deviation of replicate mu none                    ``-``
``n``       number of replicates           none                    ``-``
``surface`` counter-surface (text)         ``-``                   ``-``
=========== ============================== ======================= =====

Units go in the header in square brackets (``p [MPa]``), or through the
``units`` argument (``units="p=MPa"``) for files whose header has none.  Column
names may be aliases (``cof``, ``pressure``, ``speed``, ``load``...) or be
mapped explicitly (``mapping="mu=FC,p=CP,v=DV"``).  The full schema, the rules for
what is an error and what is a reported drop, and the provenance of the
packaged datasets are in ``datasets/README.md``.

Every problem with the user's input raises :class:`~frictionlaws.errors.InputError`
naming the file, the column and the row (the line number a text editor or
spreadsheet shows; the header of a file without comments is row 1).  Rows are
never dropped silently: each drop is written to :attr:`Dataset.notes`.
"""

from __future__ import annotations

import csv
import math
import os
import re
import sys
import unicodedata
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeGuard

import numpy as np

from . import units as _units
from .errors import Argument, InputError
from .law import VARIABLES
from .sanitize import comment_lines, csv_cell, csv_cell_text, split_lines

if TYPE_CHECKING:  # pandas is imported where a DataFrame is made or asked for
    import pandas as pd

__all__ = [
    "CANONICAL",
    "VARIABLE_COLUMNS",
    "ALIASES",
    "Dataset",
    "load_dataset",
    "list_datasets",
    "datasets_dir",
    "output_dir",
    "parse_mapping",
    "parse_units",
    "canonical_name",
]

#: The canonical columns that are independent variables of a law
#: (:data:`frictionlaws.law.VARIABLES`; their units: :data:`frictionlaws.units.QUANTITIES`).
VARIABLE_COLUMNS: tuple[str, ...] = tuple(VARIABLES)
#: Canonical columns, in the order a dataset stores and writes them.
CANONICAL: tuple[str, ...] = ("mu", *VARIABLE_COLUMNS, "mu_std", "n", "surface",
                              "condition_id")
#: Canonical columns that hold text: the counter-surface, and the test condition each
#: row belongs to (repeats share it: the unit the bootstrap resamples).
TEXT_COLUMNS: tuple[str, ...] = ("surface", "condition_id")
_NUMERIC = tuple(c for c in CANONICAL if c not in TEXT_COLUMNS)
_DIMENSIONLESS = tuple(c for c in _NUMERIC if not _units.si_unit(c))

#: Accepted column names for each canonical column, in :data:`CANONICAL` order (the
#: one alias table; a test checks it has every canonical column and no other).  The
#: canonical names themselves match exactly (``T`` is temperature, ``t`` is not); these
#: aliases match case-insensitively, with spaces, ``_`` and ``-`` equivalent.
ALIASES: dict[str, tuple[str, ...]] = {
    "mu": ("mu", "μ", "cof", "coef", "friction", "friction coefficient",
           "coefficient of friction", "friction coef", "mu mean", "mean mu"),
    "p": ("p", "pressure", "contact pressure", "normal pressure", "nominal pressure"),
    "v": ("v", "velocity", "speed", "sliding velocity", "sliding speed", "slip velocity",
          "slip speed"),
    "T": ("temperature", "temp", "surface temperature"),
    "F_N": ("f_n", "fn", "load", "normal load", "normal force", "force normal"),
    "s": ("slip", "slip ratio", "longitudinal slip", "kappa", "κ"),
    "mu_std": ("mu_std", "mu std", "std mu", "std", "sd", "stdev", "std dev",
               "standard deviation", "mu sd", "sd mu"),
    "n": ("count", "replicates", "repeats", "n tests", "n repeats", "n replicates"),
    "surface": ("surface", "counter surface", "countersurface", "counterface", "material"),
    "condition_id": ("condition_id", "condition id", "test condition"),
}

#: Cell contents read as a missing value (the row is then dropped and reported).
MISSING_TOKENS = frozenset({"", "nan", "na", "n/a", "#n/a", "null", "none", "-", "—", "–"})

_DELIMITERS = (";", "\t", ",")
_DELIMITER_NAMES = {";": "';'", "\t": "tab", ",": "','"}
_PACKAGED_PREFIX = "packaged:"
# A data row may start with a spreadsheet error value; it is data, not a comment.
_SPREADSHEET_ERROR = re.compile(
    r"^[\"']?#(N/A|VALUE!|DIV/0!|REF!|NUM!|NAME\?|NULL!)", re.IGNORECASE)


def _norm(name: str) -> str:
    # NFKC: the micro sign typed by keyboards (U+00B5) reads as the Greek mu (U+03BC)
    text = unicodedata.normalize("NFKC", name)
    return re.sub(r"[\s_\-]+", " ", text.strip().lower()).strip()


_ALIAS_LOOKUP: dict[str, str] = {}
for _canon, _names in ALIASES.items():
    for _alias in _names:
        _ALIAS_LOOKUP[_norm(_alias)] = _canon

_CANON_KEYS = {c.lower(): c for c in CANONICAL}


def canonical_name(key: str, *, what: str = "name", option: str | None = None) -> str:
    """The canonical column for a key of ``mapping``/``units`` (``"f_n"`` -> ``"F_N"``).

    ``option`` is the argument the key came from (named in the error).

    Raises
    ------
    InputError
        When ``key`` is not one of :data:`CANONICAL`.
    """
    k = key.strip()
    if k in CANONICAL:
        return k
    if k.lower() in _CANON_KEYS:
        return _CANON_KEYS[k.lower()]
    raise InputError(
        f"{what} '{k}' is not a dataset column; expected one of {', '.join(CANONICAL)}",
        option=option,
    )


def _split_pairs(text: str | Sequence[str], option: str, example: str
                 ) -> list[tuple[str, str]]:
    """``"a=1,b=2"`` (or several such strings) -> ``[("a", "1"), ("b", "2")]``."""
    parts: list[str] = []
    for chunk in ([text] if isinstance(text, str) else list(text)):
        parts.extend(str(chunk).split(","))
    items = []
    for part in parts:
        if not part.strip():
            if len(parts) > 1:
                continue
            raise InputError(["is empty; expected NAME=VALUE pairs, e.g. ",
                              Argument(option, example)], option=option)
        if "=" not in part:
            raise InputError([f"'{part.strip()}' is not NAME=VALUE; expected e.g. ",
                              Argument(option, example)], option=option)
        k, v = part.split("=", 1)
        items.append((k, v))
    return items


def _parse_pairs(text: str | Sequence[str] | Mapping[str, str] | None, option: str,
                 example: str) -> dict[str, str]:
    """``NAME=VALUE`` pairs of the argument ``option`` by canonical column name."""
    if text is None:
        return {}
    if isinstance(text, Mapping):
        items = [(str(k), str(v)) for k, v in text.items()]
    else:
        items = _split_pairs(text, option, example)
    out: dict[str, str] = {}
    for k, v in items:
        k, v = k.strip(), v.strip()
        if not k or not v:
            raise InputError([f"'{k}={v}' has an empty name or value; expected e.g. ",
                              Argument(option, example)], option=option)
        canon = canonical_name(k, option=option)
        if canon in out:
            raise InputError(f"'{canon}' is given twice", option=option)
        out[canon] = v
    return out


def parse_mapping(text: str | Sequence[str] | Mapping[str, str] | None) -> dict[str, str]:
    """Parse ``"mu=FC,p=CP,v=DV"`` into ``{"mu": "FC", "p": "CP", "v": "DV"}``.

    Keys are canonical column names (case-insensitive: ``f_n`` is ``F_N``);
    values are the user's column names.  A list of such strings or a dict is
    accepted too.

    Raises
    ------
    InputError
        On text that is not ``NAME=COLUMN`` pairs, an unknown canonical name, a
        name given twice or one column mapped twice.
    """
    out = _parse_pairs(text, "mapping", "mu=FC,p=CP,v=DV")
    seen: dict[str, str] = {}
    for canon, col in out.items():
        if col in seen:
            raise InputError(f"column '{col}' is mapped to both '{seen[col]}' and '{canon}'",
                             option="mapping")
        seen[col] = canon
    return out


def parse_units(text: str | Sequence[str] | Mapping[str, str] | None) -> dict[str, str]:
    """Parse ``"p=MPa,v=km/h"`` into ``{"p": "MPa", "v": "km/h"}``.

    Only the syntax is checked here; each unit is checked against its column
    (with pint) when the data are loaded.

    Raises
    ------
    InputError
        On text that is not ``NAME=UNIT`` pairs or an unknown canonical name.
    """
    return _parse_pairs(text, "units", "p=MPa,v=m/s")


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
        from .interop import dataset_html

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
            read in this process, see :mod:`frictionlaws.outputs`).

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
        from .outputs import atomic_write  # never over a file read in this process

        with atomic_write(path, newline="") as fh:
            if self.provenance:
                for line in comment_lines(split_lines(self.provenance)):
                    fh.write(line + "\n")
            writer = csv.writer(fh, lineterminator="\n")
            writer.writerow(headers)
            for row in zip(*columns, strict=True):
                writer.writerow(row)
        return path


# --------------------------------------------------------------------------- reading text
@dataclass
class _Table:
    """Raw cells of a table, before columns are resolved."""

    headers: list[str]
    columns: list[list[Any]]
    rows: list[int]  # source row of each data row
    source: str
    comments: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    decimal_comma: bool = False
    from_file: bool = True
    delimiter: str | None = None
    #: A dict of arrays (the API's SI arrays): a column without a unit is in SI.  A file
    #: and a DataFrame must state every unit (one rule for both).
    si_by_default: bool = False


def refuse_nul(raw: bytes, source: str) -> None:
    """Refuse text with a NUL byte anywhere, naming the row it is on.

    A NUL is never part of a CSV cell; CSV readers either stop at it or fail with an
    internal message, so every table reader calls this before parsing.
    """
    at = raw.find(b"\x00")
    if at >= 0:
        raise InputError("contains a NUL byte (binary content inside a text file); "
                         "expected CSV text", file=source, row=raw.count(b"\n", 0, at) + 1)


def decode_text(raw: bytes, source: str, what: str = "CSV file") -> tuple[str, str | None]:
    """Decode the bytes of a text input file; the one encoding rule of every reader.

    UTF-16 with a byte-order mark, UTF-8 (with or without BOM), then cp1252 and
    latin-1 with a note.  Binary content (a spreadsheet, an image) and NUL bytes
    anywhere are refused.

    Returns
    -------
    text : str
    note : str or None
        Set when the file was not UTF-8, to be shown to the user.
    """
    raw = raw.rstrip(b"\x1a")  # a DOS end-of-file mark (Ctrl-Z) is not content
    for bom, codec in ((b"\xff\xfe\x00\x00", "utf-32"), (b"\x00\x00\xfe\xff", "utf-32"),
                       (b"\xff\xfe", "utf-16"), (b"\xfe\xff", "utf-16")):
        if raw.startswith(bom):
            try:
                return raw.decode(codec), None
            except UnicodeDecodeError:
                raise InputError(f"starts with a {codec.upper()} byte-order mark but does not "
                                 f"decode as {codec.upper()}", file=source) from None
    head = raw[:8192]
    controls = sum(1 for b in head if b < 32 and b not in (9, 10, 12, 13))
    if b"\x00" in head or controls > max(2, len(head) // 20):
        raise InputError(
            f"is not a text {what} (binary content, e.g. a spreadsheet or an image); "
            f"export it as text",
            file=source,
        )
    refuse_nul(raw, source)
    try:
        return raw.decode("utf-8-sig"), None
    except UnicodeDecodeError:
        pass
    for enc in ("cp1252", "latin-1"):
        try:
            return raw.decode(enc), f"file is not UTF-8; read it as {enc}"
        except UnicodeDecodeError:
            continue
    raise InputError("cannot decode the file as text", file=source)  # pragma: no cover


def _detect_delimiter(header_line: str) -> str | None:
    for d in _DELIMITERS:
        if d in header_line:
            return d
    return None


def read_table(path: str | os.PathLike[str], *, source: str | None = None,
               raw: bytes | None = None, header_hint: str = "'mu,p [MPa],v [m/s]'",
               what: str = "data file") -> _Table:
    """Read a CSV file into raw cells: the one table reader (datasets, manifests).

    Detects ``;``, tab or ``,`` delimiters from the header line, decimal commas
    (with ``;`` or tab), the encoding (:func:`decode_text`), ``#`` comment lines
    and blank lines.  Quoted fields must close on their line.  Cells stay strings;
    :func:`load_dataset` converts them.

    Parameters
    ----------
    path : path-like
        The file (ignored for reading when ``raw`` is given).
    source : str, optional
        Name used in messages (default: ``path``).
    raw : bytes, optional
        The file's content, when already read.
    header_hint : str
        An example header, for the message on a file without one.
    what : str
        What the file is, for messages ("data file", "manifest file").
    """
    source = source or str(path)
    if raw is None:
        raw = _read_bytes(Path(path), source, what)
    text, enc_note = decode_text(raw, source)
    table = _scan_lines(split_lines(text), source, header_hint)
    if enc_note:
        table.notes.append(enc_note)
    return table


def _read_bytes(p: Path, source: str, what: str) -> bytes:
    if not p.exists():
        raise InputError(
            "file not found; expected a CSV file or the name of a packaged dataset "
            f"({', '.join(_packaged_names()) or 'none'})" if what == "data file"
            else f"{what} not found", file=source)
    if p.is_dir():
        raise InputError(f"is a directory; expected a {what} (CSV)", file=source)
    from .limits import read_input
    from .outputs import check_input_file

    check_input_file(p, what)  # a FIFO or device would block or never end
    return read_input(p, what, source)  # bounded in size


def _scan_lines(lines: list[str], source: str, header_hint: str) -> _Table:
    """Header, comments and data rows of the decoded lines (see :func:`read_table`)."""
    comments: list[str] = []
    header: list[str] | None = None
    header_row = 0
    delimiter: str | None = None
    data: list[list[str]] = []
    rows: list[int] = []
    for number, line in enumerate(lines, start=1):
        stripped = line.strip()
        if stripped.startswith("#") and not (header is not None
                                             and _SPREADSHEET_ERROR.match(stripped)):
            comments.append(stripped[1:].strip() if stripped[1:2] != " " else stripped[2:])
            continue
        if not stripped:
            continue
        if header is None:
            delimiter = _detect_delimiter(line)
            header = _split(line, delimiter, source, number)
            header_row = number
            continue
        if delimiter is None and any(d in line for d in _DELIMITERS):
            found = next(_DELIMITER_NAMES[d] for d in _DELIMITERS if d in line)
            raise InputError(
                f"the header has a single column '{header[0]}' but this row contains "
                f"{found}: the header and the data use different delimiters",
                file=source, row=number,
            )
        data.append(_split(line, delimiter, source, number))
        rows.append(number)
    if header is None:
        raise InputError(f"file is empty (no header line); expected a header such as "
                         f"{header_hint} followed by data rows", file=source)
    if not data:
        raise InputError(f"file has a header (row {header_row}) but no data rows",
                         file=source)
    headers = [h.strip() for h in header]
    columns = _rectangular(data, rows, headers, delimiter, source)
    return _Table(headers, columns, rows, source, comments, [], delimiter in (";", "\t"),
                  True, delimiter)


def _rectangular(data: list[list[str]], rows: list[int], headers: list[str],
                 delimiter: str | None, source: str) -> list[list[str]]:
    """Columns of the rows, each padded or checked to the header's width."""
    ncol = len(headers)
    for cells, number in zip(data, rows, strict=True):
        if len(cells) > ncol:
            if any(c.strip() for c in cells[ncol:]):
                raise InputError(
                    f"has {len(cells)} fields but the header has {ncol} "
                    f"(delimiter {_DELIMITER_NAMES.get(delimiter or '', 'none')}); "
                    "check the delimiter and the quoting"
                    + ("; a decimal comma needs ';' or tab as the delimiter"
                       if delimiter == "," else ""),
                    file=source, row=number,
                )
            del cells[ncol:]
        elif len(cells) < ncol:
            if len(cells) == 1 and ncol > 1 and any(d in cells[0] for d in _DELIMITERS):
                raise InputError(
                    f"has 1 field but the header has {ncol}: the row uses another "
                    f"delimiter than the header ({_DELIMITER_NAMES.get(delimiter or '')})",
                    file=source, row=number,
                )
            cells.extend([""] * (ncol - len(cells)))
    return [[cells[j] for cells in data] for j in range(ncol)]


def _split(line: str, delimiter: str | None, source: str, row: int) -> list[str]:
    if delimiter is None:
        return [line.strip()]
    try:
        return next(csv.reader([line], delimiter=delimiter, skipinitialspace=True,
                               strict=True))
    except csv.Error as exc:
        hint = ("a quoted field is not closed on its line (a line break inside quotes?); "
                "write each row on one line" if "end of data" in str(exc)
                else f"malformed quoting ({exc})")
        raise InputError(hint, file=source, row=row) from None


def _table_from_frame(df: pd.DataFrame, source: str) -> _Table:
    headers = [str(c) for c in df.columns]
    columns = [df.iloc[:, j].tolist() for j in range(df.shape[1])]
    rows = list(range(1, len(df) + 1))
    if not len(df):
        raise InputError("the DataFrame has no rows", file=source)
    return _Table(headers, columns, rows, source, from_file=False)


# --------------------------------------------------------------------------- building
def split_header(h: str, *, brackets_in_name: bool = True) -> tuple[str, str | None]:
    """``"p [MPa]"`` -> ``("p", "MPa")``; ``"p"`` -> ``("p", None)``: the one header rule.

    The unit is the text between the last ``[`` and a final ``]``; it may hold no
    bracket.  Done with string searches, in time linear in the header's length (a
    regular expression with a lazy name and optional spaces is quadratic on a cell
    padded with spaces).

    Parameters
    ----------
    h : str
        The header cell.
    brackets_in_name : bool
        Whether the name before the unit may hold ``[`` or ``]`` (a record's may not).

    Returns
    -------
    tuple of (str, str or None)
        The name and the unit (stripped), or the stripped header and None.
    """
    s = h.rstrip()
    opening = s.rfind("[", 0, len(s) - 1)
    if not s.endswith("]") or opening < 0 or "]" in s[opening + 1:-1]:
        return h.strip(), None
    name = s[:opening]
    if not brackets_in_name and ("[" in name or "]" in name):
        return h.strip(), None
    return name.strip(), s[opening + 1:-1].strip()


_split_header = split_header


def _match_column(wanted: str, headers: list[str], names: list[str]) -> int | None:
    for pool in (headers, names):
        hits = [j for j, h in enumerate(pool) if h == wanted]
        if len(hits) == 1:
            return hits[0]
    low = wanted.strip().lower()
    for pool in (headers, names):
        hits = [j for j, h in enumerate(pool) if h.lower() == low]
        if len(hits) == 1:
            return hits[0]
    return None


def _resolve_name(name: str) -> str | None:
    if name in CANONICAL:
        return name
    return _ALIAS_LOOKUP.get(_norm(name))


def _to_float(cell: Any, decimal_comma: bool) -> float | None:
    """A float, ``nan`` for a missing value, or None when not a number."""
    if cell is None or (not isinstance(cell, str) and _is_missing(cell)):
        return math.nan
    if isinstance(cell, (bool, np.bool_)):
        return None
    if isinstance(cell, (int, float, np.integer, np.floating)):
        return float(cell)
    text = str(cell).strip()
    if text.lower() in MISSING_TOKENS:
        return math.nan
    from .numbers import parse_number

    if text.lower().lstrip("+-") in ("inf", "infinity"):
        return math.inf  # reported as "not finite" with its row
    try:  # the one number parser: no 1_000, no full-width digits, no overflow
        return parse_number(text, decimal_comma=decimal_comma and "," in text)
    except ValueError:
        return None


def _is_frame(x: Any) -> TypeGuard[pd.DataFrame]:
    """True for a pandas DataFrame (without importing pandas: none exists before it is)."""
    pd = sys.modules.get("pandas")
    return pd is not None and isinstance(x, pd.DataFrame)


def _is_missing(cell: Any) -> bool:
    """A scalar cell that is a missing value (NaN, or pandas' NA and NaT)."""
    if np.ndim(cell) != 0:
        return False
    pd = sys.modules.get("pandas")
    if pd is not None:
        return bool(pd.isna(cell))
    return isinstance(cell, (float, np.floating)) and math.isnan(cell)


def _row_label(table: _Table, i: int) -> int | None:
    return table.rows[i] if table.from_file else None


def _where(table: _Table, i: int) -> str:
    return "" if table.from_file else f" (DataFrame row position {i})"


def _build(table: _Table, name: str, mapping: Mapping[str, str] | None,
           units: Mapping[str, str] | None, area: str | float | None,
           provenance: str | None) -> Dataset:
    """The dataset of a table's raw cells: every check of the input layer, in order."""
    notes = list(table.notes)
    _check_headers(table)
    names = [_split_header(h)[0] for h in table.headers]
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


def _check_headers(table: _Table) -> None:
    """Refuse unnamed columns that hold data and duplicate headers."""
    src = table.source
    seen: dict[str, int] = {}
    for j, h in enumerate(table.headers):
        if not h:
            if any(str(c).strip() for c in table.columns[j] if c is not None):
                raise InputError(f"column {j + 1} has no name in the header but holds data",
                                 file=src)
            continue
        if h in seen:
            raise InputError(
                f"duplicate column (columns {seen[h] + 1} and {j + 1} have the same "
                "header); keep one or rename it",
                file=src, column=h,
            )
        seen[h] = j


def _listed(headers: Sequence[str]) -> str:
    return ", ".join(h for h in headers if h) or "none"


def _assign_columns(table: _Table, names: list[str], mapping: Mapping[str, str] | None,
                    notes: list[str]) -> tuple[dict[str, int], set[str]]:
    """Canonical name -> column index (the mapping first, then recognised names)."""
    src, headers = table.source, table.headers
    map_ = parse_mapping(mapping) if mapping else {}
    assigned: dict[str, int] = {}
    for canon, user_col in map_.items():
        j = _match_column(user_col, headers, names)
        if j is None:
            raise InputError([Argument("mapping", f"{canon}={user_col}"),
                              f": no such column in the file (columns: {_listed(headers)})"],
                             file=src, column=user_col)
        if j in assigned.values():
            other = next(c for c, k in assigned.items() if k == j)
            raise InputError(f"column mapped to both '{other}' and '{canon}'",
                             file=src, column=headers[j], option="mapping")
        assigned[canon] = j
    explicit = set(assigned)
    ignored: list[str] = []
    for j, nm in enumerate(names):
        if j in assigned.values() or not headers[j]:
            continue
        found = _resolve_name(nm)
        if found is None:
            ignored.append(headers[j])
        elif found in explicit:
            notes.append(f"column '{headers[j]}' ignored: {found} comes from "
                         f"the mapping {found}={map_[found]}")
        elif found in assigned:
            raise InputError(
                [f"columns '{headers[assigned[found]]}' and '{headers[j]}' both give "
                 f"'{found}'; keep one, or choose with ", Argument("mapping", f"{found}=COLUMN")],
                file=src, column=headers[j],
            )
        else:
            assigned[found] = j
    if "mu" not in assigned:
        _no_mu(table)
    if ignored:
        notes.append(
            f"ignored column{'s' if len(ignored) > 1 else ''} not in the schema: "
            f"{', '.join(ignored)} (map them to use them)"
        )
    return assigned, explicit


def _no_mu(table: _Table) -> None:
    headers = table.headers
    if len([h for h in headers if h]) == 1 and table.from_file:
        only = headers[0]
        if re.search(r"[|:]|\S\s+\S", only):
            raise InputError(
                f"found a single column '{only}': the delimiter is not recognised; "
                "expected columns separated by ',', ';' or a tab",
                file=table.source,
            )
    raise InputError(
        ["no friction coefficient column: expected a column named 'mu' (or cof, "
         "friction, ...) or ", Argument("mapping", "mu=COLUMN"),
         f" (columns: {_listed(headers)})"],
        file=table.source,
    )


def _extra_units(table: _Table, names: list[str], assigned: Mapping[str, int],
                 units: Mapping[str, str] | None) -> dict[str, str]:
    """Units given outside the header, by canonical name (checked against the columns)."""
    src, headers = table.source, table.headers
    extra: dict[str, str] = {}
    for key, unit in (units or {}).items():
        try:
            canon: str | None = canonical_name(key, option="units")
        except InputError:
            j = _match_column(key, headers, names)
            if j is None:
                raise InputError(
                    [Argument("units", f"{key}={unit}"),
                     f": '{key}' is neither a dataset column ({', '.join(CANONICAL)}) nor "
                     f"a column of the file (columns: {_listed(headers)})"], file=src) from None
            canon = next((c for c, k in assigned.items() if k == j), None)
            if canon is None:
                raise InputError(
                    [Argument("units", f"{key}={unit}"), ": the column is not used; map it "
                     "first, e.g. ", Argument("mapping", f"p={key}")],
                    file=src, column=headers[j]) from None
        extra[str(canon)] = str(unit).strip()
    for canon, unit in extra.items():
        if canon not in assigned:
            raise InputError([Argument("units", f"{canon}={unit}"),
                              f": the file has no '{canon}' column "
                              f"(columns: {_listed(headers)})"], file=src)
    return extra


def _column_units(table: _Table, names: list[str], assigned: Mapping[str, int],
                  units: Mapping[str, str] | None) -> dict[str, str]:
    """The checked unit of every assigned column (header or ``units``, given once)."""
    src, headers = table.source, table.headers
    extra = _extra_units(table, names, assigned, units)
    unit_of: dict[str, str] = {}
    for canon, j in assigned.items():
        header_unit = _split_header(headers[j])[1]
        given = extra.get(canon)
        if header_unit is not None and given is not None and header_unit != given:
            raise InputError(
                [f"the header gives unit '{header_unit}' but ",
                 Argument("units", f"{canon}={given}"), " gives another; give the unit once"],
                file=src, column=headers[j],
            )
        unit = header_unit if header_unit is not None else given
        if canon in TEXT_COLUMNS:
            continue
        if unit is None:
            if canon in _DIMENSIONLESS:
                unit = ""
            elif table.si_by_default:
                unit = _units.si_unit(canon)
            else:
                ex = _units.display_unit(canon)
                raise InputError(
                    [f"column has no unit; give it in the header as '{names[j]} [{ex}]' "
                     "or with ", Argument("units", f"{canon}={ex}")],
                    file=src, column=headers[j],
                )
        _units.check_unit(unit, canon, column=headers[j], file=src)
        unit_of[canon] = unit
    return unit_of


def _shown(text: str, width: int = 40) -> str:
    """A cell as quoted in a message: long values cut, so one line stays one line."""
    return text if len(text) <= width else f"{text[:width - 10]}...{text[-7:]} " \
        f"({len(text)} characters)"


def _overflows(text: str) -> bool:
    try:
        return math.isinf(float(text.replace(",", ".")))
    except (ValueError, OverflowError):
        return False


def _not_a_number(table: _Table, cell: Any, i: int, column: str) -> InputError:
    text = str(cell).strip()
    if _overflows(text):
        return InputError(f"value '{_shown(text)}'{_where(table, i)} overflows a double "
                          "(beyond 1.8e308): not a measured value", file=table.source,
                          column=column, row=_row_label(table, i))
    others = [_DELIMITER_NAMES[d] for d in _DELIMITERS if d in text and d != table.delimiter]
    hint = (f" (it contains {others[0]}: does this row use another delimiter "
            f"than the header's {_DELIMITER_NAMES.get(table.delimiter or '')}?)"
            if others and table.delimiter else "")
    if table.delimiter == "," and re.fullmatch(r"[-+]?\d+,\d+", text):
        hint = " (a decimal comma needs ';' or tab as the delimiter)"
    return InputError(
        f"non-numeric value '{_shown(text)}'{_where(table, i)}; expected "
        f"a number{' (decimal comma or point)' if table.decimal_comma else ''} "
        f"or an empty cell{hint}",
        file=table.source, column=column, row=_row_label(table, i),
    )


_THOUSANDS = re.compile(r"[-+]?\d{1,3}(\.\d{3})+")
_COMMA_DECIMAL = re.compile(r"\d,\d")


def _uses_decimal_commas(table: _Table) -> bool:
    """True when the file writes decimal commas somewhere (not only its delimiter)."""
    return table.decimal_comma and any(
        isinstance(c, str) and _COMMA_DECIMAL.search(c) for col in table.columns for c in col)


def _column_numbers(table: _Table, j: int, commas: bool = False) -> np.ndarray:
    """The numbers of column ``j`` (NaN where empty); text and infinities refused.

    With ``commas`` (the file writes decimal commas), ``1.200`` is ambiguous (a
    thousands separator or a decimal point) and refused.
    """
    col = table.headers[j]
    out = np.empty(len(table.rows))
    for i, cell in enumerate(table.columns[j]):
        if commas and isinstance(cell, str) and _THOUSANDS.fullmatch(cell.strip()):
            raise InputError(
                f"value '{cell.strip()}'{_where(table, i)} is ambiguous in a file with "
                f"decimal commas: a thousands separator ({cell.strip().replace('.', '')}) "
                f"or a decimal point ({cell.strip().replace('.', ',')})? Write it without "
                "the point, or with a decimal comma", file=table.source, column=col,
                row=_row_label(table, i))
        x = _to_float(cell, table.decimal_comma)
        if x is None:
            raise _not_a_number(table, cell, i, col)
        if math.isinf(x):
            raise InputError(f"value '{cell}' is not finite{_where(table, i)}",
                             file=table.source, column=col, row=_row_label(table, i))
        out[i] = x
    return out


def _numbers(table: _Table, assigned: Mapping[str, int], explicit: set[str],
             unit_of: dict[str, str], notes: list[str]) -> dict[str, np.ndarray]:
    """Numeric columns as written; an empty optional column is ignored with a note."""
    values: dict[str, np.ndarray] = {}
    commas = _uses_decimal_commas(table)
    for canon in [c for c in CANONICAL if c in assigned and c not in TEXT_COLUMNS]:
        col = table.headers[assigned[canon]]
        out = _column_numbers(table, assigned[canon], commas)
        if np.isnan(out).all():
            if canon == "mu" or canon in explicit:
                raise InputError(f"column is empty (every cell is empty or NaN); "
                                 f"'{canon}' needs values", file=table.source, column=col)
            notes.append(f"column '{col}' ({canon}) is empty: ignored")
            unit_of.pop(canon, None)
            continue
        values[canon] = out
    return values


#: Physical checks on values as written (before unit conversion): rule and reason.
_PHYSICAL: dict[str, tuple[Callable[[np.ndarray], np.ndarray], str]] = {
    "mu": (lambda x: x < 0, "a friction coefficient must be >= 0"),
    "p": (lambda x: x < 0, "a contact pressure must be >= 0"),
    "F_N": (lambda x: x < 0, "a normal load must be >= 0"),
    "mu_std": (lambda x: x < 0, "a standard deviation must be >= 0"),
    "n": (lambda x: (x < 1) | (x != np.round(x)),
          "a number of replicates must be a whole number >= 1"),
}


def _first_bad(table: _Table, j: int, bad: np.ndarray, message: str) -> None:
    """Raise naming the first of the rows ``bad`` (indices), if any."""
    if bad.size:
        i = int(bad[0])
        raise InputError(message.format(cell=table.columns[j][i], where=_where(table, i),
                                        more=f" ({bad.size} such rows)" if bad.size > 1
                                        else ""),
                         file=table.source, column=table.headers[j],
                         row=_row_label(table, i))


def _to_si_checked(table: _Table, assigned: Mapping[str, int],
                   values: Mapping[str, np.ndarray], unit_of: Mapping[str, str],
                   notes: list[str]) -> dict[str, np.ndarray]:
    """Physical checks, then SI conversion (overflow and absolute zero refused)."""
    si: dict[str, np.ndarray] = {}
    for canon, arr in values.items():
        j, unit = assigned[canon], unit_of[canon]
        if canon in _PHYSICAL:
            bad_fn, msg = _PHYSICAL[canon]
            with np.errstate(invalid="ignore"):
                bad = np.flatnonzero(bad_fn(arr) & ~np.isnan(arr))
            _first_bad(table, j, bad, "value {cell}{where} is not allowed: " + msg + "{more}")
        si[canon] = _units.to_si(arr, unit, canon, column=table.headers[j], file=table.source)
        _first_bad(table, j, np.flatnonzero(np.isinf(si[canon])),
                   "value {cell} " + unit + "{where} overflows when converted to SI: "
                   "not a measured value")
        note = _units.conversion_note(unit, canon, column=table.headers[j])
        if note:
            notes.append(note)
        if canon == "T":
            with np.errstate(invalid="ignore"):
                bad = np.flatnonzero(si[canon] < 0)
            _first_bad(table, j, bad, "temperature {cell} " + unit + "{where} is below "
                       "absolute zero (is the unit right?)")
    return si


def _rows_to_keep(table: _Table, assigned: Mapping[str, int],
                  si: Mapping[str, np.ndarray], notes: list[str],
                  dropped: dict[str, list[str]]) -> np.ndarray:
    """Rows without a missing value; every dropped row is named in a note.

    ``dropped`` receives, per canonical column, the labels of the rows dropped for it.
    """
    keep = np.ones(len(table.rows), dtype=bool)
    for canon in [c for c in CANONICAL if c in si]:
        nan_rows = np.flatnonzero(np.isnan(si[canon]) & keep)
        if not nan_rows.size:
            continue
        keep[nan_rows] = False
        dropped[canon] = [str(table.rows[i]) if table.from_file else f"position {i}"
                          for i in nan_rows]
        if table.from_file:
            labels = [str(table.rows[i]) for i in nan_rows]
            shown = ", ".join(labels[:12]) + (", ..." if len(labels) > 12 else "")
            where = f"row{'s' if len(labels) > 1 else ''} {shown}"
        else:
            where = f"positions {', '.join(str(i) for i in nan_rows[:12])}"
        notes.append(f"dropped {nan_rows.size} row{'s' if nan_rows.size > 1 else ''} "
                     f"({where}): empty or NaN in column '{table.headers[assigned[canon]]}'")
    if not keep.any():
        raise InputError(
            f"no usable rows: all {len(table.rows)} data rows have an empty or NaN value in "
            "mu or a variable column",
            file=table.source,
        )
    return keep


def _kept_columns(table: _Table, assigned: Mapping[str, int], si: Mapping[str, np.ndarray],
                  keep: np.ndarray) -> dict[str, np.ndarray]:
    """The kept rows in SI, canonical column order, the text columns as text."""
    columns = {c: si[c][keep] for c in CANONICAL if c in si}
    for name in (c for c in TEXT_COLUMNS if c in assigned):
        cells = ["" if c is None or (isinstance(c, float) and math.isnan(c)) else
                 csv_cell_text(str(c).strip()) if table.from_file else str(c).strip()
                 for c in table.columns[assigned[name]]]
        text = np.empty(int(np.count_nonzero(keep)), dtype=object)
        text[:] = [s for s, k in zip(cells, keep, strict=True) if k]
        columns[name] = text
    return {c: columns[c] for c in CANONICAL if c in columns}


def _pressure_from_area(columns: dict[str, np.ndarray], area: str | float, src: str,
                        units_given: dict[str, str], notes: list[str]
                        ) -> dict[str, np.ndarray]:
    """p = F_N / area when the data have a load and no pressure (the area is checked anyway)."""
    try:
        a = _units.parse_quantity(area, "area", what="area", file=src)
    except InputError as exc:  # "area '1 m' is a length...": the argument named by the front end
        raise InputError([Argument("area"), exc.bare_message.removeprefix("area")],
                         file=src) from None
    if not a > 0:
        raise InputError([Argument("area", str(area)), " must be > 0"], file=src)
    if "p" in columns:
        notes.append(f"area {area!r} not used: the data have a pressure column")
        return columns
    if "F_N" not in columns:
        raise InputError([Argument("area", str(area)), " needs a normal-load column F_N to "
                          "derive the pressure, and the data have none"], file=src)
    columns = {**columns, "p": columns["F_N"].astype(float) / a}
    units_given["p"] = f"F_N / area ({area})"
    notes.append(f"p derived as F_N / area with area = {area} = {a:.6g} m^2")
    return {c: columns[c] for c in CANONICAL if c in columns}


def _column_notes(columns: Mapping[str, np.ndarray]) -> list[str]:
    """What the user should know about the values: negative v, slip outside 0..1, weights."""
    notes = []
    if "v" in columns:
        neg = int(np.count_nonzero(columns["v"] < 0))
        if neg:
            notes.append(f"{neg} row{'s' if neg > 1 else ''} with negative v: laws use |v|")
    if "s" in columns:
        out_range = int(np.count_nonzero((columns["s"] < 0) | (columns["s"] > 1)))
        if out_range:
            notes.append(f"{out_range} row(s) with slip ratio s outside 0..1")
    if "mu_std" in columns and not (columns["mu_std"] > 0).all():
        zero = int(np.count_nonzero(columns["mu_std"] <= 0))
        alt = "sqrt(n)" if "n" in columns else "none (unweighted fit)"
        notes.append(f"mu_std is 0 in {zero} row(s): weights cannot be 1/mu_std; "
                     f"weights used: {alt}")
    return notes


# --------------------------------------------------------------------------- packaged
def output_dir(path: str | Path, what: str = "output directory") -> Path:
    """Create ``path`` (and parents) for writing; an :class:`InputError` names it when it fails."""
    out = Path(path)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"cannot create the {what} ({exc.strerror})", file=str(out)) from None
    return out


def datasets_dir() -> Any:
    """The packaged datasets directory (an importlib.resources Traversable).

    The installed package ships them as ``frictionlaws._datasets``; in a
    source checkout (tests run from the clone) they are the top-level
    ``datasets/`` folder beside the package.
    """
    from importlib import resources

    try:
        return resources.files("frictionlaws._datasets")
    except ModuleNotFoundError:  # a source checkout not (re)installed
        here = Path(__file__).resolve().parent.parent / "datasets"
        return here


def _packaged_names() -> list[str]:
    try:
        base = datasets_dir()
        return sorted(p.name[:-4] for p in base.iterdir() if p.name.endswith(".csv"))
    except (OSError, FileNotFoundError):  # pragma: no cover - broken install
        return []


def _header_info(text: str) -> tuple[str, str, int]:
    """Title (first comment line), provenance (all comment lines), data rows."""
    comments: list[str] = []
    count = -1
    for line in split_lines(text):
        s = line.strip()
        if s.startswith("#"):
            comments.append(s[2:] if s[1:2] == " " else s[1:])
        elif s:
            count += 1
    title = comments[0] if comments else ""
    return title, "\n".join(comments), max(count, 0)


def list_datasets() -> list[dict[str, Any]]:
    """List the packaged datasets.

    Returns
    -------
    list of dict
        One dict per packaged dataset, by name: ``name`` (what
        :func:`load_dataset` accepts), ``title`` (the first ``#`` line of the
        file), ``rows`` (the number of data lines) and ``provenance`` (the whole
        ``#`` comment block).
    """
    base = datasets_dir()
    out = []
    for name in _packaged_names():
        text = (base / f"{name}.csv").read_text(encoding="utf-8-sig")
        title, prov, rows = _header_info(text)
        out.append({"name": name, "title": title, "rows": rows, "provenance": prov})
    return out


# --------------------------------------------------------------------------- entry point
def load_dataset(
    name_or_path: str | os.PathLike[str] | pd.DataFrame | Mapping[str, Any] | Dataset,
    *,
    mapping: Mapping[str, str] | str | None = None,
    units: Mapping[str, str] | str | None = None,
    area: str | float | None = None,
) -> Dataset:
    """Load a dataset from a CSV file, a packaged dataset name or a DataFrame.

    Parameters
    ----------
    name_or_path : str, path, DataFrame, dict or Dataset
        A CSV path; the name of a packaged dataset (see :func:`list_datasets`,
        e.g. ``"thesis-steel"``); a DataFrame (its columns named as in a CSV file,
        each with its unit in the name or in ``units``: a column without a unit is
        refused, as in a file); a dict of columns (canonical or aliased names,
        SI where the name gives no unit); or a :class:`Dataset`, returned unchanged.
    mapping : dict or str, optional
        Canonical column -> the user's column, e.g. ``{"mu": "FC", "p": "CP"}``
        or ``"mu=FC,p=CP"``.
    units : dict or str, optional
        Units of columns whose header has none, e.g. ``{"p": "MPa"}`` or
        ``"p=MPa,v=m/s"``.
    area : str or float, optional
        Nominal contact area, ``"314.16 mm^2"`` or a float in m^2: when the
        data have a normal load ``F_N`` but no pressure, ``p = F_N / area``.

    Returns
    -------
    Dataset
        The data in canonical SI columns, with the units given, the provenance
        and notes of what the loader did (dropped rows, ignored columns,
        conversions); a :class:`Dataset` passed in is returned unchanged.

    Raises
    ------
    InputError
        For a missing, empty, binary or malformed file, an unknown or
        wrong-dimension unit, a missing ``mu`` column, a non-numeric cell, a
        negative pressure, load or friction coefficient, a bad mapping, or when
        no row is left after dropping rows with missing values.  The message
        names the file, column and row.
    """
    if isinstance(mapping, str):
        mapping = parse_mapping(mapping)
    if isinstance(units, str):
        units = parse_units(units)
    if isinstance(name_or_path, Dataset):
        if mapping or units or area is not None:
            raise InputError(
                f"dataset '{name_or_path.name}' is already loaded; mapping, units and area "
                "apply only when reading a file or a DataFrame"
            )
        return name_or_path
    if _is_frame(name_or_path) or isinstance(name_or_path, Mapping):
        table, name = _table_in_memory(name_or_path)
        return _build(table, name, mapping, units, area, None)
    if not isinstance(name_or_path, (str, os.PathLike)):
        raise InputError(
            f"cannot load a dataset from a {type(name_or_path).__name__}; expected a path, "
            "a packaged dataset name, a DataFrame or a Dataset"
        )
    table, name = _table_on_disk(os.fspath(name_or_path))
    prov = "\n".join(table.comments) or None
    return _build(table, name, mapping, units, area, prov)


def _table_in_memory(data: pd.DataFrame | Mapping[str, Any]) -> tuple[_Table, str]:
    """A DataFrame or a dict of columns as a table, and the dataset's name."""
    if _is_frame(data):
        return _table_from_frame(data, "<DataFrame>"), "dataframe"
    import pandas as pd

    try:
        frame = pd.DataFrame({str(k): np.atleast_1d(v) for k, v in data.items()})
    except ValueError as exc:
        raise InputError(f"cannot build a table from the dict: {exc}") from None
    table = _table_from_frame(frame, "<dict>")
    table.si_by_default = True
    return table, "data"


def _table_on_disk(text: str) -> tuple[_Table, str]:
    """A CSV file or a packaged dataset (``NAME`` or ``packaged:NAME``), and its name."""
    path = Path(text)
    if not path.exists() and text.startswith(_PACKAGED_PREFIX):
        bare = text[len(_PACKAGED_PREFIX):]
        if bare not in _packaged_names():
            raise InputError(
                f"no packaged dataset '{bare}' (packaged: {', '.join(_packaged_names())})")
        text = bare
        path = Path(text)
    if not path.exists() and text in _packaged_names():
        raw = (datasets_dir() / f"{text}.csv").read_bytes()
        return read_table(text, source=f"{_PACKAGED_PREFIX}{text}", raw=raw), text
    return read_table(path, source=text), path.stem
