"""The shape of the command line's messages that every part of it shares: a usage error,
a warning cut to one readable line (``-v`` prints it in full), and standard input named as
the user gave it.

Kept apart from :mod:`frictionlaws.cli._common` (which imports the library) so that
:mod:`frictionlaws.cli` itself loads nothing of the library.
"""

from __future__ import annotations

import re

__all__ = ["UsageError", "WARNING_WIDTH", "short_warning", "shown_source"]

#: The private copy of standard input a command reads
#: (:func:`frictionlaws.cli._common.data_source`: ``.../frictionlaws-stdin-XXXX/stdin.csv``).
_STDIN_COPY = re.compile(r"(?:[A-Za-z]:)?[^\s'\"]*frictionlaws-stdin-[^\\/\s'\"]+[\\/]"
                         r"stdin\.\w+")


class UsageError(Exception):
    """Bad command-line usage (a malformed, conflicting or inapplicable option)."""


#: Length of a warning line without ``--verbose`` (the whole text with it).
WARNING_WIDTH = 220


def short_warning(text: str) -> str:
    """A long warning cut at a clause boundary, pointing to ``-v`` for the rest."""
    if len(text) <= WARNING_WIDTH:
        return text
    head = text[:WARNING_WIDTH]
    cut = head.rfind("; ")  # the end of a sentence-like clause first, then a shorter one
    if cut <= WARNING_WIDTH // 2:
        cut = max(head.rfind(": "), head.rfind(", "))
    return (head[:cut] if cut > WARNING_WIDTH // 2 else head).rstrip() + " ... (-v: in full)"


def shown_source(text: str) -> str:
    """``text`` (a path, or a message naming paths) with the private copy of standard input
    named as the user gave it: ``<stdin>``."""
    return _STDIN_COPY.sub("<stdin>", str(text))
