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

__all__ = ["parse_number", "is_number", "NUMBER_HELP"]

_POINT = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?\Z", re.ASCII)
_COMMA = re.compile(r"[+-]?(?:[0-9]+(?:,[0-9]*)?|,[0-9]+)(?:[eE][+-]?[0-9]+)?\Z", re.ASCII)

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
