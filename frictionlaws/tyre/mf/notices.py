"""The one path of the Magic Formula's warnings: raised where they arise, collected once.

A condition (an input beyond the file's range, a load clamped, an option not used) is
raised once, where it arises, as a Python warning
(:class:`~frictionlaws.base.errors.ExtrapolationWarning`, :class:`UserWarning`).  Every path
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
from collections.abc import Iterator

__all__ = ["collected"]


@contextlib.contextmanager
def collected() -> Iterator[list[str]]:
    """Collect the warnings raised inside the block, once each, in order.

    Yields
    ------
    list of str
        Filled when the block ends: the text of each distinct warning.  The warnings are
        then issued again (once each), so that the caller's filters apply to them.
    """
    texts: list[str] = []
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        yield texts
    seen: set[tuple[type, str]] = set()
    for w in caught:
        key = (w.category, str(w.message))
        if key in seen:
            continue
        seen.add(key)
        texts.append(str(w.message))
        warnings.warn_explicit(w.message, w.category, w.filename, w.lineno,
                               source=w.source)
