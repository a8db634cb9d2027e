"""Independent reference implementations of every registered law.

Each law of the catalogue (``laws.md`` in the project's shared reference
material; thesis Eqs. 5-1/5-2 for the polynomials) is written here a second
time, by hand, in plain scalar arithmetic, from the published form: not by
calling the law's formula, its sympy form or any of the library's helpers.
The functions take a math namespace ``M`` so the same text runs with
:mod:`mpmath` (40 significant digits: the reference values of the validation
suite) and with :mod:`math` (fast: the synthetic data of the recovery study).
Where the catalogue gives an equivalent second form, the reference uses it
(Wriggers' velocity factor as ``sech(ln(v / vbar))^c``, Huemer through
``x = (v/v_ref)^(-1/m)``), so that a slip in either form shows.

The floors the library applies (``v_min`` for logs and negative powers of v)
are not reproduced: the reference points lie away from them.  The sliding
velocity enters as ``|v|`` (catalogue convention).

:data:`REFERENCES` maps law id -> :class:`Reference` with the reference
points, the settings the catalogue documents and the published presets.  The
forms themselves live in the one example table, :mod:`frictionlaws.validation.law_examples`;
the validation suite fails when a built-in law has no entry there.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from itertools import product

from .law_examples import (
    BURCKHARDT_DOC,
    EXAMPLES,
    LAWS_MD,
    PACEJKA_DOC,
    TABLE_5_1,
    TABLE_5_2,
    Reference,
)

__all__ = ["Reference", "REFERENCES", "reference_points", "evaluate_reference",
           "LAWS_MD", "TABLE_5_1", "TABLE_5_2", "PACEJKA_DOC", "BURCKHARDT_DOC"]

#: Law id -> :class:`Reference`, from the one example table
#: (:mod:`frictionlaws.validation.law_examples`).
REFERENCES: dict[str, Reference] = {law_id: ex.reference for law_id, ex in EXAMPLES.items()}


def reference_points(ref: Reference) -> list[tuple[dict[str, float], dict[str, float]]]:
    """All (variables, parameters) pairs of a reference: parameter sets x variable grid."""
    names = list(ref.variables)
    grids = [ref.grid[n] for n in names]
    out = []
    for params in ref.param_sets:
        for values in product(*grids) if names else [()]:
            out.append((dict(zip(names, values)), dict(params)))
    return out


def evaluate_reference(ref: Reference, variables: Mapping[str, float],
                       params: Mapping[str, float], *, precise: bool = True) -> float:
    """The reference value at one point: mpmath with 40 digits, or plain :mod:`math`."""
    if not precise:
        return float(ref.func(math, **variables, **params))
    import mpmath

    with mpmath.workdps(40):
        args = {k: mpmath.mpf(float(v)) for k, v in {**variables, **params}.items()}
        return float(ref.func(mpmath, **args))
