"""A campaign at scale: many small datasets x 3 laws (thirion, coulomb, quadratic-pv), the
campaign serially and on all local workers, beside a bare ``pandas.read_csv`` +
``scipy.optimize.curve_fit`` loop over the same files and laws, in the same run.

Each round times, one after the other:

* the bare loop: each file read with ``pandas.read_csv`` and the three laws fitted with
  ``curve_fit`` (plain numpy models, the laws' defaults as the start, no bounds: the
  fastest a user would write; no uncertainty, warnings or table);
* the campaign serially: ``fit_many(LAWS, folder)`` and its table (``to_frame()``);
* the campaign on all local workers (``jobs=-1``; the pool is started before the first
  round, so start-up is not timed), then once more for its memory (the sampling of the
  memory takes CPU time, so the timed run has none);
* reading every file with ``pandas.read_csv`` and with the library's reader
  (:func:`frictionlaws.io.load_dataset`, which also checks units, values and rows and
  converts to SI).

Printed per round and as medians over the rounds: wall times, the campaign's time
against the bare loop, the workers' speed-up over the serial campaign, the CPU time of
the calling process while the workers run (``time.process_time``, every thread of it)
against the serial wall time, and the peak memory (resident set, sampled every 20 ms) of
the calling process and of the workers (the timed bare loop and serial campaign sample
only the caller's own, a cheap read; the workers' memory is sampled in the untimed
repeat of the parallel run, as listing them costs the caller CPU). From the measured
speed-up ``S`` on ``p`` workers the serial fraction is ``e = (1/S - 1/p) / (1 - 1/p)``
(Karp-Flatt: everything that did not run in parallel, the caller's share, start-up of
chunks, the last chunk waiting, and on a shared machine the other processes' load), and
Amdahl's law projects ``1 / (e + (1 - e) / 16)`` for 16 workers; the caller's own CPU
share gives the bound that no number of workers passes. CPU times are printed too (the
serial campaign's, the workers' together and the busiest worker's): on a machine shared
with other users' sessions the scheduler gives each session a fair share, so the
wall-time speed-up of more workers stays near 1 while the others keep the cores busy,
and the serial CPU over the busiest worker's CPU (plus the caller's) is the speed-up a
free core per worker gives. The load average is printed before and after.

It checks (exit 1 otherwise) that the parallel campaign's table equals the serial one
(same shape, columns, types and a hash of every cell).
The targets of issue 39 (over 2000 datasets): campaign <= 1.0x the bare loop, 2 workers
>= 1.6x one, the caller's CPU <= 3 % of the serial time.

Run: ``python benchmarks/bench_campaign_scale.py [--n 100000] [--rounds 3]``
(``--n 2000`` for a quick run).
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import psutil
from scipy.optimize import curve_fit

import frictionlaws as fl
from frictionlaws.fitting.campaign import fit_many

LAWS = ("thirion", "coulomb", "quadratic-pv")
P_MPA = np.repeat([0.03, 0.06, 0.12, 0.25], 6)
V = np.tile([0.1, 0.3, 0.7, 1.4, 2.0, 2.8], 4)


def write_datasets(folder: Path, count: int) -> None:
    """``count`` CSV files of 24 rows (p in MPa, v in m/s), Thirion-like with 2 % noise
    (as ``benchmarks/bench_campaign.py`` writes them, without pandas: faster at scale)."""
    rng = np.random.default_rng(0)
    head = "mu,p [MPa],v [m/s]\n"
    cells = [f",{float(p)!r},{float(v)!r}\n" for p, v in zip(P_MPA, V)]
    for i in range(count):
        a, b = rng.uniform(0.2, 0.5), rng.uniform(2e-6, 6e-6)
        mu = 1.0 / (a + b * P_MPA * 1e6) + 0.02 * rng.standard_normal(P_MPA.size)
        (folder / f"ds{i:06d}.csv").write_text(
            head + "".join(repr(float(m)) + c for m, c in zip(mu, cells)))


def _thirion(p: np.ndarray, a: float, b: float) -> np.ndarray:
    return 1.0 / (a + b * p)


def _coulomb(p: np.ndarray, mu0: float) -> np.ndarray:
    return np.full_like(p, mu0)


def _quadratic_pv(x: tuple[np.ndarray, np.ndarray], *c: float) -> np.ndarray:
    p, v = x
    return c[0] + c[1] * p + c[2] * v + c[3] * p * v + c[4] * p**2 + c[5] * v**2


def bare_loop(files: list[Path]) -> int:
    """``read_csv`` and three ``curve_fit`` per file; the number of fits made."""
    starts = {law: [p.default for p in fl.get_law(law).params] for law in LAWS}
    done = 0
    for path in files:
        frame = pd.read_csv(path)
        p, v = frame["p [MPa]"].to_numpy() * 1e6, frame["v [m/s]"].to_numpy()
        mu = frame["mu"].to_numpy()
        curve_fit(_thirion, p, mu, p0=starts["thirion"])
        curve_fit(_coulomb, p, mu, p0=starts["coulomb"])
        curve_fit(_quadratic_pv, (p, v), mu, p0=starts["quadratic-pv"])
        done += 3
    return done


@dataclass
class Peak:
    """Peak resident memory [MB] of this process and of its workers, sampled."""

    caller: float = 0.0
    workers: float | None = None
    stop: threading.Event = field(default_factory=threading.Event)

    def sample(self) -> None:
        me = psutil.Process()
        while not self.stop.wait(0.02):
            try:
                self.caller = max(self.caller, me.memory_info().rss / 1e6)
                if self.workers is not None:  # listing the workers costs the caller CPU
                    kids = sum(c.memory_info().rss for c in me.children(recursive=True))
                    self.workers = max(self.workers, kids / 1e6)
            except psutil.Error:
                continue


@contextmanager
def peak_memory(workers: bool = False) -> Iterator[Peak]:
    """Sample the peak memory of this process (and of its workers, when ``workers``)."""
    peak = Peak(workers=0.0 if workers else None)
    thread = threading.Thread(target=peak.sample, daemon=True)
    thread.start()
    try:
        yield peak
    finally:
        peak.stop.set()
        thread.join()


@dataclass
class Round:
    """One round's measurements."""

    bare: float
    serial: float
    parallel: float
    caller_cpu: float
    caller_frame_cpu: float
    memory: dict[str, Peak]
    read_csv: float = 0.0
    load_dataset: float = 0.0
    #: CPU time [s] of the serial campaign, and of each worker in the parallel one.
    cpu_serial: float = 0.0
    cpu_workers: list[float] = field(default_factory=list)


def reading(files: list[Path]) -> tuple[float, float]:
    """Seconds to read every file with ``pandas.read_csv`` and with the library's reader
    (:func:`frictionlaws.io.load_dataset`: units, checks, SI)."""
    from frictionlaws.io import load_dataset

    t0 = time.perf_counter()
    for path in files:
        pd.read_csv(path)
    t1 = time.perf_counter()
    for path in files:
        load_dataset(path)
    return t1 - t0, time.perf_counter() - t1


def one_round(folder: Path, files: list[Path], jobs: int) -> tuple[Round, bool]:
    """Bare loop, serial campaign, parallel campaign; and whether the tables agree."""
    memory = {}
    with peak_memory() as memory["bare"]:
        t0 = time.perf_counter()
        bare_loop(files)
        bare = time.perf_counter() - t0
    with peak_memory() as memory["serial"]:
        cpu_serial, t0 = time.process_time(), time.perf_counter()
        frame = fit_many(LAWS, folder).to_frame()
        serial = time.perf_counter() - t0
        cpu_serial = time.process_time() - cpu_serial
    serial_table = digest(frame)  # not timed
    del frame
    workers0 = worker_cpu()
    cpu0, t0 = time.process_time(), time.perf_counter()  # the caller's CPU: no sampling
    camp = fit_many(LAWS, folder, jobs=jobs)
    cpu1 = time.process_time()
    frame = camp.to_frame()
    parallel = time.perf_counter() - t0
    cpu2 = time.process_time()
    workers = {pid: t - workers0.get(pid, 0.0) for pid, t in worker_cpu().items()}
    same = digest(frame) == serial_table
    del camp, frame
    with peak_memory(workers=True) as memory["parallel"]:  # again, for the memory
        fit_many(LAWS, folder, jobs=jobs).to_frame()
    return Round(bare, serial, parallel, cpu1 - cpu0, cpu2 - cpu1, memory,
                 *reading(files), cpu_serial=cpu_serial,
                 cpu_workers=sorted(workers.values(), reverse=True)), same


def worker_cpu() -> dict[int, float]:
    """CPU time [s] used so far by each worker process of this one, by pid."""
    out = {}
    for proc in psutil.Process().children(recursive=True):
        try:
            t = proc.cpu_times()
        except psutil.Error:
            continue
        out[proc.pid] = t.user + t.system
    return out


def digest(frame: pd.DataFrame) -> tuple[Any, ...]:
    """What two tables must share to be equal: shape, columns, dtypes and a hash of every
    cell (so the serial table need not be kept while the parallel one is made)."""
    cells = pd.util.hash_pandas_object(frame, index=False).to_numpy()
    return (frame.shape, tuple(frame.columns), tuple(map(str, frame.dtypes)),
            int(cells.sum()), int((cells * np.arange(1, cells.size + 1, dtype=np.uint64)).sum()))


def amdahl(speedup: float, workers: int, target: int = 16) -> tuple[float, float]:
    """Serial fraction (Karp-Flatt) of a measured speed-up, and Amdahl's projection."""
    if workers < 2:
        return float("nan"), float("nan")
    e = (1.0 / speedup - 1.0 / workers) / (1.0 - 1.0 / workers)
    e = min(max(e, 0.0), 1.0)
    return e, 1.0 / (e + (1.0 - e) / target)


def report(rounds: list[Round], workers: int, count: int) -> None:
    med = statistics.median
    bare = med(r.bare for r in rounds)
    serial = med(r.serial for r in rounds)
    parallel = med(r.parallel for r in rounds)
    ratio = med(r.serial / r.bare for r in rounds)
    speedup = med(r.serial / r.parallel for r in rounds)
    caller = med(r.caller_cpu / r.serial for r in rounds)
    frame_cpu = med(r.caller_frame_cpu for r in rounds)
    e, s16 = amdahl(speedup, workers)
    bound = 1.0 / (caller + (1.0 - caller) / 16)
    print(f"medians over {len(rounds)} round(s), {count} datasets x {len(LAWS)} laws:")
    print(f"  bare read_csv + curve_fit loop     {bare:8.2f} s  ({count / bare:7.0f} datasets/s)")
    print(f"  campaign, serial (with its table)  {serial:8.2f} s  ({count / serial:7.0f} "
          f"datasets/s)  {ratio:.2f}x the bare loop (target <= 1.0x)")
    print(f"  campaign, {workers} workers               {parallel:8.2f} s  "
          f"({count / parallel:7.0f} datasets/s)  {speedup:.2f}x serial (target >= 1.6x "
          "for 2)")
    read_csv = med(r.read_csv for r in rounds)
    reader = med(r.load_dataset / r.read_csv for r in rounds)
    print(f"  reading every file: pandas.read_csv {read_csv:.2f} s, the library's reader "
          f"(load_dataset) {reader:.2f}x that (target <= 1.0x)")
    with_table = med((r.caller_cpu + r.caller_frame_cpu) / r.serial for r in rounds)
    print(f"  caller's CPU while the workers fit  {100 * caller:6.2f} % of the serial time "
          f"(target <= 3 %); its table afterwards {1e3 * frame_cpu:.0f} ms CPU "
          f"({100 * with_table:.2f} % with the table)")
    for label in ("bare", "serial", "parallel"):
        peaks = [r.memory[label] for r in rounds]
        kids = [p.workers for p in peaks if p.workers is not None]
        print(f"  peak memory, {label:<8}  caller {max(p.caller for p in peaks):7.1f} MB"
              + (f", workers {max(kids):7.1f} MB" if kids else "") + " (resident, sampled)")
    busiest = med(r.cpu_serial / (r.cpu_workers[0] + r.caller_cpu + r.caller_frame_cpu)
                  for r in rounds if r.cpu_workers)
    spent = med(sum(r.cpu_workers) / r.cpu_serial for r in rounds if r.cpu_workers)
    print(f"  CPU time: the workers together spent {spent:.2f}x the serial campaign's CPU; "
          f"the serial CPU over the busiest worker's (plus the caller's) is {busiest:.2f}: "
          "the speed-up with a free core per worker")
    print(f"  Amdahl: serial fraction {e:.3f} from the speed-up on {workers} workers "
          f"(Karp-Flatt) -> {s16:.1f}x projected for 16 workers; the caller's share alone "
          f"({100 * caller:.2f} %) bounds 16 workers at {bound:.1f}x")


#: What each timed line runs (printed with the figures, so they say what they compare).
COMPARED = f"""compared, per round, on the same files:
  bare loop:          for each file: frame = pandas.read_csv(file); scipy.optimize.curve_fit(
                        model, x, frame['mu'], p0=law defaults) for each of {LAWS}
  campaign, serial:   frictionlaws.fitting.campaign.fit_many({LAWS}, folder).to_frame()
  campaign, workers:  fit_many({LAWS}, folder, jobs=JOBS).to_frame()
  reading:            pandas.read_csv(file) / frictionlaws.io.load_dataset(file), every file"""


def load_average() -> str:
    """The 1, 5 and 15 minute load averages (the other processes' share of the cores)."""
    return " ".join(f"{x:.2f}" for x in os.getloadavg())


def main() -> int:
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--n", type=int, default=100_000, help="datasets (default 1e5)")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--jobs", type=int, default=-1, help="workers (default: all local)")
    args = ap.parse_args()
    from frictionlaws.parallel import local_workers

    workers = local_workers(args.jobs)
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp) / "campaign"
        folder.mkdir()
        write_datasets(folder, args.n)
        files = sorted(folder.glob("*.csv"))
        warm = Path(tmp) / "warm"
        warm.mkdir()
        write_datasets(warm, 40)
        fit_many(LAWS, warm, jobs=args.jobs).to_frame()  # start the pool, import
        bare_loop(sorted(warm.glob("*.csv")))
        print(f"{args.n} datasets x {len(LAWS)} laws; {psutil.cpu_count()} cores, "
              f"{workers} workers; load average (1, 5, 15 min) {load_average()}", flush=True)
        print(f"run as: python {' '.join(sys.argv)}\n{COMPARED.replace('JOBS', str(args.jobs))}",
              flush=True)
        rounds, same = [], True
        for i in range(args.rounds):
            result, agree = one_round(folder, files, args.jobs)
            same &= agree
            rounds.append(result)
            print(f"round {i + 1}: bare {result.bare:.2f} s, serial {result.serial:.2f} s "
                  f"({result.serial / result.bare:.2f}x), {workers} workers "
                  f"{result.parallel:.2f} s ({result.serial / result.parallel:.2f}x), caller "
                  f"{100 * result.caller_cpu / result.serial:.2f} %; load "
                  f"{load_average()}", flush=True)
    report(rounds, workers, args.n)
    print(f"load average (1, 5, 15 min) at the end {load_average()}; tables "
          f"{'identical' if same else 'DIFFER'} serially and on the workers")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
