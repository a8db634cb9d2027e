"""The sub-commands of ``frictionlaws``: one line each, in the order ``--help`` lists them.

Each command is a module ``frictionlaws/cli/cmd_<name>.py`` with ``add_parser(subparsers)``
(which takes its ``--help`` line from :data:`COMMANDS`) and ``run(args) -> int``.  The CLI
imports a command's module only when that command is run or its help asked for (or the
whole parser is: shell completion, the docs), so a module imports what its command needs at
its top, and ``frictionlaws --help`` loads none of them.
"""

from __future__ import annotations

__all__ = ["COMMANDS"]

#: Command name -> its line in ``frictionlaws --help``, in the order listed there.
COMMANDS: dict[str, str] = {
    "laws": "list the registered friction laws",
    "show": "show a law: formula, parameters, presets, evidence",
    "fit": "fit a law to a dataset",
    "compare": "compare laws on one dataset (fit, CV, extrapolation, report)",
    "datasets": "list packaged datasets, or describe one or a CSV file",
    "tyre": "use friction laws inside tyre models (brush model, Magic Formula)",
    "process": "process raw tribometer records into a dataset",
    "validate": "run the validation suite against published values",
    "export": "export a law to Abaqus, LS-DYNA, Ansys, Radioss, tables or Fortran",
    "examples": "write the example files the README and the guide use",
}
