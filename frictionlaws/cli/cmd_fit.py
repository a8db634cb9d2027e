"""``frictionlaws fit``: fit a law to a dataset, or to each group of many datasets."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..base.errors import InputError
from ..base.outputs import check_outputs
from ._campaign import (
    add_campaign_options,
    refuse_campaign_options,
    run_fit_campaign,
    wants_campaign,
)
from ._common import add_data_options, add_fit_options, fit_kwargs, report_text, run_fit
from .commands import COMMANDS

__all__ = ["add_parser", "run"]


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    p = sub.add_parser(
        "fit", help=COMMANDS["fit"],
        description="Fit a friction law to a dataset (CSV file, packaged dataset name or '-' "
        "for standard input) and print parameters with standard errors, 95 % confidence "
        "intervals and units, goodness of fit and warnings. Several files or a directory, "
        "or --by, fit each dataset and group separately; --shared fits parameters common "
        "to the groups. Exit 0 on success, 1 when a fit did not converge or is worse than "
        "the mean, 2 on bad input.")
    p.add_argument("data", metavar="DATA", nargs="+",
                   help="CSV file(s), a directory of CSV files, or a packaged dataset name; "
                        "several are read before any fit, and any that cannot be read "
                        "refuses the run, each named (exit 2)")
    p.add_argument("--law", required=True, help="law id or alias (see 'frictionlaws laws')")
    add_data_options(p)
    add_fit_options(p)
    add_campaign_options(p)
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--save", metavar="FILE", help="save the result as versioned JSON")
    return p


def run(args: argparse.Namespace) -> int:
    if wants_campaign(args):
        if args.save:
            raise InputError("--save writes one fit; for several datasets or groups use --out")
        return run_fit_campaign(args, fit_kwargs(args))
    if args.out:
        raise InputError("--out writes a campaign table; for one fit use --save")
    refuse_campaign_options(args)
    data = args.data[0]
    if args.save == "-":
        raise InputError("--save needs a file name ('-' is not one here; --json prints the "
                         "result on stdout)")
    if args.save:
        check_outputs([args.save], inputs=[data] if Path(data).exists() else [])
    result = run_fit(args, args.law, data)
    if args.save:
        result.save(args.save)
    if args.json:
        print(result.to_json())
    else:
        print(report_text(result.report(), args))
        if args.save:
            print(f"saved: {args.save}")
    return 0 if result.success else 1
