"""The Magic Formula's coefficient declarations at the import path of earlier releases.

They live in :mod:`frictionlaws.tyre.mf.declarations` (the table) and
:mod:`frictionlaws.tyre.mf.coefficients` (what is done with it); this module re-exports
what ``frictionlaws.tyre.mf_coefficients`` held so that code importing from here keeps
working.
"""

from __future__ import annotations

from .mf.coefficients import (
    NOT_READ_BY_52,
    PRESSURE_TERMS,
    check_values,
    checked_coefficients,
    default,
    fit_bounds,
    listing,
    outside_fit,
    rows,
    section_keys,
    unused_terms,
)
from .mf.declarations import (
    COEFFICIENT_SECTIONS,
    DECLARED,
    RANGE_SECTIONS,
    SECTIONS,
    STRUCTURE_SECTIONS,
    Coefficient,
)

__all__ = ["Coefficient", "DECLARED", "SECTIONS", "COEFFICIENT_SECTIONS", "STRUCTURE_SECTIONS",
           "RANGE_SECTIONS", "default", "fit_bounds", "section_keys", "check_values",
           "checked_coefficients", "outside_fit", "rows", "listing", "unused_terms",
           "NOT_READ_BY_52", "PRESSURE_TERMS"]
