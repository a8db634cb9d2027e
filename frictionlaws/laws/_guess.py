"""Small numerical helpers shared by the laws' initial-guess functions."""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence

import numpy as np

__all__ = ["linear_guess", "linear_lstsq", "spread", "subsample"]


def linear_lstsq(columns: Sequence[np.ndarray], y: np.ndarray) -> np.ndarray:
    """Least-squares coefficients of ``y ~ sum(c_i * columns_i)``."""
    a = np.column_stack([np.broadcast_to(np.asarray(c, float), np.shape(y)) for c in columns])
    coef, *_ = np.linalg.lstsq(a, np.asarray(y, float), rcond=None)
    return coef


def linear_guess(
    names: Sequence[str], basis: Callable[[Mapping[str, np.ndarray]], Sequence[np.ndarray]]
) -> Callable[[Mapping[str, np.ndarray]], dict[str, float]]:
    """A guess function for a law linear in its parameters.

    ``basis(data)`` returns one column per parameter (in ``names`` order); the
    guess is the ordinary least-squares solution, which is also the optimum.
    """

    def guess(data: Mapping[str, np.ndarray]) -> dict[str, float]:
        coef = linear_lstsq(basis(data), data["mu"])
        return dict(zip(names, (float(c) for c in coef)))

    return guess


def subsample(d: Mapping[str, np.ndarray], n: int) -> dict[str, np.ndarray]:
    """At most ``n`` evenly spaced rows of every array (for initial guesses only)."""
    size = np.size(d["mu"])
    if size <= n:
        return {k: np.asarray(v, float) for k, v in d.items()}
    idx = np.linspace(0, size - 1, n).astype(int)
    return {k: np.asarray(v, float)[idx] for k, v in d.items()}


def spread(x: np.ndarray) -> float:
    """Max/min ratio of the positive values of ``x`` (1 when constant)."""
    x = np.asarray(x, float)
    x = x[x > 0]
    return float(x.max() / x.min()) if x.size else 1.0
