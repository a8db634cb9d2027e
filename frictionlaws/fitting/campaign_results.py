"""A campaign's results: records in blocks (one per chunk of datasets), the tidy table,
streaming to a file.

A worker of :func:`frictionlaws.fitting.campaign.fit_many` returns one :class:`Block` per chunk
of datasets.  The fits made in stacks stay in the stacks' columns
(:class:`~frictionlaws.fitting.stacked.StackedFits`): a block travels between processes
as a few arrays, not thousands of small objects, and its records are written out only
when asked for (:attr:`Block.records`).  :class:`Campaign` holds the blocks; its table
(:meth:`Campaign.to_frame`) and records come from them.
"""

from __future__ import annotations

import csv
import gc
import math
import os
from collections.abc import Iterable, Iterator, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..base import jsonio
from ..base.errors import InputError
from ..base.outputs import atomic_write, write_text_atomic
from ..base.sanitize import csv_row, frame_csv
from ..law import VARIABLES
from .stacked import notes_text

__all__ = ["Campaign", "Block", "doubts", "key_text", "group_column", "tidy_columns",
           "stream_blocks"]


def key_text(key: Mapping[str, Any]) -> str:
    """Write a group key as text, variables with their SI unit.

    Parameters
    ----------
    key : mapping
        Column -> value.

    Returns
    -------
    str
        E.g. ``surface=steel, T=293.15 K``.
    """
    parts = []
    for col, value in key.items():
        unit = VARIABLES[col].unit if col in VARIABLES else ""
        text = f"{value:g}" if isinstance(value, float) else str(value)
        parts.append(f"{col}={text}{' ' + unit if unit else ''}")
    return ", ".join(parts)


class Block:
    """The records of one chunk of a campaign's datasets, and the datasets it could not read.

    A record is its head (``dataset``, ``source``, ``group``, ``law``, ``rows``) and its
    part: a dict (``{"result": ...}`` or ``{"error": ...}``) for a fit made alone, or
    ``(table, row)`` for one made in a stack, whose numbers stay in the stack's columns
    (:class:`~frictionlaws.fitting.stacked.StackedFits`) until a record or a table row is
    asked for.  So a block is cheap to send between processes and to keep.

    Parameters
    ----------
    heads : list of tuple
        ``(dataset, source, group, law, rows)`` of each record, in order.
    parts : list
        Each record's part, as said above.
    tables : list of StackedFits
        The stacks the parts point into.
    problems : list of InputError
        Why each unreadable dataset of the chunk cannot be read (then no records).
    """

    def __init__(self, heads: list[tuple[Any, ...]] | None = None,
                 parts: list[Any] | None = None, tables: Sequence[Any] = (),
                 problems: Sequence[InputError] = ()) -> None:
        self.heads, self.parts = heads or [], parts or []
        self.tables = list(tables)
        self.problems = list(problems)

    def __len__(self) -> int:
        return len(self.heads)

    @property
    def records(self) -> list[dict[str, Any]]:
        """The records, written out."""
        out = []
        for (dataset, source, group, law, rows), part in zip(self.heads, self.parts):
            rec = {"dataset": dataset, "source": source, "group": group, "law": law,
                   "rows": rows}
            if isinstance(part, dict):
                rec.update(part)
            else:
                rec["result"] = self.tables[part[0]].at(part[1])
            out.append(rec)
        return out

    def tidy(self, by: Sequence[str]) -> Iterator[tuple[Any, ...]]:
        """The records' rows of the tidy table (:func:`tidy_columns`), in order."""
        for (dataset, _, group, law, rows), part in zip(self.heads, self.parts):
            if isinstance(part, dict):
                yield from _tidy({"dataset": dataset, "group": group, "law": law,
                                  "rows": rows, **part}, by)
            else:
                base = (dataset, *(group.get(c) for c in by), law, rows)
                yield from self.tables[part[0]].tidy(part[1], base)


    def columns(self, by: Sequence[str]) -> dict[str, Any]:
        """The records' tidy table, column by column, the stacks' rows written at once.

        A numeric column is ``(values, present)`` (floats, NaN where the cell is empty),
        any other an object array of the cells :meth:`tidy` gives.
        """
        names = tidy_columns(by)
        width = 3 + len(by)
        counts = np.array([len(self.tables[p[0]].names) if not isinstance(p, dict) else 0
                           for p in self.parts], int)
        loose = {i: list(_tidy({"dataset": h[0], "group": h[2], "law": h[3], "rows": h[4],
                                **p}, by))
                 for i, (h, p) in enumerate(zip(self.heads, self.parts)) if isinstance(p, dict)}
        for i, rows in loose.items():
            counts[i] = len(rows)
        starts = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(int)
        heads = np.empty((len(self.heads), width), object)
        heads[:] = [(h[0], *(h[2].get(c) for c in by), h[3], h[4]) for h in self.heads]
        out: dict[str, Any] = {c: np.repeat(heads[:, j], counts)
                               for j, c in enumerate(names[:width])}
        total = int(counts.sum())
        for c in names[width:]:
            out[c] = (np.full(total, np.nan), np.zeros(total, bool)) if c in NUMERIC_COLUMNS \
                else np.full(total, None, object)
        for i, rows in loose.items():
            for n, row in enumerate(rows):
                for c, cell in zip(names[width:], row[width:]):
                    _put(out[c], starts[i] + n, cell)
        for t, table in enumerate(self.tables):
            at = [(i, p[1]) for i, p in enumerate(self.parts)
                  if not isinstance(p, dict) and p[0] == t]
            if at:
                records, rows = np.array(at).T
                spots = (starts[records][:, None] + np.arange(len(table.names))).ravel()
                for c, cells in table.tidy_columns(rows).items():
                    _put(out[c], spots, cells)
        return out


#: The tidy table's columns of numbers (kept as floats until the frame is made), and
#: those of whole numbers among them.
NUMERIC_COLUMNS = frozenset({"value", "stderr", "ci95_low", "ci95_high", "r2", "rmse", "aic",
                             "bic", "n", "warnings"})
INTEGER_COLUMNS = frozenset({"n", "warnings"})


def _put(column: Any, at: Any, cells: Any) -> None:
    """Write ``cells`` at ``at`` into a column of :meth:`Block.columns` (a numeric cell of
    None stays empty)."""
    if isinstance(column, tuple):
        if cells is not None:
            column[0][at], column[1][at] = cells, True
    else:
        column[at] = cells


def _frame_column(name: str, parts: Sequence[Any]) -> list[Any] | np.ndarray:
    """One column of the frame from the blocks' parts, as pandas reads the list of its
    cells: numbers as floats (NaN for empty cells), whole numbers as integers when none is
    empty, a column of empty cells as objects."""
    if not parts:
        return []
    if not isinstance(parts[0], tuple):
        return np.concatenate(parts).tolist()
    values = np.concatenate([p[0] for p in parts])
    present = np.concatenate([p[1] for p in parts])
    if not present.any():
        return [None] * len(values)
    if name in INTEGER_COLUMNS and present.all():
        return values.astype(np.int64)
    return values


class Campaign:
    """The results of :func:`~frictionlaws.fitting.campaign.fit_many`: one plain record per
    (dataset, group, law).

    Each record has ``dataset``, ``source``, ``group`` (column -> value), ``law``,
    ``rows`` and either ``result`` (the fit's parameters, metrics, derived values,
    warnings, notes such as the rows the reader dropped, and convergence, as in
    :meth:`FitResult.to_dict`) or ``error`` (why that fit could not be made).

    Parameters
    ----------
    records : list of dict, optional
        The records held in memory (empty when they were streamed to ``path``).
    by : tuple of str
        The grouping columns.
    laws : tuple of str
        The law ids fitted.
    notes : list of str
        Remarks on the campaign as a whole.
    path : Path, optional
        The file the records were streamed to.
    count : int
        Number of records (also when streamed).
    failed : list of dict
        The failed records of a streamed campaign.
    blocks : list of Block, optional
        The records as the workers returned them (instead of ``records``).
    """

    def __init__(self, records: list[dict[str, Any]] | None = None, by: tuple[str, ...] = (),
                 laws: tuple[str, ...] = (), notes: list[str] | None = None,
                 path: Path | None = None, count: int = 0,
                 failed: list[dict[str, Any]] | None = None, *,
                 blocks: Sequence[Block] = ()) -> None:
        self._records: list[dict[str, Any]] | None = (
            list(records or []) if records is not None or not blocks else None)
        self._blocks = list(blocks)
        self.by, self.laws = tuple(by), tuple(laws)
        self.notes = list(notes or [])
        self.path, self.failed = path, list(failed or [])
        self.count = count or sum(len(b) for b in self._blocks)

    @property
    def records(self) -> list[dict[str, Any]]:
        """The records held in memory, in the campaign's order (empty when streamed)."""
        if self._records is None:
            self._records = [rec for block in self._blocks for rec in block.records]
            self._blocks = []
        return self._records

    def _tidy_rows(self) -> list[tuple[Any, ...]]:
        if self._records is None:
            return [row for block in self._blocks for row in block.tidy(self.by)]
        return [row for rec in self._records for row in _tidy(rec, self.by)]

    def __len__(self) -> int:
        return self.count if self._records is None else (len(self._records) or self.count)

    def __repr__(self) -> str:
        where = f", streamed to {self.path}" if self.path is not None else ""
        return (f"<Campaign: {len(self)} fits of {', '.join(self.laws)}"
                f"{' by ' + ', '.join(self.by) if self.by else ''}{where}>")

    @property
    def errors(self) -> list[dict[str, Any]]:
        """Records whose fit failed, with the reason."""
        return [r for r in self.records if "error" in r] or list(self.failed)

    def rows(self) -> Iterator[dict[str, Any]]:
        """Tidy rows: one per (dataset, group, law, parameter), metrics repeated."""
        columns = tidy_columns(self.by)
        for row in self._tidy_rows():
            yield dict(zip(columns, row))

    def to_frame(self) -> Any:
        """The tidy rows as a :class:`pandas.DataFrame` (units in the ``unit`` column).

        For a campaign streamed to a CSV file (``fit_many(..., output=...)``) the
        frame is read back from that file.
        """
        import pandas as pd

        if self.path is not None and self._records == []:
            if self.path.suffix.lower() == ".csv":
                return pd.read_csv(self.path, keep_default_na=False, na_values=[""])
            raise InputError("a campaign streamed to JSON Lines is read with "
                             "pandas.read_json(path, lines=True)", file=str(self.path))
        columns = tidy_columns(self.by)
        if self._records is None:  # the blocks' columns at once
            parts = [block.columns(self.by) for block in self._blocks]
            frame = pd.DataFrame({c: _frame_column(c, [p[c] for p in parts])
                                  for c in columns}, columns=columns)
        else:
            frame = pd.DataFrame(self._tidy_rows(), columns=columns)
        for col in frame.columns:
            if frame[col].dtype == object:  # None -> NaN, as read back from a CSV
                frame[col] = frame[col].where(frame[col].notna(), np.nan)
        return frame

    def to_dict(self) -> dict[str, Any]:
        """JSON-able: the records, the grouping columns, laws and notes."""
        return {"by": list(self.by), "laws": list(self.laws), "records": self.records,
                "notes": list(self.notes)}

    def save(self, path: str | os.PathLike[str]) -> Path:
        """Write CSV (the tidy frame) or JSON (the records), by the file's suffix, atomically."""
        target = Path(path)
        if target.suffix.lower() == ".json":
            return write_text_atomic(target, jsonio.dumps(self.to_dict()) + "\n")
        if target.suffix.lower() != ".csv":
            raise InputError("campaign results are written as .csv or .json",
                             file=str(target))
        return write_text_atomic(target, frame_csv(self.to_frame(), float_format="%.10g"))

    def summary(self) -> str:
        """One line per record: dataset, group, law, R^2, RMSE or the error."""
        lines = []
        for rec in self.records:
            group = key_text(rec["group"])
            head = f"{rec['dataset']}{' [' + group + ']' if group else ''} {rec['law']}"
            if "error" in rec:
                lines.append(f"{head}: error: {rec['error']}")
                continue
            m = rec["result"]["metrics"]
            doubt = doubts(rec["result"])
            lines.append(f"{head}: R^2 = {_fmt(m.get('r2'))}, RMSE = {_fmt(m.get('rmse'))}, "
                         f"n = {m.get('n')}{'; ' + doubt if doubt else ''}")
        return "\n".join(lines)


def doubts(result: Mapping[str, Any]) -> str:
    """A fit's doubts in words: undetermined parameters, withheld errors, warnings, and
    its notes (rows dropped, columns ignored, ...) as they are.

    Parameters
    ----------
    result : mapping
        A record's ``result`` (:meth:`FitResult.to_dict`).

    Returns
    -------
    str
        E.g. ``cannot determine a, b; 1 warning (listed in the JSON output); dropped 1
        row (row 3): empty or NaN in column 'p [MPa]'``; empty when the fit has no doubts.
    """
    parts = []
    undetermined = result.get("non_identifiable") or []
    if undetermined:
        parts.append(f"cannot determine {', '.join(undetermined)}")
    withheld = [k for k, e in (result.get("params") or {}).items()
                if not e.get("fixed") and e.get("stderr") is None and k not in undetermined]
    if withheld:
        parts.append(f"no standard error for {', '.join(withheld)}")
    n = len(result.get("warnings") or [])
    if n:
        parts.append(f"{n} warning{'s' if n > 1 else ''} (listed in the JSON output)")
    parts.extend(result.get("notes") or [])
    return "; ".join(parts)


def _fmt(x: Any) -> str:
    return "-" if x is None or (isinstance(x, float) and not math.isfinite(x)) else f"{x:.4g}"


_METRICS = ("r2", "rmse", "aic", "bic", "n")


def group_column(name: str) -> str:
    """Name the tidy table's column of grouping column ``name``.

    Parameters
    ----------
    name : str
        A grouping column.

    Returns
    -------
    str
        ``name``, followed by ``[unit]`` (SI) when it is a law variable.
    """
    unit = VARIABLES[name].unit if name in VARIABLES else ""
    return f"{name} [{unit}]" if unit else name


def tidy_columns(by: Sequence[str]) -> list[str]:
    """List the columns of a campaign's tidy table (the CSV header).

    Parameters
    ----------
    by : sequence of str
        The grouping columns.

    Returns
    -------
    list of str
        The header, grouping columns with their units.
    """
    return ["dataset", *(group_column(c) for c in by), "law", "rows", "param", "value",
            "stderr", "ci95_low", "ci95_high", "uncertainty", "unit", "fixed", "converged",
            *_METRICS,
            "warnings", "notes", "error"]


def _tidy(rec: Mapping[str, Any], by: Sequence[str]) -> Iterator[tuple[Any, ...]]:
    """A record's tidy rows, as tuples in the order of :func:`tidy_columns`."""
    group = rec["group"]
    base = (rec["dataset"], *(group.get(c) for c in by), rec["law"], rec.get("rows"))
    if "error" in rec:
        yield (*base, *_NO_FIT, rec["error"])
        return
    res = rec["result"]
    metrics = res["metrics"]
    tail = (res["success"], *(metrics.get(k) for k in _METRICS), len(res["warnings"]),
            notes_text(res.get("notes")), None)
    method = (res.get("uncertainty") or {}).get("method")
    for name, est in res["params"].items():
        ci = est.get("ci95") or (None, None)
        yield (*base, name, est["value"], est["stderr"], ci[0], ci[1], method,
               est["unit"] or "-", est["fixed"], *tail)


#: The cells of a failed fit's row from ``param`` to ``notes``.
_NO_FIT = (None,) * (9 + len(_METRICS) + 2)


def stream_blocks(blocks: Iterable[Block], output: Path, by: tuple[str, ...],
                  laws: tuple[str, ...]) -> Campaign:
    """Write the records of ``blocks`` as they come (CSV tidy rows or JSON Lines).

    Only the failed records are kept; the file appears only when complete (an error
    while the blocks come leaves no file).

    Parameters
    ----------
    blocks : iterable of Block
        The campaign's blocks, in order.
    output : Path
        A checked ``.csv`` or ``.jsonl`` file.
    by, laws : tuple of str
        The grouping columns and the laws.

    Returns
    -------
    Campaign
        With the file, the number of records and the failed ones.
    """
    count, failed = 0, []
    columns = tidy_columns(by)
    as_csv = output.suffix.lower() == ".csv"
    with atomic_write(output, newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=tidy_columns(by)) if as_csv else None
        if writer is not None:
            writer.writeheader()
        for block in blocks:
            count += len(block)
            errors = [i for i, part in enumerate(block.parts)
                      if isinstance(part, dict) and "error" in part]
            if errors:
                records = block.records
                failed += [records[i] for i in errors]
            if writer is not None:
                writer.writerows(csv_row(jsonio.to_jsonable(dict(zip(columns, row))))
                                 for row in block.tidy(by))
            else:
                fh.writelines(jsonio.dumps(rec, indent=None) + "\n" for rec in block.records)
            gc.collect()  # a one-fit path (lmfit) leaves reference cycles: free them
    return Campaign([], by, laws, path=output, count=count, failed=failed)
