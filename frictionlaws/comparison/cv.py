"""Seeded k-fold cross-validation of a law on a dataset.

The rows of the *dataset* are shuffled once with ``numpy.random.default_rng(seed)``
and dealt into ``K`` folds (sizes differ by at most one), so every law sees the
same folds.  For each fold the law is refitted with :func:`frictionlaws.fitting.fit`
on the other folds (the same procedure as the full fit: the data-driven guess
of the training rows, never the full-data optimum, so nothing leaks from the
held-out fold) and predicts the held-out rows.  The cross-validated RMSE pools
the squared prediction errors of all scored rows (unweighted, in units of mu).

Rows where a law is singular (``v = 0`` in a log-velocity law) are not used by
that law at all: they are neither trained on nor scored.  A fold whose fit
fails (too few rows for the parameters, an optimiser failure) or whose
predictions are not finite is *reported* in :attr:`CVResult.failed`, and the
RMSE then covers the other folds only (:attr:`CVResult.complete` is False).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import FitError, InputError
from ..fitting import FitData, fit
from ..law import Law

__all__ = ["kfold_assignment", "CVResult", "cross_validate", "error_text"]


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

    @property
    def complete(self) -> bool:
        """True when every fold with rows of this law was fitted and scored."""
        return not self.failed

    def to_dict(self) -> dict[str, Any]:
        return {"folds": self.folds, "seed": self.seed, "rmse": self.rmse, "mae": self.mae,
                "n_scored": self.n_scored, "fold_rmse": list(self.fold_rmse),
                "complete": self.complete, "failed": list(self.failed)}


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
    """
    kw = dict(fit_kwargs or {})
    folds = int(assign.max()) + 1
    pred = np.full(data.n, np.nan)
    fold_rmse: list[float | None] = []
    failed: list[dict[str, Any]] = []
    y = data.arrays["mu"]
    for f in range(folds):
        test = usable & (assign == f)
        train = usable & (assign != f)
        if not test.any():
            fold_rmse.append(None)
            if step:
                step()
            continue
        try:
            res = fit(law, data.subset(train), on_invalid="error", **kw)
        except Exception as exc:  # noqa: BLE001 - a fold may fail in any way; report it
            failed.append({"fold": f + 1, "n_train": int(train.sum()),
                           "n_test": int(test.sum()), "error": error_text(exc)})
            fold_rmse.append(None)
            if step:
                step()
            continue
        xs = {k: data.arrays[k][test] for k in law.variables if k in data.arrays}
        with np.errstate(all="ignore"):
            p = np.asarray(law.evaluate(xs, res.values), float)
        p = np.broadcast_to(p, (int(test.sum()),))
        if not np.all(np.isfinite(p)):
            failed.append({"fold": f + 1, "n_train": int(train.sum()),
                           "n_test": int(test.sum()),
                           "error": f"the fitted law predicts non-finite mu at "
                                    f"{int(np.sum(~np.isfinite(p)))} held-out rows"})
            fold_rmse.append(None)
        else:
            pred[test] = p
            fold_rmse.append(float(np.sqrt(np.mean((y[test] - p) ** 2))))
        if step:
            step()
    scored = np.isfinite(pred)
    err = y[scored] - pred[scored]
    rmse = float(np.sqrt(np.mean(err**2))) if err.size else math.nan
    mae = float(np.mean(np.abs(err))) if err.size else math.nan
    return CVResult(folds, int(kw.get("seed", 0)), rmse, mae, int(scored.sum()), fold_rmse,
                    failed, pred)
