"""The fit methods: how a fit's least squares are solved, one table entry each.

:func:`~frictionlaws.fitting.fit` takes ``method=`` one of the names of :data:`FIT_METHODS`:

* ``least_squares`` (the default): the package's lean bounded trust region
  (:func:`frictionlaws.fitting.lsq.solve`), with the law's analytic Jacobian on large
  data, the best fit polished to :data:`~frictionlaws.fitting.search.POLISH_TOL` so that
  the optimum does not depend on the solver's path;
* lmfit's bounded, deterministic minimisers, by their lmfit names, on an
  :class:`lmfit.Model` of the law (:func:`frictionlaws.fitting.lsq.lmfit_fit`).

The search (:mod:`frictionlaws.fitting.search`) reads the table and branches on no name:
adding a method is one :class:`FitMethod` entry, its local solve taking the search, a
start, the parameters held at a bound and a tolerance, and returning a result with
``chisqr`` and ``params`` (as lmfit's do).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..base.errors import InputError
from .lsq import lmfit_fit, solve

__all__ = ["FitMethod", "FIT_METHODS", "DEFAULT_METHOD", "fit_method"]


@dataclass(frozen=True)
class FitMethod:
    """A way to solve a fit's least squares.

    Attributes
    ----------
    name : str
        The name ``fit(method=...)`` takes.
    description : str
        One line for the docs and the messages.
    solve : callable
        ``solve(search, start, pinned, tol)``: one local fit from the start values
        ``start`` (a name -> value mapping) with the parameters ``pinned`` held where
        they are, to the relative tolerance ``tol``; returns a result with ``chisqr``
        and ``params`` (lmfit's ``Parameters`` or the lean solver's equivalent).
    lmfit_model : bool
        True when ``solve`` needs an :class:`lmfit.Model` of the law (the search
        builds one, ``search.model``).
    polished : bool
        True when the best fit is refined to the tight tolerance of the polish.
    """

    name: str
    description: str
    solve: Callable[[Any, Mapping[str, float], tuple[str, ...], float], Any]
    lmfit_model: bool = False
    polished: bool = False


def _lean_solve(search: Any, start: Mapping[str, float], pinned: tuple[str, ...],
                tol: float) -> Any:
    """The bounded trust region on the law's model, with its analytic Jacobian if any."""
    s = search.setup
    values = search.start_values(start, pinned)
    vary = [k for k in s.names if k not in s.fix and k not in pinned]
    jac = None
    if search.jac_func is not None:
        def jac(v: Mapping[str, float]) -> np.ndarray:
            out = search.jacobian(v, vary)
            assert out is not None
            return out
    return solve(search.evaluate, s.y, s.w, values, vary, s.bounds, search.max_nfev, jac, tol)


def _lmfit_solve(search: Any, start: Mapping[str, float], pinned: tuple[str, ...],
                 tol: float) -> Any:
    """lmfit's minimiser of the search's method on the law's lmfit model (its own tolerances)."""
    s = search.setup
    return lmfit_fit(search.model, s.y, search.params(start, pinned), weights=s.w,
                     method=search.method, max_nfev=search.max_nfev, **search.kwargs)


def _lmfit(name: str, description: str) -> FitMethod:
    return FitMethod(name, f"{description} (lmfit)", _lmfit_solve, lmfit_model=True)


#: The default method of a fit.
DEFAULT_METHOD = "least_squares"

#: Fit methods by name: the lean trust region and lmfit's bounded, deterministic minimisers.
FIT_METHODS: dict[str, FitMethod] = {m.name: m for m in (
    FitMethod(DEFAULT_METHOD, "bounded trust region, analytic Jacobians on large data, "
              "polished to the optimum", _lean_solve, polished=True),
    _lmfit("leastsq", "MINPACK's Levenberg-Marquardt"),
    _lmfit("nelder", "Nelder-Mead simplex"),
    _lmfit("lbfgsb", "L-BFGS-B"),
    _lmfit("powell", "Powell's conjugate directions"),
    _lmfit("trust-constr", "trust-region constrained"),
)}


def fit_method(name: Any) -> FitMethod:
    """The fit method named ``name``.

    Parameters
    ----------
    name : str
        One of :data:`FIT_METHODS`.

    Returns
    -------
    FitMethod
        Its entry.

    Raises
    ------
    InputError
        Naming the methods there are (``option="method"``).
    """
    if not isinstance(name, str) or name not in FIT_METHODS:
        raise InputError(f"method must be one of {', '.join(FIT_METHODS)}, not {name!r}",
                         option="method")
    return FIT_METHODS[name]
