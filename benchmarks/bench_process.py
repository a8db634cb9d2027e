"""Benchmark: process a campaign the size of the thesis' (843 records of 30 s at 1 kHz).

Run::

    python benchmarks/bench_process.py            # full size: 843 records
    python benchmarks/bench_process.py --records 100 --keep DIR

Steps:

1. generate the synthetic campaign (record counts of thesis Table 4-2, 30 s
   at 1 kHz, 4 columns) into a temporary directory - not timed;
2. baseline, in the same run: read every record with ``pandas.read_csv`` and
   apply a plain ``scipy.signal.filtfilt`` (4th-order Butterworth, 20 Hz) to
   its torque column - the least any processing has to do;
3. ``process_campaign`` (the whole pipeline: manifest, reading and checks,
   auto cut-off, filter, offsets, window detection, statistics, outliers),
   with one worker process and with one per CPU; then the dataset and the
   per-record table are written.

Printed: wall times, throughput in samples per second, the ratio to the
baseline, and whether the whole campaign took under the 10 s target.  The
processed dataset is also checked against the known mu of every condition.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np


def _baseline(manifest: Path) -> tuple[float, int]:
    import pandas as pd
    from scipy import signal

    files = [line.split(",", 1)[0] for line in manifest.read_text().splitlines()[1:] if line]
    b, a = signal.butter(4, 20.0, fs=1000.0)
    t0 = time.perf_counter()
    samples = 0
    for f in files:
        frame = pd.read_csv(manifest.parent / f)
        y = signal.filtfilt(b, a, frame.iloc[:, 1].to_numpy())
        samples += y.size
    return time.perf_counter() - t0, samples


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--records", type=int, default=843,
                        help="campaign size (default 843, the thesis' valid tests)")
    parser.add_argument("--duration", type=float, default=30.0, help="record length [s]")
    parser.add_argument("--keep", metavar="DIR",
                        help="write the campaign here and keep it (reused if already there)")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                        help="workers of the parallel run (default: one per CPU)")
    parser.add_argument("--skip-serial", action="store_true", help="skip the 1-worker run")
    args = parser.parse_args(argv)

    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
    from frictionlaws.tribometer.process import process_campaign
    from frictionlaws.tribometer.rig import load_rig
    from frictionlaws.tribometer.synthetic import (
        campaign_truth,
        make_campaign,
        thesis_conditions,
    )

    conditions = thesis_conditions(seed=1)
    if args.records != 843:
        kept, left = [], args.records
        for c in conditions:
            if left <= 0:
                break
            kept.append(c)
            left -= c.repeats
        conditions = kept
    n_records = sum(c.repeats for c in conditions)
    tmp = None
    if args.keep:
        root = Path(args.keep)
    else:
        tmp = tempfile.TemporaryDirectory(prefix="bench_process_")
        root = Path(tmp.name)
    try:
        print(f"machine: {os.cpu_count()} CPUs; python {sys.version.split()[0]}")
        t0 = time.perf_counter()
        kw = {"duration": args.duration}
        truth = campaign_truth(root, conditions, seed=7, record_kwargs=kw)
        files = [root / r["file"] for r in truth.records]
        if args.keep and truth.manifest.exists() and all(f.exists() for f in files):
            what = "reused"
        else:
            truth = make_campaign(root, conditions, seed=7, jobs=args.jobs, record_kwargs=kw)
            what = "generated"
        size = sum(f.stat().st_size for f in files)
        print(f"{what} {n_records} records ({len(conditions)} conditions, "
              f"{args.duration:g} s at 1 kHz, {size / 1e6:.0f} MB of CSV) in "
              f"{time.perf_counter() - t0:.1f} s (not timed)")
        rig = load_rig(truth.rig_file)

        t_base, samples = _baseline(truth.manifest)
        print(f"baseline  pandas.read_csv + filtfilt, 1 process : {t_base:6.2f} s  "
              f"{samples / t_base:12.4g} samples/s")

        runs = [] if args.skip_serial else [1]
        if args.jobs > 1 or not runs:
            runs.append(args.jobs)
        camp = None
        for jobs in runs:
            t0 = time.perf_counter()
            camp = process_campaign(truth.manifest, rig, jobs=jobs, progress=False)
            camp.write_dataset(root / "dataset.csv")
            camp.write_records(root / "records.csv")
            dt = time.perf_counter() - t0
            n_samples = sum(r.n_samples for r in camp.records)
            print(f"frictionlaws process, {jobs} worker{'s' if jobs > 1 else ' '}       : "
                  f"{dt:6.2f} s  {n_samples / dt:12.4g} samples/s  "
                  f"({dt / t_base:.2f} x baseline time; "
                  f"{'under' if dt < 10 else 'OVER'} the 10 s target)")
        assert camp is not None
        # accuracy check on the full campaign
        true_mu = truth.condition_mu()
        errs = np.array([abs(c.mu / true_mu[c.condition] - 1.0) for c in camp.conditions
                         if c.written])
        cover = np.mean([c.ci95[0] <= true_mu[c.condition] <= c.ci95[1]
                         for c in camp.conditions if c.written])
        print(f"records: {len(camp.used)} used, {len(camp.outliers)} outliers, "
              f"{len(camp.unusable)} unusable; conditions: {errs.size}")
        true_rec = truth.record_mu()
        rec_err = np.array([abs(r.mu / true_rec[r.file] - 1.0) for r in camp.records
                            if r.usable])
        print(f"|mu error| per record: median {100 * np.median(rec_err):.3f} %, max "
              f"{100 * rec_err.max():.3f} %")
        print(f"|mu error| per condition (includes the 3..6 % repeat scatter): median "
              f"{100 * np.median(errs):.2f} %, max {100 * errs.max():.2f} %; "
              f"95 % CI coverage {cover:.3f}")
    finally:
        if tmp is not None:
            tmp.cleanup()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
