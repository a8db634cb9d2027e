"""Benchmark of ``frictionlaws.compare`` on the packaged thesis-steel dataset.

Baseline, measured in the same run: one plain :func:`frictionlaws.fit` of every law
(the least any comparison must do).  A comparison refits each law once per
cross-validation fold and once per holdout split, so its cost should be close to
``1 + K + splits`` baselines; everything beyond that (plausibility scan, residual
tests, bookkeeping) is overhead, printed as a ratio.  The report (six PNG figures,
HTML, Markdown) is timed against the comparison.

Run: ``python benchmarks/bench_compare.py [--quick]`` (``--quick``: five laws).
"""

from __future__ import annotations

import argparse
import tempfile
import time

from frictionlaws.comparison import compare
from frictionlaws.fitting import as_fit_data, fit
from frictionlaws.registry import list_laws

QUICK = ["coulomb", "thirion", "thesis-poly2", "thesis-poly3", "savkoor"]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="five laws instead of all")
    args = ap.parse_args()
    data = as_fit_data("thesis-steel")
    laws = QUICK if args.quick else [
        law.id for law in list_laws("sliding") if all(v in data.variables for v in law.variables)]
    fit("coulomb", data)  # import lmfit/scipy outside the timings

    t0 = time.perf_counter()
    for law in laws:
        fit(law, data, on_invalid="drop")
    t_fit = time.perf_counter() - t0

    t0 = time.perf_counter()
    cmp = compare(laws, data, progress=False)
    t_cmp = time.perf_counter() - t0
    refits = 1 + cmp.settings["folds"] + sum(1 for s in cmp.splits if s.usable)

    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        cmp.write_report(tmp)
        t_rep = time.perf_counter() - t0

    print(f"laws: {len(laws)} ({', '.join(laws)})")
    print(f"baseline, one fit per law:        {t_fit:8.2f} s")
    print(f"compare (fit + {cmp.settings['folds']} folds + "
          f"{refits - 1 - cmp.settings['folds']} holdouts): {t_cmp:8.2f} s  "
          f"ratio {t_cmp / t_fit:5.1f}x (expected about {refits}x from refits alone; "
          f"overhead {t_cmp / (refits * t_fit):4.2f}x)")
    print(f"report (figures, HTML, Markdown): {t_rep:8.2f} s  ratio to compare "
          f"{t_rep / t_cmp:5.2f}x")


if __name__ == "__main__":
    main()
