"""``frictionlaws validate``: run the validation suite against published values."""

from __future__ import annotations

import argparse
import sys

from ..validation import list_cases, run_validation
from ..validation.core import select_cases
from ._common import add_json_option, parse_names, print_json
from .commands import COMMANDS

__all__ = ["add_parser", "run"]


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    p = sub.add_parser(
        "validate", help=COMMANDS["validate"],
        description="Run the validation suite: the library against figures from the source "
        "thesis and the law catalogue, the FE manuals' friction formulas, independent "
        "reference implementations of every law, a parameter-recovery study and the "
        "thesis' tyre conclusion. Prints, per case, the source, the expected and obtained "
        "values, the tolerance and pass or fail. Exit code 0 when every case passes, 1 "
        "when any fails, 2 for an unknown case name.")
    p.add_argument("--case", metavar="NAME", action="append", default=[],
                   help="run only this case (id or shell pattern such as 'thesis-*'; "
                        "repeatable)")
    p.add_argument("--list", action="store_true", help="list the cases and their sources")
    add_json_option(p)
    return p


def run(args: argparse.Namespace) -> int:
    names = parse_names(args.case, "--case")  # '' or a repeated name: exit 2
    cases = select_cases(list_cases(), names or None)  # unknown names: exit 2
    if args.list:
        if args.json:
            print_json([{"id": c.id, "title": c.title, "source": c.source} for c in cases])
            return 0
        for case in cases:
            print(f"{case.id}: {case.title}\n    source: {case.source}")
        return 0

    def progress(res) -> None:
        if not args.json:
            print(res.format() + "\n", flush=True)

    report = run_validation(names or None, progress=progress)
    if args.json:
        print_json(report.to_dict())
    else:
        for w in report.warnings:
            print(f"warning: {w}")
        print(report.summary_line())
        if not report.passed:
            failed = ", ".join(r.id for r in report.results if not r.passed)
            print(f"failed: {failed}", file=sys.stderr)
    return 0 if report.passed else 1
