"""Benchmark of Persson's friction integral: mu(v) on 100 velocities.

The fast path (:func:`frictionlaws.persson.friction`: Gauss-Legendre panels in
ln q, spectral cumulative integral for G, tabulated angular integrals, all
velocities at once) against the baseline of the independent reference
implementation (``frictionlaws.validation.law_examples._persson``: one adaptive
ODE in ln q per velocity, fixed Gauss-Legendre angular integrals of the Prony
sum), timed on 10 of the velocities and scaled to 100.  Both use the packaged
tread compound on the asphalt-like surface; the largest relative difference is
printed with the times.  Target: 100 velocities in under 1 s.  The first call on a
material also builds its angular-integral tables; that cold call is timed too (in a
fresh process, before anything else touched the material).

The flash temperature (Persson 2006, :mod:`frictionlaws.persson.flash`): the
volume closure (the default) against the surface-flux closure shipped before it,
as the baseline, on the same 100 velocities from 10 um/s to 10 m/s at 20 degC,
0.2 MPa, in alternating runs (``bench_laws.paired_times``), best of each.

Run: ``python benchmarks/bench_persson.py``.
"""

from __future__ import annotations

import math
import time
import warnings
from typing import Any

import numpy as np
from bench_laws import best_time, paired_times

from frictionlaws.base.errors import ExtrapolationWarning
from frictionlaws.persson import TREAD_THERMAL, Flash, asphalt_like, friction, tread_compound
from frictionlaws.validation.law_examples import _persson


def main() -> None:
    t0 = time.perf_counter()
    mat = tread_compound()
    surf = asphalt_like(1e6)
    v = np.logspace(-8, 4, 100)
    T, p = 293.15, 2e5
    friction(mat, surf, v, T, p)
    cold = time.perf_counter() - t0
    times = []
    for _ in range(5):
        t0 = time.perf_counter()
        mu = friction(mat, surf, v, T, p)
        times.append(time.perf_counter() - t0)
    fast = min(times)
    sub = v[::10]
    t0 = time.perf_counter()
    ref = np.array([_persson(math, p, vi, T, surf.q1, 0.0, surf.q0, surf.H, 0.3e-3,
                             material=mat) for vi in sub])
    t_base = (time.perf_counter() - t0) * v.size / sub.size
    diff = float(np.max(np.abs(mu[::10] / ref - 1)))
    print(f"persson mu(v), 100 velocities: cold (material and tables built) {cold:.2f} s; "
          f"fast {fast * 1e3:.1f} ms; baseline (reference "
          f"ODE per velocity, 10 timed, scaled to 100) {t_base:.1f} s; ratio "
          f"{t_base / fast:.0f}x; largest relative difference {diff:.1e}; target under 1 s: "
          f"{'met' if fast < 1.0 else 'MISSED'}")
    bench_flash(mat, surf)


def bench_flash(mat: Any, surf: Any) -> None:
    """The volume closure against the surface-flux closure (the former default)."""
    v = np.logspace(-5, 1, 100)
    T, p = 293.15, 2e5
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        new, old = paired_times(
            lambda: friction(mat, surf, v, T, p, flash=TREAD_THERMAL),
            lambda: friction(mat, surf, v, T, p, flash=Flash(closure="surface-flux")),
            rounds=2, run=2)
        iso = best_time(lambda: friction(mat, surf, v, T, p), repeat=3)
    print(f"flash temperature, 100 velocities 10 um/s..10 m/s at 20 degC: volume closure "
          f"(default) {new * 1e3:.0f} ms; baseline surface-flux closure {old * 1e3:.0f} ms; "
          f"ratio {old / new:.2f}x; isothermal {iso * 1e3:.0f} ms")

if __name__ == "__main__":
    main()
