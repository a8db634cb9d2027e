"""The validation cases: published numbers, manual formulas and independent checks.

Each case below names its source, holds its reference numbers (typed from the
source, not read from the library) and compares them with what the library's
public interface computes.  Tolerances are chosen from the source: half a unit
of the last printed digit for a printed figure, round-off for an identity
between two formulas, the discretisation error for a numerical model.  The
human-readable catalogue of these cases, with their figures, is
``validation/README.md`` at the top of the repository.
"""

from __future__ import annotations

from .catalogue import CASES
from .common import (
    LAWS_MD,
    THESIS,
    THESIS_STEEL_ROWS,
    builtin_law_ids,
)
from .thesis_tables import TABLE_6_2

__all__ = ["CASES", "THESIS_STEEL_ROWS", "builtin_law_ids", "LAWS_MD", "THESIS", "TABLE_6_2"]
