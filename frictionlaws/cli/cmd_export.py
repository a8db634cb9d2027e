"""``frictionlaws export``: write a law to an FE code's input, a table or a subroutine."""

from __future__ import annotations

import argparse
import re
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

from ..base.errors import InputError
from ..base.outputs import check_outputs, check_unique_names, write_text_atomic
from ..fe_export import export
from ..fe_export.formats import FORMATS, OPTIONS, formats_taking
from ..fe_export.fortran import check_source_name
from ..fe_export.systems import SYSTEMS, unit_system
from ..fitting.campaign import check_grouping, fit_groups, group_keys, key_text
from ..io import load_dataset
from ..law import VARIABLES
from ._campaign import split_names
from ._common import (
    FIT_OPTIONS,
    UsageError,
    add_data_options,
    add_fit_options,
    add_json_option,
    add_law_source_options,
    bound_from_args,
    bounded_int,
    bounded_number,
    data_options,
    data_source,
    fit_kwargs,
    parse_assignments,
    print_json,
    range_option,
    refuse_unused,
)
from .commands import COMMANDS

_EPILOG = """\
ranges: {box} take MIN:MAX or MIN:MAX:N.  Bare numbers are in the
--units system (mm-N-s: p in MPa, v in mm/s; SI: Pa, m/s; T in K unless overridden); a
bound may carry its own unit, without spaces or quoted:
  --p 0.01:0.5:20 --units mm-N-s        (MPa)      --p 10kPa:0.5MPa:20
  --v 1e-3m/s:10m/s:30 --spacing v=log             --T 20degC:80degC:7
With N for every variable and no --tol the grid is as given; with --tol (or a missing N)
breakpoints are placed until the solver's interpolation (linear between points, end
values held) is within TOL of the law everywhere in the box (default TOL 0.001).

unit systems: {systems};
override a unit after the name, e.g. --units mm-N-s,T=degC.

formats:
{formats}
"""


def _system_list(with_units: bool) -> str:
    """``SI (Pa, m/s, K, N), mm-N-s (...)`` or ``SI (default), mm-N-s, ...``."""
    out = []
    for i, (name, units) in enumerate(SYSTEMS.items()):
        shown = [units[v] for v in VARIABLES if units.get(v)]
        out.append(f"{name} ({', '.join(shown)})" if with_units
                   else f"{name} (default)" if i == 0 else name)
    return ", ".join(out)


def _format_lines() -> str:
    width = max(map(len, FORMATS))
    return "\n".join(f"  {name:<{width}}  {f.line}" + ("" if f.needs_box else "; no ranges needed")
                      for name, f in FORMATS.items())


class _HelpFormatter(argparse.RawDescriptionHelpFormatter):
    """Fills the help's lists (formats, unit systems) from the library's tables."""

    def add_text(self, text: str | None) -> None:
        if text == _EPILOG:
            text = _EPILOG.format(box=", ".join(f"--{v}" for v in _BOX),
                                  systems=_system_list(True), formats=_format_lines())
        super().add_text(text)

    def _get_help_string(self, action: argparse.Action) -> str | None:
        text = action.help
        if text and "{systems}" in text:
            text = text.replace("{systems}", _system_list(False))
        return text


__all__ = ["add_parser", "run"]

#: The variables a box may give ranges of (one flag each: --p, --v, ...): the law variables.
_BOX = tuple(VARIABLES)


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    p = sub.add_parser(
        "export", help=COMMANDS["export"],
        description="Write a friction law in a finite-element code's own input (or a grid, or "
        "an Abaqus user subroutine), in the model's units, with a header stating the law, "
        "parameters, units, box, the maximum interpolation error and where it occurs.",
        epilog=_EPILOG, formatter_class=_HelpFormatter)
    p.add_argument("--law", help="law id or alias (may be omitted with --params)")
    add_law_source_options(p)
    p.add_argument("--format", required=True, choices=list(FORMATS), metavar="FORMAT",
                   help="output format: %(choices)s")
    for var in _BOX:
        p.add_argument(f"--{var}", metavar="MIN:MAX[:N]", dest=f"range_{var}",
                       help=f"range of {var} (see below)")
    p.add_argument("--spacing", metavar="VAR=lin|log,...", action="append", default=[],
                   help="point spacing per variable (default log when MAX/MIN >= 100)")
    p.add_argument("--units", default="SI", metavar="SYSTEM",
                   help="unit system of the file: {systems}[,VAR=UNIT]")
    p.add_argument("--tol", type=bounded_number(0.0, lo_open=True), metavar="TOL",
                   help="largest interpolation error in mu (adaptive grid; a number > 0)")
    p.add_argument("--max-rows", type=bounded_int(1, 10_000_000), default=200_000, metavar="N",
                   help="largest table allowed (default 200000; 1..10000000)")
    p.add_argument("-o", "--output", required=True, metavar="FILE",
                   help="output file ('-' for standard output)")
    add_json_option(p)
    g = p.add_argument_group("fit options (with --fit)")
    add_data_options(g, units_flag="--data-units")
    g.add_argument("--by", metavar="COLUMN[,COLUMN]", action="append", default=[],
                   help="fit and export each group separately, one file per group named "
                        "FILE's stem + _VALUE (e.g. -o deck.inp --by surface: deck_steel.inp)")
    add_fit_options(g)
    _format_options(p)
    # library arguments named by this command's flags (--units is the unit system here)
    p.set_defaults(_option_flags={"units": "--data-units"})
    return p


def _flag(option: str) -> str:
    """The flag of a format option: ``ansys_mat`` -> ``--ansys-mat``."""
    return "--" + option.replace("_", "-")


def _format_options(p: argparse.ArgumentParser) -> None:
    """One flag per option of the library's table of formats (``fe_export.formats``)."""
    g = p.add_argument_group("format options (each for the formats named)")
    for opt in OPTIONS.values():
        g.add_argument(_flag(opt.name), dest=opt.name, type=bounded_int(opt.lo, opt.hi),
                       metavar=opt.metavar,
                       help=f"{opt.meaning} ({', '.join(formats_taking(opt.name))}; "
                            f"{opt.lo}..{opt.hi}, default {opt.default})")


def _options(args: argparse.Namespace) -> dict[str, int]:
    """The format options given (the library adds the defaults of the others)."""
    return {name: value for name in OPTIONS if (value := getattr(args, name)) is not None}


def _box(args: argparse.Namespace, system: Any) -> tuple[dict, dict[str, str]]:
    """The ranges given (SI ``(min, max, n)``, the one range grammar) and their spacing."""
    spacing = parse_assignments(args.spacing, "--spacing")
    box = {}
    for var in _BOX:
        text = getattr(args, f"range_{var}")
        if text is not None:
            spec = range_option(text, var, option=f"--{var}", min_points=1,
                                unit=_model_to_si(system, var))
            box[var] = (spec.lo, spec.hi, spec.n)
    for var in spacing:
        if var not in box:
            raise UsageError(f"--spacing {var}=...: no range given for {var} (--{var} MIN:MAX)")
    return box, spacing


def _model_to_si(system: Any, var: str) -> Callable[[float], float]:
    """A bare bound in the export's unit system -> SI."""
    def convert(x: float) -> float:
        return float(system.to_si(var, x))

    return convert


def _check_args(args: argparse.Namespace) -> None:
    """Outputs, --json, and the options that only apply to --fit, before any work."""
    _check_files(args)
    if args.json and args.output == "-":
        raise UsageError("--json prints the export's summary on stdout, where -o - puts the "
                         "file: give -o FILE")
    if not args.fit:
        refuse_unused(args, (*FIT_OPTIONS, *data_options(args), "by"), "without --fit")
    taken = {o.name for o in FORMATS[args.format].options}
    refuse_unused(args, [name for name in OPTIONS if name not in taken],
                  f"with --format {args.format}")


def run(args: argparse.Namespace) -> int:
    _check_args(args)
    system = unit_system(args.units)
    box, spacing = _box(args, system)
    if args.fit and args.by:
        if not args.law:
            raise UsageError("--law is required (except with --params)")
        if args.set:
            raise UsageError("--set cannot be combined with --fit (hold values with --fix)")
        return _export_groups(args, args.law, box, spacing, system)
    bound = bound_from_args(args, args.law)
    if not bound.converged and args.fit:
        print(f"error: the fit of '{bound.law.id}' to {args.fit} did not converge; "
              "nothing exported", file=sys.stderr)
        return 1
    # the fit's notes come back among the export's warnings ("fit: ..."), printed once
    res = export(bound, None, args.format, box, units=system, tol=args.tol, spacing=spacing,
                 path=None if args.output == "-" else args.output, max_rows=args.max_rows,
                 options=_options(args))
    if args.output == "-":
        sys.stdout.write(res.text)
        print(res.report(), file=sys.stderr)
    elif args.json:
        print_json(res.to_dict())
    else:
        print(res.report())
    return 0


def _export_groups(args: argparse.Namespace, law: str, box: dict, spacing: dict[str, str],
                   system: Any) -> int:
    """``export --fit DATA --by COL``: one fit and one file per group, all or nothing.

    Every group is fitted and exported in memory first; the files are written only
    when all succeeded, each atomically, none over an input.
    """
    if args.output == "-":
        raise UsageError("--by writes one file per group: give -o FILE, not -o -")
    options = fit_kwargs(args)
    load = {k: options.pop(k) for k in ("mapping", "units", "area")}
    by = check_grouping(split_names(args.by), [law])
    out = Path(args.output)
    with data_source(args.fit) as source:
        dataset = load_dataset(source, **load)
    keys = [key for key, _ in group_keys(dataset, list(by))]
    paths = [_group_path(out, key) for key in keys]
    # one file per group, each its own name, checked before any fit
    check_unique_names([(f"group {key_text(k)}", p.name) for k, p in zip(keys, paths)],
                       what="groups' files", file=args.fit)
    check_outputs(paths, inputs=[args.fit] if Path(args.fit).exists() else [])
    groups = fit_groups(law, dataset, by, **options)
    failed = [key_text(k) for k, r in groups if not r.success]
    if failed:
        raise InputError(f"the fit did not converge for {', '.join(failed)}; nothing exported",
                         file=args.fit)
    results = []
    for (key, fitted), path in zip(groups, paths, strict=True):
        m = fitted.metrics
        source = (f"fit to {args.fit}, group {key_text(key)} (n = {m.get('n')}, "
                  f"R^2 = {m.get('r2', float('nan')):.4g})")
        results.append((path, export(fitted.bound, None, args.format, box, units=system,
                                     tol=args.tol, spacing=spacing, path=None,
                                     max_rows=args.max_rows, source=source,
                                     options=_options(args))))
    for path, res in results:
        write_text_atomic(path, res.text)
        res.path = str(path)
    if args.json:
        print_json([res.to_dict() for _, res in results])
    else:
        print("\n".join(res.report() for _, res in results))
    return 0


def _group_path(out: Path, key: dict) -> Path:
    """``deck.inp`` and {surface: steel} -> ``deck_steel.inp`` (file-name safe)."""
    tag = "_".join(re.sub(r"[^A-Za-z0-9.+-]+", "-", str(v)).strip("-") or "none"
                   for v in key.values())
    return out.with_name(f"{out.stem}_{tag}{out.suffix}")


def _check_files(args: argparse.Namespace) -> None:
    """The output is checked before any work: not an input, a writable file."""
    if args.output == "-":
        return

    if FORMATS[args.format].source_code:
        check_source_name(args.output)
    inputs = [x for x in (args.params, args.fit) if x and Path(x).exists()]
    check_outputs([args.output], inputs=inputs)
