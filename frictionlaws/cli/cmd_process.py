"""``frictionlaws process``: raw tribometer records -> a friction dataset with intervals."""

from __future__ import annotations

import argparse


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    p = sub.add_parser(
        "process", help="process raw tribometer records into a dataset",
        description="Process the raw torque records listed in a manifest CSV (file, "
        "load [kg] or load [N], surface, optional condition, mode, window_start [s], "
        "window_end [s], direction) with a rig description (TOML): filter, subtract the "
        "offsets, find the steady window, average the repeats of each condition, drop "
        "outliers (Grubbs), and write a dataset with mu, mu_std, n, 95 % Student-t "
        "intervals, p, v, s and F_N, ready for 'fit' and 'compare'. Unusable records are "
        "reported with the reason and the rest processed.")
    p.add_argument("manifest", metavar="MANIFEST", help="manifest CSV, one row per record")
    p.add_argument("--rig", required=True, metavar="RIG.toml", help="rig description (TOML)")
    p.add_argument("-o", "--output", required=True, metavar="DATASET.csv",
                   help="dataset to write (one row per condition)")
    p.add_argument("--records-out", metavar="RECORDS.csv",
                   help="per-record table (default: DATASET_records.csv next to the dataset)")
    p.add_argument("--plots", metavar="DIR",
                   help="write diagnostic plots (raw, filtered, window) for every record")
    p.add_argument("--jobs", type=int, default=0, metavar="N",
                   help="worker processes (default 0: one per CPU)")
    p.add_argument("--min-repeats", type=int, default=2, metavar="N",
                   help="conditions with fewer usable records are not written (default 2)")
    bar = p.add_mutually_exclusive_group()
    bar.add_argument("--progress", dest="progress", action="store_true", default=None,
                     help="always show the progress bar (default: when stderr is a terminal)")
    bar.add_argument("--no-progress", dest="progress", action="store_false",
                     help="never show the progress bar")
    return p


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    from frictionlaws.errors import InputError
    from frictionlaws.tribometer.process import process_campaign
    from frictionlaws.tribometer.rig import load_rig

    out = Path(args.output)
    if not out.parent.exists():
        raise InputError("the output directory does not exist", file=str(out))
    records_out = (Path(args.records_out) if args.records_out
                   else out.with_name(f"{out.stem}_records.csv"))
    rig = load_rig(args.rig)
    camp = process_campaign(args.manifest, rig, jobs=args.jobs, progress=args.progress,
                            plots=args.plots, min_repeats=args.min_repeats)
    camp.write_records(records_out)
    print(camp.summary())
    print(f"per-record table: {records_out}")
    if args.plots:
        print(f"plots: {args.plots}")
    if not any(c.written for c in camp.conditions):
        raise InputError(
            f"no condition has {args.min_repeats} or more usable records: no dataset written "
            f"(reasons above and in {records_out})", file=args.manifest)
    camp.write_dataset(out)
    print(f"dataset: {out}")
    return 0
