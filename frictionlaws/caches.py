"""The files generated from the built-in laws' declarations, and the one command that
rebuilds them.

A law is declared once, in its module under ``frictionlaws/laws/``; two caches are derived
from the declarations so that a fit or a report need not load sympy:

* ``frictionlaws/law/formula_text.json``: sympy's text of each formula, read by
  :meth:`Law.pretty <frictionlaws.law.Law.pretty>`;
* ``frictionlaws/fitting/_jacobians.py``: each law's analytic Jacobian as numpy code,
  read by the fits (:mod:`frictionlaws.fitting.derivatives`).

Every entry carries its law's :func:`~frictionlaws.law.formula_check` and is used only
while the law still computes what it recorded, so a law works without its caches (sympy
renders the text on demand, the fit takes finite differences); they make fits and
reports faster.  After changing or adding a law, run::

    python -m frictionlaws.caches

which rewrites each cache that no longer matches the declarations (:func:`rebuild`) and
names the files it wrote.  The tests check :func:`stale` is empty, naming this command.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from .fitting.derivatives import MODULE_PATH, module_current, write_module
from .law import FORMULA_TEXT_FILE, Law, formula_texts_current, write_formula_texts
from .law.registry import builtin_laws

__all__ = ["Cache", "CACHES", "COMMAND", "stale", "rebuild", "main"]

#: The command that rebuilds the caches (named by the tests when one is stale).
COMMAND = "python -m frictionlaws.caches"


@dataclass(frozen=True)
class Cache:
    """A file generated from the built-in laws, and how its owner checks and writes it.

    Attributes
    ----------
    name : str
        What it holds.
    path : Path
        The file.
    current : callable
        ``current(laws, path)``: True when the file holds what ``laws`` give now.
    write : callable
        ``write(laws, path)``: writes the file, returns its path.
    """

    name: str
    path: Path
    current: Callable[[list[Law], Path], bool]
    write: Callable[[list[Law], Path], Path]


#: Every generated cache, one entry each.
CACHES: tuple[Cache, ...] = (
    Cache("formula texts", FORMULA_TEXT_FILE, formula_texts_current, write_formula_texts),
    Cache("analytic Jacobians", MODULE_PATH, module_current, write_module),
)


def stale(caches: Sequence[Cache] = CACHES) -> list[Cache]:
    """The caches that do not hold what the built-in laws give now.

    Parameters
    ----------
    caches : sequence of Cache
        The caches to check (default :data:`CACHES`).

    Returns
    -------
    list of Cache
        Those to rebuild, in table order; empty when every one is current.
    """
    laws = builtin_laws()
    return [c for c in caches if not c.current(laws, c.path)]


def rebuild(caches: Sequence[Cache] = CACHES) -> list[Path]:
    """Rewrite the stale ones of ``caches`` from the built-in laws.

    Parameters
    ----------
    caches : sequence of Cache
        The caches to bring up to date (default :data:`CACHES`).

    Returns
    -------
    list of Path
        The files written (none when every cache was current).
    """
    laws = builtin_laws()
    return [c.write(laws, c.path) for c in stale(caches)]


def main() -> int:
    """``python -m frictionlaws.caches``: rebuild the stale caches and name them."""
    written = rebuild()
    for path in written:
        print(f"wrote {path}")
    if not written:
        print("every cache is current: " + ", ".join(str(c.path) for c in CACHES))
    return 0


if __name__ == "__main__":
    sys.exit(main())
