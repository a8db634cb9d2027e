"""The one number parser for text frictionlaws reads (datasets, manifests, records, rigs,
property files, command-line values).

Python's ``float()`` is too lenient for engineering input: it accepts ``1_000``,
full-width or other non-ASCII digits, surrounding white space inside cells,
``nan``, ``inf`` and ``infinity`` in any case.  :func:`parse_number` accepts
plain decimal numbers only: an optional sign, digits with one decimal separator,
and an optional exponent.  With ``decimal_comma=True`` the separator is ``,``
(and ``.`` is refused, so a file mixing decimal commas with thousands dots
cannot be read as the wrong number).
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence

import numpy as np

__all__ = ["parse_number", "parse_numbers", "is_number", "NUMBER_HELP"]

_POINT = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?\Z", re.ASCII)
_COMMA = re.compile(r"[+-]?(?:[0-9]+(?:,[0-9]*)?|,[0-9]+)(?:[eE][+-]?[0-9]+)?\Z", re.ASCII)

#: One cell that :data:`_POINT` or :data:`_COMMA` reads (the comma form has no point), or
#: an empty one, with spaces or tabs around.
_POINT_CELL = re.compile(r"[ \t]*(?:(?:" + _POINT.pattern[:-2] + r")[ \t]*)?\Z", re.ASCII)
_COMMA_CELL = re.compile(r"[ \t]*(?:(?:" + _COMMA.pattern[:-2] + r")[ \t]*)?\Z", re.ASCII)

#: What a number looks like, for error messages.
NUMBER_HELP = "a plain decimal number such as 0.25, -3 or 1.5e-6"


def parse_number(text: str, *, decimal_comma: bool = False, finite: bool = True) -> float:
    """Parse one number written as text.

    Parameters
    ----------
    text : str
        The text; leading and trailing white space is ignored.
    decimal_comma : bool
        Read ``,`` as the decimal separator (and refuse ``.``).
    finite : bool
        Refuse results that overflow to infinity (e.g. ``1e999``).

    Returns
    -------
    float

    Raises
    ------
    ValueError
        With a message saying what was expected.  Callers wrap it into an
        :class:`~frictionlaws.base.errors.InputError` naming file, column and row.
    """
    if not isinstance(text, str):
        raise ValueError(f"expected text, got {type(text).__name__}")
    s = text.strip()
    pattern = _COMMA if decimal_comma else _POINT
    if not pattern.match(s):
        sep = "decimal comma" if decimal_comma else "decimal point"
        raise ValueError(f"'{text.strip()}' is not a number (expected {NUMBER_HELP}, "
                         f"with a {sep})")
    value = float(s.replace(",", ".")) if decimal_comma else float(s)
    if finite and not math.isfinite(value):
        raise ValueError(f"'{s}' overflows (the magnitude is beyond 1.8e308)")
    return value


def is_number(text: str, *, decimal_comma: bool = False) -> bool:
    """True when :func:`parse_number` accepts ``text``."""
    try:
        parse_number(text, decimal_comma=decimal_comma)
    except ValueError:
        return False
    return True


def parse_numbers(cells: Sequence[str], *, decimal_comma: bool = False) -> np.ndarray | None:
    """Parse a column of cells at once, each as :func:`parse_number` reads it.

    For the common column (every cell a plain number or empty, with at most spaces or
    tabs around it) a pattern check and a conversion per cell replace the checks and
    messages of :func:`parse_number`.  Anything else (another missing-value token, a cell
    :func:`parse_number` refuses, a number that overflows, a decimal point in a file
    of decimal commas) gives None, and the caller reads the column cell by cell with
    its messages.

    Parameters
    ----------
    cells : sequence of str
        The cells.
    decimal_comma : bool
        The file writes decimal commas: every number must then be written with ``,``
        or without a separator.

    Returns
    -------
    numpy.ndarray or None
        The numbers, NaN for an empty cell; None as said above.
    """
    if not all(map((_COMMA_CELL if decimal_comma else _POINT_CELL).match, cells)):
        return None
    if decimal_comma:
        cells = [c.replace(",", ".") for c in cells]
    values = np.array([float(c) if c.strip(" \t") else math.nan for c in cells], float)
    if np.isinf(values).any():
        return None
    return values
