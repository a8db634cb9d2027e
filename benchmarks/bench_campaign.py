"""Campaign throughput: many synthetic datasets x 3 laws, serial vs 2 local processes vs a
2-worker Dask LocalCluster, measured in one run.

For each way of running it prints the wall time, datasets per second and the ratio to
the serial run of the same round, and the CPU time spent by the calling process and
all its worker processes (the CPU cost of the parallel machinery, which the load of
a shared machine does not change much).  The Dask cluster runs twice: with the
workers configured as :data:`frictionlaws.fitting.campaign.DASK_WORKER_CONFIG` recommends and
with Dask's defaults, to show what that configuration is worth.

It checks (and exits 1 otherwise) that every run gives the serial table exactly, and
that the peak memory of the calling process (tracemalloc), with the results streamed
to a CSV file, does not grow with the number of datasets (less than
``FLAT_BYTES_PER_DATASET`` per extra dataset: the list of file names), serially and
on Dask; serially the caller is the worker and holds one chunk of datasets
(:data:`frictionlaws.parallel.MAX_CHUNK`) at a time, so the small run has the
datasets of a chunk (the default ``--datasets`` is two chunks).  The peak with the
results held in memory (on Dask, where the caller does no fitting) is printed for
contrast.

Run: ``python benchmarks/bench_campaign.py [--datasets 1024] [--rounds 1] [--no-dask]
[--no-timing] [--no-memory]``.
"""

from __future__ import annotations

import argparse
import contextlib
import sys
import tempfile
import time
import tracemalloc
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import psutil

import frictionlaws as fl
from frictionlaws.fitting.campaign import DASK_WORKER_CONFIG, fit_many
from frictionlaws.parallel import MAX_CHUNK

LAWS = ("thirion", "coulomb", "quadratic-pv")
#: Growth of the caller's peak memory per extra dataset still called flat: the sorted
#: list of dataset files (a path and a small job record each) is all that may grow.
FLAT_BYTES_PER_DATASET = 2000
TARGET = 1.7


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


def cpu_seconds() -> dict[int, float]:
    """CPU time [s] used so far by this process and each of its descendants, by pid."""
    me = psutil.Process()
    out = {}
    for proc in [me, *me.children(recursive=True)]:
        with contextlib.suppress(psutil.Error):
            t = proc.cpu_times()
            out[proc.pid] = t.user + t.system
    return out


@dataclass
class Run:
    """One timed campaign: wall time [s], CPU time of caller and workers [s], its table."""

    label: str
    wall: float
    cpu: float
    frame: pd.DataFrame


def timed(label: str, folder: Path, count: int, **kw: Any) -> Run:
    """Fit the laws to every dataset of ``folder`` and time it (results as a frame)."""
    before = cpu_seconds()
    t0 = time.perf_counter()
    frame = fit_many(LAWS, folder, **kw).to_frame()
    wall = time.perf_counter() - t0
    after = cpu_seconds()
    cpu = sum(t - before.get(pid, 0.0) for pid, t in after.items())
    print(f"  {label:<34} {wall:7.2f} s  {count / wall:7.1f} datasets/s  "
          f"CPU {1e3 * cpu / count:6.1f} ms/dataset", flush=True)
    return Run(label, wall, cpu, frame)


def peak_memory(folder: Path, **kw: Any) -> float:
    """Peak memory traced in the calling process during a campaign [MB]."""
    tracemalloc.start()
    try:
        fit_many(LAWS, folder, **kw)
        return tracemalloc.get_traced_memory()[1] / 1e6
    finally:
        tracemalloc.stop()


@contextlib.contextmanager
def local_cluster(config: dict[str, Any]) -> Iterator[str]:
    """A 2-worker, 1-thread-each LocalCluster started with ``config``; its address."""
    import dask
    from dask.distributed import LocalCluster

    with dask.config.set(config), LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True,
            dashboard_address=None) as cluster:
        yield cluster.scheduler_address


def one_round(folder: Path, warm: Path, count: int, dask: bool) -> list[Run]:
    """Serial, jobs=2 and (with ``dask``) the two LocalClusters, one after the other.

    Each parallel run is warmed up first on a few datasets (the workers import the
    library once), so the ratios compare steady-state throughput.
    """
    runs = [timed("serial", folder, count)]
    fit_many(LAWS, warm, jobs=2)
    runs.append(timed("jobs=2 (joblib processes)", folder, count, jobs=2))
    if dask:
        for label, config in (("Dask LocalCluster 2x1, recommended", DASK_WORKER_CONFIG),
                              ("Dask LocalCluster 2x1, Dask defaults", {})):
            with local_cluster(config) as address:
                fit_many(LAWS, warm, scheduler=address)
                runs.append(timed(label, folder, count, scheduler=address))
    return runs


def report_round(runs: list[Run]) -> dict[str, float]:
    """Print each parallel run's throughput and CPU vs serial; check identical tables."""
    serial = runs[0]
    ratios = {}
    for run in runs[1:]:
        pd.testing.assert_frame_equal(serial.frame, run.frame)
        ratios[run.label] = serial.wall / run.wall
        print(f"  {run.label:<34} throughput {ratios[run.label]:.2f}x serial "
              f"(target >= {TARGET}x), CPU {run.cpu / serial.cpu:.2f}x serial; "
              "results identical")
    return ratios


def memory_checks(folder: Path, small: Path, tmp: Path, counts: tuple[int, int],
                  dask: bool) -> bool:
    """Peak memory of the caller for few and many datasets; True when flat."""
    out = tmp / "streamed.csv"
    cases: list[tuple[str, dict[str, Any], bool]] = [
        ("serial, streamed to CSV", {"output": out}, True)]
    flat = True
    with contextlib.ExitStack() as stack:
        if dask:
            address = stack.enter_context(local_cluster(DASK_WORKER_CONFIG))
            fit_many(LAWS, small, scheduler=address)
            cases += [("Dask, streamed to CSV", {"output": out, "scheduler": address}, True),
                      ("Dask, held in memory", {"scheduler": address}, False)]
        for label, kw, must_be_flat in cases:
            fit_many(LAWS, small, **kw)  # imports and one-time caches are not counted
            few, many = peak_memory(small, **kw), peak_memory(folder, **kw)
            per = (many - few) * 1e6 / (counts[1] - counts[0])
            ok = per < FLAT_BYTES_PER_DATASET
            flat &= ok or not must_be_flat
            verdict = ("flat" if ok else "NOT FLAT") if must_be_flat else "grows with results"
            print(f"  {label:<26} {few:6.1f} MB for {counts[0]} datasets, {many:6.1f} MB "
                  f"for {counts[1]}: {per:7.0f} B per extra dataset ({verdict})")
    return flat


def main() -> int:
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--datasets", type=int, default=2 * MAX_CHUNK)
    ap.add_argument("--rounds", type=int, default=1,
                    help="repeat the timed runs (shows the noise of a shared machine)")
    ap.add_argument("--no-dask", action="store_true")
    ap.add_argument("--no-timing", action="store_true",
                    help="only the memory checks")
    ap.add_argument("--no-memory", action="store_true",
                    help="only the timed runs")
    args = ap.parse_args()
    # a worker holds one chunk of datasets (MAX_CHUNK): serially, flat means beyond that
    n_small = min(MAX_CHUNK, args.datasets // 2)
    with tempfile.TemporaryDirectory() as tmp_name:
        tmp = Path(tmp_name)
        folder, small = tmp / "all", tmp / "small"
        folder.mkdir()
        small.mkdir()
        write_datasets(folder, args.datasets)
        write_datasets(small, n_small)
        print(f"{args.datasets} datasets x {len(LAWS)} laws ({', '.join(LAWS)}); "
              f"{psutil.cpu_count()} cores, load average {psutil.getloadavg()[0]:.1f}")
        table: list[dict[str, float]] = []
        for i in range(0 if args.no_timing else args.rounds):
            print(f"round {i + 1}:")
            table.append(report_round(one_round(folder, small, args.datasets,
                                                not args.no_dask)))
        if len(table) > 1:
            for label in table[0]:
                values = [r[label] for r in table]
                print(f"{label}: throughput vs serial {min(values):.2f}x .. "
                      f"{max(values):.2f}x over {args.rounds} rounds")
        if args.no_memory:
            return 0
        print(f"peak memory of the calling process (load average "
              f"{psutil.getloadavg()[0]:.1f}):")
        flat = memory_checks(folder, small, tmp, (n_small, args.datasets), not args.no_dask)
    return 0 if flat else 1


if __name__ == "__main__":
    sys.exit(main())
