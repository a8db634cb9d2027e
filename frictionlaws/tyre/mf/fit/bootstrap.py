"""Standard errors of a Magic Formula fit by resampling whole sweeps.

The asymptotic standard errors of :func:`~frictionlaws.tyre.mf.fit.fit_mf` (Gauss-Newton,
``s^2 (J^T J)^-1``) assume independent residuals.  A rig's residuals are not: within a
sweep they share the sweep's offsets (a slip-angle zero, a load drift, the tyre's wear
and temperature), so a misfit repeats along the whole sweep and the asymptotic errors
are too small.  The sweep bootstrap keeps each sweep whole:

1. **sweeps** are found in the row order (:func:`find_sweeps`): a new sweep starts
   where the load, pressure or camber level changes, where the slips jump by more
   than :data:`SWEEP_JUMP` of their measured range (at least :data:`SWEEP_REACH`: a
   channel that only jitters starts no sweep), and at the turning point of an
   up-and-down sweep; or they are given (``sweeps=`` labels);
2. **strata**: the sweeps are grouped by kind (slip ratio or slip angle swept, near
   pure slip or at a combined slip) and load level; each resample draws, within every
   stratum, as many sweeps as it has, with replacement, so that every load and kind
   stays in the design;
3. **refit from the point estimate**: on each resample the final stages (the
   forces F_x, F_y with their pure and combined coefficients on every row, or on the
   rows near pure slip without combined-slip rows (as the fit,
   :func:`~frictionlaws.tyre.mf.fit.stages.together_rows`), then
   M_z with M_z0 and the SSZ terms) are refitted, starting at the fitted values,
   with the same free coefficients;
4. the standard error of each coefficient is the standard deviation of its
   resampled values.

Resamples are seeded from one seed (:class:`numpy.random.SeedSequence`), so the
result is the same serially and on any number of workers
(:func:`frictionlaws.parallel.run_parallel`).
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ....base.errors import InputError
from ....fitting.resampling import check_can_vary, spread_errors, withheld_message
from ....parallel import check_jobs, run_parallel
from .peak import FittingModel
from .stages import (
    ALPHA_PURE,
    KAPPA_PURE,
    CombinedData,
    load_levels,
    predict_fx,
    predict_fy,
    predict_mz,
    solve,
    together_rows,
)

__all__ = ["find_sweeps", "sweep_bootstrap", "check_options", "SWEEP_JUMP", "SWEEP_REACH",
           "DEFAULT_RESAMPLES", "MIN_MEDIAN_SWEEP", "check_can_resample", "STRATA"]

#: A step of (kappa, alpha), each as a share of its measured range, larger than this
#: starts a new sweep.
SWEEP_JUMP = 0.2
#: The least range a swept slip ratio and slip angle [rad] have: a channel that moves less
#: only jitters (a slip angle held at zero in a slip-ratio sweep), and its steps are taken
#: as shares of this range, not of its own.
SWEEP_REACH = (0.05, math.radians(2.0))
#: Resamples of the sweep bootstrap unless told otherwise.
DEFAULT_RESAMPLES = 100
#: Rows in order have sweeps of at least this median length; shorter means the rows
#: are not in the order measured (the sweeps must then be given).
MIN_MEDIAN_SWEEP = 5


def _labels(values: np.ndarray, tol: float) -> np.ndarray:
    order = np.argsort(values)
    out = np.empty(values.size, dtype=int)
    out[order] = np.concatenate([[0], np.cumsum(np.diff(values[order]) > tol)])
    return out


def find_sweeps(data: Any) -> np.ndarray:
    """A sweep label for each row of ``data``, in the row order (module notes, step 1).

    Raises
    ------
    InputError
        When the sweeps found have a median length under :data:`MIN_MEDIAN_SWEEP`
        rows: the rows are not in the order they were measured.
    """
    n = len(data)
    p = np.where(np.isfinite(data.pressure), data.pressure, 0.0)
    condition = np.stack([load_levels(data.fz),
                          _labels(p, 0.02 * max(float(np.median(p)), 1.0)),
                          _labels(data.gamma, math.radians(0.2))], axis=1)
    span_k = max(float(np.ptp(data.kappa)), SWEEP_REACH[0])
    span_a = max(float(np.ptp(data.alpha)), SWEEP_REACH[1])
    step = np.hypot(np.diff(data.kappa) / span_k, np.diff(data.alpha) / span_a)
    starts = np.flatnonzero((step > SWEEP_JUMP) | np.any(np.diff(condition, axis=0) != 0,
                                                         axis=1)) + 1
    bounds = [0, *starts.tolist(), n]
    cuts: list[int] = []
    for a, b in zip(bounds[:-1], bounds[1:]):
        cuts.extend(_turns(data.kappa[a:b] / span_k, data.alpha[a:b] / span_a, a))
    edges = np.sort(np.array([*bounds[1:-1], *cuts], dtype=int))
    labels = np.zeros(n, dtype=int)
    labels[edges] = 1
    labels = np.cumsum(labels)
    lengths = np.bincount(labels)
    if float(np.median(lengths)) < MIN_MEDIAN_SWEEP:
        raise InputError(
            f"the sweep bootstrap found sweeps of median length {np.median(lengths):g} rows "
            "in the row order: the rows are not in the order measured (sorted or "
            "shuffled); give each row's sweep (sweeps=...) or use the asymptotic "
            "standard errors", file=data.source)
    return labels


def _turns(k: np.ndarray, a: np.ndarray, offset: int) -> list[int]:
    """Rows where an up-and-down run turns (the extreme of its swept slip)."""
    v = k if np.ptp(k) >= np.ptp(a) else a
    if v.size < 2 * MIN_MEDIAN_SWEEP:
        return []
    for i in (int(np.argmax(v)), int(np.argmin(v))):
        if 2 < i < v.size - 3:
            return [*_turns(k[:i + 1], a[:i + 1], offset), offset + i + 1,
                    *_turns(k[i + 1:], a[i + 1:], offset + i + 1)]
    return []


#: What a stratum of the sweep bootstrap is, for messages.
STRATA = "kind of sweep x load level"


def check_can_resample(data: Any, sweeps: Any = None) -> list[list[np.ndarray]]:
    """The strata of the sweep bootstrap, refused when its resamples cannot vary.

    Each resample draws within every stratum: with one sweep in each (the usual rig
    layout of one sweep per load), every resample is the data itself (the one rule of
    :mod:`frictionlaws.fitting.resampling`).

    Raises
    ------
    InputError
        Saying why, before any fit is run.
    """
    labels = find_sweeps(data) if sweeps is None else _given(sweeps, len(data))
    strata = _strata(data, labels)
    check_can_vary([len(s) for s in strata], unit="sweep", method="the sweep bootstrap",
                   strata=STRATA, source=data.source,
                   remedy="repeat sweeps of a kind at a load level, or use the asymptotic "
                          "standard errors")
    return strata


def _strata(data: Any, labels: np.ndarray) -> list[list[np.ndarray]]:
    """The rows of each sweep, grouped by (kind, load level) (module notes, step 2)."""
    level = load_levels(data.fz)
    span_k = max(float(np.ptp(data.kappa)), SWEEP_REACH[0])
    span_a = max(float(np.ptp(data.alpha)), SWEEP_REACH[1])
    groups: dict[tuple[int, int], list[np.ndarray]] = {}
    for s in np.unique(labels):
        rows = np.flatnonzero(labels == s)
        k, a = data.kappa[rows], data.alpha[rows]
        swept_k = np.ptp(k) / span_k >= np.ptp(a) / span_a
        cross = (np.median(np.abs(a)) > ALPHA_PURE if swept_k
                 else np.median(np.abs(k)) > KAPPA_PURE)
        key = (2 * int(swept_k) + int(cross), int(np.bincount(level[rows]).argmax()))
        groups.setdefault(key, []).append(rows)
    return list(groups.values())


@dataclass
class _Task:
    """What every resample needs (sent once per batch of resamples)."""

    model: FittingModel
    data: Any
    strata: list[list[np.ndarray]]
    groups: dict[str, list[str]]
    p_nom: float | None
    bounds: dict[str, tuple[float, float]]


_QUANTITY = {"x": ("fx", predict_fx), "y": ("fy", predict_fy), "z": ("mz", predict_mz)}


def _resample(item: tuple[_Task, np.random.SeedSequence]) -> dict[str, float] | None:
    """One resample: draw sweeps per stratum, refit the final stages; None if it fails."""
    task, seed = item
    rng = np.random.default_rng(seed)
    rows = np.concatenate([sweeps[j] for sweeps in task.strata
                           for j in rng.integers(0, len(sweeps), len(sweeps))])
    data = task.data.subset(rows)
    mf = copy.copy(task.model)
    mf.coefficients = dict(task.model.coefficients)
    out: dict[str, float] = {}
    try:
        for name in ("x", "y", "z"):
            names = task.groups.get(name, [])
            if not names:
                continue
            column, predict = _QUANTITY[name]
            d = CombinedData.select(data, getattr(data, column),
                                            np.ones(len(data), bool), task.p_nom)
            if name != "z":  # the rows the point estimate's final stage fitted
                d = d.rows(together_rows(d, name))
            solve(mf, names, d, predict, task.bounds)
            out.update({k: float(mf.coefficients[k]) for k in names})
    except (ArithmeticError, ValueError, np.linalg.LinAlgError):
        return None
    return out


def sweep_bootstrap(model: FittingModel, data: Any, groups: dict[str, list[str]],
                    p_nom: float | None, bounds: dict[str, tuple[float, float]], *,
                    resamples: int = DEFAULT_RESAMPLES, seed: int = 0, jobs: int = 1,
                    sweeps: Any = None, warnings_out: list[str] | None = None
                    ) -> tuple[dict[str, float], str]:
    """Standard errors of the coefficients in ``groups`` by the sweep bootstrap.

    Parameters
    ----------
    model : FittingModel
        The fitted model (its coefficients are the point estimate; not changed).
    data : TyreData
        The rows fitted.
    groups : dict
        ``"x"``, ``"y"``, ``"z"`` -> the coefficients refitted on the F_x, F_y and M_z
        rows, in that order (M_z rests on the resample's F_y).
    p_nom : float or None
        The nominal pressure of the fit.
    bounds : dict
        Coefficient bounds of the stages.
    resamples : int
        Number of resamples (at least 20).
    seed : int
        Seed of the resamples.
    jobs : int
        Worker processes (:func:`frictionlaws.parallel.run_parallel`).
    sweeps : array-like, optional
        A sweep label per row (default: :func:`find_sweeps`).
    warnings_out : list of str, optional
        Receives the warning naming coefficients whose resampled values do not spread
        (their standard error is NaN: undetermined, not zero).

    Returns
    -------
    stderr : dict
        Coefficient -> standard deviation of its resampled values.
    method : str
        How they were made, for the report and the file's header.
    """
    check_options(resamples, jobs, sweeps, len(data))
    strata = check_can_resample(data, sweeps)
    task = _Task(model, data, strata, groups, p_nom, bounds)
    seeds = np.random.SeedSequence(seed).spawn(int(resamples))
    results = [r for r in run_parallel(_resample, [(task, s) for s in seeds], jobs=jobs)
               if r is not None]
    if len(results) < max(20, resamples // 2):
        raise InputError(f"the sweep bootstrap failed on {resamples - len(results)} of "
                         f"{resamples} resamples: too few sweeps per stratum to refit")
    names = [k for g in groups.values() for k in g]
    values = np.array([[r[k] for k in names] for r in results])
    se = spread_errors(values)  # NaN where the resamples do not spread: not 0
    withheld = [k for k, e in zip(names, se) if not math.isfinite(e)]
    if withheld and warnings_out is not None:
        warnings_out.append(withheld_message("the sweep bootstrap", withheld))
    n_sweeps = sum(len(s) for s in strata)
    method = (f"sweep bootstrap: {len(results)} resamples (seed {seed}) of {n_sweeps} "
              f"whole sweeps within {len(strata)} strata ({STRATA}), "
              "final stages refitted from the point estimate; standard error = standard "
              "deviation of the resampled values")
    if len(results) < resamples:
        method += f" ({resamples - len(results)} resamples failed to refit, left out)"
    return dict(zip(names, map(float, se))), method


def check_options(resamples: Any, jobs: Any, sweeps: Any, n: int) -> None:
    """Refuse bootstrap options that cannot work (before any fit is run)."""
    if isinstance(resamples, bool) or not isinstance(resamples, (int, np.integer)) \
            or resamples < 20:
        raise InputError(f"resamples must be a whole number of at least 20 (got "
                         f"{resamples!r}): fewer cannot estimate a standard deviation")
    check_jobs(jobs)
    if sweeps is not None:
        _given(sweeps, n)


def _given(sweeps: Any, n: int) -> np.ndarray:
    """Sweep labels given by the caller, as integers (one per row)."""
    arr = np.asarray(sweeps)
    if arr.shape != (n,):
        raise InputError(f"sweeps must give one label per row ({n}), got shape {arr.shape}")
    return np.unique(arr, return_inverse=True)[1].ravel()
