"""Conventions shared by every sub-command: option groups, option parsing, ranges, stdin.

Rules (documented in ``docs/cli.md``):

* **Repeated options merge.**  ``--map``, ``--units``, ``--fix``, ``--set``,
  ``--free`` may be given several times; the pieces are merged, and a name given
  twice (in one occurrence or across several) is an error naming it.
* **One range grammar**: ``MIN:MAX[:N]`` where each bound is a number (in the
  command's default unit) or a number with its unit (``0.01MPa:0.5MPa:20``,
  ``20degC:80degC``), and ``N`` is the number of points, ends included.  A list
  ``A,B,C`` is accepted where a command takes explicit values.  See
  :func:`range_option`.
* **Integers are checked** by the argparse ``type=`` functions
  :func:`non_negative_int`, :func:`positive_int` and :func:`bounded_int`, so a
  negative ``--seed`` or an unbounded ``--points`` is a usage error (exit 2) that
  names the option and the allowed range.
* **Options that do not apply are refused** (:func:`refuse_unused`), never
  silently ignored.
* **One progress flag**: ``--progress {auto,on,off}`` (:func:`add_progress_option`).
* **``-`` as DATA** reads standard input (:func:`data_source`).
"""

from __future__ import annotations

import argparse
import contextlib
import math
import os
import re
import sys
import tempfile
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import Any

from ..base.errors import InputError
from ..base.jsonio import dumps
from ..base.limits import read_stream
from ..base.numbers import parse_integer, parse_number
from ..base.outputs import check_input_file
from ..base.units import parse_quantity, to_si
from ..fitting import fit, load_result
from ..law.bound import Source, bound_from_result, freeze
from ..law.registry import get_law
from ._messages import WARNING_WIDTH, UsageError, short_warning

__all__ = [
    "UsageError",
    "SCHEDULER_TRUST",
    "MergeAssignments",
    "MergeNames",
    "non_negative_int",
    "positive_int",
    "bounded_int",
    "job_count",
    "JOBS_ALLOWED",
    "bounded_number",
    "SEED_MAX",
    "add_data_options",
    "add_fit_options",
    "add_progress_option",
    "add_json_option",
    "progress_value",
    "parse_assignments",
    "parse_floats",
    "parse_names",
    "data_kwargs",
    "fit_kwargs",
    "run_fit",
    "data_options",
    "FIT_OPTIONS",
    "PARAMS_HELP",
    "add_law_source_options",
    "bound_from_args",
    "refuse_unused",
    "flag_of",
    "RangeSpec",
    "range_option",
    "parse_values",
    "range_values",
    "RANGE_HELP",
    "MAX_POINTS",
    "data_source",
    "STDIN",
    "print_json",
    "WARNING_WIDTH",
    "short_warning",
    "report_text",
]

#: Largest seed numpy's legacy generators accept.
SEED_MAX = 2**32 - 1
#: Largest number of points a range may ask for (a guard against memory exhaustion).
MAX_POINTS = 100_000
#: The DATA argument that means standard input.
STDIN = "-"
#: What a range looks like, for help texts and messages.
RANGE_HELP = ("MIN:MAX[:N]: bounds as numbers in the default unit or with their own unit "
              "(e.g. 0.01MPa:0.5MPa:20), N points with both ends included")


def report_text(report: str, args: argparse.Namespace) -> str:
    """A result's report for the terminal: its ``warning:`` lines short unless ``--verbose``."""
    if getattr(args, "verbose", False):
        return report
    prefix = "warning: "
    return "\n".join(prefix + short_warning(line[len(prefix):]) if line.startswith(prefix)
                     else line for line in report.split("\n"))


#: The trust a ``--scheduler`` asks for, said in its help (``docs/user-guide/security.rst``).
SCHEDULER_TRUST = ("The scheduler and its workers are trusted with code execution here (Dask "
                   "exchanges pickles): only this option connects, $FRICTIONLAWS_SCHEDULER "
                   "is not read. Needs the 'dask' extra.")


# ------------------------------------------------------------------- integer types


def bounded_int(lo: int | None = None, hi: int | None = None) -> Callable[[str], int]:
    """An argparse ``type=`` accepting whole numbers in ``[lo, hi]`` (either end open)."""
    if lo is not None and hi is not None:
        allowed = f"a whole number from {lo} to {hi}"
    elif lo is not None:
        allowed = f"a whole number >= {lo}"
    elif hi is not None:
        allowed = f"a whole number <= {hi}"
    else:
        allowed = "a whole number"

    def convert(text: str) -> int:
        try:  # the one number parser: no 1_0, no non-ASCII digits
            value = parse_integer(str(text))
        except ValueError:
            raise argparse.ArgumentTypeError(f"'{text}' is not {allowed}") from None
        if (lo is not None and value < lo) or (hi is not None and value > hi):
            raise argparse.ArgumentTypeError(f"{value} is out of range: expected {allowed}")
        return value

    convert.__name__ = "integer"
    return convert


def bounded_number(lo: float | None = None, hi: float | None = None, *,
                   lo_open: bool = False) -> Callable[[str], float]:
    """An argparse ``type=`` accepting finite numbers (the one number parser) in a range.

    Parameters
    ----------
    lo, hi : float, optional
        The bounds (either end open).
    lo_open : bool
        Exclude ``lo`` itself (``> lo`` rather than ``>= lo``).

    Returns
    -------
    callable
        Text -> float, raising :class:`argparse.ArgumentTypeError` naming the value.
    """
    low = "" if lo is None else f"{'>' if lo_open else '>='} {lo:g}"
    high = "" if hi is None else f"<= {hi:g}"
    allowed = " and ".join(x for x in (low, high) if x) or "any finite value"

    def convert(text: str) -> float:
        try:
            value = parse_number(str(text))
        except ValueError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None
        if ((lo is not None and (value <= lo if lo_open else value < lo))
                or (hi is not None and value > hi)):
            raise argparse.ArgumentTypeError(f"'{str(text).strip()}' is out of range: "
                                             f"expected a number {allowed}")
        return value

    convert.__name__ = "number"
    return convert


#: A whole number >= 0 (``--jobs``, ``--starts``).
non_negative_int = bounded_int(0)
#: A whole number >= 1 (``--max-rows``, ``--folds``).
positive_int = bounded_int(1)


# ------------------------------------------------------------- merged repeated options


def _bare(exc: Exception, option: str | None) -> str:
    """The message without the option's name in front (argparse adds it)."""
    msg = str(exc)
    for prefix in (f"{option}: ", f"{option} "):
        if option and msg.startswith(prefix):
            return msg[len(prefix):]
    return msg


class MergeAssignments(argparse.Action):
    """``--map a=X --map b=Y`` -> ``"a=X,b=Y"``; a name given twice is a usage error.

    The merged value stays one ``NAME=VALUE,...`` string, the form every
    library function accepts; checking happens as the options are parsed, so
    the message names the option.
    """

    def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace,
                 values: Any, option_string: str | None = None) -> None:
        previous = getattr(namespace, self.dest, None)
        pieces = [previous] if previous else []
        text = str(values)
        try:
            parse_assignments([*pieces, text], option_string or self.dest)
        except UsageError as exc:
            raise argparse.ArgumentError(self, _bare(exc, option_string)) from None
        pieces.append(",".join(p for p in text.split(",") if p.strip()))
        setattr(namespace, self.dest, ",".join(pieces))


class MergeNames(argparse.Action):
    """``--free A --free B`` -> ``"A,B"``; a name given twice is a usage error."""

    def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace,
                 values: Any, option_string: str | None = None) -> None:
        previous = getattr(namespace, self.dest, None)
        pieces = [previous] if previous else []
        try:
            parse_names([*pieces, str(values)], option_string or self.dest)
        except UsageError as exc:
            raise argparse.ArgumentError(self, _bare(exc, option_string)) from None
        pieces.append(",".join(p.strip() for p in str(values).split(",") if p.strip()))
        setattr(namespace, self.dest, ",".join(pieces))


# ------------------------------------------------------------------- option groups


def data_options(args: argparse.Namespace) -> tuple[str, ...]:
    """The destinations :func:`add_data_options` created: options that only apply to data."""
    return ("map", _units_dest(args), "area")


def _units_dest(args: argparse.Namespace) -> str:
    """``units``, or ``data_units`` where the command's ``--units`` means something else."""
    return "data_units" if hasattr(args, "data_units") else "units"


def add_data_options(p: argparse.ArgumentParser | Any, *, units_flag: str = "--units") -> None:
    """The one group of data options: ``--map``, ``--units`` and ``--area`` (repeatable maps).

    Every command that reads a user's table (``fit``, ``compare``, ``datasets``,
    ``export --fit``, ``tyre cornering --fit``) takes them.  ``units_flag`` renames
    ``--units`` where the command's ``--units`` means something else (``export``:
    ``--data-units``, destination ``data_units``).
    """
    p.add_argument("--map", metavar="COL=NAME,...", action=MergeAssignments,
                   help="map canonical columns to your file's columns, e.g. mu=FC,p=CP,v=DV "
                        "(repeatable; a column given twice is an error)")
    p.add_argument(units_flag, metavar="COL=UNIT,...",
                   action=MergeAssignments,
                   help="units of data columns whose header has none, e.g. p=MPa,v=m/s "
                        "(repeatable)")
    p.add_argument("--area", metavar="AREA",
                   help="nominal contact area to derive p from F_N, e.g. '314.16 mm^2'")


#: The destinations :func:`add_fit_options` creates: options that only apply to a fit.
FIT_OPTIONS = ("fix", "free", "weights", "drop_invalid", "starts", "seed", "uncertainty",
               "boot", "boot_jobs", "boot_interval")


def _fit_option_specs() -> dict[str, tuple[tuple[str, ...], dict[str, Any]]]:
    """dest -> (flags, add_argument keywords) of every fit option, defined once."""
    return {
        "fix": (("--fix",), dict(
            metavar="NAME=VALUE,...", action=MergeAssignments,
            help="hold parameters (or settings) at values, e.g. n=0.3333 (repeatable)")),
        "free": (("--free",), dict(
            metavar="SETTING,...", action=MergeNames,
            help="fit a fixed setting as a parameter, e.g. E_v (repeatable)")),
        "weights": (("--weights",), dict(
            choices=("auto", "none"), default="auto",
            help="auto: 1/mu_std or sqrt(n) when the data have them (default)")),
        "drop_invalid": (("--drop-invalid",), dict(
            action="store_true",
            help="drop (and report) rows where the law is singular, e.g. v = 0 in a "
                 "log-velocity law, instead of stopping")),
        "starts": (("--starts",), dict(
            type=bounded_int(0, 1000), default=None, metavar="N",
            help="extra random starts for non-linear laws, 0 to 1000 (default: the "
                 "fitter's rule, 6)")),
        "seed": (("--seed",), dict(
            type=bounded_int(0, SEED_MAX), default=0, metavar="SEED",
            help=f"seed of the random starts, the folds and the bootstrap, 0 to {SEED_MAX} "
                 "(default 0)")),
        "uncertainty": (("--uncertainty",), dict(
            choices=("asymptotic", "sandwich", "bootstrap"), default="asymptotic",
            help="standard errors: asymptotic (fit covariance, default, fast), sandwich "
                 "(HC3, robust to uneven scatter) or bootstrap (resamples whole test "
                 "conditions; robust to a law that misses a trend)")),
        "boot": (("--boot",), dict(
            type=bounded_int(20, 100_000), default=1000, metavar="N",
            help="bootstrap replicates, 20 to 100000 (default 1000; with --uncertainty "
                 "bootstrap)")),
        "boot_jobs": (("--boot-jobs",), dict(
            type=job_count, default=1, metavar="N",
            help="worker processes for the bootstrap refits (default 1; -1 = one per core; "
                 "with --uncertainty bootstrap)")),
        "boot_interval": (("--boot-interval",), dict(
            choices=("bca", "percentile"), default="bca",
            help="bootstrap interval: bca (bias-corrected, accelerated; default) or "
                 "percentile (with --uncertainty bootstrap)")),
    }


def add_fit_options(p: argparse.ArgumentParser | Any, only: Sequence[str] | None = None
                    ) -> None:
    """The one group of fit options (``--fix``, ``--free``, weights, starts, seed, ...).

    ``only`` adds a subset (argparse dests of :data:`FIT_OPTIONS`), for a command
    that fits with fewer choices (``compare``: ``weights``, ``starts``, ``seed``).
    """
    specs = _fit_option_specs()
    for dest in only or FIT_OPTIONS:
        flags, kwargs = specs[dest]
        p.add_argument(*flags, **kwargs)


#: Bootstrap-only options (argparse dests), refused with another --uncertainty.
BOOT_OPTIONS = ("boot", "boot_jobs", "boot_interval")


#: What a worker count may be: the words of every ``--jobs`` option's message.
JOBS_ALLOWED = "a whole number from 1 to 1024, or -1 for one per core"


def job_count(text: str) -> int:
    """``--jobs``, ``--boot-jobs``: 1..1024, or -1 for one per core."""
    try:  # the one number parser: no 1_0, no non-ASCII digits
        value = parse_integer(str(text).strip())
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{str(text)[:40]}' is not {JOBS_ALLOWED}") from None
    if value != -1 and not 1 <= value <= 1024:
        raise argparse.ArgumentTypeError(f"{value} is out of range: expected {JOBS_ALLOWED}")
    return value


job_count.__name__ = "integer"


def add_progress_option(p: argparse.ArgumentParser | Any) -> None:
    """The one progress flag: ``--progress {auto,on,off}`` (a bar on stderr)."""
    p.add_argument("--progress", choices=("auto", "on", "off"), default="auto",
                   help="progress bar on stderr (auto: only when stderr is a terminal)")


def add_json_option(p: argparse.ArgumentParser | Any) -> None:
    """``--json``: print the result as one strict JSON document on stdout."""
    p.add_argument("--json", action="store_true",
                   help="print one JSON document (strict: null for missing numbers)")


def progress_value(args: argparse.Namespace) -> bool | None:
    """``--progress`` as the library's ``progress=``: None (auto), True or False.

    ``--quiet`` turns an automatic bar off.
    """
    value = getattr(args, "progress", "auto")
    if value in (None, "auto"):
        return False if getattr(args, "quiet", False) else None
    if isinstance(value, bool):
        return value
    return value == "on"


# ------------------------------------------------------------------ option parsing


def _chunks(items: Sequence[str] | str | None) -> list[str]:
    if items is None:
        return []
    return [items] if isinstance(items, str) else [str(x) for x in items]


def parse_assignments(items: Sequence[str] | str | None, what: str) -> dict[str, str]:
    """Merge ``a=1,b=2`` pieces (possibly repeated) into one dict of strings.

    Raises
    ------
    UsageError
        On a piece that is not ``NAME=VALUE`` or a name given twice.
    """
    out: dict[str, str] = {}
    for chunk in _chunks(items):
        parts = chunk.split(",")
        if not any(part.strip() for part in parts):
            raise UsageError(f"{what} is empty; expected NAME=VALUE,...")
        for part in parts:
            if not part.strip():
                continue
            k, sep, v = (s.strip() for s in part.partition("="))
            if not sep or not k or not v:
                raise UsageError(f"{what}: expected NAME=VALUE, got '{part.strip()}'")
            if k in out:
                raise UsageError(f"{what}: '{k}' is given twice ({k}={out[k]} and {k}={v})")
            out[k] = v
    return out


def parse_floats(items: Sequence[str] | str | None, what: str) -> dict[str, float]:
    """Merge ``n=0.333,...`` pieces into finite floats (the strict number parser)."""
    out = {}
    for k, v in parse_assignments(items, what).items():
        try:
            out[k] = parse_number(v)
        except ValueError as exc:
            raise UsageError(f"{what}: '{k}={v}': {exc}") from None
    return out


def parse_names(items: Sequence[str] | str | None, what: str) -> list[str]:
    """Merge ``A,B`` pieces (possibly repeated) into a list; a name given twice is an error."""
    out: list[str] = []
    for chunk in _chunks(items):
        names = [s.strip() for s in chunk.split(",")]
        if not any(names):
            raise UsageError(f"{what} is empty; expected NAME,...")
        for name in filter(None, names):
            if name in out:
                raise UsageError(f"{what}: '{name}' is given twice")
            out.append(name)
    return out


def data_kwargs(args: argparse.Namespace) -> dict[str, Any]:
    """``mapping``/``units``/``area`` keyword arguments for load_dataset and fit."""
    return {
        "mapping": parse_assignments(args.map, "--map") or None,
        "units": parse_assignments(getattr(args, _units_dest(args)),
                                   flag_of(args, _units_dest(args))) or None,
        "area": args.area,
    }


def fit_kwargs(args: argparse.Namespace) -> dict[str, Any]:
    """Keyword arguments for :func:`frictionlaws.fitting.fit` from the fit options."""
    uncertainty = getattr(args, "uncertainty", "asymptotic")
    if uncertainty != "bootstrap":
        refuse_unused(args, BOOT_OPTIONS, f"with --uncertainty {uncertainty}")
    return {
        "uncertainty": uncertainty,
        "n_boot": getattr(args, "boot", 1000),
        "n_jobs": getattr(args, "boot_jobs", 1),
        "interval": getattr(args, "boot_interval", "bca"),
        "fix": parse_floats(args.fix, "--fix"),
        "free": parse_names(args.free, "--free"),
        "weights": "auto" if args.weights == "auto" else None,
        "on_invalid": "drop" if args.drop_invalid else "error",
        "starts": args.starts,
        "seed": args.seed,
        **data_kwargs(args),
    }


def run_fit(args: argparse.Namespace, law: str, data: str) -> Any:
    """Fit ``law`` to ``data`` with the command's options (``-`` reads stdin)."""
    with data_source(data) as source:
        return fit(law, source, **fit_kwargs(args))


# ------------------------------------------------------------- a law with values


#: What :func:`bound_from_args` asks for when no values are given.
PARAMS_HELP = "--preset NAME, --params FILE.json, --fit DATA or --set NAME=VALUE,..."


def add_law_source_options(p: argparse.ArgumentParser | Any, *, fit: bool = True) -> None:
    """The one way to give a law its values: ``--preset``, ``--params``, ``--fit``, ``--set``.

    ``--preset``, ``--params`` and ``--fit`` exclude each other; ``--set`` gives or
    overrides values (alone or over a preset).  :func:`bound_from_args` turns them
    into a :class:`~frictionlaws.law.bound.BoundLaw`.  With ``fit``, the command also
    needs :func:`add_data_options` and :func:`add_fit_options`.
    """
    src = p.add_mutually_exclusive_group()
    src.add_argument("--preset", metavar="NAME", help="a named preset of the law")
    src.add_argument("--params", metavar="FILE.json",
                     help="parameters: a 'fit --save' file or {'law': ..., 'params': {...}}")
    if fit:
        src.add_argument("--fit", metavar="DATA",
                         help="fit the law to DATA (CSV file, packaged dataset or '-') first")
    p.add_argument("--set", metavar="NAME=VALUE,...", action=MergeAssignments,
                   help="give or override parameter values in SI, e.g. mu0=0.9 (alone or "
                        "over --preset; repeatable)")


def bound_from_args(args: argparse.Namespace, law: str | None) -> Any:
    """``--preset/--set/--params/--fit`` (and ``--law``) as a
    :class:`~frictionlaws.law.bound.BoundLaw`.

    ``--params`` gives the law itself (``law`` must agree when given); ``--fit``
    fits ``law`` with the command's data and fit options (a fit that did not
    converge comes back with ``converged`` False: the command decides); options
    that only apply to a fit are refused without ``--fit``.

    Raises
    ------
    UsageError
        A missing ``--law`` or missing values, or ``--set`` with a file or a fit.
    InputError
        A law that does not match the file, an unknown preset, a bad value...
    """
    fit_data = getattr(args, "fit", None)
    if not fit_data and hasattr(args, "fix"):
        refuse_unused(args, (*FIT_OPTIONS, *data_options(args)), "without --fit")
    values = parse_floats(args.set, "--set")
    if args.params:
        if values:
            raise UsageError("--set cannot be combined with --params (edit the file instead)")
        return _bound_from_file(args.params, law)
    if not law:
        raise UsageError("--law is required (except with --params)")
    if fit_data:
        if values:
            raise UsageError("--set cannot be combined with --fit (hold values with --fix)")
        return bound_from_result(run_fit(args, law, fit_data), dataset=fit_data)
    if not args.preset and not values:
        raise UsageError(f"give the parameters: {PARAMS_HELP}")
    return freeze(law, values, preset=args.preset)


def _bound_from_file(path: str, law: str | None) -> Any:
    with data_source(path, "stdin.json") as real:  # '-': the file from standard input
        result = load_result(real)
    shown = "<stdin>" if path == STDIN else path
    if law and get_law(law).id != result.law.id:
        raise InputError(f"--law {law} does not match the law in the file "
                         f"('{result.law.id}')", file=shown)
    return bound_from_result(result, Source("file", file=shown))


# -------------------------------------------------------------- inapplicable options


def flag_of(args: argparse.Namespace, dest: str) -> str:
    """The option string of ``dest`` (``range_p`` -> ``--p``), as the user typed it."""
    parser = getattr(args, "_parser", None)
    for action in getattr(parser, "_actions", ()):
        if action.dest == dest and action.option_strings:
            longs = [s for s in action.option_strings if s.startswith("--")]
            return (longs or action.option_strings)[0]
    return "--" + dest.replace("_", "-")


def _is_given(args: argparse.Namespace, dest: str) -> bool:
    value = getattr(args, dest, None)
    parser = getattr(args, "_parser", None)
    if parser is not None:
        return bool(value != parser.get_default(dest))
    return value not in (None, False, [], "", ())


def refuse_unused(args: argparse.Namespace, names: Sequence[str], why: str) -> None:
    """Refuse options (argparse dests) that were given but do not apply.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed arguments; ``args._parser`` (set by :func:`frictionlaws.cli.main`)
        gives the defaults.  Without it, None/False/empty count as not given.
    names : sequence of str
        Destinations to check, e.g. ``["fix", "starts"]``.
    why : str
        The situation, completing "... not used {why}", e.g. ``"without --fit"``.

    Raises
    ------
    UsageError
        Naming every inapplicable option given.
    """
    given = [flag_of(args, n) for n in names if _is_given(args, n)]
    if given:
        verb = "is" if len(given) == 1 else "are"
        raise UsageError(f"{', '.join(given)} {verb} not used {why}; remove "
                         f"{'it' if len(given) == 1 else 'them'}")


# ------------------------------------------------------------------------ ranges


#: Linear time (a lookahead for the digit, then one run): ``[0-9._]*[0-9][0-9._]*`` would
#: backtrack quadratically on a long run of digits followed by a letter.
_BARE_NUMBER = re.compile(r"[+-]?(?=[0-9._]*[0-9])[0-9._]+(?:[eE][+-]?[0-9]+)?")


@dataclass(frozen=True)
class RangeSpec:
    """A parsed ``MIN:MAX[:N]``: bounds in SI and the number of points (None: not given)."""

    lo: float
    hi: float
    n: int | None


def _bound(text: str, quantity: str, option: str, whole: str,
           unit: str | Callable[[float], float] | None) -> float:
    s = text.strip()
    if not s:
        raise UsageError(f"{option} '{whole}': empty bound; expected {RANGE_HELP}")
    try:
        x = parse_number(s)
    except ValueError as exc:
        if _BARE_NUMBER.fullmatch(s):  # a number without a unit that parse_number refuses
            raise UsageError(f"{option} '{whole}': {exc}") from None
        try:
            return float(parse_quantity(s, quantity, what=option))
        except InputError as exc:
            raise UsageError(f"{option} '{whole}': {exc.bare_message}") from None
    if unit is None:
        value = x
    elif callable(unit):
        value = float(unit(x))
    else:
        value = float(to_si(x, unit, quantity, column=option))
    if not math.isfinite(value):
        raise UsageError(f"{option} '{whole}': bounds must be finite")
    return value


def range_option(text: str, quantity: str, *, option: str,
                 unit: str | Callable[[float], float] | None = None,
                 max_points: int = MAX_POINTS, min_points: int = 2) -> RangeSpec:
    """A range option (``--p``, ``--loads``) in the one range grammar ``MIN:MAX[:N]``.

    The grammar is the library's (:func:`frictionlaws.fe_export.parse_range`, the one
    ``parse_range``); here bare numbers may be in a command's default unit or given by a
    function, and errors name the option as the user typed it.

    Parameters
    ----------
    text : str
        E.g. ``"0.01:0.5:20"``, ``"0.01MPa:0.5MPa"``, ``"20degC:80degC:7"``.
    quantity : str
        The quantity (``"p"``, ``"v"``, ``"T"``, ``"F_N"``, ``"s"``) that fixes the
        unit dimension.
    option : str
        The option's name for messages (``"--p"``).
    unit : str or callable, optional
        Unit of bare numbers (e.g. ``"kN"``), or a function from a bare number to
        SI; None means bare numbers are SI.
    max_points, min_points : int
        Allowed range of ``N``.

    Returns
    -------
    RangeSpec
        ``lo <= hi`` in SI; ``n`` None when not given.

    Raises
    ------
    UsageError
        Naming the option, the text and what was expected.
    """
    parts = str(text).split(":")
    if len(parts) not in (2, 3):
        raise UsageError(f"{option} '{text}': expected {RANGE_HELP}")
    lo = _bound(parts[0], quantity, option, text, unit)
    hi = _bound(parts[1], quantity, option, text, unit)
    if hi < lo:
        raise UsageError(f"{option} '{text}': MIN is above MAX")
    n = None
    if len(parts) == 3:
        try:
            n = bounded_int(min_points, max_points)(parts[2])
        except argparse.ArgumentTypeError as exc:
            raise UsageError(f"{option} '{text}': N {exc}") from None
        if n > 1 and hi == lo:
            raise UsageError(f"{option} '{text}': {n} points need MIN < MAX")
    return RangeSpec(lo, hi, n)


def parse_values(text: str, quantity: str, *, option: str,
                 unit: str | Callable[[float], float] | None = None,
                 max_points: int = MAX_POINTS) -> list[float]:
    """Values in SI from a range ``MIN:MAX:N`` (evenly spaced) or a list ``A,B,C``."""
    s = str(text).strip()
    if not s:
        raise UsageError(f"{option} is empty; expected A,B,C or {RANGE_HELP}")
    if ":" in s:
        spec = range_option(s, quantity, option=option, unit=unit, max_points=max_points,
                            min_points=1)
        if spec.n is None:
            raise UsageError(f"{option} '{text}': give the number of points, MIN:MAX:N")
        return range_values(spec)
    items = [x for x in s.split(",")]
    if len(items) > max_points:
        raise UsageError(f"{option}: {len(items)} values (at most {max_points})")
    empty = [i + 1 for i, x in enumerate(items) if not x.strip()]
    if empty:
        raise UsageError(f"{option} '{text}': item {empty[0]} of the list is empty; expected "
                         "A,B,C, values separated by single commas")
    return [_bound(x, quantity, option, s, unit) for x in items]


def range_values(spec: RangeSpec, spacing: str = "lin") -> list[float]:
    """The ``spec.n`` points of a range, both ends included (``lin`` or ``log`` spacing)."""
    n = spec.n or 2
    if n == 1:
        return [spec.lo]
    if spacing == "log":
        if spec.lo <= 0:
            raise UsageError("log spacing needs MIN > 0")
        ratio = spec.hi / spec.lo
        return [spec.lo * ratio ** (i / (n - 1)) for i in range(n)]
    step = (spec.hi - spec.lo) / (n - 1)
    return [spec.hi if i == n - 1 else spec.lo + i * step for i in range(n)]


# ------------------------------------------------------------------------- stdin


@contextlib.contextmanager
def data_source(data: str, name: str | Callable[[bytes], str] = "stdin.csv"
                ) -> Iterator[str]:
    """Yield a path for the DATA argument; ``-`` spools standard input to a private file.

    ``name`` is the private file's name, or a function choosing it from the bytes read
    (a reader that goes by the suffix: ``stdin.tir`` or ``stdin.json``).

    A DATA that names an existing path must be a regular, readable file (a FIFO
    would block forever, a directory is a mistake).

    The library reads files by path (it needs the bytes twice: encoding and
    delimiter detection, then parsing), so standard input is copied to a file
    named ``stdin.csv`` in a private temporary directory, removed afterwards.
    """
    if data != STDIN:
        if os.path.lexists(data):  # a path, not a packaged name: refuse FIFOs, directories

            check_input_file(data, "data file")
        yield data
        return
    if sys.stdin is None or sys.stdin.isatty():
        raise UsageError("DATA '-' reads standard input, which is a terminal here; pipe a "
                         "table in (e.g. 'cat runs.csv | frictionlaws fit - ...') or give "
                         "a file name")

    raw = read_stream(sys.stdin)  # bounded in size

    with tempfile.TemporaryDirectory(prefix="frictionlaws-stdin-") as tmp:
        path = os.path.join(tmp, name(raw) if callable(name) else name)
        with open(path, "wb") as fh:
            fh.write(raw)
        try:
            yield path
        except InputError as exc:  # name standard input, not the private copy
            exc.replace_text(path, "<stdin>")
            raise


@contextlib.contextmanager
def data_sources(data: Sequence[str]) -> Iterator[list[str]]:
    """A campaign's DATA arguments with ``-`` spooled as :func:`data_source` does.

    The others (files, directories, packaged names) are passed on as given.
    """
    with contextlib.ExitStack() as stack:
        yield [stack.enter_context(data_source(d)) if d == STDIN else d for d in data]


def print_json(obj: Any) -> None:
    """Print ``obj`` as strict JSON on stdout (null for non-finite numbers)."""
    print(dumps(obj))
