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

__all__ = ["parse_number", "parse_numbers", "parse_integer", "is_number",
           "looks_numeric", "NUMBER_HELP", "INTEGER_HELP"]

_POINT = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?\Z", re.ASCII)
_COMMA = re.compile(r"[+-]?(?:[0-9]+(?:,[0-9]*)?|,[0-9]+)(?:[eE][+-]?[0-9]+)?\Z", re.ASCII)
#: Fortran's exponent letter ``D`` too (``1.5D-03``: ADAMS property files).
_FORTRAN = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eEdD][+-]?[0-9]+)?\Z",
                      re.ASCII)
_INTEGER = re.compile(r"[+-]?[0-9]+\Z", re.ASCII)
#: Spellings Python's float() reads that no file format here allows (non-finite words).
_NON_FINITE = re.compile(r"[+-]?(?:nan|inf|infinity)\Z", re.IGNORECASE)

#: One cell that :data:`_POINT` or :data:`_COMMA` reads (the comma form has no point), or
#: an empty one, with spaces or tabs around.
_POINT_CELL = re.compile(r"[ \t]*(?:(?:" + _POINT.pattern[:-2] + r")[ \t]*)?\Z", re.ASCII)
_COMMA_CELL = re.compile(r"[ \t]*(?:(?:" + _COMMA.pattern[:-2] + r")[ \t]*)?\Z", re.ASCII)

#: What a number looks like, for error messages.
NUMBER_HELP = "a plain decimal number such as 0.25, -3 or 1.5e-6"
#: What a whole number looks like, for error messages.
INTEGER_HELP = "a whole number written with the digits 0-9, such as 3 or -1"


def parse_number(text: str, *, decimal_comma: bool = False, finite: bool = True,
                 fortran: bool = False) -> float:
    """Parse one number written as text.

    Parameters
    ----------
    text : str
        The text; leading and trailing white space is ignored.
    decimal_comma : bool
        Read ``,`` as the decimal separator (and refuse ``.``).
    finite : bool
        Refuse results that overflow to infinity (e.g. ``1e999``).
    fortran : bool
        Also read Fortran's exponent letter ``D`` (``1.5D-03``), as ADAMS property
        files write it.

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
    pattern = _COMMA if decimal_comma else _FORTRAN if fortran else _POINT
    if not pattern.match(s):
        sep = "decimal comma" if decimal_comma else "decimal point"
        raise ValueError(f"'{text.strip()}' is not a number (expected {NUMBER_HELP}, "
                         f"with a {sep})")
    if fortran:
        s = s.replace("d", "e").replace("D", "E")
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


def parse_integer(text: str, *, lo: int | None = None, hi: int | None = None) -> int:
    """Parse one whole number written as text (the digits 0-9 and an optional sign).

    Python's ``int()`` also reads ``1_000``, full-width and other non-ASCII digits and
    surrounding white space inside a value; this reads what a user means by a count.

    Parameters
    ----------
    text : str
        The text; leading and trailing white space is ignored.
    lo, hi : int, optional
        The smallest and largest value accepted.

    Returns
    -------
    int

    Raises
    ------
    ValueError
        Saying what was expected.
    """
    if not isinstance(text, str):
        raise ValueError(f"expected text, got {type(text).__name__}")
    s = text.strip()
    if len(s) > 40 or not _INTEGER.match(s):
        raise ValueError(f"'{s[:40]}' is not {INTEGER_HELP}")
    value = int(s)
    if (lo is not None and value < lo) or (hi is not None and value > hi):
        bounds = (f"from {lo} to {hi}" if lo is not None and hi is not None else
                  f">= {lo}" if lo is not None else f"<= {hi}")
        raise ValueError(f"{value} is out of range: expected a whole number {bounds}")
    return value


def looks_numeric(text: str) -> bool:
    """True for text a lenient reader (Python's ``float``) might take for a number but
    :func:`parse_number` refuses to be one: a non-finite word (``nan``, ``inf``), or text
    that starts like a number (a sign, a point or any digit, non-ASCII ones included).

    Readers use it to refuse such text where a number belongs, instead of keeping it as a
    word.
    """
    s = str(text).strip()
    if _NON_FINITE.match(s):
        return True
    body = s.lstrip("+-\u2212")
    return bool(body) and (body[0].isdigit() or body[0] == "." or
                           (body[0] == "," and body[1:2].isdigit()))
