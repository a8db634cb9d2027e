"""The ``frictionlaws`` command line.

The CLI is thin: each sub-command lives in its own module ``cmd_<name>.py``
that defines ``add_parser(subparsers)`` and ``run(args) -> int`` (the commands and
their ``--help`` lines: :data:`~frictionlaws.cli.commands.COMMANDS`).  :func:`main`
builds the parser of the command it is given only, so that a command module imports
what its command needs at its top and ``frictionlaws --help`` loads none of them.  It
parses, dispatches and keeps the output clean:

* bad input or usage -> exit 2 and one line on stderr (``error: ...``), naming
  the file, column, row or option concerned; an unreadable or unwritable user
  file (``OSError``) and malformed JSON/TOML are bad input too;
* Python, numpy, scipy and pandas warnings raised during a command are collected
  and printed once each, after the command's output, as ``warning: ...`` lines
  (with a count when repeated), never with source paths; when the command then fails,
  they come before its one ``error:`` line (what was warned of before the refusal is
  not lost, and the last line is the error);
* an unexpected internal error -> exit 3 and one line asking for a report;
  ``--debug`` adds the traceback.

Global flags (before or after the command): ``--quiet`` (no warning lines, whether
collected or printed by the command, and no automatic progress bar),
``--verbose`` (warnings in full, with their category and origin; without it a
warning longer than :data:`WARNING_WIDTH` characters is cut at a clause), ``--debug``
(tracebacks of internal errors); ``--print-completion SHELL`` before the command.
A mistyped command, choice or option gets the closest names suggested (difflib).

Exit codes: 0 success; 1 a check failed (``validate``) or a fit did not
converge; 2 bad input or usage; 3 an unexpected internal error (a bug: the
message asks to report it).
"""

from __future__ import annotations

import argparse
import contextlib
import difflib
import io
import json
import re
import signal
import sys
import threading
import traceback
import warnings
from collections.abc import Callable, Collection, Iterator, Sequence
from importlib import import_module
from typing import Any

from .. import __version__
from ..base.errors import FitError, InputError, bounded_message
from ._messages import WARNING_WIDTH, UsageError, shown_source
from ._messages import short_warning as _short
from .commands import COMMANDS

__all__ = ["COMMANDS", "UsageError", "build_parser", "main", "entry", "OPTION_FLAGS",
           "command_names", "WARNING_WIDTH"]


#: Library argument (``InputError.option``) -> the flag that sets it.  A command
#: may override entries with ``set_defaults(_option_flags={...})``.
OPTION_FLAGS = {
    "mapping": "--map",
    "units": "--units",
    "area": "--area",
    "fix": "--fix",
    "on_invalid=drop": "--drop-invalid",
    "free": "--free",
    "starts": "--starts",
    "seed": "--seed",
    "weights": "--weights",
    "uncertainty": "--uncertainty",
    "n_boot": "--boot",
    "n_jobs": "--boot-jobs",
    "interval": "--boot-interval",
    "params": "--set",
    "preset": "--preset",
    "folds": "--folds",
    "mu_limits": "--mu-min/--mu-max",
    "holdout": "--holdout",
    "jobs": "--jobs",
    "by": "--by",
    "min_repeats": "--min-repeats",
    "tol": "--tol",
    "max_rows": "--max-rows",
    "spacing": "--spacing",
    "box.p": "--p",
    "box.v": "--v",
    "box.T": "--T",
    "box.F_N": "--F_N",
    "box.s": "--s",
}

_SHELLS = ("bash", "zsh", "tcsh")


class _StoreOnce(argparse._StoreAction):
    """The default ``store`` action, refusing a single-valued option given twice differently.

    ``--law thirion --law coulomb`` would otherwise keep the last silently.
    """

    def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace,
                 values: Any, option_string: str | None = None) -> None:
        given = namespace.__dict__.setdefault("_given_once", {})
        if self.option_strings and self.dest in given and given[self.dest] != values:
            raise argparse.ArgumentError(
                self, f"given twice with different values ('{given[self.dest]}' and "
                      f"'{values}'); give it once")
        given[self.dest] = values
        setattr(namespace, self.dest, values)


class _Parser(argparse.ArgumentParser):
    """An ArgumentParser that raises instead of exiting, for a one-line message."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.register("action", None, _StoreOnce)
        self.register("action", "store", _StoreOnce)

    def error(self, message: str) -> None:  # type: ignore[override]
        raise _ParseError(f"{self.prog}: {_suggest_choice(message)}",
                          usage=self.format_usage())


_INVALID_CHOICE = re.compile(r"invalid choice: '(.*?)' \(choose from (.*)\)$", re.S)


def _did_you_mean(word: str, candidates: Sequence[str]) -> str:
    """``"; did you mean 'fit'?"`` for the closest candidates (difflib), or ``""``."""
    close = difflib.get_close_matches(word, list(candidates), n=2, cutoff=0.6)
    return f"; did you mean {' or '.join(repr(c) for c in close)}?" if close else ""


def _suggest_choice(message: str) -> str:
    """argparse's 'invalid choice' message with the closest choices suggested."""
    m = _INVALID_CHOICE.search(message)
    if not m:
        return message
    choices = re.findall(r"'([^']*)'", m.group(2))
    return message + _did_you_mean(m.group(1), choices)


class _ParseError(UsageError):
    """A command line argparse could not parse, with the usage of the parser that failed."""

    def __init__(self, message: str, *, usage: str) -> None:
        super().__init__(message)
        self.usage = usage


def build_parser(commands: Collection[str] | None = None) -> argparse.ArgumentParser:
    """The argument parser, with the arguments of ``commands`` (default: every command).

    Parameters
    ----------
    commands : collection of str, optional
        The sub-commands whose module is imported and whose arguments are added; the
        others are listed with their ``--help`` line only.  None: every one (the docs'
        CLI reference, shell completion).

    Returns
    -------
    argparse.ArgumentParser
        The parser.
    """
    parser = _Parser(
        prog="frictionlaws",
        description="Friction laws for rubber and tyres: list, fit, compare, export.",
        allow_abbrev=False,  # else '--v' after a command would be read as '--verbose'
    )
    parser.add_argument("--version", action="version", version=f"frictionlaws {__version__}")
    talk = parser.add_mutually_exclusive_group()
    talk.add_argument("-q", "--quiet", action="store_true",
                      help="no warnings and no automatic progress bar on stderr (this flag, "
                           "-v and --debug may also follow the command)")
    talk.add_argument("-v", "--verbose", action="store_true",
                      help="warnings in full, with their category and origin")
    parser.add_argument("--debug", action="store_true",
                        help="print the traceback behind an internal error (exit 3)")
    parser.add_argument("--print-completion", choices=_SHELLS, metavar="SHELL",
                        help="print a shell completion script (bash, zsh or tcsh) and exit")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for name, line in COMMANDS.items():
        if commands is not None and name not in commands:
            sub.add_parser(name, help=line)
            continue
        module = import_module(f"frictionlaws.cli.cmd_{name.replace('-', '_')}")
        p = module.add_parser(sub)
        p.set_defaults(_run=module.run, _parser=p)
        _mark_nested(p)
    return parser


def _command_of(argv: Sequence[str]) -> list[str] | None:
    """The sub-command ``argv`` runs, as :func:`build_parser` takes it: ``[name]``, ``[]``
    for none (or an unknown one: the names alone let argparse suggest the closest), None
    for every command (a shell completion script describes them all)."""
    for token in argv:  # before the command come global flags, none of which takes a value
        if token == "--":
            return []
        if token == "--print-completion" or token.startswith("--print-completion="):
            return None
        if not token.startswith("-"):
            return [token] if token in COMMANDS else []
    return []


def _mark_nested(p: argparse.ArgumentParser) -> None:
    """Give nested sub-commands (``tyre cornering``) their own ``_parser`` default."""
    for action in p._actions:
        if isinstance(action, argparse._SubParsersAction):
            for child in action.choices.values():
                child.set_defaults(_parser=child)
                _mark_nested(child)


# --------------------------------------------------------------------- messages


def _one_line(text: str) -> str:
    """A message on one line, at most :data:`~frictionlaws.base.limits.MAX_MESSAGE_CHARS` long."""
    return bounded_message(" ".join(str(text).split()))


#: A word of a message (no white space, no quote): matched in linear time.
_WORD = re.compile(r"[^\s'\"]+")
#: Where a library source path starts inside a word: an optional drive, then a separator.
_PATH_START = re.compile(r"(?:[A-Za-z]:)?[\\/]")


def _library_path(word: re.Match[str]) -> str:
    """``word`` with a path into an installed package (``site-packages/``) cut to <library>."""
    text = word.group(0)
    if not any(f"{d}-packages{sep}" in text for d in ("site", "dist") for sep in "/\\"):
        return text
    start = _PATH_START.search(text)
    return text if start is None else text[:start.start()] + "<library>"


def _clean(text: str) -> str:
    """One line, without library source paths (``.../site-packages/x/y.py:12``) and with
    standard input's private copy named ``<stdin>``."""
    return _one_line(shown_source(_WORD.sub(_library_path, str(text))))


def flag_label(args: argparse.Namespace | None) -> Callable[[str], str]:
    """How this command names a library argument: its flag (``"mapping"`` -> ``--map``)."""
    flags = dict(OPTION_FLAGS)
    flags.update(getattr(args, "_option_flags", None) or {})

    def label(option: str) -> str:
        return flags.get(option, "--" + option.replace("_", "-"))

    return label


def _input_message(exc: Exception, args: argparse.Namespace | None) -> str:
    """A library error in the CLI's words: its arguments and settings named as flags."""
    compose = getattr(exc, "compose", None)
    if callable(compose):
        return _one_line(compose(label=flag_label(args)))
    return _one_line(str(exc))


def _os_message(exc: OSError) -> str:
    what = exc.strerror or type(exc).__name__
    name = exc.filename
    if name is None:
        return _clean(f"{what} ({exc})" if str(exc) and str(exc) != what else what)
    extra = f" -> '{exc.filename2}'" if exc.filename2 else ""
    return _clean(f"file '{name}'{extra}: {what.lower() if what[:1].isupper() else what}")


class _Warnings:
    """Warnings collected during a command, printed once per distinct message."""

    def __init__(self) -> None:
        self.seen: dict[str, list[Any]] = {}

    def add(self, record: warnings.WarningMessage, verbose: bool) -> None:
        text = _clean(str(record.message)) or type(record.message).__name__
        if verbose:
            origin = re.sub(r"\.py$", "", str(record.filename).replace("\\", "/"))
            origin = origin.rsplit("site-packages/", 1)[-1].rsplit("/", 1)[-1]
            text = f"{record.category.__name__} from {origin}: {text}"
        if text in self.seen:
            self.seen[text][0] += 1
        else:
            self.seen[text] = [1]

    def print(self, verbose: bool = False) -> None:
        for text, (count,) in self.seen.items():
            times = f" ({count} times)" if count > 1 else ""
            print(f"warning: {text if verbose else _short(text)}{times}", file=sys.stderr)




class _DropWarnings(io.TextIOBase):
    """A stderr wrapper that drops whole lines starting with ``warning:`` (``--quiet``)."""

    def __init__(self, target: Any) -> None:
        self.target = target
        self.pending = ""

    def writable(self) -> bool:
        return True

    def write(self, text: str) -> int:
        self.pending += text
        *lines, self.pending = self.pending.split("\n")
        for line in lines:
            if not line.split("\r")[-1].lstrip().startswith("warning:"):
                self.target.write(line + "\n")
        if "\r" in self.pending:  # a progress bar redrawing its line: pass it on now
            self.target.write(self.pending)
            self.pending = ""
        return len(text)

    def flush(self) -> None:
        self.target.flush()

    def isatty(self) -> bool:
        return bool(getattr(self.target, "isatty", lambda: False)())

    def finish(self) -> None:
        if self.pending and not self.pending.lstrip().startswith("warning:"):
            self.target.write(self.pending)
        self.pending = ""


@contextlib.contextmanager
def _quiet_stderr(quiet: bool) -> Iterator[None]:
    """With ``--quiet``, the command's own ``warning:`` lines are dropped too."""
    if not quiet:
        yield
        return
    original = sys.stderr
    wrapper = _DropWarnings(original)
    sys.stderr = wrapper
    try:
        yield
    finally:
        wrapper.finish()
        sys.stderr = original


def _strictly(text: str) -> str:
    """``text`` as strict JSON: ``NaN``/``Infinity`` become ``null``; other text unchanged."""
    from ..base.jsonio import dumps  # numpy: loaded by the command that wrote JSON already

    def refuse(name: str) -> Any:
        raise ValueError(name)

    try:
        json.loads(text, parse_constant=refuse)
        return text
    except ValueError:
        pass
    try:
        doc = json.loads(text)
    except ValueError:
        return text  # not one JSON document (a command's own text): leave it alone
    return dumps(doc) + "\n"


@contextlib.contextmanager
def _strict_json_stdout(enabled: bool) -> Iterator[None]:
    """With ``--json``, hold stdout and make sure it leaves as strict JSON.

    Commands write their document with :func:`frictionlaws.base.jsonio.dumps`; this is
    the safety net that keeps ``NaN`` and ``Infinity`` out of stdout whatever a
    command printed.
    """
    if not enabled:
        yield
        return
    original = sys.stdout
    held = io.StringIO()
    sys.stdout = held
    try:
        yield
    finally:
        sys.stdout = original
        text = held.getvalue()
        if text:
            with contextlib.suppress(BrokenPipeError):  # `... --json | head`
                original.write(_strictly(text))
                original.flush()


# ------------------------------------------------------------------------- main


def _value_options(parser: argparse.ArgumentParser) -> set[str]:
    """Every option string (of every command) that takes one value."""
    out: set[str] = set()
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for sub in action.choices.values():
                out |= _value_options(sub)
        elif action.option_strings and action.nargs is None and action.type is not bool \
                and not isinstance(action, (argparse._StoreConstAction,
                                            argparse._StoreTrueAction,
                                            argparse._HelpAction)):
            out.update(action.option_strings)
    return out


_NEGATIVE_VALUE = re.compile(r"^-([0-9]|\.[0-9])")


def _join_negative_values(parser: argparse.ArgumentParser, argv: list[str]) -> list[str]:
    """``--p -0.5MPa:1MPa`` -> ``--p=-0.5MPa:1MPa``.

    argparse takes a value starting with '-' for an option unless it is a plain
    number; ranges and lists with units (``-0.5MPa:...``, ``-1,1``) are values.
    """
    takes = _value_options(parser)
    out: list[str] = []
    for token in argv:
        if out and out[-1] in takes and _NEGATIVE_VALUE.match(token):
            out[-1] = f"{out[-1]}={token}"
        else:
            out.append(token)
    return out


def _usage_error(message: str, usage: str, argv: Sequence[str]) -> int:
    """A command line that cannot run: its usage on stdout, one ``error:`` line, exit 2.

    The usage goes to stdout so that stderr keeps one line per problem; with
    ``--json`` stdout stays empty (it carries JSON or nothing).
    """
    if "--json" not in argv:
        print(usage.rstrip("\n"))
    print(f"error: {_one_line(message)}", file=sys.stderr)
    return 2


def command_names(parser: argparse.ArgumentParser) -> list[str]:
    """List the sub-commands of ``parser`` (its sub-parsers, aliases left out), in order.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        A parser with sub-commands (the top-level one, or ``tyre``'s).

    Returns
    -------
    list of str
        The command names as ``--help`` lists them; empty when it has none.
    """
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return [choice.dest for choice in action._choices_actions]
    return []


def _without_command(parser: argparse.ArgumentParser,
                     args: argparse.Namespace) -> argparse.ArgumentParser | None:
    """The parser (top level or a command with sub-commands) whose command is missing."""
    current: argparse.ArgumentParser | None = parser
    while current is not None:
        action = next((a for a in current._actions
                       if isinstance(a, argparse._SubParsersAction)), None)
        if action is None:
            return None
        chosen = getattr(args, action.dest, None)
        if not chosen:
            return current
        current = action.choices.get(chosen)
    return None


def _empty_value(parser: argparse.ArgumentParser, argv: Sequence[str]) -> str | None:
    """The first option given an empty value (``--report ''``, ``--out=``), or None.

    An empty value never means "everything" or "nothing": ``--report ''`` would
    otherwise write no report and ``--holdout ''`` run no extrapolation test, silently.
    """
    valued = _value_options(parser)
    for i, token in enumerate(argv):
        if token == "--":
            return None
        name, eq, value = token.partition("=")
        if eq and not value and name in valued:
            return name
        if token == "" and i > 0 and argv[i - 1] in valued:
            return argv[i - 1]
    return None


#: The global flags, accepted before or after the command.
GLOBAL_FLAGS = ("-q", "--quiet", "-v", "--verbose", "--debug")


def _hoist_global_flags(parser: argparse.ArgumentParser, argv: list[str]) -> list[str]:
    """Move global flags given after the command to the front (``fit ... -q``).

    A token that is the value of the option before it, or follows ``--``, stays.
    """
    takes = _value_options(parser)
    front: list[str] = []
    rest: list[str] = []
    for i, token in enumerate(argv):
        if token == "--":
            rest += argv[i:]
            break
        is_value = bool(rest) and rest[-1] in takes
        (front if token in GLOBAL_FLAGS and not is_value else rest).append(token)
    return front + rest


def _option_strings(parser: argparse.ArgumentParser, argv: Sequence[str]) -> list[str]:
    """The options of the (sub-)command ``argv`` names, and the global ones."""
    out = [s for a in parser._actions for s in a.option_strings]
    current = parser
    for token in argv:
        action = next((a for a in current._actions
                       if isinstance(a, argparse._SubParsersAction)), None)
        if action is None:
            break
        if token in action.choices:
            current = action.choices[token]
            out += [s for a in current._actions for s in a.option_strings]
    return out


def _suggest_options(message: str, parser: argparse.ArgumentParser, argv: Sequence[str]
                     ) -> str:
    """A parse error with the closest options suggested for every unknown ``--option``.

    argparse may report a missing required option before the mistyped one, so the
    command line itself is searched, not only an 'unrecognized arguments' message.
    """
    known = _option_strings(parser, argv)
    unknown = dict.fromkeys(t.split("=", 1)[0] for t in argv
                            if t.startswith("--") and t.split("=", 1)[0] not in known)
    hints = [f"{t}: did you mean {_did_you_mean(t, known)[len('; did you mean '):]}"
             for t in unknown if _did_you_mean(t, known)]
    return message + (" (" + "; ".join(hints) + ")" if hints else "")


def _parse(parser: argparse.ArgumentParser, argv: list[str]) -> argparse.Namespace | int:
    nul = next((t for t in argv if "\x00" in t), None)
    if nul is not None:  # no shell passes one; no file name or value holds one
        shown = _one_line(nul.replace("\x00", "\\0"))[:80]
        print(f"error: the argument '{shown}' holds a NUL character", file=sys.stderr)
        return 2
    argv = _hoist_global_flags(parser, argv)
    empty = _empty_value(parser, argv)
    if empty is not None:
        print(f"error: {empty}: empty value; give one (an empty value means neither "
              "everything nor nothing)", file=sys.stderr)
        return 2
    try:
        return parser.parse_args(_join_negative_values(parser, argv))
    except _ParseError as exc:
        return _usage_error(_suggest_options(str(exc), parser, argv), exc.usage, argv)
    except UsageError as exc:
        print(f"error: {_one_line(str(exc))}", file=sys.stderr)
        return 2
    except SystemExit as exc:  # --help, --version
        return int(exc.code or 0)


def _completion(parser: argparse.ArgumentParser, shell: str) -> int:
    try:
        import shtab
    except ImportError:
        print("error: shell completion needs the 'shtab' package: "
              "pip install shtab (a dependency of frictionlaws; reinstall it)", file=sys.stderr)
        return 2
    print(shtab.complete(parser, shell=shell))
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Run the CLI with ``argv`` (default ``sys.argv[1:]``); return the exit code."""
    argv_list = list(sys.argv[1:] if argv is None else argv)
    parser = build_parser(_command_of(argv_list))
    args = _parse(parser, argv_list)
    if isinstance(args, int):
        return args
    if args.print_completion:
        return _completion(parser, args.print_completion)
    missing = _without_command(parser, args)
    if missing is not None:
        names = ", ".join(command_names(missing))
        return _usage_error(f"{missing.prog}: no command given; choose one of: {names}",
                            missing.format_usage(), argv_list)
    collected = _Warnings()
    with warnings.catch_warnings(record=True) as records, _quiet_stderr(args.quiet), \
            _terminate_as_interrupt():
        warnings.simplefilter("always")
        with _strict_json_stdout(bool(getattr(args, "json", False))):
            code, last = _dispatch(args)
    if not args.quiet:
        for record in records:
            collected.add(record, args.verbose)
        collected.print(args.verbose)
    if last:  # a failure's one line comes last, after what was warned before it
        print(last, file=sys.stderr, end="")
    return code


class _Terminated(KeyboardInterrupt):
    """SIGTERM, raised where the command runs: it unwinds as an interrupt does."""


def _raise_terminated(signum: int, frame: Any) -> None:
    raise _Terminated


@contextlib.contextmanager
def _terminate_as_interrupt() -> Iterator[None]:
    """While a command runs, SIGTERM unwinds it as Ctrl-C does.

    The worker pools are then shut down and partial outputs removed on the way out,
    instead of the process dying at once and leaving its workers running.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGTERM, _raise_terminated)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def _dispatch(args: argparse.Namespace) -> tuple[int, str]:
    """Run the command; turn every failure into an exit code and what stderr says of it
    (one line, and the traceback with ``--debug``), printed after the warnings."""
    try:
        return int(args._run(args) or 0), ""
    except BrokenPipeError:
        return 0, ""
    except _Terminated:
        return 143, "terminated\n"
    except KeyboardInterrupt:
        return 130, "interrupted\n"
    except Exception as exc:  # noqa: BLE001 - every failure is one line, never a traceback
        message, code = _failure(exc, args)
        last = f"error: {message}\n"
        if code == 3 and getattr(args, "debug", False):
            last += traceback.format_exc()
        return code, last


def _failure(exc: Exception, args: argparse.Namespace) -> tuple[str, int]:
    """The one-line message and exit code of a failed command."""
    if isinstance(exc, (InputError, UsageError)):
        return _input_message(exc, args), 2
    if isinstance(exc, FitError):
        return f"fit failed: {_one_line(str(exc))}", 1
    if isinstance(exc, OSError):
        return _os_message(exc), 2
    if isinstance(exc, (json.JSONDecodeError, UnicodeError)):
        return f"unreadable input ({_clean(str(exc))})", 2
    if isinstance(exc, MemoryError):
        return "out of memory: the request is too large (fewer points or rows)", 2
    if _is_toml_error(exc):
        return f"malformed TOML ({_clean(str(exc))})", 2
    return (f"internal error ({type(exc).__name__}: {_clean(str(exc))}); please report it "
            "with the command you ran (--debug shows the traceback)"), 3


def _is_toml_error(exc: Exception) -> bool:
    return type(exc).__name__ == "TOMLDecodeError"


def entry() -> None:
    """Console-script entry point."""
    sys.exit(main())
