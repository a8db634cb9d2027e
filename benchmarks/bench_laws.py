"""Benchmarks of the foundation, each printed as a ratio against a baseline from the same run.

1. Evaluation of every law on 1e6 points through ``law(...)`` against a hand-written numpy
   expression of the same formula (with the same floors).  Target: at most 1.3x.
2. Fit time per law with ``frictionlaws.fit`` (lmfit, diagnostics, identifiability check)
   against ``scipy.optimize.curve_fit`` of the hand-written expression on the same data.
3. CLI start-up (``python -m frictionlaws laws`` and ``--version``) against
   ``python -c "import lmfit"``.  Target: at most 1.5x.

Run: ``python benchmarks/bench_laws.py [--quick]``.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time

import numpy as np

import frictionlaws as fl
from frictionlaws.law import F_MIN, P_MIN, V_MIN

# Hand-written numpy expressions of each law (x: variables, q: parameters and settings).
# Written independently of the law modules, with the same floors the laws declare.
HAND = {
    "coulomb": lambda x, q: np.full_like(x["p"], q["mu0"]),
    "thirion": lambda x, q: 1.0 / (q["a"] + q["b"] * x["p"]),
    "schallamach": lambda x, q: q["mu_ref"] * (np.maximum(x["F_N"], F_MIN) / q["F_ref"])
    ** (-q["n"]),
    "denny": lambda x, q: 1.0 / (q["a"] * (1.0 + q["b"] * x["p"] / q["E_v"])),
    "exponential-decay": lambda x, q: q["mu_d"] + (q["mu_s"] - q["mu_d"])
    * np.exp(-((np.abs(x["v"]) / q["v_c"]) ** q["delta"])),
    "quadratic-pv": lambda x, q: q["c0"] + q["c1"] * x["p"] + q["c2"] * np.abs(x["v"])
    + q["c3"] * x["p"] * np.abs(x["v"]) + q["c4"] * x["p"] ** 2 + q["c5"] * np.abs(x["v"]) ** 2,
    "thesis-poly2": lambda x, q: q["a0"] + q["a1"] * (x["p"] / 1e6) + q["a2"] * (x["p"] / 1e6)
    ** 2 + q["a3"] * np.abs(x["v"]) + q["a4"] * np.abs(x["v"]) ** 2,
    "thesis-poly3": lambda x, q: q["a0"] + q["a1"] * (x["p"] / 1e6) + q["a2"] * (x["p"] / 1e6)
    ** 2 + q["a3"] * (x["p"] / 1e6) ** 3 + q["a4"] * np.abs(x["v"]) + q["a5"] * np.abs(x["v"])
    ** 2 + q["a6"] * np.abs(x["v"]) ** 3,
}


def _vf(x):
    """|v| floored at V_MIN, as the log-velocity laws declare."""
    return np.maximum(np.abs(x["v"]), V_MIN)


def _pf(x):
    """p floored at P_MIN, as the laws singular at p = 0 declare."""
    return np.maximum(x["p"], P_MIN)


def _bell(q, lv):
    return q["mu_s"] + (q["mu_m"] - q["mu_s"]) * np.exp(-(q["h10"] ** 2) * lv**2)


HAND.update({
    "savkoor": lambda x, q: (_pf(x) / q["p_ref"]) ** q["n"] * _bell(q, np.log10(_vf(x) / q["v_m"])),
    "nackenhorst": lambda x, q: q["A"] * (_pf(x) / q["p_ref"]) ** q["n"] + q["b0"]
    + q["b1"] * np.log(_vf(x) / q["v_ref"]) + q["b2"] * np.log(_vf(x) / q["v_ref"]) ** 2,
    "nackenhorst-thesis": lambda x, q: q["c1"] * (_pf(x) / q["c2"]) ** q["c3"]
    + q["c4"] * np.log(_vf(x) / q["c5"]) - q["c6"] * np.log(_vf(x) / q["c7"]),
    "huemer": lambda x, q: (q["alpha"] * (_pf(x) / q["p_ref"]) ** (q["n"] - 1.0) + q["beta"])
    / (1.0 + q["b"] * (_vf(x) / q["v_ref"]) ** (-1.0 / q["m_v"])
       + q["c"] * (_vf(x) / q["v_ref"]) ** (-2.0 / q["m_v"])),
    "wriggers": lambda x, q: (q["b"] / _pf(x)) * np.arctan(q["d"] * _pf(x))
    * (2.0 * np.abs(x["v"]) * q["a"] * _pf(x) / (x["v"] ** 2 + (q["a"] * _pf(x)) ** 2)) ** q["c"],
    "park": lambda x, q: (_pf(x) / q["p0"]) ** (-q["n"]) * _bell(
        q, np.log10(_vf(x) / q["v_m"])
        - q["C1"] * (x["T"] - q["T_ref"]) / (q["C2"] + x["T"] - q["T_ref"])),
    "pacejka": lambda x, q: q["D"] * np.sin(q["C"] * np.arctan(
        q["B"] * (x["s"] + q["S_h"]) - q["E"] * (q["B"] * (x["s"] + q["S_h"])
                                             - np.arctan(q["B"] * (x["s"] + q["S_h"])))))
    + q["S_v"],
    "burckhardt": lambda x, q: (q["c1"] * (1.0 - np.exp(-q["c2"] * x["s"])) - q["c3"] * x["s"])
    * np.exp(-q["c4"] * np.abs(x["v"])),
    "burckhardt-sqrt": lambda x, q: q["c1"] * np.sqrt(x["s"]) - q["c2"] * x["s"],
    "kiencke-daiss": lambda x, q: q["k_s"] * x["s"] / (q["c1"] * x["s"] ** 2 + q["c2"] * x["s"]
                                                      + 1.0),
    "germann": lambda x, q: q["a0"] + q["a1"] * x["s"] + q["a2"] * x["s"] ** 2,
})


def _persson(x, q):
    """The theory called directly (the law's own numerics: this measures the wrapper)."""
    from frictionlaws.persson import SelfAffine, default_material, friction

    surf = SelfAffine.from_rms(q["q0"], q["H"], q["h_rms"], q["q1"])
    return q["mu_a"] + friction(default_material(), surf, _vf(x), x["T"], _pf(x))


HAND["persson"] = _persson
#: Laws evaluated on fewer points (a numerical double integral: ~30 us a point).
MAX_POINTS = {"persson": 2000}


def params_for(law):
    """Preset (first) or defaults, plus settings."""
    if law.presets:
        return law.resolve(preset=next(iter(law.presets)))
    return law.resolve(law.defaults)


def points(law, n, rng):
    n = min(n, MAX_POINTS.get(law.id, n))
    out = {}
    for var in law.variables or ("p",):
        lo, hi = law.typical_range(var)
        out[var] = rng.uniform(lo, hi, n)
    return out


def best_time(f, repeat=7):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return min(times)


def paired_times(f, g, rounds=15):
    """Best times of ``f`` and ``g`` measured alternately, so both see the same machine state."""
    tf, tg = [], []
    for _ in range(rounds):
        tf.append(best_time(f, 1))
        tg.append(best_time(g, 1))
    return min(tf), min(tg)


def cases(n, rng):
    """(law, hand-written baseline, points, parameters) for every law that has a baseline."""
    for law in fl.list_laws():
        hand = HAND.get(law.id)
        if hand is None:
            print(f"{law.id:<22} no hand-written baseline")
            continue
        yield law, hand, points(law, n, rng), params_for(law)


def bench_evaluation(n, rng):
    print(f"\n1. evaluation on {n:.0e} points: law(...) vs hand-written numpy (target <= 1.3x)")
    print(f"{'law':<22} {'law [ms]':>9} {'numpy [ms]':>10} {'ratio':>6}")
    worst = 0.0
    for law, hand, x, q in cases(n, rng):
        kw = {**x, **q}
        np.testing.assert_allclose(law(**kw), hand(x, q), rtol=1e-10)
        t_law, t_hand = paired_times(lambda kw=kw, law=law: law(**kw),
                                     lambda x=x, q=q, hand=hand: hand(x, q))
        ratio = t_law / t_hand
        worst = max(worst, ratio)
        print(f"{law.id:<22} {t_law * 1e3:9.2f} {t_hand * 1e3:10.2f} {ratio:6.2f}")
    print(f"worst evaluation ratio: {worst:.2f}x")
    return worst


def bench_fit(rng, n=200):
    from scipy.optimize import curve_fit

    print(f"\n2. fit time on {n} synthetic points: frictionlaws.fit vs scipy curve_fit")
    print(f"{'law':<22} {'fit [ms]':>9} {'curve_fit [ms]':>14} {'ratio':>6}")
    ratios = []
    for law, hand, x, q in cases(n, rng):
        m = len(next(iter(x.values())))
        mu = np.broadcast_to(law(**x, **q), (m,))
        mu = mu + 0.02 * np.mean(np.abs(mu)) * rng.standard_normal(m)
        data = {**x, "mu": mu}
        names = list(law.param_names)
        settings = law.setting_values
        guess = law.initial_guess(data)
        lo = [law.param(k).bounds[0] for k in names]
        hi = [law.param(k).bounds[1] for k in names]
        p0 = [guess[k] for k in names]

        def model(_, *theta, x=x, names=names, settings=settings, hand=hand):
            return hand(x, {**settings, **dict(zip(names, theta))})

        def run_cf(model=model, p0=p0, mu=mu, lo=lo, hi=hi):
            curve_fit(model, None, mu, p0=p0, bounds=(lo, hi), maxfev=20000)

        t_fit = best_time(lambda law=law, data=data: fl.fit(law, data), repeat=3)
        t_cf = best_time(run_cf, repeat=3)
        ratios.append(t_fit / t_cf)
        print(f"{law.id:<22} {t_fit * 1e3:9.1f} {t_cf * 1e3:14.1f} {t_fit / t_cf:6.1f}")
    print(f"median fit-time ratio: {statistics.median(ratios):.1f}x (frictionlaws adds "
          "multi-start, covariance, identifiability and derived-quantity diagnostics)")


def bench_startup(repeat):
    print("\n3. CLI start-up vs `python -c \"import lmfit\"` (target <= 1.5x)")

    def timed(cmd):
        ts = []
        for _ in range(repeat):
            t0 = time.perf_counter()
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
            ts.append(time.perf_counter() - t0)
        return statistics.median(ts)

    base = timed([sys.executable, "-c", "import lmfit"])
    print(f"{'python -c import lmfit':<36} {base * 1e3:8.0f} ms  1.00")
    worst = 0.0
    for args in (["--version"], ["laws"], ["show", "thirion"]):
        t = timed([sys.executable, "-m", "frictionlaws", *args])
        worst = max(worst, t / base)
        print(f"{'frictionlaws ' + ' '.join(args):<36} {t * 1e3:8.0f} ms  {t / base:.2f}")
    print(f"worst start-up ratio: {worst:.2f}x")
    return worst


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer points and repeats")
    args = ap.parse_args()
    rng = np.random.default_rng(0)
    bench_evaluation(100_000 if args.quick else 1_000_000, rng)
    bench_fit(rng)
    bench_startup(3 if args.quick else 7)


if __name__ == "__main__":
    main()
