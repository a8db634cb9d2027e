"""Benchmark: Magic Formula F_x0 on 1e6 points against a hand-written numpy expression.

Run: ``python benchmarks/bench_mf.py``.  Prints the time of
:meth:`frictionlaws.tyre.MagicFormula.fx0` and of a baseline written by hand
with the same equations (MF 6.2 example file, pure longitudinal slip, no
checks), measured in the same run, and their ratio (target: <= 2).  Two cases:
a scalar load with 1e6 slips, and 1e6 (slip, load) pairs.

A second part measures the overhead of ``Law.bind`` (the plain function used
inside the brush model) against calling the law's formula directly and against
the checked ``Law.__call__``, on small and large arrays.
"""

from __future__ import annotations

import timeit
import warnings
from pathlib import Path

import numpy as np

from frictionlaws.base.errors import ExtrapolationWarning
from frictionlaws.law import NUMPY
from frictionlaws.law.registry import get_law
from frictionlaws.tyre import MagicFormula

N = 1_000_000
ROOT = Path(__file__).resolve().parents[1]
FILE = ROOT / "datasets" / "mf-examples" / "MagicFormula62_Parameters.json"


def handwritten_fx0(kappa, fz, c, fz0, dpi=0.0):
    """F_x0 of MF 6.x typed out directly (scaling factors 1, no camber)."""
    dfz = (fz - fz0) / fz0
    mu = (c["PDX1"] + c["PDX2"] * dfz) * (1 + c["PPX3"] * dpi + c["PPX4"] * dpi**2)
    D = mu * fz
    C = c["PCX1"]
    K = fz * (c["PKX1"] + c["PKX2"] * dfz) * np.exp(c["PKX3"] * dfz) * (
        1 + c["PPX1"] * dpi + c["PPX2"] * dpi**2)
    B = K / (C * D + 1e-6)
    SH = c["PHX1"] + c["PHX2"] * dfz
    SV = fz * (c["PVX1"] + c["PVX2"] * dfz)
    x = kappa + SH
    E = np.minimum((c["PEX1"] + c["PEX2"] * dfz + c["PEX3"] * dfz**2)
                   * (1 - c["PEX4"] * np.sign(x)), 1.0)
    bx = B * x
    return D * np.sin(C * np.arctan(bx - E * (bx - np.arctan(bx)))) + SV


def best(func, number=3, repeat=5):
    return min(timeit.repeat(func, number=number, repeat=repeat)) / number


def bench_mf() -> None:
    mf = MagicFormula.from_file(FILE)
    c = mf.coefficients
    kappa = np.linspace(-1.0, 1.0, N)
    rng = np.random.default_rng(0)
    fz_arr = rng.uniform(2000.0, 8000.0, N)
    print(f"Magic Formula {mf.version} ({FILE.name}), F_x0 on {N:.0e} points")
    for label, fz in (("scalar load 4 kN", 4000.0), ("1e6 loads 2..8 kN", fz_arr)):
        with warnings.catch_warnings():
            warnings.simplefilter("error", ExtrapolationWarning)
            ours = mf.fx0(kappa, fz)
        ref = handwritten_fx0(kappa, fz, c, mf.fz0)
        err = float(np.max(np.abs(ours - ref)) / np.max(np.abs(ref)))
        t_ours = best(lambda fz=fz: mf.fx0(kappa, fz))
        t_ref = best(lambda fz=fz: handwritten_fx0(kappa, fz, c, mf.fz0))
        print(f"  {label:<18}: MagicFormula.fx0 {1e3 * t_ours:7.1f} ms, hand-written numpy "
              f"{1e3 * t_ref:7.1f} ms, ratio {t_ours / t_ref:.2f} (target <= 2; max rel. "
              f"difference {err:.1e})")


def bench_bind() -> None:
    law = get_law("thirion")
    params = {"a": 0.147, "b": 4.72e-6}
    bound = law.bind(params)
    formula = law.formula
    print("Law.bind overhead (thirion), per call")
    for n in (10, 401, N):
        p = np.linspace(0.0, 4e5, n)
        number = max(1, 200_000 // n)
        t_direct = best(lambda p=p: formula(NUMPY, p=p, **params), number=number)
        t_bound = best(lambda p=p: bound(p), number=number)
        t_call = best(lambda p=p: law(p=p, **params), number=number)
        print(f"  n = {n:>7}: formula {1e6 * t_direct:9.2f} us, bind {1e6 * t_bound:9.2f} us "
              f"(ratio {t_bound / t_direct:.2f}), law(...) {1e6 * t_call:9.2f} us "
              f"(ratio {t_call / t_direct:.2f})")


if __name__ == "__main__":
    bench_mf()
    bench_bind()
