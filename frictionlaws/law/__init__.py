"""The declaration of a friction law, and everything derived from it.

A law is declared once, as a :class:`Law` built from

* its variables (names from :data:`VARIABLES`, always in SI),
* its fitted parameters (:class:`Param`: unit, default, bounds, meaning),
* its fixed settings (:class:`Setting`: reference scales such as ``p_ref``),
* one formula, written as a Python function ``formula(m, **names)`` where ``m``
  is a math namespace.  Called with :data:`NUMPY` it is the vectorised numpy
  evaluation; called with the sympy namespace and symbols it is the symbolic
  form used by the docs, the Fortran generator and the tests.

Floors (``v_min``, ``p_min``) and the absolute value of the sliding velocity
are applied by the :class:`Law` wrapper before the formula is called, so the
formula stays smooth, and the exporters apply the same floors.

The rooms, each importing only those above it in this list:

* :mod:`~frictionlaws.law.namespace`: the numpy and sympy math namespaces;
* :mod:`~frictionlaws.law.declaration`: :class:`Variable`, :class:`Param`, :class:`Setting`,
  :class:`Derived` and the library's limits (:data:`MU_MAX`, the floors);
* :mod:`~frictionlaws.law.parameters`: the declaration's fields and parameter values
  (presets, bounds, the one validation of values, initial guess, summary);
* :mod:`~frictionlaws.law.domain`: the checks of the variables, the floors, the strict domain;
* :mod:`~frictionlaws.law.evaluation`: checked and unchecked evaluation, bound functions;
* :mod:`~frictionlaws.law.text`: the symbolic form, LaTeX and the cached formula text;
* :mod:`~frictionlaws.law.interop`: the lmfit model and Jupyter's HTML of a law;
* :mod:`~frictionlaws.law.core`: :class:`Law` itself, assembled from these, and
  :class:`~frictionlaws.law.bound.BoundLaw`, the law bound to values.
"""

from __future__ import annotations

from .core import Law, set_lookup
from .declaration import (
    EVIDENCE_TAGS,
    F_MIN,
    FAMILIES,
    MU_MAX,
    P_MIN,
    V_MIN,
    VARIABLES,
    Derived,
    Param,
    Setting,
    Variable,
)
from .domain import LIMIT_RTOL, ZERO_PROBES
from .namespace import NUMPY, sympy_namespace
from .text import (
    FORMULA_TEXT_FILE,
    formula_check,
    formula_matches,
    formula_text_entries,
    formula_texts_current,
    write_formula_texts,
)

__all__ = [
    "VARIABLES",
    "Variable",
    "Param",
    "Setting",
    "Derived",
    "Law",
    "NUMPY",
    "sympy_namespace",
    "V_MIN",
    "P_MIN",
    "F_MIN",
    "MU_MAX",
    "FAMILIES",
    "EVIDENCE_TAGS",
    "ZERO_PROBES",
    "LIMIT_RTOL",
    "FORMULA_TEXT_FILE",
    "formula_check",
    "formula_matches",
    "formula_text_entries",
    "formula_texts_current",
    "write_formula_texts",
    "set_lookup",
]
