"""Compare friction laws on one dataset.

:func:`compare` fits every applicable law and reports goodness of fit,
Akaike weights, seeded k-fold cross-validation, extrapolation to the held-out
upper part of the pressure and velocity ranges, a plausibility scan over an
extended box, and residual structure tests; :class:`Comparison` prints a
ranked table and writes JSON and a self-contained HTML/Markdown report.

Modules: :mod:`.core` (compare, ranking, Akaike weights), :mod:`.cv`,
:mod:`.extrapolation`, :mod:`.residuals`, :mod:`.report` (matplotlib, imported
only when a report is written).
"""

import sys
import types
from typing import Any

from .core import Comparison, LawComparison, compare

__all__ = ["compare", "Comparison", "LawComparison"]


class _CallableModule(types.ModuleType):
    """This package shares its name with its main function, ``frictionlaws.compare``.

    Importing a submodule (``frictionlaws.compare.core``) makes Python bind the
    *package* to the attribute ``frictionlaws.compare``; calling the package
    calls :func:`compare`, so ``frictionlaws.compare(laws, data)`` works
    whatever was imported first.
    """

    def __call__(self, *args: Any, **kwargs: Any) -> Comparison:
        return compare(*args, **kwargs)


sys.modules[__name__].__class__ = _CallableModule
