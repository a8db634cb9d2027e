"""The ``frictionlaws`` command line.

The CLI is thin: each sub-command lives in its own module ``cmd_<name>.py``
that defines ``add_parser(subparsers)`` and ``run(args) -> int`` and imports
heavy libraries only inside ``run``.  :func:`main` parses, dispatches and turns
bad input into exit code 2 with a one-line message.

Exit codes: 0 success; 1 a check failed (``validate``) or a fit did not
converge; 2 bad input or usage; 3 an unexpected internal error (a bug: the
message asks to report it).
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from importlib import import_module

#: Sub-command modules, in the order ``--help`` lists them.
COMMANDS = (
    "laws",
    "show",
    "fit",
    "compare",
    "datasets",
    "tyre",
    "process",
    "validate",
    "export",
)


class _Parser(argparse.ArgumentParser):
    """An ArgumentParser that raises instead of exiting, for a one-line message."""

    def error(self, message: str) -> None:  # type: ignore[override]
        raise UsageError(f"{self.prog}: {message}")


class UsageError(Exception):
    """Bad command-line usage."""


def build_parser() -> argparse.ArgumentParser:
    """The argument parser with every sub-command (used by the docs' CLI reference)."""
    from frictionlaws import __version__

    parser = _Parser(
        prog="frictionlaws",
        description="Friction laws for rubber and tyres: list, fit, compare, export.",
    )
    parser.add_argument("--version", action="version", version=f"frictionlaws {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for name in COMMANDS:
        module = import_module(f"frictionlaws.cli.cmd_{name.replace('-', '_')}")
        p = module.add_parser(sub)
        p.set_defaults(_run=module.run)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the CLI with ``argv`` (default ``sys.argv[1:]``); return the exit code."""
    from frictionlaws.errors import FitError, InputError

    parser = build_parser()
    try:
        args = parser.parse_args(list(sys.argv[1:] if argv is None else argv))
    except UsageError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except SystemExit as exc:  # --help, --version
        return int(exc.code or 0)
    if not getattr(args, "command", None):
        parser.print_help()
        return 2
    try:
        return int(args._run(args) or 0)
    except InputError as exc:
        print(f"error: {_one_line(str(exc))}", file=sys.stderr)
        return 2
    except UsageError as exc:
        print(f"error: {_one_line(str(exc))}", file=sys.stderr)
        return 2
    except FitError as exc:
        print(f"error: fit failed: {_one_line(str(exc))}", file=sys.stderr)
        return 1
    except BrokenPipeError:
        return 0
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    except Exception as exc:  # noqa: BLE001 - last resort: never a traceback
        print(
            f"error: internal error ({type(exc).__name__}: {_one_line(str(exc))}); "
            "please report it with the command you ran",
            file=sys.stderr,
        )
        return 3


def _one_line(text: str) -> str:
    return " ".join(text.split())


def entry() -> None:
    """Console-script entry point."""
    sys.exit(main())
