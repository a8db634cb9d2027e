"""Text crossing a file boundary: the one line rule of readers, one sanitiser per output format.

Readers split lines only at ``\\n``, ``\\r\\n`` and ``\\r`` (:func:`split_lines`), as the
csv module, pandas and other tools' readers do; :meth:`str.splitlines` would also split
at ``\\v``, ``\\f``, U+001C-U+001E, U+0085, U+2028 and U+2029, so one row of a file
could become two.

Writers put every string that came from a user or a file (names, sources, groups,
notes, messages) through the sanitiser of the format they write, so that no such
string can add a line, a section, a key, a formula or markup:

==================================  ==========================================
format                              sanitiser
==================================  ==========================================
solver decks, Fortran, ``.tir``     :func:`ascii_line` (comments: ``$``, ``!``,
                                    ``**``, ``#``, ``C``); ``.tir`` strings:
                                    :func:`tir_string`
CSV comment blocks (``#`` lines)    :func:`comment_lines`
CSV text cells                      :func:`csv_cell` (:func:`csv_row`, :func:`frame_csv`;
                                    read back by :func:`csv_cell_text`)
Markdown                            :func:`markdown_text`
HTML                                :func:`html_text`
==================================  ==========================================

Units are written in the canonical form of :func:`frictionlaws.base.units.canonical_unit`,
never as typed.
"""

from __future__ import annotations

import html
import unicodedata
from collections.abc import Iterable, Mapping
from typing import Any

from .numbers import is_number

__all__ = ["split_lines", "one_line", "ascii_line", "comment_lines", "csv_cell",
           "csv_cell_text", "csv_row", "frame_csv", "markdown_text", "html_text", "tir_string"]

#: Unicode categories that never belong inside one line of a generated file: control
#: characters (``\\r``, ``\\v``, ``\\f``, U+0085...), format characters (bidirectional
#: overrides, zero-width joiners), line and paragraph separators, surrogates.
_BREAKING = frozenset({"Cc", "Cf", "Zl", "Zp", "Cs"})

#: Characters that start a formula in a spreadsheet when they open a cell.
_FORMULA_START = ("=", "+", "-", "@")


def split_lines(text: str) -> list[str]:
    """The lines of ``text``, split only at ``\\n``, ``\\r\\n`` and ``\\r`` (no line ends kept).

    Parameters
    ----------
    text : str
        Decoded file content.

    Returns
    -------
    list of str
        As :meth:`str.splitlines` would give for text with those line ends only: a
        final line end does not add an empty line.
    """
    lines = text.replace("\r\n", "\n").replace("\r", "\n").split("\n")
    if lines and lines[-1] == "":
        lines.pop()
    return lines


def one_line(text: object) -> str:
    """``text`` on one line: every line break and control or format character a space.

    Parameters
    ----------
    text : object
        Any value; it is written with :class:`str`.

    Returns
    -------
    str
    """
    s = str(text)
    if s.isprintable() and s.isascii():
        return s
    return "".join(" " if unicodedata.category(ch) in _BREAKING else ch for ch in s)


def ascii_line(text: object) -> str:
    """``text`` on one ASCII line, other characters escaped (``\\u00b5``): decks, sources, .tir.

    Parameters
    ----------
    text : object

    Returns
    -------
    str
    """
    return one_line(text).encode("ascii", "backslashreplace").decode("ascii")


def comment_lines(lines: Iterable[object], prefix: str = "# ") -> list[str]:
    """Comment lines of a CSV file: each given line one line, then ``prefix`` before it.

    A given line that holds line ends stays one comment line (its breaks become
    spaces): nothing it holds can become a data line.

    Parameters
    ----------
    lines : iterable
        The comment texts, one per line.
    prefix : str
        Written before each.

    Returns
    -------
    list of str
        Without trailing white space.
    """
    return [f"{prefix}{one_line(line)}".rstrip() for line in lines]


def _formula_like(text: str) -> bool:
    """True when a spreadsheet would read ``text`` as a formula (not a plain number)."""
    head = text.lstrip()
    return head.startswith(_FORMULA_START) and len(head) > 1 and not is_number(text)


def csv_cell(text: object) -> str:
    """A text cell of a CSV table: one line, and never a spreadsheet formula.

    A cell that starts with ``=``, ``+``, ``-`` or ``@`` and is not a number gets a
    leading ``'`` (the spreadsheet convention for "text"); so does one that already
    starts with ``'`` before such a character, so that :func:`csv_cell_text` gives
    every text back.

    Parameters
    ----------
    text : object

    Returns
    -------
    str
    """
    s = one_line(text)
    return "'" + s if _formula_like(s.lstrip("'")) else s


def csv_cell_text(cell: str) -> str:
    """The text a cell written by :func:`csv_cell` holds: one ``'`` before a formula removed.

    The inverse the readers apply to text cells, so that a table written by frictionlaws
    reads back as it was (spreadsheets hide that ``'`` the same way).

    Parameters
    ----------
    cell : str

    Returns
    -------
    str
    """
    return cell[1:] if cell[:1] == "'" and _formula_like(cell.lstrip("'")) else cell


def csv_row(row: Mapping[str, Any]) -> dict[str, Any]:
    """A row of a CSV table with its text cells through :func:`csv_cell` (numbers kept)."""
    return {k: csv_cell(v) if isinstance(v, str) else v for k, v in row.items()}


def frame_csv(frame: Any, **options: Any) -> str:
    """A DataFrame as CSV text, its headers and text cells through :func:`csv_cell`.

    Parameters
    ----------
    frame : pandas.DataFrame
        The table (not changed).
    **options
        Passed on to :meth:`pandas.DataFrame.to_csv` (``index`` is False).

    Returns
    -------
    str
    """
    import pandas as pd

    out = frame.copy()
    for col in out.columns:
        if not pd.api.types.is_numeric_dtype(out[col]):
            out[col] = out[col].map(lambda x: csv_cell(x) if isinstance(x, str) else x)
    out.columns = [csv_cell(c) for c in out.columns]
    return str(out.to_csv(index=False, **options))


def markdown_text(text: object) -> str:
    """Text inside a Markdown line or table cell: one line, HTML and link syntax escaped.

    Parameters
    ----------
    text : object

    Returns
    -------
    str
    """
    s = one_line(text)
    for ch in "\\`[]|":
        s = s.replace(ch, "\\" + ch)
    return html.escape(s, quote=False)  # quotes are plain text in Markdown


def html_text(text: object) -> str:
    """Text inside an HTML element or attribute: one line, escaped.

    Parameters
    ----------
    text : object

    Returns
    -------
    str
    """
    return html.escape(one_line(text), quote=True)


def tir_string(text: object) -> str:
    """A quoted string value of a ``.tir`` file (without its quotes): one ASCII line, no ``'``.

    Parameters
    ----------
    text : object

    Returns
    -------
    str
    """
    return ascii_line(text).replace("'", '"')
