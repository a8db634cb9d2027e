"""From a read table to a :class:`~frictionlaws.io.dataset.Dataset`: columns assigned, numbers
parsed, units converted to SI, rows checked, with the file, column and row of anything refused.
"""

from __future__ import annotations

import math
import re
import sys
from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Any, TypeGuard

import numpy as np

from ..base import units as _units
from ..base.errors import Argument, InputError
from ..base.sanitize import csv_cell_text

if TYPE_CHECKING:  # pandas is imported where a DataFrame is made or asked for
    import pandas as pd

from ..base.numbers import parse_number, parse_numbers
from .columns import (
    _DIMENSIONLESS,
    CANONICAL,
    MISSING_TOKENS,
    TEXT_COLUMNS,
    canonical_name,
    column_for,
    parse_mapping,
)
from .reading import _DELIMITER_NAMES, _DELIMITERS, Table, split_header

__all__ = ["to_float", "column_numbers"]


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


def to_float(cell: Any, decimal_comma: bool) -> float | None:
    """The number in a cell: the one reading of a cell the tables of every room share.

    Parameters
    ----------
    cell : object
        A cell as read (text) or given (a number).
    decimal_comma : bool
        True when the file writes decimal commas (``1,5`` is 1.5).

    Returns
    -------
    float or None
        The number, ``nan`` for a missing value (:data:`~frictionlaws.io.MISSING_TOKENS`),
        ``inf`` for a written infinity (refused by the callers, with its row), None when
        the cell is not a number (:func:`frictionlaws.base.numbers.parse_number` decides).
    """
    if cell is None or (not isinstance(cell, str) and _is_missing(cell)):
        return math.nan
    if isinstance(cell, (bool, np.bool_)):
        return None
    if isinstance(cell, (int, float, np.integer, np.floating)):
        return float(cell)
    text = str(cell).strip()
    if text.lower() in MISSING_TOKENS:
        return math.nan

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


def _row_label(table: Table, i: int) -> int | None:
    return table.rows[i] if table.from_file else None


def _where(table: Table, i: int) -> str:
    return "" if table.from_file else f" (DataFrame row position {i})"


def _check_headers(table: Table) -> None:
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


def _assign_columns(table: Table, names: list[str], mapping: Mapping[str, str] | None,
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
        found = column_for(nm)
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


def _no_mu(table: Table) -> None:
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


def _extra_units(table: Table, names: list[str], assigned: Mapping[str, int],
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


def _column_units(table: Table, names: list[str], assigned: Mapping[str, int],
                  units: Mapping[str, str] | None) -> dict[str, str]:
    """The checked unit of every assigned column (header or ``units``, given once)."""
    src, headers = table.source, table.headers
    extra = _extra_units(table, names, assigned, units)
    unit_of: dict[str, str] = {}
    for canon, j in assigned.items():
        header_unit = split_header(headers[j])[1]
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


def _not_a_number(table: Table, cell: Any, i: int, column: str) -> InputError:
    text = str(cell).strip()
    if _overflows(text):
        return InputError(f"value '{_shown(text)}'{_where(table, i)} overflows a double "
                          "(beyond 1.8e308): not a measured value", file=table.source,
                          column=column, row=_row_label(table, i))
    others = [_DELIMITER_NAMES[d] for d in _DELIMITERS if d in text and d != table.delimiter]
    hint = (f" (it contains {others[0]}: does this row use another delimiter "
            f"than the header's {_DELIMITER_NAMES.get(table.delimiter or '')}?)"
            if others and table.delimiter else "")
    if table.delimiter == "," and re.fullmatch(r"[-+]?[0-9]+,[0-9]+", text):
        hint = " (a decimal comma needs ';' or tab as the delimiter)"
    return InputError(
        f"non-numeric value '{_shown(text)}'{_where(table, i)}; expected "
        f"a number{' (decimal comma or point)' if table.decimal_comma else ''} "
        f"or an empty cell{hint}",
        file=table.source, column=column, row=_row_label(table, i),
    )


_THOUSANDS = re.compile(r"[-+]?[0-9]{1,3}(\.[0-9]{3})+")


_COMMA_DECIMAL = re.compile(r"[0-9],[0-9]")


def _uses_decimal_commas(table: Table) -> bool:
    """True when the file writes decimal commas somewhere (not only its delimiter)."""
    return table.decimal_comma and any(
        isinstance(c, str) and _COMMA_DECIMAL.search(c) for col in table.columns for c in col)


def column_numbers(table: Table, j: int, commas: bool = False) -> np.ndarray:
    """The numbers of column ``j`` of a table (NaN where empty); text and infinities refused.

    Parameters
    ----------
    table : Table
        The table read.
    j : int
        The column's index.
    commas : bool
        True when the file writes decimal commas: ``1.200`` is then ambiguous (a thousands
        separator or a decimal point) and refused.

    Returns
    -------
    numpy.ndarray
        One float per data row.

    Raises
    ------
    InputError
        A cell that is not a number, is not finite or is ambiguous, naming the file, the
        column and the row.
    """
    col = table.headers[j]
    if table.from_file:  # every cell a plain number or empty: the column at once
        fast = parse_numbers(table.columns[j], decimal_comma=commas)
        if fast is not None:
            return fast
    out = np.empty(len(table.rows))
    for i, cell in enumerate(table.columns[j]):
        if commas and isinstance(cell, str) and _THOUSANDS.fullmatch(cell.strip()):
            raise InputError(
                f"value '{cell.strip()}'{_where(table, i)} is ambiguous in a file with "
                f"decimal commas: a thousands separator ({cell.strip().replace('.', '')}) "
                f"or a decimal point ({cell.strip().replace('.', ',')})? Write it without "
                "the point, or with a decimal comma", file=table.source, column=col,
                row=_row_label(table, i))
        x = to_float(cell, table.decimal_comma)
        if x is None:
            raise _not_a_number(table, cell, i, col)
        if math.isinf(x):
            raise InputError(f"value '{cell}' is not finite{_where(table, i)}",
                             file=table.source, column=col, row=_row_label(table, i))
        out[i] = x
    return out


def _numbers(table: Table, assigned: Mapping[str, int], explicit: set[str],
             unit_of: dict[str, str], notes: list[str]) -> dict[str, np.ndarray]:
    """Numeric columns as written; an empty optional column is ignored with a note."""
    values: dict[str, np.ndarray] = {}
    commas = _uses_decimal_commas(table)
    for canon in [c for c in CANONICAL if c in assigned and c not in TEXT_COLUMNS]:
        col = table.headers[assigned[canon]]
        out = column_numbers(table, assigned[canon], commas)
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


def _first_bad(table: Table, j: int, mask: np.ndarray, message: str) -> None:
    """Raise naming the first of the rows where ``mask`` is True, if any."""
    if mask.any():
        bad = np.flatnonzero(mask)
        i = int(bad[0])
        raise InputError(message.format(cell=table.columns[j][i], where=_where(table, i),
                                        more=f" ({bad.size} such rows)" if bad.size > 1
                                        else ""),
                         file=table.source, column=table.headers[j],
                         row=_row_label(table, i))


def _to_si_checked(table: Table, assigned: Mapping[str, int],
                   values: Mapping[str, np.ndarray], unit_of: Mapping[str, str],
                   notes: list[str]) -> dict[str, np.ndarray]:
    """Physical checks, then SI conversion (overflow and absolute zero refused)."""
    si: dict[str, np.ndarray] = {}
    for canon, arr in values.items():
        j, unit = assigned[canon], unit_of[canon]
        if canon in _PHYSICAL:
            bad_fn, msg = _PHYSICAL[canon]
            with np.errstate(invalid="ignore"):
                bad = bad_fn(arr) & ~np.isnan(arr)
            _first_bad(table, j, bad, "value {cell}{where} is not allowed: " + msg + "{more}")
        si[canon] = _units.to_si(arr, unit, canon, column=table.headers[j], file=table.source)
        _first_bad(table, j, np.isinf(si[canon]),
                   "value {cell} " + unit + "{where} overflows when converted to SI: "
                   "not a measured value")
        note = _units.conversion_note(unit, canon, column=table.headers[j])
        if note:
            notes.append(note)
        if canon == "T":
            with np.errstate(invalid="ignore"):
                bad = si[canon] < 0
            _first_bad(table, j, bad, "temperature {cell} " + unit + "{where} is below "
                       "absolute zero (is the unit right?)")
    return si


def _rows_to_keep(table: Table, assigned: Mapping[str, int],
                  si: Mapping[str, np.ndarray], notes: list[str],
                  dropped: dict[str, list[str]]) -> np.ndarray:
    """Rows without a missing value; every dropped row is named in a note.

    ``dropped`` receives, per canonical column, the labels of the rows dropped for it.
    """
    keep = np.ones(len(table.rows), dtype=bool)
    for canon in [c for c in CANONICAL if c in si]:
        missing = np.isnan(si[canon])
        if not missing.any():
            continue
        nan_rows = np.flatnonzero(missing & keep)
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


def _kept_columns(table: Table, assigned: Mapping[str, int], si: Mapping[str, np.ndarray],
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

