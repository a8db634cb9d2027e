"""Peak memory of a 2e6-row fit against lmfit's leastsq on the same data.

Each side runs in its own subprocess: it builds the same synthetic thirion data (2e6 rows,
seeded), records the resident set size, fits, and reports the growth of the peak resident
set size (``ru_maxrss``) over the size after the data were built.  frictionlaws runs
``fit(..., weights=None)`` (diagnostics included); the baseline runs ``lmfit.minimize``
with ``method="leastsq"`` on a plain residual function from the law's own start.
Target: frictionlaws' growth at most 2x lmfit's.

Run: ``python benchmarks/bench_memory.py [--rows 2000000] [--law thirion]``.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys

CHILD = r"""
import json, resource, sys
import numpy as np
import frictionlaws as fl
from frictionlaws.validation.law_examples import EXAMPLES
side, law_id, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
law = fl.get_law(law_id)
ex = EXAMPLES[law_id].battery
rng = np.random.default_rng(0)
x = {}
for var, (lo, hi) in ex.ranges.items():
    x[var] = (np.exp(rng.uniform(np.log(lo), np.log(hi), n)) if var in ex.log
              else rng.uniform(lo, hi, n))
mu = law.evaluate(x, law.resolve({**ex.params, **ex.fix}))
mu = mu + 0.02 * np.mean(np.abs(mu)) * rng.standard_normal(n)
data = {**x, "mu": mu}
guess = law.initial_guess(data)
if side == "lmfit":
    import lmfit
names = [k for k in law.param_names if k not in ex.fix]
def rss():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
before = rss()
if side == "lmfit":
    params = lmfit.Parameters()
    for k in names:
        lo, hi = law.param(k).bounds
        params.add(k, value=guess[k], min=lo, max=hi)
    settings = {**law.setting_values, **ex.fix}
    def resid(p):
        return law.evaluate(x, {**settings, **p.valuesdict()}) - mu
    res = lmfit.minimize(resid, params, method="leastsq")
    chi = float(res.chisqr)
else:
    res = fl.fit(law_id, data, fix=dict(ex.fix), weights=None)
    chi = float(res.metrics["chisqr"])
print(json.dumps({"before": before, "peak": rss(), "chisqr": chi}))
"""


def run(side: str, law: str, n: int) -> dict[str, float]:
    out = subprocess.run([sys.executable, "-c", CHILD, side, law, str(n)], check=True,
                         capture_output=True, text=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", type=int, default=2_000_000)
    ap.add_argument("--law", default="thirion")
    args = ap.parse_args()
    fl_side = run("frictionlaws", args.law, args.rows)
    lm_side = run("lmfit", args.law, args.rows)
    data_mb = args.rows * 8 * 3 / 2**20
    print(f"{args.rows:.0e} rows of {args.law} (the data: about {data_mb:.0f} MB of arrays)")
    print(f"{'side':<14} {'RSS before [MB]':>15} {'peak [MB]':>10} {'growth [MB]':>12} "
          f"{'chi2':>12}")
    for name, r in (("frictionlaws", fl_side), ("lmfit leastsq", lm_side)):
        print(f"{name:<14} {r['before']:15.0f} {r['peak']:10.0f} "
              f"{r['peak'] - r['before']:12.0f} {r['chisqr']:12.6g}")
    ratio = (fl_side["peak"] - fl_side["before"]) / max(lm_side["peak"] - lm_side["before"],
                                                        1.0)
    print(f"growth ratio: {ratio:.2f}x (target <= 2x)")


if __name__ == "__main__":
    main()
