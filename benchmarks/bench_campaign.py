"""Campaign throughput: many synthetic datasets x 3 laws, serial vs 2 local processes vs a
2-worker Dask LocalCluster, measured in one run (issue 17).

Prints datasets per second for each, the ratios to serial, checks that the three give
identical results, and the peak memory of the calling process (tracemalloc) for a small
and the full number of datasets, to show it does not grow with the data.

Run: ``python benchmarks/bench_campaign.py [--datasets 1000] [--no-dask]``.
"""

from __future__ import annotations

import argparse
import tempfile
import time
import tracemalloc
from pathlib import Path

import numpy as np
import pandas as pd

import frictionlaws as fl
from frictionlaws.campaign import fit_many

LAWS = ("thirion", "coulomb", "quadratic-pv")


def write_datasets(folder: Path, count: int) -> None:
    """``count`` CSV files of 24 rows each (p in MPa, v in m/s), Thirion-like with noise."""
    law = fl.get_law("thirion")
    rng = np.random.default_rng(0)
    p = np.repeat([0.03, 0.06, 0.12, 0.25], 6)
    v = np.tile([0.1, 0.3, 0.7, 1.4, 2.0, 2.8], 4)
    for i in range(count):
        a, b = rng.uniform(0.2, 0.5), rng.uniform(2e-6, 6e-6)
        mu = law(p=p * 1e6, a=a, b=b) + 0.02 * rng.standard_normal(p.size)
        pd.DataFrame({"mu": mu, "p [MPa]": p, "v [m/s]": v}).to_csv(
            folder / f"ds{i:05d}.csv", index=False)


def timed(label: str, count: int, **kw) -> tuple[float, pd.DataFrame]:
    t0 = time.perf_counter()
    frame = fit_many(LAWS, kw.pop("folder"), **kw).to_frame()
    dt = time.perf_counter() - t0
    print(f"{label:<28} {dt:7.2f} s  {count / dt:8.1f} datasets/s")
    return dt, frame


def peak_memory(folder: Path, output: Path | None) -> float:
    """Peak memory traced in the calling process during a serial campaign [MB]."""
    tracemalloc.start()
    fit_many(LAWS, folder, output=output)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak / 1e6


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--datasets", type=int, default=1000)
    ap.add_argument("--no-dask", action="store_true")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp) / "all"
        small = Path(tmp) / "small"
        folder.mkdir()
        small.mkdir()
        write_datasets(folder, args.datasets)
        write_datasets(small, max(args.datasets // 10, 10))
        print(f"{args.datasets} datasets x {len(LAWS)} laws ({', '.join(LAWS)})")
        t_serial, serial = timed("serial", args.datasets, folder=folder)
        # each parallel run is warmed up on a few datasets first (workers import the
        # library once), so the ratios compare steady-state throughput
        fit_many(LAWS, small, jobs=2)
        t_jobs, jobs = timed("jobs=2 (joblib, processes)", args.datasets, folder=folder, jobs=2)
        pd.testing.assert_frame_equal(serial, jobs)
        print(f"jobs=2 / serial throughput: {t_serial / t_jobs:.2f}x (target >= 1.7x); "
              "results identical")
        if not args.no_dask:
            from dask.distributed import LocalCluster

            with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                              dashboard_address=None) as cluster:
                fit_many(LAWS, small, scheduler=cluster.scheduler_address)
                t_dask, dask = timed("Dask LocalCluster, 2 workers", args.datasets,
                                     folder=folder, scheduler=cluster.scheduler_address)
            pd.testing.assert_frame_equal(serial, dask)
            print(f"dask / serial throughput: {t_serial / t_dask:.2f}x (target >= 1.7x); "
                  "results identical")
        n_small = len(list(small.glob("*.csv")))
        for label, out in (("held in memory", None), ("streamed to CSV", Path(tmp) / "o.csv")):
            few, many = peak_memory(small, out), peak_memory(folder, out)
            print(f"peak memory of the caller, results {label}: {few:.1f} MB for {n_small} "
                  f"datasets, {many:.1f} MB for {args.datasets}")


if __name__ == "__main__":
    main()
