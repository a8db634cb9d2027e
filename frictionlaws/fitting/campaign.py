"""Campaigns: many datasets, groups within them, laws fitted to each, in parallel.

A tribometer campaign has several compounds, counter-surfaces and temperatures,
repeated over weeks.  :func:`fit_many` fits one or more laws to every group
(``by=`` columns such as ``surface``) of every dataset and returns a
:class:`Campaign` of plain result records, as a tidy :class:`pandas.DataFrame`
(:meth:`Campaign.to_frame`), CSV or JSON.

The unit of work is one dataset: a worker loads it, splits it into groups, fits
every law to every group and returns plain dictionaries (never laws or lmfit
objects), so the work runs unchanged serially, on local processes
(``jobs=N``, joblib) or on a Dask cluster (``scheduler="tcp://host:8786"``,
Dask futures; needs the ``dask`` extra).  Both parallel back ends send datasets in
batches (:func:`batch_size`) with a bounded window of batches in flight.  Datasets
are loaded inside the workers, so the memory of the calling process grows with the
number of results held, not with the data (and not at all when they are streamed
to a file).
"""

from __future__ import annotations

import csv
import gc
import itertools
import math
import os
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..base import jsonio
from ..base.errors import Argument, FitError, InputError
from ..base.jsonio import to_jsonable
from ..base.outputs import atomic_write, check_outputs, write_text_atomic
from ..base.sanitize import csv_row, frame_csv
from ..io import MISSING_TOKENS, Dataset, column_for, load_dataset
from ..law import VARIABLES
from ..law.registry import get_law
from ..parallel import (
    DASK_WORKER_CONFIG,
    MAX_BATCH,
    SCHEDULER_ENV,
    batch_size,
    iter_parallel,
    run_parallel,
)
from . import fit

__all__ = ["Campaign", "doubts", "fit_many", "compare_many", "group_keys", "iter_datasets",
           "run_parallel", "group_subset",
           "iter_parallel", "batch_size", "SCHEDULER_ENV", "DASK_WORKER_CONFIG", "MAX_BATCH",
           "tidy_columns", "key_text", "fit_groups", "group_column", "check_grouping",
           "UnreadableDatasets", "NEVER_GROUPING", "MIN_ROWS_PER_GROUP"]


#: Columns that are never grouping columns: the fitted quantity and its statistics.
NEVER_GROUPING = ("mu", "mu_std", "n")
#: A grouping column must leave at least this many rows a group on average.  Every law
#: has a parameter and a fit needs more rows than parameters, so a column that splits
#: the rows into groups of one or two (a measured value, a row id) is no grouping.
MIN_ROWS_PER_GROUP = 2


class UnreadableDatasets(InputError):
    """Some datasets of a campaign cannot be read (or grouped): nothing is fitted.

    Parameters
    ----------
    problems : list of InputError
        Why each unreadable dataset cannot be read, in the campaign's order.
    total : int
        Number of datasets in the campaign.
    """

    def __init__(self, problems: Sequence[InputError], total: int) -> None:
        self.problems = list(problems)
        self.total = total
        super().__init__(f"{len(self.problems)} of {total} datasets of the campaign cannot "
                         "be read or grouped, so nothing was fitted: "
                         + "; ".join(str(p) for p in self.problems))

    def summary(self) -> str:
        """One line that sums the problems up (a front end lists each one before it).

        Returns
        -------
        str
            E.g. ``1 of 2 datasets of the campaign cannot be read or grouped; ...``.
        """
        return (f"{len(self.problems)} of {self.total} datasets of the campaign cannot be "
                "read or grouped; nothing was fitted (fix or remove each file named)")


def check_grouping(by: Sequence[str], laws: Sequence[str] = ()) -> tuple[str, ...]:
    """Check grouping column names before any data are read.

    A grouping column groups rows under a test condition (``surface``, or a variable
    the laws fitted do not use, such as ``T`` for an isothermal law).  The fitted
    quantity and its statistics (:data:`NEVER_GROUPING`) and the variables a law uses
    are measured quantities: grouping by them leaves nothing for the law to fit.

    Parameters
    ----------
    by : sequence of str
        The grouping columns.
    laws : sequence of str
        The laws to be fitted to each group (ids or aliases); none: only the
        quantities that are never grouping columns are refused.

    Returns
    -------
    tuple of str
        The columns, unchanged.

    Raises
    ------
    InputError
        A column given twice, empty, or naming a measured quantity.
    """
    columns = (by,) if isinstance(by, str) else tuple(by)
    used = {v: get_law(law).id for law in laws for v in get_law(law).variables}
    seen: set[str] = set()
    for col in columns:
        if not isinstance(col, str) or not col.strip():
            raise InputError(f"a grouping column must be a column name, got {col!r}",
                             option="by")
        if col in seen:
            raise InputError(f"'{col}' is given twice", option="by")
        seen.add(col)
        if col in NEVER_GROUPING or col in used:
            why = (f"law '{used[col]}' is fitted on it" if col in used
                   else "it is the fitted quantity or its statistics")
            raise InputError(f"must name a grouping column such as surface, not a measured "
                             f"quantity ('{col}': {why})", option="by")
    return columns


# ------------------------------------------------------------------ inputs
def iter_datasets(sources: Any) -> list[Any]:
    """Expand dataset sources into the items :func:`frictionlaws.io.load_dataset` reads.

    Parameters
    ----------
    sources : str, path, Dataset or a sequence of them
        Packaged names, files, directories or datasets.  A directory stands for its
        ``*.csv`` files, sorted by name.

    Returns
    -------
    list
        One item per dataset, in order.

    Raises
    ------
    InputError
        When nothing is given or a directory holds no ``*.csv`` file (naming it).
    """
    if isinstance(sources, (str, os.PathLike)) or not isinstance(sources, Iterable):
        sources = [sources]
    out: list[Any] = []
    for item in sources:
        if isinstance(item, (str, os.PathLike)) and Path(item).is_dir():
            files = sorted(Path(item).glob("*.csv"))
            if not files:
                raise InputError("the directory holds no *.csv dataset", file=str(item))
            out.extend(files)
        else:
            out.append(item)
    if not out:
        raise InputError("no datasets given")
    return out


def group_keys(dataset: Any, by: Sequence[str]) -> list[tuple[dict[str, Any], np.ndarray]]:
    """Split ``dataset`` into the groups of the columns ``by``.

    Parameters
    ----------
    dataset : Dataset
        A loaded dataset.
    by : sequence of str
        The grouping columns; none gives one group of all rows.

    Returns
    -------
    list of (dict, numpy.ndarray)
        Each group's key (column -> value) and boolean row mask, in the order the
        groups first appear.

    Raises
    ------
    InputError
        When a grouping column is the fitted quantity or its statistics
        (:data:`NEVER_GROUPING`), is not in the dataset (naming the columns it has), or
        leaves fewer than :data:`MIN_ROWS_PER_GROUP` rows a group on average.
    """
    frame = dataset.frame
    if not by:
        return [({}, np.ones(len(frame), dtype=bool))]
    check_grouping(by)
    missing = [c for c in by if c not in frame.columns]
    if missing:
        _refuse_missing_group_column(dataset, missing[0])
    for col in by:
        count = int(frame[col].astype(str).nunique())
        if count > 1 and len(frame) < MIN_ROWS_PER_GROUP * count:
            raise InputError(f"column '{col}' splits the {len(frame)} rows into {count} groups "
                             f"(fewer than {MIN_ROWS_PER_GROUP} rows a group on average): it "
                             "must name a grouping column such as surface, not a measured "
                             "quantity", file=str(dataset.source), option="by")
    _refuse_empty_keys(dataset, by)
    keys = frame[list(by)].astype(str).agg("\x1f".join, axis=1).to_numpy()
    groups = []
    for key in dict.fromkeys(keys.tolist()):
        mask = keys == key
        first = int(np.flatnonzero(mask)[0])
        groups.append(({c: _plain(frame[c].iloc[first]) for c in by}, mask))
    return groups


def _refuse_empty_keys(dataset: Any, by: Sequence[str]) -> None:
    """Refuse rows whose grouping cell is empty, naming the file, column and rows.

    Empty means any of :data:`frictionlaws.io.MISSING_TOKENS` (``""``, ``nan``, ``-``...),
    or a row the loader dropped for an empty value in that column.

    An empty cell is no group: fitting its rows as a group of their own (or with
    another) would give a result that belongs to no condition.
    """
    frame = dataset.frame
    for col in by:
        lost = (getattr(dataset, "dropped", None) or {}).get(col)
        if lost:  # the loader dropped them (a variable column): refused all the same
            raise InputError(f"{len(lost)} row(s) have no value of the grouping column "
                             f"'{col}' (rows {', '.join(lost[:8])}"
                             f"{f' and {len(lost) - 8} more' if len(lost) > 8 else ''}): "
                             "fill them in or remove them", file=str(dataset.source),
                             column=col, option="by")
        cells = frame[col]
        text = cells.astype(str).str.strip().str.lower()
        empty = cells.isna().to_numpy() | text.isin(MISSING_TOKENS).to_numpy()
        if empty.any():
            idx = np.flatnonzero(empty)
            rows = getattr(dataset, "rows", None)
            labels = [str(rows[i]) if rows is not None else str(i + 1) for i in idx[:8]]
            more = f" and {idx.size - 8} more" if idx.size > 8 else ""
            raise InputError(f"{idx.size} row(s) have no value of the grouping column "
                             f"'{col}' (rows {', '.join(labels)}{more}): fill them in or "
                             "remove them", file=str(dataset.source), column=col,
                             option="by")


def fit_groups(law: str, data: Any, by: Sequence[str], *,
               load_options: Mapping[str, Any] | None = None,
               **fit_options: Any) -> list[tuple[dict[str, Any], Any]]:
    """Fit ``law`` to each group of one dataset, keeping the full fit results.

    Parameters
    ----------
    law : str
        Law id or alias.
    data : str, path or Dataset
        One dataset (file, packaged name or :class:`~frictionlaws.io.Dataset`).
    by : sequence of str
        The grouping columns (e.g. ``["surface"]``).
    load_options : mapping, optional
        ``mapping``, ``units``, ``area`` for :func:`frictionlaws.io.load_dataset`.
    **fit_options
        Passed to :func:`frictionlaws.fitting.fit` for every group.

    Returns
    -------
    list of (dict, FitResult)
        The group key (column -> value) and its fit, in the order the groups
        first appear in the data.
    """
    check_grouping(by, [law])
    dataset = data if isinstance(data, Dataset) else load_dataset(data, **(load_options or {}))
    out = []
    for key, mask in group_keys(dataset, list(by)):
        out.append((key, fit(law, group_subset(dataset, key, mask), **fit_options)))
    return out


def group_subset(dataset: Any, key: Mapping[str, Any], mask: np.ndarray) -> Any:
    """The rows of one group, named by it, so every message names the group.

    Parameters
    ----------
    dataset : Dataset
        The whole dataset.
    key : mapping
        The group's key (column -> value); empty for all rows.
    mask : numpy.ndarray
        The group's rows.

    Returns
    -------
    Dataset
        ``dataset`` itself when the group is every row and has no key, else its
        subset named ``NAME [KEY]`` (e.g. ``campaign [surface=steel]``).
    """
    if not key and mask.all():
        return dataset
    subset = dataset.subset(mask)
    subset.name = f"{dataset.name} [{key_text(key)}]"
    return subset


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


def _plain(x: Any) -> Any:
    if isinstance(x, (np.floating, float)):
        return float(x)
    if isinstance(x, (np.integer, int)):
        return int(x)
    return str(x)


# ------------------------------------------------------------------ work
@dataclass(frozen=True)
class _Job:
    """One dataset's work: plain, picklable data only."""

    source: Any
    laws: tuple[str, ...]
    by: tuple[str, ...]
    fit_options: Mapping[str, Any]
    load_options: Mapping[str, Any]
    #: The dataset's name in the tables (unique in the campaign); None: its own name.
    label: str | None = None
    #: How to show the source in records and messages (None: its path).
    shown: str | None = None


def dataset_labels(sources: Sequence[Any]) -> list[str | None]:
    """A unique name per dataset of a campaign, or None where its own name is unique.

    Files are named by their stem (``runs.csv`` -> ``runs``) as :func:`load_dataset`
    names them; where two stems are the same (``a/data.csv``, ``b/data.csv``) those
    files are named by their path as given, so the tables can tell them apart.  The
    same file given twice is refused.

    Parameters
    ----------
    sources : sequence
        The items of :func:`iter_datasets`.

    Returns
    -------
    list of str or None
        One entry per source.

    Raises
    ------
    InputError
        When one file is given twice.
    """
    seen: dict[str, int] = {}
    for i, src in enumerate(sources):
        if isinstance(src, (str, os.PathLike)) and Path(src).is_file():
            key = str(Path(src).resolve())
            if key in seen:
                raise InputError(f"the same file is given twice (datasets {seen[key] + 1} and "
                                 f"{i + 1}); give each dataset once", file=str(src))
            seen[key] = i
    names = [_own_name(src) for src in sources]
    labels: list[str | None] = []
    for i, (src, name) in enumerate(zip(sources, names)):
        if names.count(name) == 1:
            labels.append(None)
        elif isinstance(src, (str, os.PathLike)):
            labels.append(os.fspath(src))
        else:  # data in memory: named by their place in the campaign
            labels.append(f"{name} #{i + 1}")
    named = [lab for lab in labels if lab is not None]
    if len(set(named)) < len(named):
        raise InputError("two datasets have the same name; give them distinct paths")
    return labels


def _own_name(source: Any) -> str:
    """The name :func:`~frictionlaws.io.load_dataset` gives a source, without loading it."""
    if isinstance(source, (str, os.PathLike)):
        return Path(source).stem if Path(source).is_file() else os.fspath(source)
    if isinstance(source, Dataset):
        return str(source.name)
    return "data" if isinstance(source, Mapping) else "dataframe"


def _read_problem(job: _Job) -> InputError | None:
    """Load one dataset and split it into groups: None, or why that cannot be done.

    The error is rebuilt as a plain :class:`InputError` (message parts and location),
    so that it travels between processes whatever its class.
    """
    try:
        group_keys(load_dataset(job.source, **job.load_options), job.by)
    except InputError as exc:
        return InputError(exc.parts, file=exc.file, column=exc.column, row=exc.row,
                          option=exc.option)
    return None


def _refuse_unreadable(work: Sequence[_Job], **parallel: Any) -> None:
    """Read every dataset of a campaign before any fit; refuse it naming each bad one.

    A campaign half done is worse than none: the fits of the readable datasets would
    look complete.  So every dataset is read (and grouped) first, in parallel as the
    fits are, and an :class:`UnreadableDatasets` lists all that cannot be.
    """
    problems = [p for p in iter_parallel(_read_problem, work, total=len(work), **parallel)
                if p is not None]
    if len(work) == 1 and problems:
        raise problems[0]  # one dataset: its own error says it all
    if problems:
        raise UnreadableDatasets(problems, len(work))


def _fit_dataset(job: _Job) -> list[dict[str, Any]]:
    """Load one dataset, split it into groups, fit every law to every group."""
    try:
        ds = load_dataset(job.source, **job.load_options)
        groups = group_keys(ds, job.by)
    except InputError as exc:  # the input itself: marked, so a front end can say so
        return [{"dataset": job.shown or str(job.source), "group": {}, "law": law,
                 "error": _shown_error(exc, job), "input_error": True} for law in job.laws]
    records = []
    for (key, mask), law in itertools.product(groups, job.laws):
        record: dict[str, Any] = {"dataset": job.label or ds.name,
                                  "source": job.shown or str(ds.source),
                                  "group": key, "law": law, "rows": int(mask.sum())}
        try:
            res = fit(law, group_subset(ds, key, mask), **job.fit_options)
        except (InputError, FitError) as exc:
            record["error"] = _shown_error(exc, job)
        else:
            record["result"] = _compact(res.to_dict())
        records.append(record)
    return records


def _shown_error(exc: Exception, job: Any) -> str:
    """An error's message with the source shown as the job names it."""
    if job.shown and isinstance(exc, InputError):
        exc.replace_text(os.fspath(job.source), job.shown)
    return str(exc)


#: What a campaign record keeps of a fit (the full result stays with single fits).
_KEEP = ("params", "metrics", "success", "warnings", "non_identifiable", "derived",
         "uncertainty")


def _compact(doc: Mapping[str, Any]) -> dict[str, Any]:
    """The parts of a fit's dict a campaign table needs, as plain JSON-able values."""
    return to_jsonable({k: doc[k] for k in _KEEP if k in doc})


# ------------------------------------------------------------------ results
@dataclass
class Campaign:
    """The results of :func:`fit_many`: one plain record per (dataset, group, law).

    Each record has ``dataset``, ``source``, ``group`` (column -> value), ``law``,
    ``rows`` and either ``result`` (the fit's parameters, metrics, derived values,
    warnings and convergence, as in :meth:`FitResult.to_dict`) or ``error`` (why that
    fit could not be made).

    Parameters
    ----------
    records : list of dict
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
    """

    records: list[dict[str, Any]]
    by: tuple[str, ...] = ()
    laws: tuple[str, ...] = ()
    notes: list[str] = field(default_factory=list)
    path: Path | None = None
    count: int = 0
    failed: list[dict[str, Any]] = field(default_factory=list)

    def __len__(self) -> int:
        return len(self.records) or self.count

    @property
    def errors(self) -> list[dict[str, Any]]:
        """Records whose fit failed, with the reason."""
        return [r for r in self.records if "error" in r] or list(self.failed)

    def rows(self) -> Iterator[dict[str, Any]]:
        """Tidy rows: one per (dataset, group, law, parameter), metrics repeated."""
        for rec in self.records:
            yield from _tidy(rec, self.by)

    def to_frame(self) -> Any:
        """The tidy rows as a :class:`pandas.DataFrame` (units in the ``unit`` column).

        For a campaign streamed to a CSV file (``fit_many(..., output=...)``) the
        frame is read back from that file.
        """
        import pandas as pd

        if self.path is not None and not self.records:
            if self.path.suffix.lower() == ".csv":
                return pd.read_csv(self.path, keep_default_na=False, na_values=[""])
            raise InputError("a campaign streamed to JSON Lines is read with "
                             "pandas.read_json(path, lines=True)", file=str(self.path))
        frame = pd.DataFrame(list(self.rows()), columns=tidy_columns(self.by))
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
    """A fit's doubts in words: undetermined parameters, withheld errors, warnings.

    Parameters
    ----------
    result : mapping
        A record's ``result`` (:meth:`FitResult.to_dict`).

    Returns
    -------
    str
        E.g. ``cannot determine a, b; 1 warning (listed in the JSON output)``; empty when
        the fit has no doubts.
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
    return "; ".join(parts)


def _fmt(x: Any) -> str:
    return "-" if x is None or (isinstance(x, float) and not math.isfinite(x)) else f"{x:.4g}"


_METRICS = ("r2", "rmse", "aic", "bic", "n")
#: Datasets between two garbage collections while streaming (keeps memory flat).
_GC_EVERY = 50


def _refuse_missing_group_column(dataset: Any, col: str) -> None:
    """Name why a ``by`` column is not there: read under its dataset name, or not read."""
    columns = ", ".join(map(str, dataset.frame.columns))
    canon = column_for(col)
    if canon is not None and canon != col and canon in dataset.frame.columns:
        raise InputError(f"no column {col} to group by: a column '{col}' is read as the "
                         f"dataset column '{canon}'; group by {canon} (columns read: "
                         f"{columns})", file=str(dataset.source), option="by")
    raise InputError([f"no column {col} to group by (columns read: {columns}); a column "
                      f"of the file outside the dataset columns is not read: to group by it, "
                      "map it to surface or condition_id, e.g. ",
                      Argument("mapping", f"surface={col}")],
                     file=str(dataset.source), option="by")


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
            "warnings", "error"]


def _tidy(rec: Mapping[str, Any], by: Sequence[str]) -> Iterator[dict[str, Any]]:
    base = {"dataset": rec["dataset"], **{group_column(c): rec["group"].get(c) for c in by},
            "law": rec["law"], "rows": rec.get("rows")}
    if "error" in rec:
        yield {**base, "error": rec["error"]}
        return
    res = rec["result"]
    metrics = {k: res["metrics"].get(k) for k in _METRICS}
    for name, est in res["params"].items():
        ci = est.get("ci95") or (None, None)
        yield {**base, "param": name, "value": est["value"], "stderr": est["stderr"],
               "ci95_low": ci[0], "ci95_high": ci[1],
               "uncertainty": (res.get("uncertainty") or {}).get("method"),
               "unit": est["unit"] or "-",
               "fixed": est["fixed"], "converged": res["success"], **metrics,
               "warnings": len(res["warnings"]), "error": None}


def _stream(parts: Iterable[list[dict[str, Any]]], output: Path, by: tuple[str, ...],
            laws: tuple[str, ...]) -> Campaign:
    """Write records as they come (CSV tidy rows or JSON Lines); keep only the failures."""
    count, failed = 0, []
    as_csv = output.suffix.lower() == ".csv"
    with atomic_write(output, newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=tidy_columns(by)) if as_csv else None
        if writer is not None:
            writer.writeheader()
        for i, part in enumerate(parts, 1):
            if i % _GC_EVERY == 0:
                gc.collect()  # lmfit leaves reference cycles: free them as we go
            for rec in part:
                count += 1
                if "error" in rec:
                    failed.append(rec)
                if writer is not None:
                    writer.writerows(csv_row(jsonio.to_jsonable(row)) for row in _tidy(rec, by))
                else:
                    fh.write(jsonio.dumps(rec, indent=None) + "\n")
    return Campaign([], by, laws, path=output, count=count, failed=failed)


def fit_many(laws: str | Sequence[str], datasets: Any, *, by: str | Sequence[str] = (),
             jobs: int = 1, scheduler: str | None = None, progress: bool = False,
             output: str | os.PathLike[str] | None = None,
             load_options: Mapping[str, Any] | None = None,
             source_names: Mapping[str, str] | None = None, **fit_options: Any) -> Campaign:
    """Fit each law to each group of each dataset.

    Parameters
    ----------
    laws : str or sequence of str
        Law ids (or aliases).
    datasets : name, path, directory, Dataset or a sequence of them
        See :func:`iter_datasets`.
    by : str or sequence of str
        Grouping columns (e.g. ``"surface"``); each group is fitted on its own.
    jobs : int
        Local worker processes (1: serial; -1: one per core); see :func:`iter_parallel`.
    scheduler : str, optional
        A Dask scheduler address; see :func:`iter_parallel`.
    progress : bool
        Show a progress bar on stderr.
    output : path, optional
        Stream the results to this ``.csv`` (tidy rows) or ``.jsonl`` (one record a
        line) file as they are done, instead of holding them: the memory then stays
        flat however many datasets there are.  The file is checked before any work
        (it may not be an input) and appears only when complete.
    load_options : mapping, optional
        ``mapping``, ``units``, ``area`` for :func:`frictionlaws.io.load_dataset`.
    source_names : mapping, optional
        Path -> the name to show for it (a front end's private copy of standard input:
        ``{"/tmp/.../stdin.csv": "<stdin>"}``), in the records' ``source`` and messages.
    **fit_options
        Passed to :func:`frictionlaws.fit` (``fix``, ``weights``, ``seed``...).

    Returns
    -------
    Campaign
        The records (or, when streamed, their count, failures and file).

    Raises
    ------
    UnreadableDatasets
        When any dataset cannot be read or grouped: every dataset is read before
        the first fit, and all that cannot be are named (nothing is fitted).
    InputError
        A grouping column that is a measured quantity (:func:`check_grouping`), no
        law, or an output that cannot be written.
    """
    law_ids = tuple(get_law(law).id for law in ([laws] if isinstance(laws, str) else laws))
    if not law_ids:
        raise InputError("no law given")
    columns = check_grouping(by, law_ids)
    sources = iter_datasets(datasets)
    target = _check_output(output, sources)
    names = dict(source_names or {})
    jobs_ = [_Job(src, law_ids, columns, dict(fit_options), dict(load_options or {}), label,
                  names.get(os.fspath(src)) if isinstance(src, (str, os.PathLike)) else None)
             for src, label in zip(sources, dataset_labels(sources))]
    _refuse_unreadable(jobs_, jobs=jobs, scheduler=scheduler)
    parts = iter_parallel(_fit_dataset, jobs_, jobs=jobs, scheduler=scheduler,
                          progress=progress, total=len(sources))
    if target is not None:
        return _stream(parts, target, columns, law_ids)
    records = [rec for part in parts for rec in part]
    return Campaign(records, columns, law_ids, count=len(records))


def _check_output(output: Any, sources: Sequence[Any]) -> Path | None:
    if output is None:
        return None

    target = Path(output)
    if target.suffix.lower() not in (".csv", ".jsonl"):
        raise InputError("streamed campaign results are written as .csv or .jsonl",
                         file=str(target))
    check_outputs([target], inputs=[s for s in sources if isinstance(s, (str, os.PathLike))])
    return target


@dataclass(frozen=True)
class _CompareJob:
    source: Any
    laws: tuple[str, ...] | None
    by: tuple[str, ...]
    options: Mapping[str, Any]
    load_options: Mapping[str, Any]
    label: str | None = None
    shown: str | None = None


def _compare_dataset(job: _CompareJob) -> list[dict[str, Any]]:
    """Load one dataset and compare the laws on each of its groups (plain records)."""
    from ..comparison import compare  # the comparisons: not on the path of a plain fit

    try:
        ds = load_dataset(job.source, **job.load_options)
        groups = group_keys(ds, job.by)
    except InputError as exc:
        return [{"dataset": job.shown or str(job.source), "group": {},
                 "error": _shown_error(exc, job), "input_error": True}]
    out = []
    for key, mask in groups:
        record: dict[str, Any] = {"dataset": job.label or ds.name, "group": key,
                                  "rows": int(mask.sum())}
        try:
            cmp = compare(list(job.laws) if job.laws else None,
                          group_subset(ds, key, mask), **job.options)
        except (InputError, FitError) as exc:
            record["error"] = _shown_error(exc, job)
        else:
            record["ranking"] = cmp.to_frame().to_dict("records")
        out.append(record)
    return out


def compare_many(datasets: Any, laws: Sequence[str] | None = None, *,
                 by: str | Sequence[str] = (), jobs: int = 1, scheduler: str | None = None,
                 progress: bool = False, load_options: Mapping[str, Any] | None = None,
                 source_names: Mapping[str, str] | None = None,
                 **compare_options: Any) -> Any:
    """Compare laws on each group of each dataset.

    Parameters
    ----------
    datasets : name, path, directory, Dataset or a sequence of them
        See :func:`iter_datasets`.
    laws : sequence of str, optional
        Law ids; default: those :func:`frictionlaws.compare` chooses.
    by : str or sequence of str
        Grouping columns; each group is compared on its own.
    jobs : int
        Local worker processes; see :func:`iter_parallel`.
    scheduler : str, optional
        A Dask scheduler address; see :func:`iter_parallel`.
    progress : bool
        Show a progress bar on stderr.
    load_options : mapping, optional
        ``mapping``, ``units``, ``area`` for :func:`frictionlaws.io.load_dataset`.
    source_names : mapping, optional
        Path -> the name to show for it in messages (see :func:`fit_many`).
    **compare_options
        Passed to :func:`frictionlaws.compare` (``folds``, ``seed``...).

    Returns
    -------
    pandas.DataFrame
        One row per (dataset, group, law) with the ranking metrics of
        :meth:`frictionlaws.comparison.Comparison.to_frame`, plus ``error`` for a
        dataset or group that could not be compared.
    """
    import pandas as pd

    columns = check_grouping(by, tuple(laws) if laws else ())
    sources = iter_datasets(datasets)
    names = dict(source_names or {})
    work = (_CompareJob(src, tuple(laws) if laws else None, columns, dict(compare_options),
                        dict(load_options or {}), label,
                        names.get(os.fspath(src)) if isinstance(src, (str, os.PathLike))
                        else None)
            for src, label in zip(sources, dataset_labels(sources)))
    rows = []
    unreadable: list[str] = []
    for part in iter_parallel(_compare_dataset, work, jobs=jobs, scheduler=scheduler,
                              progress=progress, total=len(sources)):
        unreadable += [rec["error"] for rec in part if rec.get("input_error")]
        for rec in part:
            base = {"dataset": rec["dataset"],
                    **{group_column(c): rec["group"].get(c) for c in columns}}
            if "error" in rec:
                rows.append({**base, "error": rec["error"]})
                continue
            rows.extend({**base, **row, "error": None} for row in rec["ranking"])
    if unreadable and len(unreadable) == len(sources):  # bad input, not failed comparisons
        raise InputError(unreadable[0] if len(sources) == 1 else
                         f"none of the {len(sources)} datasets could be read; first: "
                         f"{unreadable[0]}")
    return pd.DataFrame(rows)
