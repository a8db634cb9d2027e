"""Benchmark of ``fit_mf`` with combined slip and M_z on about 10,000 rows.

Data: :func:`frictionlaws.tyre.synthetic_rig.rig_data` of a tyre unlike the template
(:func:`~frictionlaws.tyre.synthetic_rig.moved_tyre`: the MF 6.1 example with 23
coefficients moved): 5 loads x 2 pressures x 3 cambers, slip sweeps up and down, a
combined grid, slip jitter, load drift, 1 % noise.

Baseline, in the same run: one plain :func:`scipy.optimize.least_squares` (trust-region
reflective, ``x_scale="jac"``, its defaults otherwise) of the same residuals (F_x, F_y and
M_z on every row, each divided by its largest measured magnitude) over the same
coefficients that ``fit_mf`` fitted, started from the template's values, with no stages.

Printed: wall time of each, and each result's largest error against the noise-free truth
(pure F_x0, F_y0 and combined F_x, F_y as a share of the curve's peak, M_z of the peak
|M_z|) at every load, camber and pressure.

Run: ``python benchmarks/bench_fit_mf.py [--n 68] [--seed 3]`` (n = 68 gives 9,960 rows).

``--seeds S ...`` fits the random tyres of those seeds, each measured with its own seed
(the held-out test's convention). ``--corpus N`` instead fits the rig data (31 points per
sweep) of ``N`` tyres drawn at random
(:func:`~frictionlaws.tyre.synthetic_rig.random_tyre`: the MF 6.1, 6.2 and 5.2 examples in
turn with their coefficients moved by up to 20 %, FNOMIN 3-9 kN, nominal pressure 180-320
kPa), each as its own version from the default template, and prints each tyre's largest
errors against its truth and the largest over the corpus.

``--seeds S ... --draws K`` fits each of those tyres to ``K`` noise draws of its rig data
(noise seeds 1..K) and prints, per tyre, each figure's mean and standard deviation over the
draws, the share of draws over the issue's line (:data:`LINES`), and the bias of the pure
curves: the largest mean signed error of F_x0 and F_y0 over the grid of
:func:`~frictionlaws.tyre.synthetic_rig.truth_errors`, with its standard error.  A miss the
noise explains has a mean error near zero; a bias does not.  The largest of the grid's
means is itself two or three standard errors from zero by chance: a bias is a mean that
stays as ``K`` grows.
"""

from __future__ import annotations

import argparse
import time
import warnings

import numpy as np
from scipy.optimize import least_squares

from frictionlaws.base.errors import ExtrapolationWarning
from frictionlaws.tyre import MagicFormula, fit_mf
from frictionlaws.tyre.mf.fit import FITTYPS
from frictionlaws.tyre.mf.fit.peak import FittingModel
from frictionlaws.tyre.mf.fit.stages import CombinedData, predict_fx, predict_fy, predict_mz
from frictionlaws.tyre.synthetic_rig import moved_tyre, random_tyre, rig_data, truth_errors


def plain_least_squares(data: object, names: list[str]) -> tuple[MagicFormula, float, int]:
    """One least-squares of every residual over ``names`` from the template's values."""
    tpl = MagicFormula.from_file("MagicFormula61")
    mf = FittingModel(dict(tpl.coefficients), fnomin=tpl.fnomin, version="6.1",
                      pressure=tpl.pressure, nominal_pressure=tpl.nominal_pressure,
                      structure=tpl.structure)
    sets = [(CombinedData.select(data, getattr(data, q), np.ones(len(data), bool),  # type: ignore[arg-type]
                                 tpl.nominal_pressure), f)
            for q, f in (("fx", predict_fx), ("fy", predict_fy), ("mz", predict_mz))]
    scales = [float(np.abs(d.target).max()) for d, _ in sets]

    def resid(p: np.ndarray) -> np.ndarray:
        mf.coefficients.update(zip(names, map(float, p)))
        with np.errstate(all="ignore"):
            r = np.concatenate([(f(mf, d) - d.target) / s for (d, f), s in zip(sets, scales)])
        return np.where(np.isfinite(r), r, 1e3)

    t0 = time.perf_counter()
    r = least_squares(resid, np.array([mf.coefficients.get(k, 0.0) for k in names]),
                      x_scale="jac")
    seconds = time.perf_counter() - t0
    resid(r.x)
    return MagicFormula(dict(mf.coefficients), fnomin=tpl.fnomin, version="6.1",
                        pressure=tpl.pressure, nominal_pressure=tpl.nominal_pressure,
                        structure=tpl.structure), seconds, int(r.nfev)


_QUANTITIES = ("Fx0", "Fy0", "Fx", "Fy", "Mz")
#: The accuracy line of the held-out check: largest error against the truth, share of peak.
LINES = {"Fx0": 0.005, "Fy0": 0.005, "Fx": 0.01, "Fy": 0.01, "Mz": 0.02}


def pure_errors(truth: MagicFormula, fitted: MagicFormula, name: str) -> np.ndarray:
    """Signed error of the fitted pure curve ``name`` ("Fx0" or "Fy0") against the truth,
    as a share of the true curve's peak, on the grid of ``truth_errors`` (loads x pressures
    x cambers x slips)."""
    x = name == "Fx0"
    slip = np.linspace(-0.25, 0.25, 101) if x else np.radians(np.linspace(-12, 12, 97))
    out = []
    for fz in truth.fnomin * np.array([0.4, 0.7, 1.0, 1.3, 1.6]):
        for p in (truth.nominal_pressure or 2.6e5) * np.array([0.85, 1.1]):
            for g in np.radians([-3.0, 0.0, 3.0]):
                t, f = (np.asarray((m.fx0 if x else m.fy0)(
                    slip, fz, g, p if m.nominal_pressure else None)) for m in (truth, fitted))
                out.append((f - t) / np.abs(t).max())
    return np.array(out)


def noise_draws(seeds: list[int], k: int) -> None:
    """Fit each tyre of ``seeds`` to ``k`` noise draws; print the figures' spread and the
    pure curves' bias."""
    fittyp = {v: k for k, v in FITTYPS.items() if k in (6, 61, 62)}
    for seed in seeds:
        truth = random_tyre(seed)
        errs, signed = [], []
        for noise in range(1, k + 1):
            t0 = time.process_time()
            res = fit_mf(rig_data(truth, seed=noise), fittyp=fittyp[truth.version])
            cpu = time.process_time() - t0
            errs.append(truth_errors(truth, res.model))
            signed.append([pure_errors(truth, res.model, q) for q in ("Fx0", "Fy0")])
            print(f"{seed:>4} noise {noise:>3} cpu {cpu:6.1f} s"
                  + "".join(f"{100 * errs[-1][q]:>7.2f}%" for q in _QUANTITIES), flush=True)
        print(f"tyre {seed} (MF {truth.version}), {k} draws: mean, SD and share over the line")
        for q in _QUANTITIES:
            v = 100 * np.array([e[q] for e in errs])
            print(f"  {q:>3}: {v.mean():.3f} % SD {v.std(ddof=1):.3f} %, over "
                  f"{100 * LINES[q]:g} %: {int((v > 100 * LINES[q]).sum())}/{k}")
        for i, q in enumerate(("Fx0", "Fy0")):
            e = 100 * np.array([s[i] for s in signed])
            mean, sd = e.mean(0), e.std(0, ddof=1)
            j = np.unravel_index(np.argmax(np.abs(mean)), mean.shape)
            print(f"  {q} bias: largest |mean error| {abs(mean[j]):.3f} % of peak (its standard "
                  f"error {sd[j] / np.sqrt(k):.3f} %, SD of one fit there {sd[j]:.3f} %)")


def corpus(draws: list[tuple[int, int]]) -> None:
    """Fit the rig data of random tyres, ``(tyre seed, noise seed)`` each; print each
    one's and the largest errors."""
    fittyp = {v: k for k, v in FITTYPS.items() if k in (6, 61, 62)}
    print(f"{'tyre':>4} {'MF':>4} {'FNOMIN':>7} {'p_nom':>7}{'seconds':>9}"
          + "".join(f"{k:>8}" for k in _QUANTITIES))
    worst = dict.fromkeys(_QUANTITIES, 0.0)
    for seed, noise in draws:
        truth = random_tyre(seed)
        data = rig_data(truth, seed=noise)
        t0 = time.perf_counter()
        res = fit_mf(data, fittyp=fittyp[truth.version])
        seconds = time.perf_counter() - t0
        e = truth_errors(truth, res.model)
        worst = {k: max(worst[k], e[k]) for k in _QUANTITIES}
        print(f"{seed:>4} {truth.version:>4} {truth.fnomin:>7.0f} "
              f"{(truth.nominal_pressure or 0) / 1e3:>7.0f}{seconds:>9.1f}"
              + "".join(f"{100 * e[k]:>7.2f}%" for k in _QUANTITIES), flush=True)
    print(f"{'worst':>37}" + "".join(f"{100 * worst[k]:>7.2f}%" for k in _QUANTITIES))
    print("errors: largest against the noise-free truth over the data's loads, pressures "
          "and cambers, share of the curve's peak (Mz: of the peak |Mz|); p_nom in kPa")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=68, help="points per pure-slip sweep")
    parser.add_argument("--seed", type=int, default=3)
    parser.add_argument("--corpus", type=int, default=0,
                        help="fit this many random tyres instead (accuracy over a corpus): "
                             "tyre seeds 0..N-1, noise seeds 100..")
    parser.add_argument("--draws", type=int, default=0, metavar="K",
                        help="with --seeds: fit each tyre to K noise draws (seeds 1..K) and "
                             "print the figures' spread and the pure curves' bias")
    parser.add_argument("--seeds", type=int, nargs="+", default=[], metavar="S",
                        help="fit the random tyres of these seeds instead, each measured "
                             "with its own seed as the noise seed (the held-out test's "
                             "tyres: 1001 1002 1003)")
    args = parser.parse_args()
    warnings.simplefilter("ignore", ExtrapolationWarning)
    if args.draws and not args.seeds:
        parser.error("--draws needs --seeds (the tyres whose noise is drawn again)")
    if args.draws:
        noise_draws(args.seeds, args.draws)
        return
    if args.corpus or args.seeds:
        corpus([(s, s) for s in args.seeds] or [(s, 100 + s) for s in range(args.corpus)])
        return
    truth = moved_tyre()
    data = rig_data(truth, n=args.n, seed=args.seed)
    print(f"rows: {len(data)} (Fx, Fy and Mz on every row)")
    t0 = time.perf_counter()
    res = fit_mf(data, fittyp=61, template="MagicFormula61")
    staged_s = time.perf_counter() - t0
    names = list(res.values)
    plain, plain_s, nfev = plain_least_squares(data, names)
    print(f"{len(names)} coefficients fitted")
    print(f"{'':42}{'seconds':>9}" + "".join(f"{k:>8}" for k in ("Fx0", "Fy0", "Fx", "Fy",
                                                                  "Mz")))
    for label, model, s in (("fit_mf (staged)", res.model, staged_s),
                            (f"plain least_squares ({nfev} evaluations)", plain, plain_s)):
        e = truth_errors(truth, model)
        print(f"{label:42}{s:>9.1f}" + "".join(f"{100 * e[k]:>7.2f}%"
                                               for k in ("Fx0", "Fy0", "Fx", "Fy", "Mz")))
    print("errors: largest against the noise-free truth, share of the curve's peak "
          "(Mz: of the peak |Mz|)")


if __name__ == "__main__":
    main()
