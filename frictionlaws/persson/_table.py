"""Read named numeric columns with units from a CSV file (via :mod:`frictionlaws.io`)."""

from __future__ import annotations

import math
import os
from collections.abc import Mapping

import numpy as np

from ..base.errors import InputError
from ..base.units import to_si
from ..io import read_table, split_header, to_float

__all__ = ["read_columns"]


def read_columns(path: str | os.PathLike[str], wanted: Mapping[str, tuple[str, str]],
                 units: Mapping[str, str] | None = None) -> dict[str, np.ndarray]:
    """Columns of a CSV file converted to SI.

    Parameters
    ----------
    path : path-like
        The CSV file (delimiter, decimal comma, BOM and ``#`` comments are
        handled by :mod:`frictionlaws.io`).
    wanted : mapping
        Output name -> (column name in the file, quantity kind of
        :data:`frictionlaws.base.units.QUANTITIES`).  The unit comes from the
        header (``E_stor [MPa]``) or from ``units``.
    units : mapping, optional
        Column name -> unit, for headers without one.

    Raises
    ------
    InputError
        A missing column, a missing unit, a non-numeric or missing cell
        (naming the file, column and row).
    """
    table = read_table(path)
    src = table.source
    names = [split_header(h) for h in table.headers]
    units = dict(units or {})
    out: dict[str, np.ndarray] = {}
    for key, (column, kind) in wanted.items():
        hits = [j for j, (nm, _) in enumerate(names) if nm.lower() == column.lower()]
        if len(hits) != 1:
            raise InputError(f"expected one column '{column}' ({kind}); found "
                             f"{len(hits)} (columns: {', '.join(table.headers)})", file=src,
                             column=column)
        j = hits[0]
        unit = names[j][1] if names[j][1] is not None else units.get(column)
        if unit is None:
            raise InputError(f"no unit for column '{column}': write it in the header, e.g. "
                             f"'{column} [unit]'", file=src, column=column)
        values = []
        for i, cell in enumerate(table.columns[j]):
            x = to_float(cell, table.decimal_comma)
            if x is None or math.isnan(x) or not math.isfinite(x):
                raise InputError(f"expected a finite number, got {cell!r}", file=src,
                                 column=column, row=table.rows[i])
            values.append(x)
        out[key] = to_si(np.array(values), unit, kind, column=column, file=src)
    return out
