"""The test battery's view of the one example table (``frictionlaws/validation/law_examples.py``).

Each :class:`LawCase` gives true parameters for the parameter-recovery test and the
ranges (SI) where synthetic data are drawn.  ``tests/laws/test_registry_laws.py`` runs the
same battery over every entry, and its completeness guard fails when a registered law
has no entry in ``frictionlaws/validation/law_examples.py`` (or an entry names no law).  Nothing
here lists laws: adding a law touches its module and that table only.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from frictionlaws.validation.law_examples import EXAMPLES

#: Where a law's example entry belongs (named by the completeness guard).
EXAMPLES_FILE = "frictionlaws/validation/law_examples.py"


@dataclass(frozen=True)
class LawCase:
    """Test settings for one law (see :class:`frictionlaws.validation.law_examples.Sampling`)."""

    params: dict[str, float]
    ranges: dict[str, tuple[float, float]]
    log: tuple[str, ...] = ()
    n: int = 80
    fix: dict[str, float] = field(default_factory=dict)
    non_identifiable: tuple[str, ...] = ()
    seed: int = 7


CASES: dict[str, LawCase] = {
    law_id: LawCase(dict(ex.battery.params), dict(ex.battery.ranges), ex.battery.log,
                    ex.battery.n, dict(ex.battery.fix), ex.non_identifiable, ex.battery.seed)
    for law_id, ex in EXAMPLES.items()
}
