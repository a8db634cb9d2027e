"""Exception types used across frictionlaws.

Every error raised because of what a user supplied (a file, a column, a unit,
a law name, a parameter) derives from :class:`InputError`.  The CLI turns any
``InputError`` into a one-line message on stderr and exit code 2.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

__all__ = ["FrictionLawsError", "InputError", "UnknownLawError", "GroupingError",
           "DomainError", "FitError", "ExtrapolationWarning", "Argument", "Label",
           "MAX_MESSAGE_CHARS", "bounded_message"]

#: How a front end names an argument of the API (the CLI: the flag that sets it).
Label = Callable[[str], str]


@dataclass(frozen=True)
class Argument:
    """An argument and a value quoted inside an error message, named by the front end.

    The library writes ``Argument("mapping", "mu=COLUMN")`` where a message tells
    the user what to set; the API shows it as ``mapping='mu=COLUMN'``, the CLI as
    its flag followed by the value (see :meth:`InputError.compose`).  So library
    messages never quote command-line flags.

    Parameters
    ----------
    option : str
        The API argument (``"mapping"``, ``"units"``, ``"area"``, ``"box.p"``...).
    value : str
        The value to show with it (may be empty: the argument alone).
    switch : bool
        The argument and value are one choice a front end may name by itself (a
        command-line switch such as ``--drop-invalid`` for ``on_invalid='drop'``).
    """

    option: str
    value: str = ""
    switch: bool = False

    def render(self, label: Label | None = None) -> str:
        """The setting as the front end writes it (the API's keyword form by default).

        With ``switch`` the front end names the argument and value together
        (``label("on_invalid=drop")``: the CLI's ``--drop-invalid``).
        """
        if label is not None and self.switch:
            return label(f"{self.option}={self.value}")
        if label is not None:
            return f"{label(self.option)} {self.value}".rstrip()
        name, _, key = self.option.partition(".")
        target = f"{name}[{key!r}]" if key else name
        return f"{target}={self.value!r}" if self.value else target


#: Longest message [characters]; the rest is elided, saying how much (a file with a
#: million columns must not make a megabyte-long error line).
MAX_MESSAGE_CHARS = 2000


def bounded_message(text: str, limit: int = MAX_MESSAGE_CHARS) -> str:
    """``text`` cut to ``limit`` characters, saying how many were left out.

    Parameters
    ----------
    text : str
        The message.
    limit : int
        The longest text returned.

    Returns
    -------
    str
    """
    if len(text) <= limit:
        return text
    keep = limit - 60
    return f"{text[:keep]} ... ({len(text) - keep} more characters not shown)"


#: A message: plain text, or text and :class:`Argument` pieces.
Message = str | Sequence[str | Argument]


class FrictionLawsError(Exception):
    """Base class of all frictionlaws errors."""


class InputError(FrictionLawsError, ValueError):
    """Bad input: a malformed file, an unknown unit or law, an invalid value.

    Parameters
    ----------
    message : str or sequence of str and Argument
        What is wrong and what was expected; an :class:`Argument` piece names an
        argument the user may set, in the words of the front end.
    file : str, optional
        The file concerned.
    column : str, optional
        The column concerned.
    row : int, optional
        The 1-based data row concerned (as a spreadsheet shows it, header = row 1).
    option : str, optional
        The argument of the API call concerned (``"mapping"``, ``"units"``,
        ``"area"``, ``"fix"``, ``"box.p"``...).  Messages written with it do not
        repeat the argument's name: the front end names it its own way (the CLI
        as a command-line flag), see :meth:`compose`.
    """

    def __init__(
        self,
        message: Message,
        *,
        file: str | None = None,
        column: str | None = None,
        row: int | None = None,
        option: str | None = None,
    ) -> None:
        self.file = file
        self.column = column
        self.row = row
        self.option = option
        self.parts: tuple[str | Argument, ...] = (
            (message,) if isinstance(message, str) else tuple(message))
        #: The message without its location, settings named as API arguments.
        self.bare_message = self.render()
        super().__init__(self._compose())

    def render(self, label: Label | None = None) -> str:
        """Write the message without its location.

        Parameters
        ----------
        label : callable, optional
            How the front end names an API argument; by default the API's form.

        Returns
        -------
        str
            The text, with the :class:`Argument` pieces named by ``label``.
        """
        return "".join(p if isinstance(p, str) else p.render(label) for p in self.parts)

    def replace_text(self, old: str, new: str) -> None:
        """Replace ``old`` by ``new`` in the message and the file name (e.g. a private path).

        Parameters
        ----------
        old, new : str
            The text to replace and its replacement.
        """
        self.parts = tuple(p.replace(old, new) if isinstance(p, str) else p
                           for p in self.parts)
        if self.file == old:
            self.file = new
        self.bare_message = self.render()
        self.args = (self._compose(),)

    def _compose(self) -> str:
        return self.compose()

    def compose(self, option_label: str | None = None, *, label: Label | None = None) -> str:
        """Compose the message with its location (option, file, column, row).

        Parameters
        ----------
        option_label : str, optional
            How to name :attr:`option`; by default ``label(option)``, else the
            API argument (``argument 'mapping'``).
        label : callable, optional
            How the front end names an API argument (the CLI: its flag); used for
            :attr:`option` and for the :class:`Argument` pieces of the message.

        Returns
        -------
        str
            ``"<location>: <message>"``, the location listing the option, file,
            column and row that are set; the bare message when none is.
        """
        where = []
        if self.option is not None:
            where.append(option_label or (label(self.option) if label is not None
                                          else f"argument '{self.option}'"))
        if self.file is not None:
            where.append(f"file '{self.file}'")
        if self.column is not None:
            where.append(f"column '{self.column}'")
        if self.row is not None:
            where.append(f"row {self.row}")
        prefix = ", ".join(where)
        text = self.render(label)
        return bounded_message(f"{prefix}: {text}" if prefix else text)


class UnknownLawError(InputError, KeyError):
    """A law name or alias that is not registered.

    Parameters
    ----------
    message : str
        What is wrong and what was expected (the closest registered names).
    file : str, optional
        The file concerned.
    column : str, optional
        The column concerned.
    row : int, optional
        The 1-based data row concerned (as a spreadsheet shows it, header = row 1).
    option : str, optional
        The argument of the API call concerned, as for :class:`InputError`.
    """

    def __str__(self) -> str:  # KeyError would add quotes
        return self._compose()


class GroupingError(InputError):
    """Rows from several groups (counter-surfaces, compounds, rigs...) given to one pooled fit.

    ``column`` names the grouping column; the message ends with how to fit each group,
    in the words of the front end (``by='surface'`` in the API, the command line's
    own flag there).
    """

    def __init__(self, message: str, *, column: str, file: str | None = None) -> None:
        self.group_column = column
        super().__init__(message, file=file, column=column, option="by")

    def compose(self, option_label: str | None = None, *, label: Label | None = None) -> str:
        where = ", ".join(x for x in (f"file '{self.file}'" if self.file else "",
                                      f"column '{self.column}'") if x)
        flag = option_label or (label("by") if label is not None else None)
        how = f"{flag} {self.group_column}" if flag else f"by={self.group_column!r}"
        return f"{where}: {self.render(label)}; fit each group on its own ({how})"


class DomainError(InputError):
    """A law was asked to do something outside what it is defined for."""


class FitError(FrictionLawsError):
    """A fit could not be carried out (not a data-format problem)."""


class ExtrapolationWarning(UserWarning):
    """A law is used outside the range its parameters were fitted on or valid for."""


def broadcast_shape(named: Mapping[str, Any], source: str | None = None,
                    subject: str = "") -> tuple[int, ...]:
    """The common shape of named array inputs, or an :class:`InputError` naming each shape.

    Parameters
    ----------
    named : mapping
        Input name -> scalar or array.
    source : str, optional
        The file whose model is evaluated, for the message.
    subject : str, optional
        What is evaluated (``"law 'thirion'"``), said first in the message.

    Returns
    -------
    tuple of int
        The shape every input broadcasts to.
    """
    import numpy as np

    shapes = {k: np.shape(v) for k, v in named.items()}
    try:
        return tuple(np.broadcast_shapes(*shapes.values()))
    except ValueError:
        listed = ", ".join(f"{k} {s}" for k, s in shapes.items() if s != ())
        raise InputError(f"{subject + ': ' if subject else ''}the inputs' shapes do not fit "
                         f"together ({listed}): give scalars "
                         "or arrays of one length, one value per row",
                         file=source) from None
