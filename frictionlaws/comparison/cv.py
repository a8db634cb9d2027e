"""Seeded k-fold cross-validation of a law on a dataset.

The rows of the *dataset* are shuffled once with ``numpy.random.default_rng(seed)``
and dealt into ``K`` folds (sizes differ by at most one), so every law sees the
same folds.  For each fold the law is refitted with :func:`frictionlaws.fitting.fit`
on the other folds (the same procedure as the full fit: the data-driven guess
of the training rows, never the full-data optimum, so nothing leaks from the
held-out fold) and predicts the held-out rows.  The cross-validated RMSE pools
the squared prediction errors of all scored rows (unweighted, in units of mu).
Starting the refits from the full-data optimum instead would be cheaper but is not
the same test: on the thesis-steel data a fold that leaves a law's parameters
undetermined then stops elsewhere on the flat valley (the CV RMSE of
``thesis-poly2`` moved from 0.338 to 131), so every refit goes through
:func:`refit`, the one place a leaner fit would be plugged in.

Rows where a law is singular (``v = 0`` in a log-velocity law) are not used by
that law at all: they are neither trained on nor scored.  A fold whose fit
fails (too few rows for the parameters, an optimiser failure) or whose
predictions are not finite is *reported* in :attr:`CVResult.failed`, and the
RMSE then covers the other folds only (:attr:`CVResult.complete` is False).
A fold whose training rows cannot determine some of the law's parameters (the
refit's identifiability check names them) is listed in :attr:`CVResult.undetermined`.
Its held-out rows whose predictions depend on what those rows cannot determine
(:func:`undetermined_rows`) have no score: their predictions come from an arbitrary
point of a flat valley of chi^2, as with ``thesis-poly2`` above, whose fold without
the one row at v = 2.77 m/s has two velocities left for a quadratic in v (another
start, solver or library version stops elsewhere in the valley, with another
prediction there).  The CV RMSE is then *undetermined* (:attr:`CVResult.determined`
is False, the RMSE NaN, null in JSON): a score of where a solver stopped is not a
property of the law and the data.  Held-out rows the valley does not move (rows at
the velocities the training rows share) keep their predictions.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..base.errors import FitError, InputError
from ..fitting import RANK_TOL, FitData, FitResult, fit
from ..fitting.lsq import central_jacobian
from ..law import Law

__all__ = ["kfold_assignment", "CVResult", "cross_validate", "error_text", "refit",
           "FoldOutcome", "score_fold", "combine_folds", "undetermined_rows",
           "PREDICTION_TOL"]

#: A held-out row is undetermined when a direction of the parameters that the training
#: rows cannot determine (singular-value ratio below the fitter's ``RANK_TOL``, 1e-5)
#: moves its prediction by more than this fraction of the training rows' strongest
#: response.  Along such a direction chi^2 of the training rows does not change, so any
#: response that is not round-off makes the prediction arbitrary.  Rows the valley
#: leaves alone respond at round-off (about 1e-9 here); a quadratic in v trained at
#: 1.0 and 1.1 m/s and asked at 1.2 m/s responds at about 1e-3, so the line sits at
#: 1e-6, a thousand times above round-off (1e-3 let such near neighbours through).
PREDICTION_TOL = 1e-6


def error_text(exc: BaseException) -> str:
    """One line describing ``exc`` (its type too, unless it is a frictionlaws error)."""
    text = " ".join(str(exc).split())
    if isinstance(exc, (InputError, FitError)):
        return text
    return f"{type(exc).__name__}: {text}"


def kfold_assignment(n: int, folds: int, seed: int) -> np.ndarray:
    """Fold number (0 .. folds-1) of each of ``n`` rows, shuffled reproducibly.

    Parameters
    ----------
    n : int
        Number of rows.
    folds : int
        Number of folds, 2 <= folds <= n (``folds = n`` is leave-one-out).
    seed : int
        Seed of :func:`numpy.random.default_rng`.
    """
    if not 2 <= folds <= n:
        raise InputError(f"the number of folds must be between 2 and the number of rows "
                         f"({n}), not {folds}")
    perm = np.random.default_rng(seed).permutation(n)
    assign = np.empty(n, dtype=int)
    assign[perm] = np.arange(n) % folds
    return assign


@dataclass
class CVResult:
    """Cross-validation of one law (see the module docstring)."""

    folds: int
    seed: int
    rmse: float
    mae: float
    n_scored: int
    fold_rmse: list[float | None]
    failed: list[dict[str, Any]] = field(default_factory=list)
    predictions: np.ndarray | None = None
    undetermined: list[dict[str, Any]] = field(default_factory=list)
    #: Rows of the data whose out-of-fold prediction is undetermined (None: none).
    undetermined_mask: np.ndarray | None = None

    @property
    def complete(self) -> bool:
        """True when every fold with rows of this law was fitted and scored."""
        return not self.failed

    @property
    def determined(self) -> bool:
        """False when some scored row's prediction is undetermined (module docstring)."""
        return self.undetermined_mask is None or not bool(self.undetermined_mask.any())

    def determined_on(self, rows: np.ndarray) -> bool:
        """True when no row of ``rows`` (a mask of the data) has an undetermined prediction."""
        return self.undetermined_mask is None or not bool(
            np.any(self.undetermined_mask & rows))

    def to_dict(self) -> dict[str, Any]:
        return {"folds": self.folds, "seed": self.seed, "rmse": self.rmse, "mae": self.mae,
                "n_scored": self.n_scored, "fold_rmse": list(self.fold_rmse),
                "complete": self.complete, "determined": self.determined,
                "failed": list(self.failed), "undetermined": list(self.undetermined)}


def refit(law: Law, data: FitData, fit_kwargs: Mapping[str, Any] | None = None) -> FitResult:
    """Refit ``law`` on part of the data (a cross-validation fold or a hold-out split).

    The one place where a comparison refits: the same procedure as the full fit (the
    data-driven guess of these rows, the same starts and seed), so nothing leaks from
    the rows left out and the results do not depend on how the refits are scheduled.

    Parameters
    ----------
    law : Law
        The law.
    data : FitData
        The training rows (none of them singular for the law).
    fit_kwargs : mapping, optional
        Passed to :func:`~frictionlaws.fitting.fit` (``seed``, ``starts``...).

    Returns
    -------
    FitResult
        The lean fit on ``data`` (its values and metrics; no diagnostics).
    """
    return fit(law, data, on_invalid="error", lean=True, **dict(fit_kwargs or {}))


@dataclass
class FoldOutcome:
    """One fold of a cross-validation: the held-out predictions, or why there are none."""

    fold: int
    test: np.ndarray
    predictions: np.ndarray | None = None
    failure: dict[str, Any] | None = None
    #: The fold, its row counts, the parameters its training rows cannot determine and
    #: how many held-out predictions depend on them (None when they determine every one).
    undetermined: dict[str, Any] | None = None
    #: Held-out rows (of ``test``'s True rows, in order) whose prediction is undetermined.
    undetermined_rows: np.ndarray | None = None


def score_fold(law: Law, data: FitData, usable: np.ndarray, assign: np.ndarray, fold: int, *,
               fit_kwargs: Mapping[str, Any] | None = None) -> FoldOutcome:
    """Refit ``law`` without fold ``fold`` (0-based) and predict that fold's usable rows.

    Parameters
    ----------
    law : Law
        The law.
    data : FitData
        The whole dataset (SI arrays).
    usable : ndarray of bool
        Rows the law can be evaluated on.
    assign : ndarray of int
        Fold of each row, from :func:`kfold_assignment`.
    fold : int
        The fold held out.
    fit_kwargs : mapping, optional
        Passed to :func:`refit`.

    Returns
    -------
    FoldOutcome
        The predictions of the held-out rows, or the failure (a fit that failed or
        non-finite predictions); neither when the fold has no usable rows.  The
        parameters the training rows cannot determine are named with the predictions.
    """
    test = usable & (assign == fold)
    train = usable & (assign != fold)
    if not test.any():
        return FoldOutcome(fold, test)
    where = {"fold": fold + 1, "n_train": int(train.sum()), "n_test": int(test.sum())}
    try:
        res = refit(law, data.subset(train), fit_kwargs)
    except Exception as exc:  # noqa: BLE001 - a fold may fail in any way; report it
        return FoldOutcome(fold, test, failure={**where, "error": error_text(exc)})
    xs = {k: data.arrays[k][test] for k in law.variables if k in data.arrays}
    with np.errstate(all="ignore"):
        p = np.asarray(law.evaluate(xs, res.values), float)
    p = np.array(np.broadcast_to(p, (int(test.sum()),)))
    if not np.all(np.isfinite(p)):
        return FoldOutcome(fold, test, failure={
            **where, "error": f"the fitted law predicts non-finite mu at "
                              f"{int(np.sum(~np.isfinite(p)))} held-out rows"})
    if not res.non_identifiable:
        return FoldOutcome(fold, test, predictions=p)
    und = undetermined_rows(law, res, data.subset(train), xs, int(test.sum()))
    return FoldOutcome(fold, test, predictions=p, undetermined={
        **where, "params": list(res.non_identifiable), "n_undetermined": int(und.sum())},
        undetermined_rows=und)


def undetermined_rows(law: Law, res: FitResult, train: FitData,
                      test: Mapping[str, np.ndarray], n_test: int) -> np.ndarray:
    """Held-out rows whose prediction depends on what the training rows cannot determine.

    The Jacobian of the law by the fitted parameters (central differences at the
    refit's optimum) over the training and held-out rows, each column scaled to unit
    length over both, is split into its training rows A and held-out rows B.  The
    right singular vectors u of A whose singular value is below ``RANK_TOL`` of the
    largest s_0 are directions along which chi^2 of the training rows does not change
    (a flat valley); a held-out row r is undetermined when ``|B[r] u|`` exceeds
    :data:`PREDICTION_TOL` times s_0 for one of them.  Only the parameters the refit's
    last local solve varied enter (a parameter held at a bound is not in a valley).

    Parameters
    ----------
    law : Law
        The law.
    res : FitResult
        The refit on ``train``.
    train : FitData
        Its training rows (weighted as the refit was).
    test : mapping
        The held-out rows' variables (SI).
    n_test : int
        Number of held-out rows.

    Returns
    -------
    ndarray of bool
        One flag per held-out row (all False when the refit names no parameter as
        undetermined; all True when the Jacobian is not finite).
    """
    out = np.zeros(n_test, dtype=bool)
    # the parameters the final local solve varied (not those fixed or held at a bound
    # where the law changes form, as Wriggers' c = 0)
    varied = getattr(res.local_fit, "var_names", None)
    names = (list(varied) if varied is not None
             else [k for k, p in res.params.items() if not p.fixed])
    if not res.non_identifiable or not names or not n_test:
        return out
    n_tr = train.n
    xs = {k: np.concatenate([np.asarray(train.arrays[k], float),
                             np.broadcast_to(np.asarray(test[k], float), (n_test,))])
          for k in law.variables if k in train.arrays and k in test}
    base = dict(res.values)

    def model(theta: np.ndarray) -> np.ndarray:
        values = {**base, **dict(zip(names, (float(t) for t in theta)))}
        with np.errstate(all="ignore"):
            return np.array(np.broadcast_to(np.asarray(law.evaluate(xs, values), float),
                                            (n_tr + n_test,)))

    scales = np.array([law.param(k).default if k in law.param_names else 0.0 for k in names])
    jac = central_jacobian(model, np.array([base[k] for k in names], float), scales)
    if not np.all(np.isfinite(jac)):
        out[:] = True
        return out
    if train.weights is not None:
        jac[:n_tr] *= np.asarray(train.weights, float)[:, None]
    norms = np.linalg.norm(jac, axis=0)
    jac = jac[:, norms > 0] / norms[norms > 0]
    a, b = jac[:n_tr], jac[n_tr:]
    if a.shape[0] < a.shape[1]:  # fewer training rows than parameters: pad with zero rows
        a = np.vstack([a, np.zeros((a.shape[1] - a.shape[0], a.shape[1]))])
    try:
        _, s, vt = np.linalg.svd(a, full_matrices=False)
    except np.linalg.LinAlgError:
        s = np.zeros(0)
    if not s.size or s[0] <= 0:
        out[:] = True
        return out
    null = vt[s < RANK_TOL * s[0]]
    if null.size:
        out |= np.max(np.abs(b @ null.T), axis=1) > PREDICTION_TOL * s[0]
    return out


def combine_folds(data: FitData, outcomes: Sequence[FoldOutcome], seed: int) -> CVResult:
    """Pool the folds of one law into its :class:`CVResult`.

    Parameters
    ----------
    data : FitData
        The whole dataset.
    outcomes : sequence of FoldOutcome
        Every fold, in fold order.
    seed : int
        The seed of the fold assignment (recorded).

    Returns
    -------
    CVResult
        RMSE and MAE over every scored row, the RMSE of each fold, the failures and
        the folds that left parameters undetermined.
    """
    y = data.arrays["mu"]
    pred = np.full(data.n, np.nan)
    und = np.zeros(data.n, dtype=bool)
    fold_rmse: list[float | None] = []
    failed: list[dict[str, Any]] = []
    undetermined = [o.undetermined for o in outcomes if o.undetermined is not None]
    for o in outcomes:
        if o.predictions is None:
            fold_rmse.append(None)
            if o.failure is not None:
                failed.append(o.failure)
            continue
        pred[o.test] = o.predictions
        if o.undetermined_rows is not None and o.undetermined_rows.any():
            und[np.flatnonzero(o.test)[o.undetermined_rows]] = True
            fold_rmse.append(None)
            continue
        fold_rmse.append(float(np.sqrt(np.mean((y[o.test] - o.predictions) ** 2))))
    scored = np.isfinite(pred)
    err = y[scored] - pred[scored]
    rmse = mae = math.nan
    if err.size and not und.any():
        rmse = float(np.sqrt(np.mean(err**2)))
        mae = float(np.mean(np.abs(err)))
    return CVResult(len(outcomes), seed, rmse, mae, int(scored.sum()), fold_rmse, failed,
                    pred, undetermined, und)


def cross_validate(law: Law, data: FitData, usable: np.ndarray, assign: np.ndarray, *,
                   fit_kwargs: Mapping[str, Any] | None = None,
                   step: Callable[[], None] | None = None) -> CVResult:
    """K-fold cross-validated prediction error of ``law`` on ``data``.

    Parameters
    ----------
    law : Law
        The law.
    data : FitData
        The whole dataset (SI arrays).
    usable : ndarray of bool
        Rows the law can be evaluated on (its singular rows excluded).
    assign : ndarray of int
        Fold of each row, from :func:`kfold_assignment`.
    fit_kwargs : mapping, optional
        Passed to :func:`~frictionlaws.fitting.fit` (``seed``, ``starts``...).
    step : callable, optional
        Called after each fold (progress bar).

    Returns
    -------
    CVResult
        The pooled cross-validation of the law.
    """
    outcomes = []
    for f in range(int(assign.max()) + 1):
        outcomes.append(score_fold(law, data, usable, assign, f, fit_kwargs=fit_kwargs))
        if step:
            step()
    return combine_folds(data, outcomes, int(dict(fit_kwargs or {}).get("seed", 0)))
