"""Campaigns: many datasets, groups within them, laws fitted to each, in parallel.

A tribometer campaign has several compounds, counter-surfaces and temperatures,
repeated over weeks.  :func:`fit_many` fits one or more laws to every group
(``by=`` columns such as ``surface``) of every dataset and returns a
:class:`Campaign` of plain result records, as a tidy :class:`pandas.DataFrame`
(:meth:`Campaign.to_frame`), CSV or JSON.

The unit of work is a chunk of datasets (:func:`~frictionlaws.parallel.iter_chunks`):
a worker loads them, splits them into groups, fits every law to every group (the
small groups of a law together, in stacks: :mod:`frictionlaws.fitting.stacked`) and
returns the chunk's plain records as one block (never laws or lmfit objects), so the
work runs unchanged serially, on local processes (``jobs=N``, joblib) or on a Dask
cluster (``scheduler="tcp://host:8786"``, Dask futures; needs the ``dask`` extra),
with a bounded window of chunks in flight; the calling process only schedules the
chunks and keeps their blocks.  Datasets are loaded inside the workers, so the memory
of the calling process grows with the number of results held, not with the data (and
not at all when they are streamed to a file).
"""

from __future__ import annotations

import collections
import functools
import os
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..base.errors import Argument, FitError, InputError
from ..base.jsonio import to_jsonable
from ..base.outputs import check_outputs
from ..io import MISSING_TOKENS, Dataset, column_for, load_dataset
from ..law.registry import get_law
from ..parallel import (
    DASK_WORKER_CONFIG,
    MAX_BATCH,
    SCHEDULER_ENV,
    batch_size,
    iter_chunks,
    iter_parallel,
    run_parallel,
)
from . import as_fit_data, fit
from .batch import POLISH_ROWS
from .campaign_results import (
    Block,
    Campaign,
    doubts,
    group_column,
    key_text,
    stream_blocks,
    tidy_columns,
)
from .stacked import stack_fits, stackable

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
    """Some datasets of a campaign cannot be read (or grouped): the campaign gives no results.

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
                         "be read or grouped, so it gives no results: "
                         + "; ".join(str(p) for p in self.problems))

    def summary(self) -> str:
        """One line that sums the problems up (a front end lists each one before it).

        Returns
        -------
        str
            E.g. ``1 of 2 datasets of the campaign cannot be read or grouped; ...``.
        """
        return (f"{len(self.problems)} of {self.total} datasets of the campaign cannot be "
                "read or grouped; it gives no results (fix or remove each file named)")


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
    if len(sources) == 1 and isinstance(sources[0], (str, os.PathLike)) \
            and os.path.isdir(sources[0]):
        listed = _csv_files(os.fspath(sources[0]))
        if not listed:
            raise InputError("the directory holds no *.csv dataset", file=str(sources[0]))
        return listed
    out: list[Any] = []
    for item in sources:
        if isinstance(item, (str, os.PathLike)) and os.path.isdir(item):
            files = _csv_files(os.fspath(item))
            if not files:
                raise InputError("the directory holds no *.csv dataset", file=str(item))
            out.extend(files)
        else:
            out.append(item)
    if not out:
        raise InputError("no datasets given")
    return out


class _ListedFile(str):
    """A file found in a directory listing (a path as text), with its real path and stem."""

    key: str | None = None
    stem: str = ""


class _Listing(list[str]):
    """The files of one directory listing, none a link: distinct files of distinct stems."""


def _csv_files(folder: str) -> list[str]:
    """The ``*.csv`` entries of ``folder`` sorted by name, files with their real path.

    One directory listing: the real path of a plain file is the directory's own joined
    with its name, so only links are resolved one by one.  Without links (and other
    entries than files) the listing is a :class:`_Listing` of plain paths: its files are
    distinct and so are their stems (each name is its stem and ``.csv``).
    """
    csv = ".csv"
    with os.scandir(folder) as entries:
        found = sorted((e.name, e.is_file(follow_symlinks=False)) for e in entries
                       if os.path.normcase(e.name).endswith(csv))
    prefix = os.path.join(folder, "")
    if all(is_file for _, is_file in found):
        return _Listing(prefix + name for name, _ in found)
    real = os.path.join(os.path.realpath(folder), "")
    out: list[str] = []
    for name, plain in found:
        path = _ListedFile(prefix + name)
        if plain or os.path.isfile(path):
            path.key = real + name if plain else os.path.realpath(path)
            dot = name.rfind(".")  # the stem as pathlib writes it
            path.stem = name[:dot] if 0 < dot < len(name) - 1 else name
        out.append(path)
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
    if not by:
        return [({}, np.ones(len(dataset), dtype=bool))]
    frame = dataset.frame
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
    #: Only read the dataset (another one cannot be read: the campaign gives no results).
    check_only: bool = False


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
    if isinstance(sources, _Listing):
        return [None] * len(sources)
    seen: dict[str, int] = {}
    names = []
    for i, src in enumerate(sources):
        key = _file_key(src)
        if key is not None:
            if key in seen:
                raise InputError(f"the same file is given twice (datasets {seen[key] + 1} and "
                                 f"{i + 1}); give each dataset once", file=str(src))
            seen[key] = i
        names.append(_own_name(src, key is not None))
    counts = collections.Counter(names)
    labels: list[str | None] = []
    for i, (src, name) in enumerate(zip(sources, names)):
        if counts[name] == 1:
            labels.append(None)
        elif isinstance(src, (str, os.PathLike)):
            labels.append(os.fspath(src))
        else:  # data in memory: named by their place in the campaign
            labels.append(f"{name} #{i + 1}")
    named = [lab for lab in labels if lab is not None]
    if len(set(named)) < len(named):
        raise InputError("two datasets have the same name; give them distinct paths")
    return labels


def _file_key(source: Any) -> str | None:
    """The real path of a file source (None for anything else): one file, one key."""
    if isinstance(source, _ListedFile):
        return source.key
    if isinstance(source, (str, os.PathLike)) and os.path.isfile(source):
        return os.path.realpath(source)
    return None


def _own_name(source: Any, is_file: bool) -> str:
    """The name :func:`~frictionlaws.io.load_dataset` gives a source, without loading it."""
    if isinstance(source, _ListedFile) and is_file:
        return source.stem
    if isinstance(source, (str, os.PathLike)):
        return Path(source).stem if is_file else os.fspath(source)
    if isinstance(source, Dataset):
        return str(source.name)
    return "data" if isinstance(source, Mapping) else "dataframe"


def _plain_error(exc: InputError) -> InputError:
    """An input error rebuilt as a plain :class:`InputError` (message parts and location),
    so that it travels between processes whatever its class."""
    return InputError(exc.parts, file=exc.file, column=exc.column, row=exc.row,
                      option=exc.option)


@dataclass(frozen=True)
class _Settings:
    """What every dataset of a campaign is read and fitted with (sent once per chunk)."""

    laws: tuple[str, ...]
    by: tuple[str, ...]
    fit_options: Mapping[str, Any]
    load_options: Mapping[str, Any]

    def job(self, item: tuple[Any, str | None, str | None, bool]) -> _Job:
        """One dataset's job from its item ``(source, label, shown, check_only)``."""
        return _Job(item[0], self.laws, self.by, self.fit_options, self.load_options,
                    item[1], item[2], item[3])


def _fit_chunk(settings: _Settings, items: Sequence[tuple[Any, str | None, str | None, bool]]
               ) -> Block:
    """Read a chunk of datasets, split them into groups and fit every law to every group.

    Groups of fewer than :data:`~frictionlaws.fitting.batch.POLISH_ROWS` rows wait, and
    are fitted law by law in stacks (:func:`~frictionlaws.fitting.stacked.fit_stacked`)
    once the chunk is read; a larger group is fitted at once (and its data let go).  A
    member a stack hands back, and every fit when the options are not those of a stacked
    fit, is made by :func:`~frictionlaws.fitting.fit`.  A dataset that cannot be read or
    grouped makes the chunk a list of such problems, without fits (the campaign is
    refused).
    """
    problems: list[InputError] = []
    heads: list[tuple[Any, ...]] = []
    parts: list[Any] = []
    waiting = _Waiting(stackable(settings.fit_options))
    for job in map(settings.job, items):
        try:
            ds = load_dataset(job.source, **job.load_options)
            groups = group_keys(ds, job.by)
        except InputError as exc:
            problems.append(_plain_error(exc))
            continue
        if job.check_only or problems:
            continue
        name, source = job.label or ds.name, job.shown or str(ds.source)
        for key, mask in groups:
            subset = group_subset(ds, key, mask)
            fd = waiting.data(subset, job)
            rows = int(mask.sum())
            for law in job.laws:
                heads.append((name, source, key, law, rows))
                parts.append(_fit_one(law, subset, job) if fd is None else None)
                if fd is not None:
                    waiting.add(law, fd, len(parts) - 1, subset, job)
    if problems:
        return Block(problems=problems)
    return Block(heads, parts, waiting.fit(parts))


@dataclass
class _Waiting:
    """The groups of a chunk waiting to be fitted in stacks, law by law."""

    on: bool
    members: dict[str, list[tuple[Any, int, Any, _Job]]] = field(default_factory=dict)

    def data(self, subset: Any, job: _Job) -> Any:
        """The fit data of a group to stack (None: fit it at once)."""
        if not self.on or len(subset) >= POLISH_ROWS:
            return None
        try:
            return as_fit_data(subset, weights=job.fit_options.get("weights", "auto"))
        except InputError:  # the one-fit path says why, as it would alone
            return None

    def add(self, law: str, fd: Any, at: int, subset: Any, job: _Job) -> None:
        self.members.setdefault(law, []).append((fd, at, subset, job))

    def fit(self, parts: list[Any]) -> list[Any]:
        """Fit every stack, its members' parts pointing into its columns; the members
        handed back are fitted one by one.  The stacks' results (one per law)."""
        tables: list[Any] = []
        for law, members in self.members.items():
            seed = members[0][3].fit_options.get("seed", 0)
            fits = stack_fits(get_law(law), [m[0] for m in members], seed)
            for j, (_, at, subset, job) in enumerate(members):
                row = int(fits.row[j])
                parts[at] = (len(tables), row) if row >= 0 else _fit_one(law, subset, job)
            tables.append(fits)
        return tables


def _fit_one(law: str, data: Any, job: _Job) -> dict[str, Any]:
    """One fit of ``law`` to ``data``: ``{"result": ...}`` or ``{"error": ...}``."""
    try:
        res = fit(law, data, **job.fit_options)
    except (InputError, FitError) as exc:
        return {"error": _shown_error(exc, job)}
    return {"result": _compact(res.to_dict())}


def _shown_error(exc: Exception, job: Any) -> str:
    """An error's message with the source shown as the job names it."""
    if job.shown and isinstance(exc, InputError):
        exc.replace_text(os.fspath(job.source), job.shown)
    return str(exc)


#: What a campaign record keeps of a fit (the full result stays with single fits).
_KEEP = ("params", "metrics", "success", "warnings", "non_identifiable", "notes", "derived",
         "uncertainty")


def _compact(doc: Mapping[str, Any]) -> dict[str, Any]:
    """The parts of a fit's dict a campaign table needs, as plain JSON-able values."""
    return to_jsonable({k: doc[k] for k in _KEEP if k in doc})


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


def fit_many(laws: str | Sequence[str], datasets: Any, *, by: str | Sequence[str] = (),
             jobs: int = 1, scheduler: str | None = None, progress: bool = False,
             output: str | os.PathLike[str] | None = None,
             load_options: Mapping[str, Any] | None = None,
             source_names: Mapping[str, str] | None = None, **fit_options: Any) -> Campaign:
    """Fit each law to each group of each dataset.

    The datasets go to the workers in chunks (:func:`~frictionlaws.parallel.iter_chunks`);
    a worker reads its chunk and fits each law to the chunk's small groups together
    (:func:`~frictionlaws.fitting.stacked.fit_stacked`), each with the numbers and
    warnings one :func:`~frictionlaws.fitting.fit` gives it, and the rest one by one.

    Parameters
    ----------
    laws : str or sequence of str
        Law ids (or aliases).
    datasets : name, path, directory, Dataset or a sequence of them
        See :func:`iter_datasets`.
    by : str or sequence of str
        Grouping columns (e.g. ``"surface"``); each group is fitted on its own.
    jobs : int
        Local worker processes (1: serial; -1: one per core); see :func:`iter_chunks`.
    scheduler : str, optional
        A Dask scheduler address; see :func:`iter_chunks`.
    progress : bool
        Show a progress bar on stderr (counting datasets).
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
        When any dataset cannot be read or grouped: all that cannot be are named, and
        no result is given (once one is found, the chunks still to go are only read).
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
    settings = _Settings(law_ids, columns, dict(fit_options), dict(load_options or {}))
    work = [(str(src) if isinstance(src, _ListedFile) else src, label,
             names.get(os.fspath(src)) if names and isinstance(src, (str, os.PathLike))
             else None) for src, label in zip(sources, dataset_labels(sources))]
    refusal = _Refusal(len(work))
    blocks = refusal.watch(iter_chunks(
        functools.partial(_fit_chunk, settings),
        ((*item, bool(refusal.problems)) for item in work),
        jobs=jobs, scheduler=scheduler, progress=progress, total=len(work)))
    if target is not None:
        return stream_blocks(blocks, target, columns, law_ids)
    return Campaign(by=columns, laws=law_ids, blocks=list(blocks))


@dataclass
class _Refusal:
    """The datasets of a campaign that cannot be read, as the chunks report them.

    A campaign half done is worse than none: the fits of the readable datasets would
    look complete.  Every dataset is read (and grouped) in its chunk; once one cannot
    be, the chunks still to be sent only read theirs, and at the end an
    :class:`UnreadableDatasets` lists every one that cannot be read (for a single
    dataset, its own error).
    """

    total: int
    problems: list[InputError] = field(default_factory=list)

    def watch(self, blocks: Iterable[Block]) -> Iterator[Block]:
        """The blocks while every dataset reads; then the refusal."""
        for block in blocks:
            self.problems.extend(block.problems)
            if not self.problems:
                yield block
        if self.total == 1 and self.problems:
            raise self.problems[0]  # one dataset: its own error says it all
        if self.problems:
            raise UnreadableDatasets(self.problems, self.total)


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
