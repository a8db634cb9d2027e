"""``frictionlaws examples DIR``: write the example files the README and the guide use."""

from __future__ import annotations

import argparse

from ..example_files import write_example_files
from ._common import SEED_MAX, bounded_int
from .commands import COMMANDS

__all__ = ["add_parser", "run"]


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    p = sub.add_parser(
        "examples", help=COMMANDS["examples"],
        description="Write the example files of the README's 'A first look' and of the "
                    "getting-started guide into DIR (synthetic tables, tyre data and a raw "
                    "tribometer campaign; EXAMPLES.txt describes them). Existing files are "
                    "never replaced: the command stops before writing anything.")
    p.add_argument("directory", metavar="DIR", help="folder to write into (created if needed)")
    p.add_argument("--seed", type=bounded_int(0, SEED_MAX), default=0, metavar="SEED",
                   help="seed of the random scatter (default 0; the same seed writes the "
                        "same files)")
    return p


def run(args: argparse.Namespace) -> int:
    for path in write_example_files(args.directory, seed=args.seed):
        print(f"wrote {path}{'/' if path.is_dir() else ''}")
    return 0
