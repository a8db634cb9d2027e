"""Parameter recovery study: synthetic data from the reference implementations.

For every law, data are generated with the *independent* reference
implementation (:mod:`frictionlaws.validation.reference`), not with the law
itself, at known parameters, with Gaussian noise of a given level (standard
deviation = level x mean |mu| of the sample), for several noise levels and
sample sizes.  The library's fitter then has to recover the parameters: each
estimate is compared with the truth in units of its own standard error, and the
coverage of the 95 % intervals (the fraction that contain the true value) is
reported.  A law whose evaluation differs from its published form is fitted to
data it cannot reproduce and fails here as well.
"""

from __future__ import annotations

import math
import zlib
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .reference import REFERENCES, evaluate_reference

__all__ = ["RecoverySetup", "RECOVERY_SETUPS", "NOISE_LEVELS", "SAMPLE_SIZES", "Z_LIMIT",
           "COVERAGE_MIN", "recover_law"]

#: Relative noise levels (standard deviation / mean |mu|).
NOISE_LEVELS = (0.005, 0.02, 0.05)
#: Sample sizes.
SAMPLE_SIZES = (20, 80)
#: An estimate further than this many standard errors from the truth fails.
#: (At the nominal level a |z| above 5 happens by chance about once in 1.7
#: million estimates; a biased law or a wrong standard error shows far sooner.)
Z_LIMIT = 5.0
#: Minimum coverage of the nominal 95 % intervals, per noise level and sample
#: size over all laws (about 100 intervals each: 0.80 is 6 binomial standard
#: deviations below 0.95, so only a real miscalibration fails it).
COVERAGE_MIN = 0.80


@dataclass(frozen=True)
class RecoverySetup:
    """True parameters and sampling ranges of one law.

    Parameters
    ----------
    params : dict
        True parameter values (library names, SI); settings keep the law's values.
    ranges : dict
        Variable -> (low, high) in SI.
    log : tuple of str
        Variables drawn log-uniformly.
    fix : dict
        Parameters held at their true value in the fit.
    not_identifiable : bool
        The catalogue says the form cannot be identified: the fitter must name
        non-identifiable parameters and the curve (not the parameters) is checked.
    """

    params: Mapping[str, float]
    ranges: Mapping[str, tuple[float, float]]
    log: tuple[str, ...] = ()
    fix: Mapping[str, float] = field(default_factory=dict)
    not_identifiable: bool = False


_PV = {"p": (2e4, 1e6), "v": (1e-3, 10.0)}

RECOVERY_SETUPS: dict[str, RecoverySetup] = {
    "coulomb": RecoverySetup({"mu0": 0.9}, {}),
    "thirion": RecoverySetup({"a": 0.3, "b": 3e-6}, {"p": (2e4, 1e6)}),
    "schallamach": RecoverySetup({"mu_ref": 2.0, "n": 0.25}, {"F_N": (2.0, 200.0)},
                                 log=("F_N",)),
    "denny": RecoverySetup({"a": 2.0, "b": 15.0}, {"p": (1e4, 2e6)}),
    "exponential-decay": RecoverySetup({"mu_s": 1.2, "mu_d": 0.6, "v_c": 0.3, "delta": 1.3},
                                       {"v": (1e-3, 10.0)}, log=("v",)),
    "quadratic-pv": RecoverySetup({"c0": 1.2, "c1": -1.5e-6, "c2": 0.08, "c3": 2e-7,
                                   "c4": 8e-13, "c5": -0.015},
                                  {"p": (5e4, 1e6), "v": (0.0, 3.0)}),
    "thesis-poly2": RecoverySetup({"a0": 5.18, "a1": -59.2, "a2": 220.0, "a3": 1.05,
                                   "a4": -0.303}, {"p": (0.03e6, 0.25e6), "v": (0.0, 2.77)}),
    "thesis-poly3": RecoverySetup({"a0": 6.28, "a1": -108.0, "a2": 809.0, "a3": -2090.0,
                                   "a4": 0.158, "a5": 0.669, "a6": -0.235},
                                  {"p": (0.03e6, 0.25e6), "v": (0.0, 2.77)}),
    "savkoor": RecoverySetup({"mu_s": 0.4, "mu_m": 1.2, "h10": 0.4, "v_m": 0.01, "n": -0.2},
                             {"p": (2e4, 1e6), "v": (1e-6, 10.0)}, log=("p", "v")),
    "nackenhorst": RecoverySetup({"A": 0.3, "n": -0.5, "b0": 0.6, "b1": 0.02, "b2": -0.002},
                                 _PV, log=("p", "v")),
    "nackenhorst-thesis": RecoverySetup({"c1": 0.3, "c2": 1e5, "c3": -0.5, "c4": 0.05,
                                         "c5": 1.0, "c6": 0.03, "c7": 0.1},
                                        _PV, log=("p", "v"), not_identifiable=True),
    "huemer": RecoverySetup({"alpha": 0.1, "beta": 0.5, "n": 0.5, "m_v": 2.0, "b": 0.5,
                             "c": 0.2}, {"p": (1e4, 1e7), "v": (1e-4, 10.0)},
                            log=("p", "v")),
    "wriggers": RecoverySetup({"a": 1e-6, "b": 1e5, "c": 0.5, "d": 1e-5},
                              {"p": (2e4, 1e6), "v": (1e-4, 10.0)}, log=("p", "v")),
    "park": RecoverySetup({"n": 1 / 9, "mu_s": 0.4, "mu_m": 1.2, "h10": 0.4, "v_m": 0.01},
                          {"p": (2e4, 1e6), "v": (1e-5, 10.0), "T": (233.15, 313.15)},
                          log=("p", "v")),
    "persson": RecoverySetup({"q1": 3e5, "mu_a": 0.3},
                             {"p": (2e4, 1e6), "v": (1e-5, 10.0), "T": (263.15, 333.15)},
                             log=("p", "v")),
    "pacejka": RecoverySetup({"B": 10.0, "C": 1.9, "D": 1.0, "E": 0.5},
                             {"s": (0.0, 1.0)}, fix={"S_h": 0.0, "S_v": 0.0}),
    "burckhardt": RecoverySetup({"c1": 1.2801, "c2": 23.99, "c3": 0.52, "c4": 0.03},
                                {"s": (0.0, 1.0), "v": (0.0, 40.0)}),
    "burckhardt-sqrt": RecoverySetup({"c1": 2.5, "c2": 2.5}, {"s": (0.0, 1.0)}),
    "kiencke-daiss": RecoverySetup({"k_s": 20.0, "c1": 30.0, "c2": 5.0}, {"s": (0.0, 1.0)}),
    "germann": RecoverySetup({"a0": 0.0, "a1": 8.0, "a2": -15.0}, {"s": (0.0, 0.3)}),
}


@dataclass
class FitOutcome:
    """One fit of the study."""

    noise: float
    n: int
    success: bool
    z: dict[str, float]
    covered: dict[str, bool]
    non_identifiable: list[str]
    curve_rmse: float
    sigma: float
    error: str | None = None


def _sample(setup: RecoverySetup, n: int, rng: np.random.Generator) -> dict[str, np.ndarray]:
    out = {}
    for var, (lo, hi) in setup.ranges.items():
        if var in setup.log:
            out[var] = np.exp(rng.uniform(math.log(lo), math.log(hi), n))
        else:
            out[var] = rng.uniform(lo, hi, n)
    return out


def _seed(law_id: str, k: int) -> int:
    return zlib.crc32(law_id.encode()) + 7919 * k


def recover_law(law: Any, setup: RecoverySetup, *, noise_levels: Sequence[float] = NOISE_LEVELS,
                sizes: Sequence[int] = SAMPLE_SIZES, starts: int = 0) -> list[FitOutcome]:
    """Fit ``law`` to reference-generated data at each noise level and sample size.

    Parameters
    ----------
    law : Law
        The library's law under test.
    setup : RecoverySetup
        Truth and sampling.
    noise_levels, sizes : sequences
        The grid of the study.
    starts : int
        Extra random starts of the fitter (kept small: the study must be quick).

    Returns
    -------
    list of FitOutcome
    """
    from ..fitting import fit

    ref = REFERENCES[law.id]
    settings = dict(law.setting_values)
    truth = {**settings, **setup.params, **setup.fix}
    outcomes = []
    k = 0
    for n in sizes:
        for noise in noise_levels:
            k += 1
            rng = np.random.default_rng(_seed(law.id, k))
            if setup.ranges:
                x = _sample(setup, n, rng)
            else:
                x = {}
            mu_true = np.array([
                evaluate_reference(ref, {v: float(x[v][i]) for v in ref.variables}, truth,
                                   precise=False) for i in range(n)])
            sigma = noise * float(np.mean(np.abs(mu_true)))
            y = mu_true + sigma * rng.standard_normal(n)
            try:
                res = fit(law, {"mu": y, **x}, fix=dict(setup.fix), weights=None,
                          starts=starts, seed=k)
            except Exception as exc:  # noqa: BLE001 - reported as a failed fit
                outcomes.append(FitOutcome(noise, n, False, {}, {}, [], math.nan, sigma,
                                           f"{type(exc).__name__}: {exc}"))
                continue
            z, covered = {}, {}
            for name, est in res.params.items():
                if est.fixed or name not in setup.params:
                    continue
                t = setup.params[name]
                if est.stderr is not None and est.stderr > 0 and math.isfinite(est.stderr):
                    z[name] = (est.value - t) / est.stderr
                else:
                    z[name] = math.nan
                covered[name] = bool(est.ci95 is not None and est.ci95[0] <= t <= est.ci95[1])
            pred = np.asarray(res.law.evaluate(x, res.values) if x else
                              np.full(n, res.law.evaluate({}, res.values)), float)
            rmse = float(np.sqrt(np.mean((pred - mu_true) ** 2)))
            outcomes.append(FitOutcome(noise, n, bool(res.success), z, covered,
                                       list(res.non_identifiable), rmse, sigma))
    return outcomes
