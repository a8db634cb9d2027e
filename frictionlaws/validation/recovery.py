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

from ..fitting import fit
from .law_examples import EXAMPLES
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


#: Law id -> :class:`RecoverySetup`, from the one example table
#: (:mod:`frictionlaws.validation.law_examples`: each entry's ``recovery`` or ``battery`` sampling).
RECOVERY_SETUPS: dict[str, RecoverySetup] = {
    law_id: RecoverySetup(ex.study.params, ex.study.ranges, ex.study.log, ex.study.fix,
                          not ex.recovery_identifiable)
    for law_id, ex in EXAMPLES.items()
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


def _measured(mu_true: np.ndarray, sigma: float, rng: np.random.Generator) -> np.ndarray:
    """mu with Gaussian noise, redrawn where it would be negative (a measured friction
    coefficient is >= 0, and fits refuse negative mu)."""
    y = mu_true + sigma * rng.standard_normal(mu_true.size)
    for _ in range(20):
        neg = y < 0
        if not neg.any():
            break
        y[neg] = mu_true[neg] + sigma * rng.standard_normal(int(neg.sum()))
    return np.maximum(y, 0.0)


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
            y = _measured(mu_true, sigma, rng)
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
