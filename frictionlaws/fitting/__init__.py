"""Fitting a law to data, honestly.

:func:`fit` minimises the (weighted) squared residual of a law's declaration with
scipy's bounded trust region, the way lmfit's ``least_squares`` method does
(:mod:`frictionlaws.fitting.lsq`; lmfit's other minimisers on request), starts from the
law's data-driven guess, tries several starts where the surface may have several
minima, and returns a :class:`FitResult` with values, standard errors, 95 %
confidence intervals, the correlation matrix, goodness of fit and warnings.

On :data:`ANALYTIC_FROM` rows or more the solver and the
identifiability analysis use each law's analytic Jacobian, derived once from its
symbolic form (:mod:`frictionlaws.fitting.derivatives`).  The deterministic starts are
scored by their chi^2 and refined best first; the search stops when a second start
reproduces the best chi^2.  A fit of fewer than :data:`~frictionlaws.fitting.batch.
POLISH_ROWS` rows is then continued to the optimum itself with the analytic Jacobian
(:func:`frictionlaws.fitting.batch.polish`), so its values do not depend on the
solver's path; :mod:`frictionlaws.fitting.stacked` fits many datasets of one law at
once to the same numbers.

Identifiability is checked on the Jacobian at the optimum: its columns are
scaled to unit length and decomposed (SVD).  A relative singular value below
``1e-5`` means a direction in parameter space the data cannot see at all; the
parameters that carry that direction are *named* in
:attr:`FitResult.non_identifiable` and their standard errors are withheld
instead of printing meaningless numbers.  Values between ``1e-5`` and ``1e-2``
give a "poorly determined" warning.

Standard errors are the asymptotic ones from the covariance matrix (scaled by
the reduced chi-square as lmfit does); the 95 % intervals use Student's t with
``n - k`` degrees of freedom.
"""

from __future__ import annotations

from .core import fit
from .data import (
    CONDITION_COLUMN,
    GROUP_COLUMNS,
    MU_DATA_MAX,
    FitData,
    as_fit_data,
    check_fit_options,
    invalid_rows,
    refuse_pooled_groups,
)
from .diagnosis import (
    RANK_TOL,
    WEAK_TOL,
)
from .methods import (
    DEFAULT_METHOD,
    FIT_METHODS,
    FitMethod,
)
from .result import (
    RESULT_FORMAT,
    RESULT_VERSION,
    FitResult,
    ParamEstimate,
    load_result,
)
from .search import (
    ANALYTIC_FROM,
    POLISH_TOL,
    SCOUT_ROWS,
)

__all__ = ["fit", "FitResult", "ParamEstimate", "load_result", "FitData", "as_fit_data",
           "check_fit_options", "invalid_rows", "RESULT_FORMAT", "RESULT_VERSION",
           "GROUP_COLUMNS", "CONDITION_COLUMN", "refuse_pooled_groups", "MU_DATA_MAX",
           "ANALYTIC_FROM", "SCOUT_ROWS", "POLISH_TOL", "RANK_TOL", "WEAK_TOL",
           "FIT_METHODS", "FitMethod", "DEFAULT_METHOD"]
