"""``frictionlaws fit``: fit a law to a dataset."""

from __future__ import annotations

import argparse

from ._common import add_data_options, add_fit_options, run_fit


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    p = sub.add_parser(
        "fit", help="fit a law to a dataset",
        description="Fit a friction law to a dataset (CSV file or packaged dataset name) and "
        "print parameters with standard errors, 95 % confidence intervals and units, "
        "goodness of fit and warnings. Exit 0 on success, 1 when the optimiser did not "
        "converge, 2 on bad input.")
    p.add_argument("data", metavar="DATA", help="CSV file or packaged dataset name")
    p.add_argument("--law", required=True, help="law id or alias (see 'frictionlaws laws')")
    add_data_options(p)
    add_fit_options(p)
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--save", metavar="FILE", help="save the result as versioned JSON")
    return p


def run(args: argparse.Namespace) -> int:
    result = run_fit(args, args.law, args.data)
    if args.save:
        result.save(args.save)
    if args.json:
        print(result.to_json())
    else:
        print(result.report())
        if args.save:
            print(f"saved: {args.save}")
    return 0 if result.success else 1
