"""The shape of the command line's messages that every part of it shares: a usage error,
a warning cut to one readable line (``-v`` prints it in full), and standard input named as
the user gave it.

Kept apart from :mod:`frictionlaws.cli._common` (which imports the library) so that
:mod:`frictionlaws.cli` itself loads nothing of the library.
"""

from __future__ import annotations

import re

__all__ = ["UsageError", "WARNING_WIDTH", "short_warning", "shown_source"]

#: The directory name of the private copy of standard input a command reads
#: (:func:`frictionlaws.cli._common.data_source`: ``.../frictionlaws-stdin-XXXX/stdin.csv``).
_STDIN_DIR = "frictionlaws-stdin-"
#: The rest of that copy's path from its directory's name on (matched at one place only).
_STDIN_TAIL = re.compile(r"frictionlaws-stdin-[^\\/\s'\"]{1,64}[\\/]stdin\.\w{1,8}")


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
    named as the user gave it: ``<stdin>``.  Linear in the length of ``text`` (each copy's
    path is matched from its directory's name, found by a plain search)."""
    text = str(text)
    out: list[str] = []
    done = 0
    at = text.find(_STDIN_DIR)
    while at >= 0:
        tail = _STDIN_TAIL.match(text, at)
        if tail is None:
            at = text.find(_STDIN_DIR, at + 1)
            continue
        start = at  # back over the temporary directory's path to the path's first character
        while start > done and text[start - 1] not in " \t\n'\"([=":
            start -= 1
        out.append(text[done:start] + "<stdin>")
        done = tail.end()
        at = text.find(_STDIN_DIR, done)
    return "".join(out) + text[done:]
