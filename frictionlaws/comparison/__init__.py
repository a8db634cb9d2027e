"""Compare friction laws on one dataset.

:func:`compare` fits every applicable law and reports goodness of fit,
Akaike weights, seeded k-fold cross-validation, extrapolation to the held-out
upper part of the pressure and velocity ranges, a plausibility scan over an
extended box, and residual structure tests; :class:`Comparison` prints a
ranked table and writes JSON and a self-contained HTML/Markdown report.

Modules: :mod:`.core` (compare, ranking, Akaike weights), :mod:`.results` (the
result classes, plain data), :mod:`.cv`, :mod:`.extrapolation`, :mod:`.residuals`,
:mod:`.report` (tables, Markdown, HTML and figures from a result; imported only when
a table or a report is asked for; :mod:`.core` and :mod:`.report` do not import
each other).

The function is also ``frictionlaws.compare``; this package is named
``comparison`` so that the two never shadow each other.
"""

from .core import Comparison, LawComparison, compare

__all__ = ["compare", "Comparison", "LawComparison"]
