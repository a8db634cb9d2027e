"""``frictionlaws process``: raw tribometer records -> friction datasets with intervals.

One manifest writes one dataset (``-o DATASET.csv``) or, given a directory
(``-o DIR``), ``DIR/NAME.csv``.  Several manifests need a directory: each
writes ``DIR/NAME.csv`` and ``DIR/NAME_records.csv`` with ``NAME`` from
:func:`frictionlaws.tribometer.process.manifest_names`.  All records of all
manifests run as one stream of work on the campaign runner (``--jobs``,
``--scheduler``, ``--progress``), the way ``fit`` and ``compare`` run many
datasets; every manifest's result equals processing it alone.  Outputs are
checked before any work and written together at the end: all of them or none.
"""

from __future__ import annotations

import argparse
import os
from contextlib import nullcontext, suppress
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..base import jsonio
from ..base.errors import InputError
from ..base.outputs import atomic_dir, check_dir_move, check_outputs
from ..io import output_dir
from ..tribometer.process import manifest_names, process_many, read_manifest, write_tables
from ..tribometer.rig import load_rig
from ._common import (
    SCHEDULER_TRUST,
    add_json_option,
    add_progress_option,
    bounded_int,
    job_count,
    progress_value,
)
from .commands import COMMANDS

__all__ = ["add_parser", "run"]


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    p = sub.add_parser(
        "process", help=COMMANDS["process"],
        description="Process the raw torque records listed in manifest CSVs (file, "
        "load [kg] or load [N], surface, optional condition, mode, window_start [s], "
        "window_end [s], direction) with a rig description (TOML): filter, subtract the "
        "offsets, find the steady window, average the repeats of each condition, drop "
        "outliers (by default a record far from its condition's median in units of the "
        "record-to-record scatter pooled over the campaign; Grubbs on request in the rig), "
        "print the rule used, and write a dataset with mu, mu_std, n, 95 % Student-t "
        "intervals, p, v, s and F_N, ready for 'fit' and 'compare'. Unusable records are "
        "reported with the reason and the rest processed. Several manifests are processed "
        "together (each as if alone) into a directory: DIR/NAME.csv and "
        "DIR/NAME_records.csv per manifest.")
    p.add_argument("manifest", metavar="MANIFEST", nargs="+",
                   help="manifest CSV, one row per record (several: one dataset each)")
    p.add_argument("--rig", required=True, metavar="RIG.toml", help="rig description (TOML)")
    p.add_argument("-o", "--output", required=True, metavar="DATASET.csv|DIR",
                   help="dataset to write (one row per condition), or a directory that "
                        "receives NAME.csv and NAME_records.csv per manifest (created if "
                        "missing; needed for several manifests)")
    p.add_argument("--records-out", metavar="RECORDS.csv",
                   help="per-record table (default: DATASET_records.csv next to the dataset; "
                        "only with -o DATASET.csv)")
    p.add_argument("--plots", metavar="DIR",
                   help="write diagnostic plots (raw, filtered, window) for every record "
                        "to DIR (several manifests: one subdirectory NAME each; created with "
                        "its parents if missing, and only when the datasets are written)")
    p.add_argument("--jobs", type=job_count, default=-1, metavar="N",
                   help="worker processes for the records (default -1: one per core; 1 = "
                        "serial; 1..1024; never more than the cores)")
    p.add_argument("--scheduler", metavar="ADDRESS", default=None,
                   help="process the records on a Dask cluster, e.g. tcp://10.0.0.5:8786 "
                        "(or tls:// with Dask's TLS settings; the record files must be "
                        f"readable by its workers). {SCHEDULER_TRUST}")
    p.add_argument("--min-repeats", type=bounded_int(2, 10_000), default=2, metavar="N",
                   help="conditions with fewer usable records are not written (default 2)")
    add_progress_option(p)
    add_json_option(p)
    return p


@dataclass(frozen=True)
class _Target:
    """Where one manifest's outputs go."""

    manifest: str
    dataset: Path
    records: Path


def _plan(args: argparse.Namespace, names: list[str]) -> tuple[list[_Target], Path | None]:
    """The output files of every manifest, and the output directory (None: -o is a file)."""
    if str(args.output).strip() == "-":
        raise InputError("-o -: process writes a dataset file (or a directory of them), not "
                         "standard output; --json prints the results on standard output")
    out = Path(args.output)
    as_dir = out.is_dir() or str(args.output).endswith(("/", "\\")) or not out.suffix
    if not as_dir and out.suffix.lower() != ".csv":
        raise InputError(f"-o {args.output}: the dataset is written as CSV; give a .csv name "
                         "(or a directory)")
    if not as_dir:
        if len(args.manifest) > 1:
            raise InputError(f"-o {args.output}: {len(args.manifest)} manifests write one "
                             "dataset each; give -o a directory")
        records = (Path(args.records_out) if args.records_out
                   else out.with_name(f"{out.stem}_records.csv"))
        return [_Target(args.manifest[0], out, records)], None
    if args.records_out:
        raise InputError("--records-out names one file: it is used with -o DATASET.csv; with "
                         "-o DIR the per-record tables are DIR/NAME_records.csv")
    return [_Target(m, out / f"{name}.csv", out / f"{name}_records.csv")
            for m, name in zip(args.manifest, names, strict=True)], out


def _refuse_collisions(targets: list[_Target]) -> None:
    """Two outputs with one name (also differing in case only) name both manifests."""
    seen: dict[str, tuple[str, str]] = {}
    for t in targets:
        for role, path in (("dataset", t.dataset), ("per-record table", t.records)):
            key = os.path.normcase(os.path.abspath(path)).casefold()
            if key in seen:
                other_role, other = seen[key]
                raise InputError(f"outputs collide: {path} would be the {role} of '{t.manifest}' "
                                 f"and the {other_role} of '{other}'; rename a manifest or "
                                 "process them separately", file=str(path))
            seen[key] = (role, t.manifest)


def _check_before_work(args: argparse.Namespace, targets: list[_Target],
                       out_dir: Path | None, rig: Any) -> None:
    """Every output checked before any work: no input among them (manifests, the rig and
    every record the manifests list, resolved as the processing resolves them)."""
    _refuse_collisions(targets)
    records = [e.path for m in args.manifest for e in read_manifest(m, rig)[0] if e.path]
    inputs = [*args.manifest, args.rig, *records]
    files = [p for t in targets for p in (t.dataset, t.records)]
    if out_dir is None or out_dir.is_dir():
        check_outputs(files, dirs=[args.plots], inputs=inputs)
    else:  # files in a directory still to be created cannot be inputs or directories
        check_outputs(dirs=[out_dir, args.plots], inputs=inputs)


def run(args: argparse.Namespace) -> int:
    if "-" in args.manifest:
        raise InputError("MANIFEST '-': a manifest names its record files relative to its "
                         "own folder, which standard input does not have; give the "
                         "manifest's path")
    names = manifest_names(args.manifest)  # refuses a manifest given twice
    targets, out_dir = _plan(args, names)
    rig = load_rig(args.rig)
    _check_before_work(args, targets, out_dir, rig)
    # plots are drawn into a temporary directory moved into place only when the datasets
    # are written: a failed run leaves no plots (and no created directory) behind
    with atomic_dir(args.plots) if args.plots else nullcontext(None) as plots_tmp:
        camps = process_many(args.manifest, rig, jobs=args.jobs, scheduler=args.scheduler,
                             progress=progress_value(args), plots=plots_tmp,
                             min_repeats=args.min_repeats,
                             plot_dirs="flat" if len(args.manifest) == 1 else "per-manifest")
        empty = [t.manifest for t, c in zip(targets, camps, strict=True)
                 if not any(cond.written for cond in c.conditions)]
        if empty:
            _report(args, targets, camps, written=False)
            _refuse_empty(args, empty)
        if plots_tmp is not None:  # the plots must be able to move in before any table
            check_dir_move(plots_tmp, args.plots)
        _write(targets, camps, out_dir)
    _report(args, targets, camps, written=True)
    return 0


def _refuse_empty(args: argparse.Namespace, empty: list[str]) -> None:
    where = f"manifests {', '.join(empty)}: " if len(empty) > 1 else ""
    raise InputError(
        f"{where}no condition has {args.min_repeats} or more usable records: no dataset "
        "written, nothing written at all (the reasons are in the summary above)",
        file=empty[0] if len(empty) == 1 else None)


def _write(targets: list[_Target], camps: list[Any], out_dir: Path | None) -> None:
    """Write every dataset and per-record table together; on failure, none of them."""
    created = out_dir is not None and not out_dir.exists()
    if not created:
        check_outputs([p for t in targets for p in (t.dataset, t.records)],
                      inputs=[f for c in camps for f in c.record_files()])
    if out_dir is not None:
        output_dir(out_dir)
    tables = [(p, text) for t, c in zip(targets, camps, strict=True)
              for p, text in ((t.records, c.records_text()), (t.dataset, c.dataset_text()))]
    try:
        write_tables(tables)
    except BaseException:
        if created and out_dir is not None:
            with suppress(OSError):
                out_dir.rmdir()  # only when still empty
        raise


def _report(args: argparse.Namespace, targets: list[_Target], camps: list[Any], *,
            written: bool) -> None:
    """The summaries as text, or (``--json``) one strict JSON document."""
    if args.json:
        docs = []
        for t, c in zip(targets, camps, strict=True):
            outputs = ({"dataset": str(t.dataset), "records": str(t.records),
                        "plots": _plots_of(args, t, targets)} if written else None)
            docs.append({**c.to_dict(), "outputs": outputs})
        print(jsonio.dumps({"written": written, "manifests": docs}))
        return
    several = len(targets) > 1
    for t, c in zip(targets, camps, strict=True):
        if several:
            print(f"== {t.manifest}")
        print(c.summary())
        if written:
            print(f"per-record table: {t.records}")
            if args.plots:
                print(f"plots: {_plots_of(args, t, targets)}")
            print(f"dataset: {t.dataset}")


def _plots_of(args: argparse.Namespace, target: _Target, targets: list[_Target]
              ) -> str | None:
    if not args.plots:
        return None
    if len(targets) == 1:
        return str(args.plots)
    return str(Path(args.plots) / target.dataset.stem)
