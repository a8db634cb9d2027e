"""``frictionlaws datasets``: list the packaged datasets, or describe one (or a file)."""

from __future__ import annotations

import argparse

from ..base import jsonio
from ..base.errors import InputError
from ..io import list_datasets, load_dataset
from ._common import add_data_options, data_source
from .commands import COMMANDS

__all__ = ["add_parser", "run"]


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    p = sub.add_parser(
        "datasets", help=COMMANDS["datasets"],
        description="Without NAME: list the datasets shipped with frictionlaws (their names "
        "work wherever a data file is accepted). With NAME (a packaged name or a CSV path): "
        "load it as 'fit' would and print its rows, the range of each column in display "
        "units, the loader's notes and the provenance.")
    p.add_argument("name", nargs="?", metavar="NAME",
                   help="packaged dataset name or CSV file to describe")
    add_data_options(p)
    p.add_argument("--json", action="store_true", help="print JSON")
    return p


def run(args: argparse.Namespace) -> int:
    if args.name is None:
        if args.map or args.units or args.area:
            raise InputError("--map, --units and --area need a dataset NAME or file")
        items = list_datasets()
        if args.json:
            print(jsonio.dumps(items))
            return 0
        width = max([len(d["name"]) for d in items] + [4])
        print(f"{'name':<{width}}  {'rows':>4}  title")
        for d in items:
            print(f"{d['name']:<{width}}  {d['rows']:>4}  {d['title']}")
        return 0
    with data_source(args.name) as source:
        ds = load_dataset(source, mapping=args.map, units=args.units, area=args.area)
    if args.json:
        print(jsonio.dumps(ds.summary()))
        return 0
    print(ds.describe())
    if ds.provenance:
        print("provenance:")
        for line in ds.provenance.splitlines():
            print(f"  {line}")
    return 0
