"""The bounds of every input: size (files and standard input), nesting depth, message length.

Every reader takes its bytes through :func:`read_input` (files) or :func:`read_stream`
(standard input), every structured reader (JSON, TOML) checks its document with
:func:`check_nesting`, and every message is cut by
:func:`~frictionlaws.base.errors.bounded_message` (re-exported here).  An input beyond a
limit is refused with an :class:`~frictionlaws.base.errors.InputError` that names the limit
(exit 2 on the command line).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import IO, Any

from .errors import MAX_MESSAGE_CHARS, InputError, bounded_message

__all__ = ["MAX_INPUT_BYTES", "MAX_NESTING", "MAX_MESSAGE_CHARS", "read_input", "read_stream",
           "check_nesting", "nesting_error", "bounded_message"]

#: Largest input file or standard input read [bytes] (256 MiB: a day of 1 kHz records).
MAX_INPUT_BYTES = 256 * 2**20
#: Deepest nesting of arrays and tables in a JSON or TOML input (the formats use 3).
MAX_NESTING = 32


def _too_large(what: str, source: str, size: int | None = None) -> InputError:
    got = f" ({size} bytes)" if size is not None else ""
    return InputError(f"the {what} is larger than the limit of {MAX_INPUT_BYTES} bytes"
                      f"{got}; split it", file=source)


def read_input(path: str | os.PathLike[str], what: str = "input file",
               source: str | None = None) -> bytes:
    """The bytes of an input file, refused beyond :data:`MAX_INPUT_BYTES`.

    Parameters
    ----------
    path : path-like
        A regular file (checked by the caller, e.g. with
        :func:`~frictionlaws.base.outputs.check_input_file`).
    what : str
        What the file is, for the message.
    source : str, optional
        How to name the file (default: ``path``).

    Returns
    -------
    bytes

    Raises
    ------
    InputError
        Beyond the limit, or when the file cannot be read.
    """
    src = source or str(path)
    try:
        with open(Path(path), "rb") as fh:
            size = os.fstat(fh.fileno()).st_size
            if size > MAX_INPUT_BYTES:
                raise _too_large(what, src, size)
            data = _read_all(fh, size)
    except OSError as exc:
        raise InputError(f"cannot read the {what} ({exc.strerror})", file=src) from None
    if len(data) > MAX_INPUT_BYTES:
        raise _too_large(what, src)
    return data


def _read_all(fh: IO[bytes], size: int) -> bytes:
    """The bytes of ``fh`` up to one beyond the limit: the size it stated, then any more
    (a file that grew, or one whose size the system does not know) in bounded chunks."""
    data = fh.read(size + 1)
    if len(data) <= size:
        return data
    parts = [data]
    total = len(data)
    while total <= MAX_INPUT_BYTES:
        chunk = fh.read(min(1 << 20, MAX_INPUT_BYTES + 1 - total))
        if not chunk:
            break
        parts.append(chunk)
        total += len(chunk)
    return b"".join(parts)


def read_stream(stream: IO[Any], what: str = "standard input",
                source: str = "<stdin>") -> bytes:
    """Everything on ``stream`` (text or binary), refused beyond :data:`MAX_INPUT_BYTES`.

    Parameters
    ----------
    stream : file object
        Standard input (its ``buffer`` is read when it has one).
    what, source : str
        How to name it in the message.

    Returns
    -------
    bytes
    """
    raw = getattr(stream, "buffer", stream).read(MAX_INPUT_BYTES + 1)
    data = raw.encode("utf-8") if isinstance(raw, str) else bytes(raw)
    if len(data) > MAX_INPUT_BYTES:
        raise _too_large(what, source)
    return data


def check_nesting(doc: Any, what: str = "document", source: str | None = None) -> None:
    """Refuse a decoded JSON/TOML document nested deeper than :data:`MAX_NESTING`.

    Walks the document without recursion.

    Parameters
    ----------
    doc : object
        The decoded document (dicts, lists and scalars).
    what : str
        What the document is, for the message.
    source : str, optional
        The file, for the message.

    Raises
    ------
    InputError
    """
    stack: list[tuple[Any, int]] = [(doc, 0)]
    while stack:
        node, depth = stack.pop()
        if isinstance(node, dict):
            children: Any = node.values()
        elif isinstance(node, list):
            children = node
        else:
            continue
        if depth >= MAX_NESTING:
            raise nesting_error(what, source)
        stack.extend((child, depth + 1) for child in children)


def nesting_error(what: str = "document", source: str | None = None) -> InputError:
    """The error for a document nested beyond :data:`MAX_NESTING` (also for a parser's
    own recursion limit)."""
    return InputError(f"the {what} is nested deeper than the limit of {MAX_NESTING} levels",
                      file=source)
