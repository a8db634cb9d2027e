"""``frictionlaws process``: raw tribometer records -> a friction dataset with intervals."""

from __future__ import annotations

import argparse

from ._common import add_progress_option, bounded_int, progress_value

__all__ = ["add_parser", "run"]


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    p = sub.add_parser(
        "process", help="process raw tribometer records into a dataset",
        description="Process the raw torque records listed in a manifest CSV (file, "
        "load [kg] or load [N], surface, optional condition, mode, window_start [s], "
        "window_end [s], direction) with a rig description (TOML): filter, subtract the "
        "offsets, find the steady window, average the repeats of each condition, drop "
        "outliers (by default a record far from its condition's median in units of the "
        "record-to-record scatter pooled over the campaign; Grubbs on request in the rig), "
        "print the rule used, and write a dataset with mu, mu_std, n, 95 % Student-t "
        "intervals, p, v, s and F_N, ready for 'fit' and 'compare'. Unusable records are "
        "reported with the reason and the rest processed.")
    p.add_argument("manifest", metavar="MANIFEST", help="manifest CSV, one row per record")
    p.add_argument("--rig", required=True, metavar="RIG.toml", help="rig description (TOML)")
    p.add_argument("-o", "--output", required=True, metavar="DATASET.csv",
                   help="dataset to write (one row per condition)")
    p.add_argument("--records-out", metavar="RECORDS.csv",
                   help="per-record table (default: DATASET_records.csv next to the dataset)")
    p.add_argument("--plots", metavar="DIR",
                   help="write diagnostic plots (raw, filtered, window) for every record to DIR "
                        "(created with its parents if missing, like --report; only when the "
                        "dataset is written)")
    p.add_argument("--jobs", type=bounded_int(0, 1024), default=0, metavar="N",
                   help="worker processes (default 0: one per CPU; 0..1024)")
    p.add_argument("--min-repeats", type=int, default=2, metavar="N",
                   help="conditions with fewer usable records are not written (default 2)")
    add_progress_option(p)
    return p


def run(args: argparse.Namespace) -> int:
    from contextlib import nullcontext
    from pathlib import Path

    from frictionlaws.errors import InputError
    from frictionlaws.outputs import atomic_dir, check_outputs
    from frictionlaws.tribometer.process import process_campaign, read_manifest
    from frictionlaws.tribometer.rig import load_rig

    out = Path(args.output)
    if out.suffix.lower() != ".csv":
        raise InputError(f"-o {args.output}: the dataset is written as CSV; give a .csv name")
    records_out = (Path(args.records_out) if args.records_out
                   else out.with_name(f"{out.stem}_records.csv"))
    # every output is checked before any work: not an input (manifest, rig or any record
    # the manifest lists, resolved as the processing resolves them), a writable file
    check_outputs([out, records_out], dirs=[args.plots], inputs=[args.manifest, args.rig])
    rig = load_rig(args.rig)
    entries, _ = read_manifest(args.manifest, rig)
    check_outputs([out, records_out], dirs=[args.plots],
                  inputs=[e.path for e in entries if e.path])
    # plots are drawn into a temporary directory moved into place only when the dataset
    # is written: a failed run leaves no plots (and no created directory) behind
    with atomic_dir(args.plots) if args.plots else nullcontext(None) as plots_tmp:
        camp = process_campaign(args.manifest, rig, jobs=args.jobs,
                                progress=progress_value(args), plots=plots_tmp,
                                min_repeats=args.min_repeats)
        if not any(c.written for c in camp.conditions):
            print(camp.summary())
            raise InputError(
                f"no condition has {args.min_repeats} or more usable records: no dataset "
                "written, nothing written at all (the reasons are in the summary above)",
                file=args.manifest)
        camp.write_records(records_out)
        camp.write_dataset(out)
    print(camp.summary())
    print(f"per-record table: {records_out}")
    if args.plots:
        print(f"plots: {args.plots}")
    print(f"dataset: {out}")
    return 0
