"""Campaign options shared by ``fit`` and ``compare``: several datasets, groups, shared
parameters, parallel workers and a Dask scheduler."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from ..base import jsonio
from ..base.display import group_label, parameter_table
from ..base.errors import InputError
from ..base.outputs import check_outputs, write_text_atomic
from ..base.sanitize import frame_csv
from ..fitting.campaign import UnreadableDatasets, check_grouping, doubts, fit_many
from ..fitting.shared import fit_shared
from . import flag_label
from ._common import (
    SCHEDULER_TRUST,
    add_progress_option,
    data_sources,
    job_count,
    progress_value,
    refuse_unused,
)
from ._messages import shown_source

__all__ = ["add_campaign_options", "wants_campaign", "run_fit_campaign", "split_names",
           "campaign_progress"]


def add_campaign_options(p: argparse.ArgumentParser, *, shared: bool = True,
                         jobs_help: str = "worker processes for several datasets (default 1; "
                                          "-1 = one per core; never more than the cores "
                                          "or the tasks)") -> None:
    """Add ``--by``, ``--shared``, ``--jobs``, ``--scheduler``, ``--out`` and ``--progress``.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser.
    shared : bool
        Whether the command takes ``--shared`` (a global fit across groups).
    jobs_help : str
        The help of ``--jobs`` (what the command spreads over the processes).
    """
    g = p.add_argument_group("campaigns (several datasets, groups, parallel work)")
    g.add_argument("--by", metavar="COLUMN[,COLUMN]", action="append", default=[],
                   help="fit each group of these columns separately, e.g. --by surface; a "
                        "test condition, not mu, mu_std, n or a variable of a law fitted, "
                        "with 2 or more rows a group on average")
    if shared:
        g.add_argument("--shared", metavar="NAME[,NAME]", action="append", default=[],
                       help="with --by: one global fit in which these parameters are common "
                            "to all groups and the others per group, e.g. --shared b")
    g.add_argument("--jobs", type=job_count, default=1, metavar="N", help=jobs_help)
    g.add_argument("--scheduler", metavar="ADDRESS", default=None,
                   help="run the datasets on a Dask cluster, e.g. tcp://10.0.0.5:8786 "
                        f"(or tls:// with Dask's TLS settings). {SCHEDULER_TRUST}")
    g.add_argument("--out", metavar="FILE", default=None,
                   help="write the campaign's tidy table to FILE (.csv, .jsonl or .json)")
    add_progress_option(g)


def campaign_progress(args: argparse.Namespace) -> bool:
    """Decide whether a campaign shows a progress bar.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed command line.

    Returns
    -------
    bool
        ``--progress``/``--no-progress`` as given; by default, whether stderr is a
        terminal.
    """
    value = progress_value(args)
    return sys.stderr.isatty() if value is None else value


def split_names(items: list[str]) -> list[str]:
    """Split comma-separated names: ``["a,b", "c"]`` -> ``["a", "b", "c"]``.

    Parameters
    ----------
    items : list of str
        The values of a repeatable option.

    Returns
    -------
    list of str
        The names, in order.

    Raises
    ------
    InputError
        When a name is given twice.
    """
    out: list[str] = []
    for chunk in items:
        for name in (s.strip() for s in chunk.split(",")):
            if not name:
                continue
            if name in out:
                raise InputError(f"'{name}' is given twice")
            out.append(name)
    return out


def refuse_campaign_options(args: argparse.Namespace, spread: tuple[str, ...] = ("jobs",)
                            ) -> None:
    """One dataset and no groups: the options that spread work are an error, not ignored.

    ``spread`` names those that spread only a campaign's work (a command that spreads
    one dataset's work over ``--jobs`` leaves it out).
    """
    refuse_unused(args, (*spread, "scheduler"),
                  "with one dataset and no --by (they spread several datasets or groups)")


def wants_campaign(args: argparse.Namespace) -> bool:
    """Tell whether the command must run as a campaign.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed command line.

    Returns
    -------
    bool
        True for several datasets, a directory, ``--by`` or ``--shared``.
    """
    data = args.data if isinstance(args.data, list) else [args.data]
    if data.count("-") > 1:
        raise InputError("'-' (standard input) is given more than once; it can be read once")
    return (len(data) > 1 or any(Path(d).is_dir() for d in data) or bool(args.by)
            or bool(getattr(args, "shared", [])))


def _check_out(args: argparse.Namespace) -> None:
    """``--out`` is checked before any work: suffix, not an input, writable."""
    if not args.out:
        return

    if Path(args.out).suffix.lower() not in (".csv", ".jsonl", ".json"):
        raise InputError("--out takes a .csv, .jsonl or .json file", file=args.out)
    data = args.data if isinstance(args.data, list) else [args.data]
    check_outputs([args.out], inputs=[d for d in data if Path(d).exists()])


def _refuse_without_by(args: argparse.Namespace) -> None:
    if getattr(args, "shared", []) and not args.by:
        raise InputError("--shared needs --by (the groups that share the parameters)")


def run_fit_campaign(args: argparse.Namespace, fit_kwargs: dict[str, Any]) -> int:
    """Run ``fit`` over several datasets and/or groups; print a summary, write ``--out``.

    A DATA of ``-`` (standard input) is read once into a private file first.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed command line.
    fit_kwargs : dict
        The fit options built from it (load options are taken out of it).

    Returns
    -------
    int
        The exit status: 0, or 1 when a fit failed.
    """
    given = args.data
    with data_sources(given if isinstance(given, list) else [given]) as paths:
        args.data = paths if isinstance(given, list) else paths[0]
        try:
            return _run_fit_campaign(args, fit_kwargs)
        finally:
            args.data = given


def _run_fit_campaign(args: argparse.Namespace, fit_kwargs: dict[str, Any]) -> int:
    _refuse_without_by(args)
    _check_out(args)
    by = list(check_grouping(split_names(args.by), [args.law]))
    load: dict[str, Any] = {k: fit_kwargs.pop(k) for k in ("mapping", "units", "area")
                            if k in fit_kwargs}
    if getattr(args, "shared", []):
        return _run_shared(args, by, split_names(args.shared), fit_kwargs, load)
    stream = args.out if args.out and Path(args.out).suffix.lower() in (".csv", ".jsonl") \
        else None
    camp = _fit_all(args, by, stream, load, fit_kwargs)
    if args.out and stream is None:
        camp.save(args.out)
    if getattr(args, "json", False):
        print(jsonio.dumps(camp.to_dict() if camp.records else
                           {"output": str(camp.path), "fits": len(camp),
                            "errors": camp.errors}))
    elif camp.records:
        print(_by_table(camp))
    else:
        print(f"{len(camp)} fits written to {camp.path}; {len(camp.errors)} failed")
        for rec in camp.errors:
            print(f"error: {rec['dataset']} {rec['law']}: {rec['error']}", file=sys.stderr)
    _refuse_if_only_input_errors(camp)
    return 1 if camp.errors else 0


def _by_table(camp: Any) -> str:
    """Each law's fits as one table: a row per dataset and group, parameters in display units."""
    several = len({rec["dataset"] for rec in camp.records}) > 1
    blocks = []
    for law in dict.fromkeys(rec["law"] for rec in camp.records):
        rows = []
        for rec in (r for r in camp.records if r["law"] == law):
            label = group_label(rec["group"]) if rec["group"] else ""
            label = f"{rec['dataset']} {label}".strip() if several or not label else label
            if "error" in rec:
                rows.append({"label": label, "n": rec.get("rows"), "error": rec["error"]})
                continue
            res = rec["result"]
            rows.append({"label": label, "n": res["metrics"].get("n"),
                         "r2": res["metrics"].get("r2"), "rmse": res["metrics"].get("rmse"),
                         "params": res["params"], "note": doubts(res)})
        by = f" by {', '.join(camp.by)}" if camp.by else ""
        blocks.append(f"{law}: {len(rows)} fits{by}\n" + parameter_table(rows))
    return "\n\n".join(blocks)


def _fit_all(args: argparse.Namespace, by: list[str], stream: str | None,
             load: dict[str, Any], fit_kwargs: dict[str, Any]) -> Any:
    """:func:`~frictionlaws.fitting.campaign.fit_many`; a campaign with unreadable datasets is
    refused with one ``error:`` line per dataset, the last one summing up (exit 2)."""
    data = args.data if isinstance(args.data, list) else [args.data]
    try:
        return fit_many(args.law, args.data, by=by, jobs=args.jobs, scheduler=args.scheduler,
                        progress=campaign_progress(args), output=stream, load_options=load,
                        source_names={d: shown_source(d) for d in data}, **fit_kwargs)
    except UnreadableDatasets as exc:
        label = flag_label(args)
        for problem in exc.problems:  # standard input by its name, not its private copy
            for d in data:
                problem.replace_text(d, shown_source(d))
        lines = [" ".join(p.compose(label=label).split()) for p in exc.problems]
        for line in lines[:-1]:
            print("error: " + line, file=sys.stderr)
        raise InputError(f"{lines[-1]}; {exc.summary()}") from None


def _refuse_if_only_input_errors(camp: Any) -> None:
    """Every dataset failed to load or group: bad input (exit 2), not failed fits."""
    errors = camp.errors
    if errors and len(errors) == len(camp) and all(r.get("input_error") for r in errors):
        raise InputError(errors[0]["error"])


def _run_shared(args: argparse.Namespace, by: list[str], shared: list[str],
                fit_kwargs: dict[str, Any], load: dict[str, Any]) -> int:
    data = args.data if isinstance(args.data, list) else [args.data]
    if len(data) != 1:
        raise InputError("a shared-parameter fit takes one dataset (its groups share)")
    if fit_kwargs.get("uncertainty", "asymptotic") != "asymptotic":
        raise InputError("--uncertainty is not used with --shared (the shared fit reports "
                         "asymptotic errors); remove it")

    refuse_unused(args, ("jobs", "scheduler"),
                  "with --shared (a shared fit is one least-squares problem, not spread)")
    res = fit_shared(args.law, data[0], by, shared, fix=fit_kwargs.get("fix"),
                     weights=fit_kwargs.get("weights", "auto"), load_options=load)
    if args.out:
        check_outputs([args.out], inputs=data)
        text = (frame_csv(res.to_frame()) if Path(args.out).suffix.lower() == ".csv"
                else jsonio.dumps(res.to_dict()) + "\n")
        write_text_atomic(args.out, text)
    if getattr(args, "json", False):
        print(jsonio.dumps(res.to_dict()))
    else:
        print(res.report())
    return 0 if res.success else 1
