"""``frictionlaws datasets``: list the packaged datasets, or describe one (or a file)."""

from __future__ import annotations

import argparse
import json


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    p = sub.add_parser(
        "datasets", help="list packaged datasets, or describe one or a CSV file",
        description="Without NAME: list the datasets shipped with frictionlaws (their names "
        "work wherever a data file is accepted). With NAME (a packaged name or a CSV path): "
        "load it as 'fit' would and print its rows, the range of each column in display "
        "units, the loader's notes and the provenance.")
    p.add_argument("name", nargs="?", metavar="NAME",
                   help="packaged dataset name or CSV file to describe")
    p.add_argument("--map", metavar="COL=NAME,...",
                   help="map canonical columns to the file's columns, e.g. mu=FC,p=CP,v=DV")
    p.add_argument("--units", metavar="COL=UNIT,...",
                   help="units of columns whose header has none, e.g. p=MPa,v=m/s")
    p.add_argument("--area", metavar="AREA",
                   help="nominal contact area to derive p from F_N, e.g. '314.16 mm^2'")
    p.add_argument("--json", action="store_true", help="print JSON")
    return p


def run(args: argparse.Namespace) -> int:
    from frictionlaws.io import list_datasets, load_dataset

    if args.name is None:
        if args.map or args.units or args.area:
            from frictionlaws.errors import InputError

            raise InputError("--map, --units and --area need a dataset NAME or file")
        items = list_datasets()
        if args.json:
            print(json.dumps(items, indent=2))
            return 0
        width = max([len(d["name"]) for d in items] + [4])
        print(f"{'name':<{width}}  {'rows':>4}  title")
        for d in items:
            print(f"{d['name']:<{width}}  {d['rows']:>4}  {d['title']}")
        return 0
    ds = load_dataset(args.name, mapping=args.map, units=args.units, area=args.area)
    if args.json:
        print(json.dumps(ds.summary(), indent=2))
        return 0
    print(ds.describe())
    if ds.provenance:
        print("provenance:")
        for line in ds.provenance.splitlines():
            print(f"  {line}")
    return 0
