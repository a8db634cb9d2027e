"""Reading tables: bytes to text (the one encoding rule), the delimiter, lines and cells, with
the file, column and row of anything refused.
"""

from __future__ import annotations

import csv
import errno
import os
import re
import stat
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..base.errors import InputError
from ..base.limits import read_input
from ..base.outputs import check_input_file
from ..base.sanitize import split_lines

if TYPE_CHECKING:  # pandas is imported where a DataFrame is made or asked for
    import pandas as pd


__all__ = ["Table", "refuse_nul", "decode_text", "detect_delimiter", "read_table",
           "split_header", "output_dir"]


_DELIMITERS = (";", "\t", ",")


_DELIMITER_NAMES = {";": "';'", "\t": "tab", ",": "','"}


# A data row may start with a spreadsheet error value; it is data, not a comment.
_SPREADSHEET_ERROR = re.compile(
    r"^[\"']?#(N/A|VALUE!|DIV/0!|REF!|NUM!|NAME\?|NULL!)", re.IGNORECASE)


#: The control bytes that mark binary content (all below 32 but tab, line feed, form
#: feed and carriage return).
_CONTROLS = bytes(b for b in range(32) if b not in (9, 10, 12, 13))


# --------------------------------------------------------------------------- reading text
@dataclass
class Table:
    """Raw cells of a table, before columns are resolved: what :func:`read_table` returns.

    Other rooms read their own tables through it (a rig's records, a tyre's test data, a
    material's sweeps) and take its numbers with :func:`~frictionlaws.io.column_numbers`.

    Attributes
    ----------
    headers : list of str
        The header cells, as written.
    columns : list of list
        The cells of each column (text from a file; numbers from arrays or a DataFrame).
    rows : list of int
        The source row of each data row (the line a text editor shows).
    source : str
        The file (or what the table came from), named in errors.
    comments, notes : list of str
        The file's comment lines; what reading it noted (an encoding, a delimiter).
    decimal_comma : bool
        True when the file writes decimal commas.
    from_file : bool
        False for a table made from arrays or a DataFrame.
    delimiter : str or None
        The cell delimiter of a file.
    si_by_default : bool
        True for a dict of arrays (the API's SI arrays): a column without a unit is in
        SI; a file and a DataFrame must state every unit (one rule for both).
    """

    headers: list[str]
    columns: list[list[Any]]
    rows: list[int]  # source row of each data row
    source: str
    comments: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    decimal_comma: bool = False
    from_file: bool = True
    delimiter: str | None = None
    si_by_default: bool = False


def refuse_nul(raw: bytes, source: str) -> None:
    """Refuse text with a NUL byte anywhere, naming the row it is on.

    A NUL is never part of a CSV cell; CSV readers either stop at it or fail with an
    internal message, so every table reader calls this before parsing.
    """
    at = raw.find(b"\x00")
    if at >= 0:
        raise InputError("contains a NUL byte (binary content inside a text file); "
                         "expected CSV text", file=source, row=raw.count(b"\n", 0, at) + 1)


def decode_text(raw: bytes, source: str, what: str = "CSV file") -> tuple[str, str | None]:
    """Decode the bytes of a text input file; the one encoding rule of every reader.

    UTF-16 with a byte-order mark, UTF-8 (with or without BOM), then cp1252 and
    latin-1 with a note.  Binary content (a spreadsheet, an image) and NUL bytes
    anywhere are refused.

    Returns
    -------
    text : str
    note : str or None
        Set when the file was not UTF-8, to be shown to the user.
    """
    raw = raw.rstrip(b"\x1a")  # a DOS end-of-file mark (Ctrl-Z) is not content
    for bom, codec in ((b"\xff\xfe\x00\x00", "utf-32"), (b"\x00\x00\xfe\xff", "utf-32"),
                       (b"\xff\xfe", "utf-16"), (b"\xfe\xff", "utf-16")):
        if raw.startswith(bom):
            try:
                return raw.decode(codec), None
            except UnicodeDecodeError:
                raise InputError(f"starts with a {codec.upper()} byte-order mark but does not "
                                 f"decode as {codec.upper()}", file=source) from None
    head = raw[:8192]
    controls = len(head) - len(head.translate(None, _CONTROLS))
    if b"\x00" in head or controls > max(2, len(head) // 20):
        raise InputError(
            f"is not a text {what} (binary content, e.g. a spreadsheet or an image); "
            f"export it as text",
            file=source,
        )
    refuse_nul(raw, source)
    try:
        return raw.decode("utf-8-sig"), None
    except UnicodeDecodeError:
        pass
    for enc in ("cp1252", "latin-1"):
        try:
            return raw.decode(enc), f"file is not UTF-8; read it as {enc}"
        except UnicodeDecodeError:
            continue
    raise InputError("cannot decode the file as text", file=source)  # pragma: no cover


def detect_delimiter(header_line: str) -> str | None:
    """The delimiter of a header line: the first of ``;``, tab and ``,`` it holds.

    Parameters
    ----------
    header_line : str
        The header line of a table.

    Returns
    -------
    str or None
        The delimiter, or None for a single column.
    """
    for d in _DELIMITERS:
        if d in header_line:
            return d
    return None


def read_table(path: str | os.PathLike[str], *, source: str | None = None,
               raw: bytes | None = None, header_hint: str = "'mu,p [MPa],v [m/s]'",
               what: str = "data file") -> Table:
    """Read a CSV file into raw cells: the one table reader (datasets, manifests).

    Detects ``;``, tab or ``,`` delimiters from the header line, decimal commas
    (with ``;`` or tab), the encoding (:func:`decode_text`), ``#`` comment lines
    and blank lines.  Quoted fields must close on their line.  Cells stay strings;
    :func:`load_dataset` converts them.

    Parameters
    ----------
    path : path-like
        The file (ignored for reading when ``raw`` is given).
    source : str, optional
        Name used in messages (default: ``path``).
    raw : bytes, optional
        The file's content, when already read.
    header_hint : str
        An example header, for the message on a file without one.
    what : str
        What the file is, for messages ("data file", "manifest file").
    """
    source = source or str(path)
    if raw is None:
        raw = _read_bytes(Path(path), source, what)
    text, enc_note = decode_text(raw, source)
    table = _scan_lines(split_lines(text), source, header_hint)
    if enc_note:
        table.notes.append(enc_note)
    return table


def _read_bytes(p: Path, source: str, what: str) -> bytes:
    try:
        mode: int | None = os.stat(p).st_mode
    except OSError as exc:  # not there: named here; anything else: by check_input_file
        if exc.errno not in (errno.ENOENT, errno.ENOTDIR, errno.EBADF, errno.ELOOP):
            mode = None
        else:
            raise InputError(
                "file not found; expected a CSV file or the name of a packaged dataset"
                if what == "data file"
                else f"{what} not found", file=source) from None
    if mode is not None and stat.S_ISDIR(mode):
        raise InputError(f"is a directory; expected a {what} (CSV)", file=source)

    check_input_file(p, what)  # a FIFO or device would block or never end
    return read_input(p, what, source)  # bounded in size


def _scan_lines(lines: list[str], source: str, header_hint: str) -> Table:
    """Header, comments and data rows of the decoded lines (see :func:`read_table`)."""
    comments: list[str] = []
    header: list[str] | None = None
    header_row = 0
    delimiter: str | None = None
    data: list[list[str]] = []
    rows: list[int] = []
    for number, line in enumerate(lines, start=1):
        if header is not None and delimiter is not None and _plain_rows(
                lines, number - 1, delimiter, data, rows):
            break  # the rest: plain rows, split at once
        stripped = line.strip()
        if stripped.startswith("#") and not (header is not None
                                             and _SPREADSHEET_ERROR.match(stripped)):
            comments.append(stripped[1:].strip() if stripped[1:2] != " " else stripped[2:])
            continue
        if not stripped:
            continue
        if header is None:
            delimiter = detect_delimiter(line)
            header = _split(line, delimiter, source, number)
            header_row = number
            continue
        if delimiter is None and any(d in line for d in _DELIMITERS):
            found = next(_DELIMITER_NAMES[d] for d in _DELIMITERS if d in line)
            raise InputError(
                f"the header has a single column '{header[0]}' but this row contains "
                f"{found}: the header and the data use different delimiters",
                file=source, row=number,
            )
        data.append(_split(line, delimiter, source, number))
        rows.append(number)
    if header is None:
        raise InputError(f"file is empty (no header line); expected a header such as "
                         f"{header_hint} followed by data rows", file=source)
    if not data:
        raise InputError(f"file has a header (row {header_row}) but no data rows",
                         file=source)
    headers = [h.strip() for h in header]
    columns = _rectangular(data, rows, headers, delimiter, source)
    return Table(headers, columns, rows, source, comments, [], delimiter in (";", "\t"),
                  True, delimiter)


def _plain_rows(lines: list[str], start: int, delimiter: str, data: list[list[str]],
                rows: list[int]) -> bool:
    """The data rows from line ``start`` (0-based) on, when none is quoted or a comment.

    Then every non-blank line is a row, split at the delimiter (as the csv module
    splits an unquoted line, spaces after a delimiter skipped), and True is returned;
    otherwise nothing is read and False is returned (the lines go one by one).
    """
    rest = lines[start:]
    if any('"' in line or "#" in line for line in rest):
        return False
    for number, line in enumerate(rest, start=start + 1):
        if line and not line.isspace():
            cells = line.split(delimiter)
            data.append([cell.lstrip(" ") for cell in cells] if " " in line else cells)
            rows.append(number)
    return True


def _rectangular(data: list[list[str]], rows: list[int], headers: list[str],
                 delimiter: str | None, source: str) -> list[list[str]]:
    """Columns of the rows, each padded or checked to the header's width."""
    ncol = len(headers)
    for cells, number in zip(data, rows, strict=True):
        if len(cells) > ncol:
            if any(c.strip() for c in cells[ncol:]):
                raise InputError(
                    f"has {len(cells)} fields but the header has {ncol} "
                    f"(delimiter {_DELIMITER_NAMES.get(delimiter or '', 'none')}); "
                    "check the delimiter and the quoting"
                    + ("; a decimal comma needs ';' or tab as the delimiter"
                       if delimiter == "," else ""),
                    file=source, row=number,
                )
            del cells[ncol:]
        elif len(cells) < ncol:
            if len(cells) == 1 and ncol > 1 and any(d in cells[0] for d in _DELIMITERS):
                raise InputError(
                    f"has 1 field but the header has {ncol}: the row uses another "
                    f"delimiter than the header ({_DELIMITER_NAMES.get(delimiter or '')})",
                    file=source, row=number,
                )
            cells.extend([""] * (ncol - len(cells)))
    return [[cells[j] for cells in data] for j in range(ncol)]


def _split(line: str, delimiter: str | None, source: str, row: int) -> list[str]:
    if delimiter is None:
        return [line.strip()]
    if '"' not in line and line:  # no quoting: the cells csv reads, leading spaces skipped
        return [cell.lstrip(" ") for cell in line.split(delimiter)]
    try:
        return next(csv.reader([line], delimiter=delimiter, skipinitialspace=True,
                               strict=True))
    except csv.Error as exc:
        hint = ("a quoted field is not closed on its line (a line break inside quotes?); "
                "write each row on one line" if "end of data" in str(exc)
                else f"malformed quoting ({exc})")
        raise InputError(hint, file=source, row=row) from None


def _table_from_frame(df: pd.DataFrame, source: str) -> Table:
    headers = [str(c) for c in df.columns]
    columns = [df.iloc[:, j].tolist() for j in range(df.shape[1])]
    rows = list(range(1, len(df) + 1))
    if not len(df):
        raise InputError("the DataFrame has no rows", file=source)
    return Table(headers, columns, rows, source, from_file=False)


# --------------------------------------------------------------------------- building
def split_header(h: str, *, brackets_in_name: bool = True) -> tuple[str, str | None]:
    """``"p [MPa]"`` -> ``("p", "MPa")``; ``"p"`` -> ``("p", None)``: the one header rule.

    The unit is the text between the last ``[`` and a final ``]``; it may hold no
    bracket.  Done with string searches, in time linear in the header's length (a
    regular expression with a lazy name and optional spaces is quadratic on a cell
    padded with spaces).

    Parameters
    ----------
    h : str
        The header cell.
    brackets_in_name : bool
        Whether the name before the unit may hold ``[`` or ``]`` (a record's may not).

    Returns
    -------
    tuple of (str, str or None)
        The name and the unit (stripped), or the stripped header and None.
    """
    s = h.rstrip()
    opening = s.rfind("[", 0, len(s) - 1)
    if not s.endswith("]") or opening < 0 or "]" in s[opening + 1:-1]:
        return h.strip(), None
    name = s[:opening]
    if not brackets_in_name and ("[" in name or "]" in name):
        return h.strip(), None
    return name.strip(), s[opening + 1:-1].strip()


# --------------------------------------------------------------------------- packaged
def output_dir(path: str | Path, what: str = "output directory") -> Path:
    """Create ``path`` (and parents) for writing; an :class:`InputError` names it when it fails."""
    out = Path(path)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"cannot create the {what} ({exc.strerror})", file=str(out)) from None
    return out

