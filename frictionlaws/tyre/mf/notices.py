"""The one path of the Magic Formula's warnings: raised where they arise, collected once.

A condition (an input beyond the file's range, a load clamped, an option not used) is
raised once, where it arises, as a Python warning
(:class:`~frictionlaws.base.errors.ExtrapolationWarning`, :class:`UserWarning`); an option
the model cannot apply is warned of once, when the model is made, and stands in every
result's warnings after (``collected(mf.not_applied)``).  Every path
that reports an evaluation collects the warnings with :func:`collected`: the API's
structured results (:func:`~frictionlaws.tyre.mf.outputs.evaluate`,
:meth:`~frictionlaws.tyre.mf.model.MagicFormula.summary`), their JSON, the xarray
attributes, and the CLI's text, which prints what the result holds.  The warnings are then
issued again, once each, so that a caller of the API sees them as Python warnings too (and
its warning filters apply).
"""

from __future__ import annotations

import contextlib
import warnings
from collections.abc import Iterator, Sequence

__all__ = ["collected"]


@contextlib.contextmanager
def collected(standing: Sequence[str] = ()) -> Iterator[list[str]]:
    """Collect the warnings raised inside the block, once each, in order.

    Parameters
    ----------
    standing : sequence of str
        Warnings that hold for every evaluation of the model and were issued once already
        (the options it cannot apply:
        :attr:`~frictionlaws.tyre.mf.parameters.MFParameters.not_applied`): listed first,
        not issued again.

    Yields
    ------
    list of str
        Filled when the block ends: ``standing``, then the text of each other distinct
        warning raised inside.  Those are then issued again (once each), so that the
        caller's filters apply to them; also when the block raises (an input refused
        after a warning: the command line prints the warnings before its one error line).
    """
    texts: list[str] = list(dict.fromkeys(standing))
    caught: list[warnings.WarningMessage] = []
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            yield texts
    finally:  # also when the block refuses: what was warned before stays said
        _issue_again(caught, texts)


def _issue_again(caught: list[warnings.WarningMessage], texts: list[str]) -> None:
    """Add each distinct warning of ``caught`` to ``texts`` and issue it again, once."""
    seen: set[tuple[type, str]] = set()
    for w in caught:
        key = (w.category, str(w.message))
        if key in seen:
            continue
        seen.add(key)
        if str(w.message) not in texts:
            texts.append(str(w.message))
        warnings.warn_explicit(w.message, w.category, w.filename, w.lineno,
                               source=w.source)
