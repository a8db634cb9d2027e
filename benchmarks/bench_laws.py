"""Benchmarks of the foundation, each printed as a ratio against a baseline from the same run.

1. Evaluation of every law on 1e6 points through ``law(...)`` against a hand-written numpy
   expression of the same formula (with the same floors).  Target: at most 1.2x.
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
from frictionlaws.validation.law_examples import EXAMPLES, NUMPY_M


def hand_written(law):
    """The law's independent reference form (frictionlaws/validation/law_examples.py) run
    on numpy arrays.

    The reference forms are written by hand from the catalogue, not from the law modules; the
    baseline applies the floors the law declares (|v|, v_min, p_min), as the law itself does.
    """
    example = EXAMPLES.get(law.id)
    if example is None:
        return None
    if example.baseline is not None:
        return example.baseline
    ref = example.reference

    def hand(x, q):
        args = {}
        for name in ref.variables:
            value = np.abs(x[name]) if name == "v" else x[name]
            floor = law.floors.get(name)
            args[name] = value if floor is None else np.maximum(value, floor)
        out = ref.func(NUMPY_M, **args, **q)
        return np.full(np.shape(next(iter(x.values()))), out) if not ref.variables else out

    return hand


def params_for(law):
    """The example table's true parameters (the test battery's) with the law's settings."""
    example = EXAMPLES.get(law.id)
    if example is not None:
        return law.resolve(dict(example.battery.params))
    if law.presets:
        return law.resolve(preset=next(iter(law.presets)))
    return law.resolve(law.defaults)


def points(law, n, rng):
    """``n`` points where the example table samples the law (log-uniform where it says)."""
    example = EXAMPLES.get(law.id)
    n = min(n, (example.bench_points if example and example.bench_points else n))
    ranges = dict(example.battery.ranges) if example else {}
    log = example.battery.log if example else ()
    out = {}
    for var in law.variables or ("p",):
        lo, hi = ranges.get(var, law.typical_range(var))
        if var in log:
            out[var] = np.exp(rng.uniform(np.log(lo), np.log(hi), n))
        else:
            out[var] = rng.uniform(lo, hi, n)
    return out


def best_time(f, repeat=7):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return min(times)


def paired_times(f, g, rounds=15, run=3):
    """Best times of ``f`` and ``g``, measured in alternating runs of ``run`` calls each.

    Alternating lets both see the same machine state; only the calls after the first
    of a run count, so each is timed after itself (a call right after the other one
    pays for the memory the other just released: the operating system maps it afresh).
    """
    tf, tg = [], []
    for _ in range(rounds):
        tf.extend(best_time(f, 1) for _ in range(run))
        tf.pop(-run)
        tg.extend(best_time(g, 1) for _ in range(run))
        tg.pop(-run)
    return min(tf), min(tg)


def cases(n, rng):
    """(law, hand-written baseline, points, parameters) for every law that has a baseline."""
    for law in fl.list_laws():
        hand = hand_written(law)
        if hand is None:
            print(f"{law.id:<22} no hand-written baseline")
            continue
        yield law, hand, points(law, n, rng), params_for(law)


def bench_evaluation(n, rng):
    print(f"\n1. evaluation on {n:.0e} points: law(...) vs hand-written numpy (target <= 1.2x)")
    print(f"{'law':<22} {'law [ms]':>9} {'numpy [ms]':>10} {'ratio':>6}")
    worst = 0.0
    for law, hand, x, q in cases(n, rng):
        kw = {**x, **q}
        np.testing.assert_allclose(law(**kw), hand(x, q), rtol=1e-10, atol=1e-12)
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
