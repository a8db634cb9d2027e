"""``frictionlaws laws``: list the registered laws."""

from __future__ import annotations

import argparse

from ..law.registry import list_laws
from ._common import add_json_option, print_json
from .commands import COMMANDS

__all__ = ["add_parser", "run"]


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    p = sub.add_parser("laws", help=COMMANDS["laws"],
                       description="List the registered friction laws.")
    p.add_argument("--family", choices=("sliding", "slip"), help="only this family")
    add_json_option(p)
    return p


def run(args: argparse.Namespace) -> int:
    laws = list_laws(args.family)
    if args.json:
        print_json([{"id": law.id, "title": law.title, "family": law.family,
                     "aliases": list(law.aliases), "variables": list(law.variables),
                     "params": list(law.param_names), "evidence": law.evidence}
                    for law in laws])
        return 0
    width = max(len(law.id) for law in laws)
    print(f"{'id':<{width}}  {'family':<7}  {'variables':<9}  {'k':>2}  title")
    for law in laws:
        var = ",".join(law.variables) or "-"
        alias = f" (alias: {', '.join(law.aliases)})" if law.aliases else ""
        print(f"{law.id:<{width}}  {law.family:<7}  {var:<9}  {len(law.params):>2}  "
              f"{law.title}{alias}")
    return 0
