"""Benchmark of the adaptive export grid against evenly spaced grids.

For several laws and boxes, the adaptive grid (:func:`frictionlaws.fe_export.grid.
adaptive_grid`) and the baseline, the smallest evenly spaced grid meeting the same
tolerance (:func:`~frictionlaws.fe_export.grid.uniform_grid_for_tol`: per-variable
counts, each variable spaced as in the box, lin or log), are built in the same
run.  Both are then checked the same way (dense structured sample plus random
points, the solver's multilinear, end-held interpolation).  Printed: rows of each,
their ratio, the error each reaches, and the build times.

Run: ``python benchmarks/bench_export_grid.py [--tol 1e-3] [--quick]``.
"""

from __future__ import annotations

import argparse
import time

from frictionlaws import get_law
from frictionlaws.fe_export.grid import AxisSpec, adaptive_grid, uniform_grid_for_tol

CASES = [
    ("exponential-decay", {"mu_s": 1.2, "mu_d": 0.6, "v_c": 0.3, "delta": 1.0},
     [AxisSpec("v", 0.0, 3.0)]),
    ("thirion", {"a": 0.4, "b": 5e-6}, [AxisSpec("p", 1e3, 2e6)]),
    ("savkoor", {"mu_s": 0.5, "mu_m": 1.2, "h10": 0.4, "v_m": 0.01, "n": -0.1},
     [AxisSpec("p", 1e4, 1e6), AxisSpec("v", 1e-4, 10.0)]),
    ("burckhardt", "asphalt-dry", [AxisSpec("s", 0.0, 1.0), AxisSpec("v", 0.0, 40.0)]),
    ("pacejka", "dry", [AxisSpec("s", 0.0, 1.0)]),
    ("thesis-poly2", "steel", [AxisSpec("p", 0.03e6, 0.25e6), AxisSpec("v", 0.0, 2.77)]),
    ("park", {"n": 0.11, "mu_s": 0.5, "mu_m": 1.2, "h10": 0.3, "v_m": 0.01},
     [AxisSpec("p", 1e4, 1e6), AxisSpec("v", 1e-3, 10.0), AxisSpec("T", 253.15, 323.15)]),
]
QUICK = {"exponential-decay", "thirion", "savkoor", "pacejka"}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tol", type=float, default=1e-3, help="tolerance in mu (default 1e-3)")
    ap.add_argument("--quick", action="store_true", help="1D and 2D cases only")
    args = ap.parse_args()
    print(f"tolerance {args.tol:g} in mu; rows = table rows (grid points)")
    print(f"{'law':<18} {'box':<34} {'uniform':>9} {'adaptive':>9} {'ratio':>6} "
          f"{'err unif':>9} {'err adap':>9} {'t unif':>7} {'t adap':>7}")
    for law_id, values, specs in CASES:
        if args.quick and law_id not in QUICK:
            continue
        law = get_law(law_id)
        vals = law.resolve(None, values) if isinstance(values, str) else law.resolve(values)
        f = law.bind(vals)
        t0 = time.perf_counter()
        grid, err = adaptive_grid(f, specs, args.tol)
        t_adap = time.perf_counter() - t0
        t0 = time.perf_counter()
        ugrid, uerr = uniform_grid_for_tol(f, specs, args.tol, spacing="spec")
        t_unif = time.perf_counter() - t0
        box = " ".join(f"{s.name}:{s.lo:g}..{s.hi:g}({s.kind})" for s in specs)
        print(f"{law_id:<18} {box:<34} {ugrid.rows:>9} {grid.rows:>9} "
              f"{grid.rows / ugrid.rows:>6.2f} {uerr.max_abs:>9.2e} {err.max_abs:>9.2e} "
              f"{t_unif:>6.2f}s {t_adap:>6.2f}s")
        print(f"{'':<18} shapes: uniform {'x'.join(map(str, ugrid.shape))}, adaptive "
              f"{'x'.join(map(str, grid.shape))}")


if __name__ == "__main__":
    main()
