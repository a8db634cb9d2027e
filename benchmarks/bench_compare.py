"""Benchmark of ``frictionlaws.compare`` and its report on the packaged thesis-steel dataset.

Baseline, measured in the same run: one plain :func:`frictionlaws.fit` of every law
(the least any comparison must do).  A comparison refits each law once per
cross-validation fold and once per holdout split, so its cost in one process is close
to ``1 + K + splits`` baselines; ``jobs=2`` spreads those fits over two processes.
Printed, all from this one run:

* compare / one fit per law, serial and with ``jobs=2`` (target <= 2.5x);
* the overhead beyond the refits (plausibility scan, residual tests, bookkeeping);
* the report (six PNG figures, HTML, Markdown, JSON): wall and CPU seconds, the best
  and the median of ``--report-runs`` serial runs (target under 2.5 s
  wall), its ratio to the comparison, and its wall time with the figures drawn by
  ``jobs`` processes.

Wall times on a shared machine are noisy; the CPU seconds of the serial runs are
printed next to them.

Run: ``python benchmarks/bench_compare.py [--quick] [--jobs N] [--report-runs R]``
(``--quick``: five laws).
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from collections.abc import Callable
from typing import Any

from frictionlaws.comparison import compare
from frictionlaws.fitting import as_fit_data, fit
from frictionlaws.law.registry import list_laws

QUICK = ["coulomb", "thirion", "thesis-poly2", "thesis-poly3", "savkoor"]


def timed(func: Callable[[], Any]) -> tuple[Any, float, float]:
    """Run ``func``; return its value, wall seconds and CPU seconds of this process."""
    w0, c0 = time.perf_counter(), time.process_time()
    out = func()
    return out, time.perf_counter() - w0, time.process_time() - c0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="five laws instead of all")
    ap.add_argument("--jobs", type=int, default=2, help="processes of the parallel run")
    ap.add_argument("--report-runs", type=int, default=3, help="serial reports timed")
    args = ap.parse_args()
    data = as_fit_data("thesis-steel")
    laws = QUICK if args.quick else [
        law.id for law in list_laws("sliding") if all(v in data.variables for v in law.variables)]
    fit("coulomb", data)  # import lmfit/scipy outside the timings

    _, t_fit, c_fit = timed(lambda: [fit(law, data, on_invalid="drop") for law in laws])
    cmp, t_cmp, c_cmp = timed(lambda: compare(laws, data, progress=False))
    _, t_par, _ = timed(lambda: compare(laws, data, progress=False, jobs=args.jobs))
    refits = 1 + cmp.settings["folds"] + sum(1 for s in cmp.splits if s.usable)
    reports = []
    for _ in range(args.report_runs):  # the machine's noise: best and median of a few
        with tempfile.TemporaryDirectory() as tmp:
            reports.append(timed(lambda tmp=tmp: cmp.write_report(tmp))[1:])
    t_rep, c_rep = min(reports)
    t_rep_med = statistics.median(t for t, _ in reports)
    with tempfile.TemporaryDirectory() as tmp:  # the workers of compare(jobs) are reused
        _, t_rep_par, _ = timed(lambda: cmp.write_report(tmp, jobs=args.jobs))

    print(f"laws: {len(laws)} ({', '.join(laws)})")
    print(f"baseline, one fit per law:        {t_fit:8.2f} s wall  {c_fit:8.2f} s cpu")
    print(f"compare, serial ({refits} fits per law): {t_cmp:8.2f} s wall  {c_cmp:8.2f} s cpu"
          f"  ratio {t_cmp / t_fit:5.2f}x wall, {c_cmp / c_fit:5.2f}x cpu "
          f"(target <= 2.5x; refits alone {refits}x; overhead "
          f"{c_cmp / (refits * c_fit):4.2f}x)")
    print(f"compare, jobs={args.jobs}:                {t_par:8.2f} s wall"
          f"  ratio {t_par / t_fit:5.2f}x wall (target <= 2.5x)")
    print(f"report (figures, HTML, Markdown):  {t_rep:8.2f} s wall  {c_rep:8.2f} s cpu"
          f"  best of {len(reports)} (median {t_rep_med:.2f} s; target < 2.5 s wall); "
          f"ratio to the serial compare {t_rep / t_cmp:5.2f}x")
    print(f"report, figures with jobs={args.jobs}:      {t_rep_par:8.2f} s wall")


if __name__ == "__main__":
    main()
