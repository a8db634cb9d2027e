"""``frictionlaws compare``: fit several laws to one dataset and rank them."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..base import jsonio
from ..base.errors import InputError
from ..base.numbers import parse_number
from ..base.outputs import atomic_dir, check_outputs, write_text_atomic
from ..base.sanitize import frame_csv
from ..comparison import compare
from ..comparison.results import mark_undetermined
from ..fitting.campaign import compare_many
from ._campaign import (
    add_campaign_options,
    campaign_progress,
    refuse_campaign_options,
    split_names,
    wants_campaign,
)
from ._common import (
    add_data_options,
    add_fit_options,
    bounded_int,
    data_kwargs,
    data_source,
    data_sources,
    progress_value,
)
from ._messages import shown_source
from .commands import COMMANDS

__all__ = ["add_parser", "run"]


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    p = sub.add_parser(
        "compare", help=COMMANDS["compare"],
        description="Fit every applicable law (or the ones given) to a dataset and rank them "
        "by k-fold cross-validated RMSE. Per law: k, R^2, adjusted R^2, RMSE, MAE, max "
        "|residual|, AIC, AICc, BIC, Akaike weights (among laws fitted to the same rows), CV "
        "RMSE, RMSE on the held-out upper part of the pressure/velocity range, a plausibility "
        "scan over an extended box (0.5 x lowest .. 3 x highest measured value; 0 <= mu <= 5; "
        "the trend must keep the sign the data show) and residual structure tests. Rows where "
        "a law is singular (v = 0 in a log-velocity law) are dropped for that law and "
        "reported; laws the data cannot feed are listed as skipped, laws that fail to fit as "
        "failed. Exit 0 when at least one law was fitted, 1 when none could be, 2 on bad "
        "input.")
    p.add_argument("data", metavar="DATA", nargs="+",
                   help="CSV file(s), a directory of CSV files, or a packaged dataset name; "
                        "several (or --by) compare each dataset and group separately")
    which = p.add_mutually_exclusive_group()
    which.add_argument("--laws", metavar="A,B,...",
                       help="laws to compare (ids or aliases, comma-separated)")
    which.add_argument("--family", choices=("sliding", "slip"),
                       help="compare every law of this family (default: slip when the data "
                            "have a slip ratio, else sliding)")
    add_data_options(p)
    p.add_argument("--folds", type=bounded_int(2, 100_000), default=5, metavar="K",
                   help="cross-validation folds (default 5; more than the rows = leave-one-out)")
    p.add_argument("--holdout", default="0.3", metavar="FRACTION|VAR=F,...",
                   help="upper fraction of the range held out for the extrapolation test: one "
                        "number for p and v, or e.g. p=0.3,v=0.2; 0 for none (default 0.3)")
    add_fit_options(p, only=("weights", "starts", "seed"))
    p.add_argument("--mu-max", type=_mu_max, default=5.0, metavar="MU",
                   help="upper physical limit of mu in the plausibility scan (default 5)")
    p.add_argument("--max-rows", type=_max_rows, default=None, metavar="N|all",
                   help="compare data with more rows on a seeded random subsample of N rows "
                        "(every fit, fold, hold-out and test; said in the notes); 'all' for "
                        "every row, however long that takes (default "
                        f"{_DEFAULT_MAX_ROWS})")
    p.add_argument("--report", metavar="DIR",
                   help="write report.html (self-contained), report.md, comparison.json and "
                        "PNG figures to DIR (created with its parents if missing, as every "
                        "output directory; a failed run creates nothing)")
    p.add_argument("--json", action="store_true",
                   help="print the comparison as one JSON object instead of the table")
    add_campaign_options(p, shared=False, jobs_help=(
        "worker processes (default 1; -1 = one per core; never more than the cores or the "
        "tasks): the laws' fits and folds of one dataset and the report's figures, or "
        "several datasets"))
    return p


#: compare's default subsample size, frictionlaws.comparison.core.MAX_ROWS (kept here
#: as a literal so that building the parser imports no numpy; a test checks they agree).
_DEFAULT_MAX_ROWS = 2000
_ALL_ROWS = "all"


def _max_rows(text: str) -> int | str:
    """``--max-rows``: a whole number >= 3, or 'all'."""
    if text.strip().lower() == _ALL_ROWS:
        return _ALL_ROWS
    try:
        return bounded_int(3, None)(text)
    except argparse.ArgumentTypeError as exc:
        raise argparse.ArgumentTypeError(f"{exc}, or '{_ALL_ROWS}'") from None


def _mu_max(text: str) -> float:
    """``--mu-max``: a finite number > 0 (the one number parser: no 'inf', no overflow)."""
    try:
        value = parse_number(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None
    if not value > 0:
        raise argparse.ArgumentTypeError(f"{value:g} is out of range: expected a number > 0")
    return value


def _options(args: argparse.Namespace) -> dict:
    return {"family": args.family, "folds": args.folds, "holdout": args.holdout,
            "seed": args.seed, "starts": args.starts,
            "weights": "auto" if args.weights == "auto" else None,
            "mu_limits": (0.0, args.mu_max), **_rows_option(args)}


def _rows_option(args: argparse.Namespace) -> dict:
    """``max_rows`` for compare: absent (the library's default), a number, or None (all)."""
    if args.max_rows is None:
        return {}
    return {"max_rows": None if args.max_rows == _ALL_ROWS else args.max_rows}


def run(args: argparse.Namespace) -> int:
    inputs = [d for d in args.data if Path(d).exists()]
    check_outputs([args.out], dirs=[args.report], inputs=inputs)
    if wants_campaign(args):
        if args.report:
            raise InputError("--report draws one comparison; for several datasets or groups "
                             "use --out")
        return _run_many(args)
    if args.out:
        raise InputError("--out writes a campaign table; for one comparison use --json or "
                         "--report")
    refuse_campaign_options(args, spread=())
    return _run_one(args, args.data[0])


def _run_one(args: argparse.Namespace, data: str) -> int:
    with data_source(data) as source:
        cmp = compare(args.laws, source, **_options(args),
                      progress=progress_value(args), jobs=args.jobs,
                      **data_kwargs(args))
    written = {}
    if args.report:
        with atomic_dir(args.report) as tmp:
            written = {k: Path(args.report) / Path(v).relative_to(tmp)
                       for k, v in cmp.write_report(tmp, jobs=args.jobs).items()}
    if args.json:
        print(cmp.to_json())
    else:
        print(cmp.table())
        if written:
            print(f"\nreport: {written['report.html']} (also report.md, comparison.json and "
                  f"{sum(1 for k in written if not k.startswith(('report', 'comparison')))} "
                  "PNG figures)")
    if args.report and args.json:
        print(f"report: {written['report.html']}", file=sys.stderr)
    return 0


def _run_many(args: argparse.Namespace) -> int:
    laws = split_names([args.laws]) if args.laws else None
    load = {k: v for k, v in data_kwargs(args).items() if v is not None}
    with data_sources(args.data) as paths:
        frame = compare_many(paths, laws, by=split_names(args.by), jobs=args.jobs,
                             scheduler=args.scheduler, progress=campaign_progress(args),
                             load_options=load,
                             source_names={p: shown_source(p) for p in paths},
                             **_options(args))
    shown = mark_undetermined(frame)  # undetermined scores as n/d in text and CSV
    if args.out:
        text = (frame_csv(shown, float_format="%.10g")
                if args.out.lower().endswith(".csv")
                else jsonio.dumps(frame.to_dict("records")) + "\n")
        write_text_atomic(args.out, text)
    if args.json:
        print(jsonio.dumps(frame.to_dict("records")))
    else:
        print(shown.to_string(index=False, float_format=lambda x: f"{x:.4g}"))
    errors = int(frame["error"].notna().sum()) if "error" in frame else 0
    return 1 if errors else 0
