"""Running a campaign: manifests and records in, processed in one or several processes, plots
and tables out (:func:`process_campaign`, :func:`process_many`, :func:`process_records`).
"""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from ...base.errors import InputError
from ...base.outputs import check_unique_names
from ...io import output_dir
from ...parallel import check_jobs, iter_parallel, local_workers
from ..plots import plot_conditions, plot_name, plot_record
from ..records import Record, read_record
from ..rig import Rig, load_rig
from .conditions import summarise
from .manifest import ManifestEntry, manifest_from_rows, read_manifest
from .reduce import RecordResult, _base_result, process_record
from .results import ProcessedCampaign

__all__ = ["process_campaign", "process_many", "manifest_names", "process_records"]


# --------------------------------------------------------------------------- drivers
@dataclass(frozen=True)
class _Chunk:
    """Records to process in one unit of work: plain, picklable data only."""

    rig: Rig
    entries: tuple[ManifestEntry, ...]
    plots: tuple[str | None, ...]


def _run_chunk(chunk: _Chunk) -> list[RecordResult]:
    """Read and process the records of a chunk (a worker's unit of work)."""
    return [_handle(e, chunk.rig, plots, None)
            for e, plots in zip(chunk.entries, chunk.plots, strict=True)]


def _handle(entry: ManifestEntry, rig: Rig, plots: str | None,
            record: Record | None) -> RecordResult:
    if entry.error:
        res = _base_result(entry)
        res.reason = entry.error
        return res
    try:
        rec = record if record is not None else read_record(entry.path, source=entry.file)
        if record is not None:
            rec.check()
    except InputError as exc:
        res = _base_result(entry)
        res.reason = " ".join(str(exc).split())
        return res
    if plots is None:
        return process_record(rec, entry, rig)  # type: ignore[return-value]
    res, sig = process_record(rec, entry, rig, keep_signals=True)  # type: ignore[misc]

    try:
        plot_record(Path(plots), res, rec, sig)
    except Exception as exc:  # noqa: BLE001 - a failed plot must not lose the record
        res.notes.append(f"diagnostic plot failed: {type(exc).__name__}: {exc}")
    return res


def _progress(total: int, progress: bool | None, desc: str) -> Any:
    from tqdm import tqdm

    return tqdm(total=total, disable=None if progress is None else not progress,
                unit="record", desc=desc, file=sys.stderr, leave=False)


def _job_count(jobs: int | None) -> int:
    """``jobs`` as the campaign runner takes it: None or 0 (one per CPU) become -1."""
    return -1 if jobs is None or jobs == 0 else jobs


def _run_files(work: list[tuple[ManifestEntry, str | None]], rig: Rig, jobs: int | None,
               scheduler: str | None, progress: bool | None) -> list[RecordResult]:
    """Process records read from files, on the campaign runner (serial, joblib or Dask).

    The results are in the order of ``work`` and do not depend on how the work ran.
    """
    jobs = _job_count(jobs)
    check_jobs(jobs)
    remote = scheduler is not None  # only an address given connects, never the environment
    workers = local_workers(jobs)
    if not remote and len(work) < 2 * workers:  # too few records to be worth a pool
        jobs = 1
    # one record per item: the campaign runner batches the items into tasks itself
    chunks = (_Chunk(rig, (e,), (p,)) for e, p in work)
    results: list[RecordResult] = []
    bar = _progress(len(work), progress, "processing")
    try:
        for part in iter_parallel(_run_chunk, chunks, jobs=jobs, scheduler=scheduler,
                                  total=len(work)):
            results.extend(part)
            bar.update(len(part))
    finally:
        bar.close()
    return results


def _run_memory(entries: list[ManifestEntry], rig: Rig, records: Sequence[Record],
                progress: bool | None, plots: str | None) -> list[RecordResult]:
    """Process records held in memory, in this process."""
    results: list[RecordResult] = []
    bar = _progress(len(entries), progress, "processing")
    try:
        for entry, rec in zip(entries, records, strict=True):
            results.append(_handle(entry, rig, plots, rec))
            bar.update(1)
    finally:
        bar.close()
    return results


def _check_min_repeats(min_repeats: int) -> None:
    if min_repeats < 2:
        raise InputError(f"min_repeats must be at least 2 (a standard deviation needs two "
                         f"records), got {min_repeats}")


def process_campaign(
    manifest: str | os.PathLike[str],
    rig: Rig | str | os.PathLike[str],
    *,
    jobs: int | None = 1,
    progress: bool | None = None,
    plots: str | os.PathLike[str] | None = None,
    min_repeats: int = 2,
    scheduler: str | None = None,
) -> ProcessedCampaign:
    """Process every record of a manifest into per-record and per-condition results.

    Parameters
    ----------
    manifest : str or path
        The manifest CSV (format in the module docstring).
    rig : Rig or path
        A :class:`Rig` or the path of its TOML description.
    jobs : int, optional
        Worker processes: 1 (default) serial, N > 1 that many, ``-1``, ``0`` or
        ``None`` one per CPU.  Results do not depend on it.
    progress : bool, optional
        Show a progress bar on stderr; ``None`` (default): only when stderr is a
        terminal.
    plots : str or path, optional
        Directory for diagnostic plots (created); matplotlib is imported only then.
    min_repeats : int
        Conditions with fewer usable records are not written to the dataset
        (at least 2: a standard deviation needs two).
    scheduler : str, optional
        A Dask scheduler address: the records are processed on that cluster (see
        :func:`frictionlaws.fitting.campaign.iter_parallel`; the record files must be
        readable by its workers).

    Returns
    -------
    ProcessedCampaign
        The per-record results, the conditions with their statistics, the notes
        and the outlier rule used.

    Raises
    ------
    InputError
        For a bad manifest or rig (problems of single records are reported in
        the results instead).
    """
    return process_many([manifest], rig, jobs=jobs, progress=progress, plots=plots,
                        min_repeats=min_repeats, scheduler=scheduler, plot_dirs="flat")[0]


def process_many(
    manifests: Sequence[str | os.PathLike[str]],
    rig: Rig | str | os.PathLike[str],
    *,
    jobs: int | None = 1,
    progress: bool | None = None,
    plots: str | os.PathLike[str] | None = None,
    min_repeats: int = 2,
    scheduler: str | None = None,
    plot_dirs: str = "per-manifest",
) -> list[ProcessedCampaign]:
    """Process several manifests with one rig: one :class:`ProcessedCampaign` per manifest.

    Every manifest is read and checked before any record is processed.  The
    records of all manifests are then processed as one stream of work, serially,
    on local processes (``jobs``) or on a Dask cluster (``scheduler``), the way
    :func:`frictionlaws.fitting.campaign.fit_many` runs many datasets; each manifest's
    conditions and outlier rule are then computed from its own records only, so
    each result equals :func:`process_campaign` of that manifest alone.

    Parameters
    ----------
    manifests : sequence of str or path
        The manifest CSVs; the same file may not be given twice.
    rig : Rig or path
        The rig of every manifest.
    jobs : int, optional
        Worker processes, as in :func:`process_campaign`.
    progress : bool, optional
        Progress bar on stderr (``None``: only on a terminal).
    plots : str or path, optional
        Directory for diagnostic plots.
    min_repeats : int
        As in :func:`process_campaign`, for every manifest.
    scheduler : str, optional
        A Dask scheduler address, as in :func:`process_campaign`.
    plot_dirs : {"per-manifest", "flat"}
        ``per-manifest`` (default): each manifest's plots go to a subdirectory
        named by :func:`manifest_names`; ``flat``: all in ``plots`` (one manifest).

    Returns
    -------
    list of ProcessedCampaign
        In the order of ``manifests``.

    Raises
    ------
    InputError
        For a bad rig, a manifest given twice, or a bad manifest (naming it);
        nothing is processed then.
    """
    if not isinstance(rig, Rig):
        rig = load_rig(rig)
    _check_min_repeats(min_repeats)
    names = manifest_names(manifests)
    read = [read_manifest(m, rig) for m in manifests]
    dirs = _plot_dirs(plots, names, plot_dirs)
    for m, (entries, _), d in zip(manifests, read, dirs, strict=True):
        _refuse_plot_clash(entries, d, os.fspath(m))
    work = [(e, d) for (entries, _), d in zip(read, dirs, strict=True) for e in entries]
    results = iter(_run_files(work, rig, jobs, scheduler, progress))
    camps = []
    for m, (entries, notes), d in zip(manifests, read, dirs, strict=True):
        mine = [next(results) for _ in entries]
        camps.append(_campaign(mine, rig, os.fspath(m), notes, min_repeats, d))
    return camps


def _campaign(results: list[RecordResult], rig: Rig, source: str, notes: list[str],
              min_repeats: int, plots_dir: str | None) -> ProcessedCampaign:
    conditions, rule = summarise(results, rig, min_repeats=min_repeats)
    camp = ProcessedCampaign(results, conditions, rig, source, notes, min_repeats, rule)
    if plots_dir is not None:
        _summary_plot(camp, plots_dir)
    return camp


def _plot_dirs(plots: str | os.PathLike[str] | None, names: list[str], layout: str
               ) -> list[str | None]:
    if layout not in ("per-manifest", "flat"):
        raise InputError(f"plot_dirs must be 'per-manifest' or 'flat', got {layout!r}")
    if plots is None:
        return [None] * len(names)
    if layout == "flat":
        if len(names) > 1:
            raise InputError("several manifests need a plot directory each: use "
                             "plot_dirs='per-manifest'")
        return [_plots_dir(plots)]
    return [_plots_dir(Path(plots) / name) for name in names]


def manifest_names(manifests: Sequence[str | os.PathLike[str]]) -> list[str]:
    """Give manifests short, distinct names for their outputs.

    The name is the file stem, or parent and stem when two stems are the same
    (``week1/manifest.csv`` -> ``week1_manifest``).

    Parameters
    ----------
    manifests : sequence of str or path
        The manifest files.

    Returns
    -------
    list of str
        One name per manifest, in order; used for output files and plot folders.

    Raises
    ------
    InputError
        When no manifest is given, one is given twice (the same file, also
        through a link), or two names still collide (naming both files).
    """
    if not manifests:
        raise InputError("no manifest given")
    paths = [Path(m) for m in manifests]
    _refuse_repeats(paths)
    stems = [p.stem for p in paths]
    names = [f"{p.resolve().parent.name}_{p.stem}" if stems.count(p.stem) > 1 else p.stem
             for p in paths]
    seen: dict[str, Path] = {}
    for name, p in zip(names, paths, strict=True):
        key = name.casefold()  # outputs may land on a case-insensitive file system
        if key in seen:
            raise InputError(f"manifests '{seen[key]}' and '{p}' would write outputs of the "
                             f"same name '{name}': rename one, or process them separately",
                             file=str(p))
        seen[key] = p
    return names


def _refuse_repeats(paths: list[Path]) -> None:
    """A manifest given twice (same path, or the same file through a link) is refused."""
    for i, p in enumerate(paths):
        for q in paths[:i]:
            same = os.path.realpath(p) == os.path.realpath(q)
            if not same and p.exists() and q.exists():
                same = os.path.samefile(p, q)
            if same:
                raise InputError(f"the manifest is given twice ('{q}' and '{p}'); give it "
                                 "once", file=str(p))


def process_records(
    records: Sequence[Record],
    manifest: Sequence[Mapping[str, Any]] | Sequence[ManifestEntry],
    rig: Rig,
    *,
    progress: bool | None = False,
    plots: str | os.PathLike[str] | None = None,
    min_repeats: int = 2,
) -> ProcessedCampaign:
    """Process records held in memory (e.g. from :mod:`~frictionlaws.tribometer.synthetic`),
    one manifest row each.

    ``manifest`` holds dicts with the manifest's columns (``file``,
    ``load [kg]``, ``surface``, ``condition``, ``mode``...) or ready
    :class:`ManifestEntry` objects; ``file`` only names the record.
    """
    if len(records) != len(manifest):
        raise InputError(f"{len(records)} records but {len(manifest)} manifest rows")
    _check_min_repeats(min_repeats)
    notes: list[str] = []
    if manifest and all(isinstance(m, ManifestEntry) for m in manifest):
        entries = [m for m in manifest if isinstance(m, ManifestEntry)]
    else:
        rows = [m for m in manifest if isinstance(m, Mapping)]
        if len(rows) != len(manifest):
            raise InputError("manifest rows must all be dicts or all be ManifestEntry objects")
        entries, notes = manifest_from_rows(rows, rig)
    entries = [replace(e, path="") for e in entries]
    plots_dir = _plots_dir(plots)
    _refuse_plot_clash(entries, plots_dir, "<memory>")
    results = _run_memory(entries, rig, records, progress, plots_dir)
    return _campaign(results, rig, "<memory>", notes, min_repeats, plots_dir)


#: The summary plot of a campaign, beside the records' plots.
_SUMMARY_PLOT = "conditions.png"


def _refuse_plot_clash(entries: Sequence[ManifestEntry], plots_dir: str | None,
                       source: str) -> None:
    """Each record's plot, and the summary, get a file name of their own (before any work)."""
    if plots_dir is None:
        return

    check_unique_names([("the summary plot", _SUMMARY_PLOT)]
                       + [(f"row {e.row} ('{e.file}')", plot_name(e.file)) for e in entries],
                       what="plots", file=source)


def _plots_dir(plots: str | os.PathLike[str] | None) -> str | None:
    if plots is None:
        return None

    return str(output_dir(os.fspath(plots), "plots directory"))


def _summary_plot(camp: ProcessedCampaign, plots_dir: str) -> None:
    try:
        plot_conditions(Path(plots_dir) / _SUMMARY_PLOT, camp)
    except Exception as exc:  # noqa: BLE001 - report, do not lose the processing
        camp.notes.append(f"summary plot failed: {type(exc).__name__}: {exc}")

