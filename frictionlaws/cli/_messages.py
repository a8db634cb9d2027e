"""The shape of the command line's messages that every part of it shares: a usage error,
and a warning cut to one readable line (``-v`` prints it in full).

Kept apart from :mod:`frictionlaws.cli._common` (which imports the library) so that
:mod:`frictionlaws.cli` itself loads nothing of the library.
"""

from __future__ import annotations

__all__ = ["UsageError", "WARNING_WIDTH", "short_warning"]


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
