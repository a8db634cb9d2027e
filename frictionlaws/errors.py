"""Exception types used across frictionlaws.

Every error raised because of what a user supplied (a file, a column, a unit,
a law name, a parameter) derives from :class:`InputError`.  The CLI turns any
``InputError`` into a one-line message on stderr and exit code 2.
"""

from __future__ import annotations

__all__ = ["FrictionLawsError", "InputError", "UnknownLawError", "GroupingError",
           "DomainError", "FitError", "ExtrapolationWarning"]


class FrictionLawsError(Exception):
    """Base class of all frictionlaws errors."""


class InputError(FrictionLawsError, ValueError):
    """Bad input: a malformed file, an unknown unit or law, an invalid value.

    Parameters
    ----------
    message : str
        What is wrong and what was expected.
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
        as a flag such as ``--map``), see :meth:`compose`.
    """

    def __init__(
        self,
        message: str,
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
        self.bare_message = message
        super().__init__(self._compose())

    def _compose(self) -> str:
        return self.compose()

    def compose(self, option_label: str | None = None) -> str:
        """Compose the message with its location (option, file, column, row).

        Parameters
        ----------
        option_label : str, optional
            How to name :attr:`option`: the CLI passes its flag (``--map``).
            Without a label the option is named as the API argument
            (``argument 'mapping'``).

        Returns
        -------
        str
            ``"<location>: <message>"``, the location listing the option, file,
            column and row that are set; the bare message when none is.
        """
        where = []
        if self.option is not None:
            where.append(option_label or f"argument '{self.option}'")
        if self.file is not None:
            where.append(f"file '{self.file}'")
        if self.column is not None:
            where.append(f"column '{self.column}'")
        if self.row is not None:
            where.append(f"row {self.row}")
        prefix = ", ".join(where)
        return f"{prefix}: {self.bare_message}" if prefix else self.bare_message


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
    in the words of the front end (``by='surface'`` in the API, ``--by surface`` on the
    command line).
    """

    def __init__(self, message: str, *, column: str, file: str | None = None) -> None:
        self.group_column = column
        super().__init__(message, file=file, column=column, option="by")

    def compose(self, option_label: str | None = None) -> str:
        where = ", ".join(x for x in (f"file '{self.file}'" if self.file else "",
                                      f"column '{self.column}'") if x)
        how = (f"{option_label} {self.group_column}" if option_label
               else f"by={self.group_column!r}")
        return f"{where}: {self.bare_message}; fit each group on its own ({how})"


class DomainError(InputError):
    """A law was asked to do something outside what it is defined for."""


class FitError(FrictionLawsError):
    """A fit could not be carried out (not a data-format problem)."""


class ExtrapolationWarning(UserWarning):
    """A law is used outside the range its parameters were fitted on or valid for."""
