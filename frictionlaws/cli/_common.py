"""Options shared by several sub-commands (data loading, fitting)."""

from __future__ import annotations

import argparse
from typing import Any


def add_data_options(p: argparse.ArgumentParser) -> None:
    """``--map``, ``--units`` and ``--area`` for reading a user's file."""
    p.add_argument("--map", metavar="COL=NAME,...",
                   help="map canonical columns to your file's columns, e.g. mu=FC,p=CP,v=DV")
    p.add_argument("--units", metavar="COL=UNIT,...",
                   help="units of columns whose header has none, e.g. p=MPa,v=m/s")
    p.add_argument("--area", metavar="AREA",
                   help="nominal contact area to derive p from F_N, e.g. '314.16 mm^2'")


def add_fit_options(p: argparse.ArgumentParser) -> None:
    """Options that control a fit (``--fix``, ``--free``, weights, starts)."""
    p.add_argument("--fix", metavar="NAME=VALUE,...", action="append", default=[],
                   help="hold parameters (or settings) at values, e.g. n=0.3333")
    p.add_argument("--free", metavar="SETTING,...", action="append", default=[],
                   help="fit a fixed setting as a parameter, e.g. E_v")
    p.add_argument("--weights", choices=("auto", "none"), default="auto",
                   help="auto: 1/mu_std or sqrt(n) when the data have them (default)")
    p.add_argument("--drop-invalid", action="store_true",
                   help="drop (and report) rows where the law is singular, e.g. v = 0 in a "
                        "log-velocity law, instead of stopping")
    p.add_argument("--starts", type=int, default=None, metavar="N",
                   help="extra random starts for non-linear laws (default 6)")
    p.add_argument("--seed", type=int, default=0, help="seed of the random starts")


def parse_assignments(items: list[str] | str | None, what: str) -> dict[str, str]:
    """Parse ``a=1,b=2`` (possibly repeated) into a dict of strings."""
    from frictionlaws.errors import InputError

    if not items:
        return {}
    if isinstance(items, str):
        items = [items]
    out: dict[str, str] = {}
    for chunk in items:
        for part in chunk.split(","):
            part = part.strip()
            if not part:
                continue
            if "=" not in part:
                raise InputError(f"{what}: expected NAME=VALUE, got '{part}'")
            k, v = (s.strip() for s in part.split("=", 1))
            if not k or not v:
                raise InputError(f"{what}: expected NAME=VALUE, got '{part}'")
            out[k] = v
    return out


def parse_floats(items: list[str] | None, what: str) -> dict[str, float]:
    """Parse ``n=0.333,...`` into floats, with a clear error."""
    from frictionlaws.errors import InputError

    out = {}
    for k, v in parse_assignments(items, what).items():
        try:
            out[k] = float(v)
        except ValueError:
            raise InputError(f"{what}: '{k}={v}' is not a number") from None
    return out


def data_kwargs(args: argparse.Namespace) -> dict[str, Any]:
    """mapping/units/area keyword arguments for load_dataset and fit."""
    return {
        "mapping": parse_assignments(args.map, "--map") or None,
        "units": parse_assignments(args.units, "--units") or None,
        "area": args.area,
    }


def fit_kwargs(args: argparse.Namespace) -> dict[str, Any]:
    """Keyword arguments for :func:`frictionlaws.fitting.fit` from the fit options."""
    free = [s.strip() for chunk in args.free for s in chunk.split(",") if s.strip()]
    return {
        "fix": parse_floats(args.fix, "--fix"),
        "free": free,
        "weights": "auto" if args.weights == "auto" else None,
        "on_invalid": "drop" if args.drop_invalid else "error",
        "starts": args.starts,
        "seed": args.seed,
        **data_kwargs(args),
    }


def run_fit(args: argparse.Namespace, law: str, data: str) -> Any:
    """Fit ``law`` to ``data`` with the command's options."""
    from frictionlaws.fitting import fit

    return fit(law, data, **fit_kwargs(args))
