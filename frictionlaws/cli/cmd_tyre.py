"""``frictionlaws tyre``: friction laws inside tyre models.

Sub-commands:

* ``cornering``: cornering stiffness of a brush tyre against load with a law
  (preset, explicit values, a saved fit, or a fit run on the spot);
* ``thesis``: the thesis' comparison (constant mu against laws fitted to
  ``thesis-steel``) beside its Table 6-2;
* ``mf``: summary of a Magic Formula property file (.tir or JSON), or every steady-state
  output at the conditions given (``--kappa``, ``--alpha``, ...: the library's table of
  inputs, :data:`frictionlaws.tyre.mf.inputs.INPUTS`);
* ``reduce``: fit a slip law (pacejka, burckhardt...) to a property file's
  F_x0/F_z curve at one load;
* ``fit-mf``: fit a Magic Formula property file to tyre test data;
* ``prepare``: turn a raw rig run into the steady sweeps fit-mf uses.
"""

from __future__ import annotations

import argparse
import itertools
import json
import sys
import warnings
from typing import Any

import numpy as np

from ..base import jsonio
from ..base.errors import ExtrapolationWarning, FitError, InputError
from ..base.numbers import parse_number
from ..base.outputs import check_figure_path, check_outputs
from ..base.units import parse_quantity, to_si
from ..tyre.brush import BrushModel, BrushTyre
from ..tyre.data import load_raw_run, prepare_run, write_plots, write_tyre_csv
from ..tyre.data.tydex import write_tydex
from ..tyre.mf.fit import check_tir_path, fit_mf
from ..tyre.mf.fit.checks import plausibility_warnings
from ..tyre.mf.fit.staged import refuse_not_applied
from ..tyre.mf.inputs import INPUTS
from ..tyre.mf.model import MagicFormula
from ..tyre.mf.outputs import OUTPUTS, evaluate
from ..tyre.reduce import MIN_POINTS as REDUCE_MIN_POINTS
from ..tyre.reduce import reduce_mf
from ..tyre.thesis import thesis_comparison
from ._common import (
    RANGE_HELP,
    SEED_MAX,
    UsageError,
    add_data_options,
    add_fit_options,
    add_law_source_options,
    bound_from_args,
    bounded_int,
    bounded_number,
    data_source,
    data_sources,
    job_count,
    parse_values,
    refuse_unused,
    report_text,
)
from ._messages import shown_source
from .commands import COMMANDS

__all__ = ["add_parser", "run", "parse_loads"]

_MAX_LOADS = 1000


def add_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    p = sub.add_parser(
        "tyre", help=COMMANDS["tyre"],
        description="Friction laws inside tyre models: brush-model cornering stiffness with "
        "any sliding law, the thesis' comparison, Magic Formula property files (.tir/JSON) "
        "and their reduction to simple slip laws.")
    tsub = p.add_subparsers(dest="tyre_command", metavar="SUBCOMMAND",
                            parser_class=type(p))

    c = tsub.add_parser(
        "cornering", help="cornering stiffness of a brush tyre against load",
        description="Cornering stiffness (kN/deg) of a brush tyre whose bristles obey a "
        "friction law mu(p, v), against load: the least-squares slope of Fy over the slip "
        "angles (default 1, 2, 3 deg, as in the thesis) and the slope at the origin.")
    c.add_argument("--law", help="law id or alias (a law of p and/or v); optional with "
                   "--params")
    add_law_source_options(c)
    _load_options(c, default="2:6.5:10")
    c.add_argument("--angles", default="1,2,3", metavar="DEG,...",
                   help="slip angles of the secant [deg] (default 1,2,3)")
    _tyre_options(c)
    add_data_options(c)
    add_fit_options(c)
    c.add_argument("--json", action="store_true", help="print one JSON object")

    t = tsub.add_parser(
        "thesis", help="the thesis' cornering comparison beside its Table 6-2",
        description="Brush-model cornering stiffness with constant mu 0.9 and 1.0 and with "
        "laws fitted to the thesis-steel dataset, beside the thesis' FE results (Table 6-2), "
        "with the ratio CS(6.5 kN)/CS(2 kN).")
    t.add_argument("--laws", default="thirion", metavar="LAW,...",
                   help="laws of p to fit to the data (default thirion)")
    t.add_argument("--data", default="thesis-steel", metavar="DATA",
                   help="dataset the laws are fitted to (default thesis-steel)")
    _tyre_options(t)
    t.add_argument("--json", action="store_true", help="print one JSON object")

    m = tsub.add_parser(
        "mf", help="summary or steady state of a Magic Formula property file",
        description="Read a Magic Formula property file (ADAMS .tir or JSON) and print its "
        "version, nominal load, peak friction coefficients and slip stiffnesses; with "
        "--kappa, --alpha, --gamma, --pressure, --vx, --phit, --omega (or --outputs, "
        "--saturate, --turn-slip, --no-limit-checks) every steady-state output (forces, "
        "moments, radii, stiffnesses...) for each combination of the values given.")
    m.add_argument("file", metavar="FILE", help=".tir or .json property file, or a packaged "
                   "example (MagicFormula52, MagicFormula61, MagicFormula62)")
    _load_options(m, default=None)
    _mf_options(m)
    _steady_state_options(m)
    m.add_argument("--coefficients", action="store_true",
                   help="list the coefficients the version evaluates instead: value (or the "
                        "default taken), SI unit and meaning, from their declarations")
    m.add_argument("--json", action="store_true", help="print one JSON object")

    r = tsub.add_parser(
        "reduce", help="fit a slip law to a property file's Fx0/Fz curve",
        description="Fit a slip law (pacejka, burckhardt, ...) to mu = |Fx0|/Fz of a Magic "
        "Formula property file at one load and report the fit error.")
    r.add_argument("file", metavar="FILE", help=".tir or .json property file")
    r.add_argument("--law", default="pacejka", help="slip law (default pacejka)")
    r.add_argument("--load", required=True, metavar="LOAD",
                   help="vertical load, in --load-unit (default kN)")
    r.add_argument("--load-unit", default="kN", metavar="UNIT", help="unit of --load")
    r.add_argument("--side", choices=("braking", "driving"), default="braking")
    r.add_argument("--slip-max", type=bounded_number(0.0, 1.0, lo_open=True), default=1.0,
                   metavar="SLIP", help="largest slip ratio (0 < SLIP <= 1, default 1)")
    r.add_argument("--points", type=bounded_int(REDUCE_MIN_POINTS, 100_000), default=201,
                   help=f"number of slip points ({REDUCE_MIN_POINTS}..100000, default 201)")
    _mf_options(r)
    r.add_argument("--json", action="store_true", help="print one JSON object")
    r.add_argument("--save", metavar="FILE", help="save the fitted law as versioned JSON "
                   "(usable with --params)")

    _add_fit_mf(tsub)
    _add_prepare(tsub)
    return p


def _add_prepare(tsub: argparse._SubParsersAction) -> None:
    r = tsub.add_parser(
        "prepare", help="turn a raw rig run into the steady sweeps fit-mf uses",
        description="Read a raw rig run (one row per sample under a row of channel names "
        "such as ET, SA, SL, FX, FY, FZ, MZ and a row of their units, SAE axes), convert it "
        "to SI and ISO-W axes and cut it into steady sweeps: lifts, transitions between "
        "loads, cambers and pressures, the warm-up and one-way stretches are dropped and "
        "counted, the force channels' zero offsets measured while lifted are subtracted, the "
        "forces' lag behind the slip is found from the up and down halves of each sweep and "
        "taken out, and each sweep is averaged in blocks, up and down apart. Writes what "
        "fit-mf would use.")
    r.add_argument("raw", metavar="RAW", help="raw rig run (text; '-' reads standard input)")
    r.add_argument("-o", "--output", required=True, metavar="FILE",
                   help="the sweeps written: FILE.csv (a tidy CSV, with sweep and direction "
                        "columns) or FILE.tdx (TYDEX)")
    r.add_argument("--plots", metavar="DIR", help="write segments.png (the run, kept and "
                   "dropped) and sweeps.png (the rows kept) into DIR")
    r.add_argument("--sign-convention", choices=("sae", "iso"), default="sae",
                   help="axes of the run: sae (default, as the public test programmes "
                        "publish) or iso (ISO-W)")
    r.add_argument("--warm-up", metavar="TIME", help="drop the first TIME (e.g. '60 s') "
                   "as warm-up, beside the conditions the run returns to later")
    r.add_argument("--json", action="store_true", help="print one JSON object")


def _add_fit_mf(tsub: argparse._SubParsersAction) -> None:
    f = tsub.add_parser(
        "fit-mf", help="fit a Magic Formula property file to tyre test data",
        description="Fit the Magic Formula to tyre test data (one or several files: a tidy "
        "CSV with 'Fz [N]', 'kappa [-]', 'alpha [deg]', 'gamma [deg]', 'pressure [kPa]', "
        "'Fx [N]', 'Fy [N]', 'Mz [N m]'; TYDEX files; raw rig runs, cut into steady sweeps "
        "as 'tyre prepare' does) in stages: pure-slip Fx0 and Fy0, the combined-slip "
        "weighting functions, the aligning moment Mz0 and combined Mz; write a .tir property "
        "file. Coefficients the data cannot determine keep the template's value (listed); "
        "data whose slips, angles or loads look like another unit than declared are refused.")
    f.add_argument("data", metavar="DATA", nargs="+",
                   help="tyre test data: CSV tables, TYDEX files (.tdx) or raw rig runs, told "
                        "apart by their content, fitted together ('-': standard input, once)")
    f.add_argument("--fittyp", type=bounded_int(), choices=(5, 6, 21, 61, 62), default=61,
                   help="FITTYP written: 61 (MF 6.1, default), 62 (MF 6.2), 5/6/21 "
                        "(MF 5.2 / PAC2002)")
    f.add_argument("--template", metavar="FILE", help="property file giving FNOMIN, the "
                   "nominal pressure, the other sections and undetermined coefficients "
                   "(default: the packaged example of the version)")
    f.add_argument("--sign-convention", choices=("iso", "sae"), default=None,
                   help="axes of the data: iso (ISO-W, as property files) or sae (Fz, Fy, Mz "
                        "and alpha negated to ISO); default: each format's, iso for CSV and "
                        "TYDEX, sae for raw rig runs")
    f.add_argument("--uncertainty", choices=("asymptotic", "sweeps"), default="asymptotic",
                   help="standard errors: asymptotic (from the Jacobian; default) or sweeps "
                        "(bootstrap of whole sweeps found in the row order, honest when a "
                        "sweep's residuals share an offset; costs --boot refits)")
    f.add_argument("--boot", type=bounded_int(20, 100_000), default=None, metavar="N",
                   help="sweep-bootstrap resamples, 20 to 100000 (default 100; with "
                        "--uncertainty sweeps)")
    f.add_argument("--boot-jobs", type=job_count, default=None, metavar="N",
                   help="worker processes for the bootstrap refits (default 1; -1 = one "
                        "per core; with --uncertainty sweeps)")
    f.add_argument("--seed", type=bounded_int(0, SEED_MAX), default=None, metavar="SEED",
                   help=f"seed of the sweep bootstrap, 0 to {SEED_MAX} (default 0)")
    f.add_argument("-o", "--output", required=True, metavar="FILE.tir",
                   help="property file to write")
    f.add_argument("--plot", metavar="FILE", help="save a figure of data and fit per load "
                   "(png, pdf, svg)")
    f.add_argument("--json", action="store_true", help="print one JSON object")
    f.set_defaults(_option_flags={"resamples": "--boot", "jobs": "--boot-jobs",
                                  "sign_convention": "--sign-convention"})


def _mf_options(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("Magic Formula conventions (see the tyre page of the guide)")
    g.add_argument("--slip-angle", choices=("tan_alpha", "alpha"), default="tan_alpha",
                   help="slip variable of the lateral curve: tan(alpha) (default, the "
                        "book's alpha*) or alpha itself")
    g.add_argument("--friction-scaling", choices=("linear", "degressive"),
                   default="linear",
                   help="MF 6.x friction scaling LMU': linear, A_mu = 1 (default; MFeval "
                        "4.0) or degressive, A_mu = 10 (Pacejka 2012, eq. 4.E8)")
    g.add_argument("--loads-above-fzmax", choices=("extrapolate", "clamp"),
                   default="extrapolate",
                   help="loads above the file's FZMAX: extrapolate with a warning "
                        "(default) or clamp to FZMAX")
    g.add_argument("--equations", choices=("mfeval", "published"), default="mfeval",
                   help="where MFeval 4.0 departs from the published equations: its forms "
                        "(default) or the published ones")


#: The options of the steady state besides the inputs' (``--loads`` gives the load).
_STEADY_STATE_EXTRA = ("saturate", "turn_slip", "no_limit_checks", "outputs")
#: At most this many rows (combinations of the values given) are evaluated.
MAX_STEADY_ROWS = 100_000


def _steady_state_options(p: argparse.ArgumentParser) -> None:
    """One option per input of the steady state (the library's table, read without numpy),
    the load being ``--loads``; ``--saturate`` and ``--outputs``."""
    g = p.add_argument_group(
        "steady state at given conditions",
        "with any of these, every steady-state output (or those of --outputs) is printed "
        "for each combination of the values given (the load: --loads, default FNOMIN)")
    for name, inp in INPUTS.items():
        if name == "fz":
            continue
        g.add_argument(f"--{name.replace('_', '-')}", metavar="MIN:MAX:N|A,B,C",
                       help=f"{inp.meaning}: a list or a range {RANGE_HELP}; bare numbers "
                            f"in {inp.display} (default {inp.default})")
    g.add_argument("--saturate", action="store_true",
                   help="clamp the inputs at the file's ranges as MFeval's limit checks do "
                        "(default: evaluate as given, warning outside them)")
    g.add_argument("--turn-slip", action="store_true",
                   help="evaluate MF-Tyre's turn-slip model (MFeval's useModes x2), the path "
                        "curvature given by --phit (default: without it; --phit other "
                        "than 0 needs it)")
    g.add_argument("--no-limit-checks", action="store_true",
                   help="evaluate as MFeval's useModes 2xx: E not capped at 1, no low-speed "
                        "reductions, M_x and M_y reduced below FZMIN (default: the limit "
                        "checks)")
    g.add_argument("--outputs", metavar="NAME,...",
                   help="the outputs to print (default: every output the file gives; the "
                        "names are listed in the tyre page of the guide)")


def _steady_state_dests() -> list[str]:
    return [n for n in INPUTS if n != "fz"] + list(_STEADY_STATE_EXTRA)


def _steady_state_given(args: argparse.Namespace) -> bool:
    return any(getattr(args, d, None) not in (None, False) for d in _steady_state_dests())


def _mf_file(args: argparse.Namespace) -> Any:
    """The property file read with the Magic Formula conventions chosen (``-``: stdin)."""
    return MagicFormula.from_file(args.file, slip_angle=args.slip_angle,
                                  friction_scaling=args.friction_scaling,
                                  loads_above_fzmax=args.loads_above_fzmax,
                                  equations=args.equations)


def _on_property_file(run: Any, args: argparse.Namespace) -> int:
    """Run a command on its property FILE; ``-`` reads it from standard input."""
    given = args.file
    with data_source(given, _property_name) as path:
        args.file = path
        try:
            return int(run(args))
        finally:
            args.file = given


def _property_name(raw: bytes) -> str:
    """A property file from standard input: JSON when it opens with '{', else .tir."""
    return "stdin.json" if raw.lstrip().startswith(b"{") else "stdin.tir"


def _load_options(p: argparse.ArgumentParser, default: str | None) -> None:
    p.add_argument("--loads", default=default, metavar="MIN:MAX:N|A,B,C",
                   help=f"vertical loads: a range {RANGE_HELP} (the grammar of every command; "
                        "the third number is a count, not a step), or a list A,B,C; bare "
                        "numbers in --load-unit"
                        + (f" (default {default})" if default else ""))
    p.add_argument("--load-unit", default="kN", metavar="UNIT",
                   help="unit of --loads (default kN)")


def _tyre_options(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("brush tyre (defaults: a passenger tyre like the thesis')")
    g.add_argument("--width", metavar="LEN", help="contact patch width (default '150 mm')")
    g.add_argument("--half-length", metavar="LEN",
                   help="contact half-length at --ref-load (default '55 mm')")
    g.add_argument("--ref-load", metavar="LOAD", help="reference load (default '3 kN')")
    g.add_argument("--c-py", metavar="STIFF",
                   help="lateral tread stiffness per unit patch length (default "
                        "'8.49e6 N/m^2')")
    g.add_argument("--pressure-shape", choices=("parabolic", "uniform"), default=None,
                   help="contact pressure along the patch (default parabolic)")
    g.add_argument("--speed", metavar="SPEED", help="road speed (default '10 km/h')")


# --------------------------------------------------------------------- helpers


def parse_loads(text: str, unit: str, flag: str = "--loads") -> Any:
    """``"2:6.5:10"`` (MIN:MAX:N) or ``"2,3,4"`` in ``unit`` -> loads in N (numpy array).

    The one range grammar (:func:`~frictionlaws.cli._common.range_option`); the old
    ``START:STOP:STEP`` form is recognised by a third number that is not a count
    and refused with its translation.
    """
    try:
        to_si(1.0, unit, "F_N")
    except InputError as exc:
        raise InputError(f"--load-unit {unit}: {exc}") from None
    _refuse_step_form(text, flag)
    loads = np.asarray(parse_values(text, "F_N", option=flag, unit=unit,
                                    max_points=_MAX_LOADS), dtype=float)
    if loads.size == 0 or not np.all(np.isfinite(loads)) or np.any(loads <= 0):
        raise UsageError(f"{flag} '{text}': loads must be positive")
    return loads


def _refuse_step_form(text: str, flag: str) -> None:
    """``START:STOP:STEP`` (the form before the grammar was one): refused when the third
    number cannot be a count, flagged when it reads both ways."""
    parts = str(text or "").split(":")
    if len(parts) != 3:
        return
    try:
        start, stop, step = (parse_number(x) for x in parts)
    except ValueError:
        return  # with units or malformed: the range parser says what is wrong
    if not (step > 0 and stop > start):
        return
    count = int((stop - start) / step + 1e-9) + 1
    as_step = f"{start:g}:{start + (count - 1) * step:g}:{count}"
    if step != int(step):
        raise UsageError(f"{flag} '{text}': a range is MIN:MAX:N with N the number of loads, "
                         f"not START:STOP:STEP; a step of {step:g} is {as_step}")
    if abs(start + (count - 1) * step - stop) <= 1e-9 * abs(stop) and count != step:
        print(f"warning: {flag} '{text}' is MIN:MAX:N, {int(step)} loads; for a step of "
              f"{step:g} write {as_step}", file=sys.stderr)


def _quantity(text: str | None, kind: str, what: str) -> float | None:
    if text is None:
        return None
    return parse_quantity(text, kind, what=what)


def _stiffness(text: str | None) -> float | None:
    """A stiffness per unit length [N/m^2] such as '8.49e6 N/m^2' or '8.49 N/mm^2'."""
    if text is None:
        return None
    value = parse_quantity(text, "stiffness_per_length", what="--c-py")
    if not value > 0:
        raise InputError(f"--c-py '{text}' must be positive")
    return value


def _tyre(args: argparse.Namespace) -> Any:
    kw: dict[str, Any] = {}
    for opt, key, kind in (("width", "width", "length"),
                           ("half_length", "half_length_ref", "length"),
                           ("ref_load", "ref_load", "F_N"), ("speed", "speed", "v")):
        value = _quantity(getattr(args, opt), kind, "--" + opt.replace("_", "-"))
        if value is not None:
            kw[key] = value
    c_py = _stiffness(args.c_py)
    if c_py is not None:
        kw["c_py"] = c_py
    if args.pressure_shape:
        kw["pressure"] = args.pressure_shape
    return BrushTyre(**kw)


def _said_once(report: str, raised: list[str], args: argparse.Namespace) -> str:
    """A result's report without the ``warning:`` lines of ``raised``, the warnings the
    result also issued as Python warnings, which the command line prints on stderr once
    each (as ``tyre mf`` does): each warning is said once, on one channel."""
    lines = [line for line in report.split("\n")
             if line.removeprefix("warning: ") not in raised or not line.startswith("warning: ")]
    return report_text("\n".join(lines), args)


def _warn(messages: list[str]) -> None:
    for m in messages:
        print(f"warning: {m}", file=sys.stderr)


# ------------------------------------------------------------------------ run


def run(args: argparse.Namespace) -> int:
    cmd = getattr(args, "tyre_command", None)
    if cmd == "cornering":
        return _run_cornering(args)
    if cmd == "thesis":
        return _run_thesis(args)
    if cmd == "mf":
        return _on_property_file(_run_mf, args)
    if cmd == "reduce":
        return _on_property_file(_run_reduce, args)
    if cmd == "fit-mf":
        return _run_fit_mf(args)
    if cmd == "prepare":
        return _run_prepare(args)
    raise InputError("frictionlaws tyre: choose a sub-command: cornering, thesis, mf, reduce, "
                     "fit-mf, prepare")


def _angles(text: str) -> list[float]:
    try:  # the one number parser: no 1_0, no non-ASCII digits, finite
        return [parse_number(a) for a in text.split(",") if a.strip()]
    except ValueError as exc:
        raise InputError(f"--angles '{text}': expected numbers in degrees, "
                         f"e.g. 1,2,3 ({exc})") from None


def _source_notes(args: argparse.Namespace, bound: Any) -> list[str]:
    """What ``cornering`` says about where the law's values came from."""
    if args.params:
        return [f"parameters from {args.params}"]
    if not args.fit:
        return []
    units = {p.name: p.unit for p in bound.law.params}
    values = ", ".join(f"{k} = {v:.6g} {units.get(k, '')}".rstrip()
                       for k, v in bound.param_values.items())
    src = bound.source
    return [f"law fitted to {src.dataset}: {values} ({src.detail})",
            *(f"fit: {w}" for w in bound.notes)]


def _run_cornering(args: argparse.Namespace) -> int:
    loads = parse_loads(args.loads, args.load_unit)
    angles = _angles(args.angles)
    tyre = _tyre(args)
    bound = bound_from_args(args, args.law)
    model = BrushModel(bound, tyre=tyre)
    notes = _source_notes(args, bound)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        res = model.cornering(loads, angles)
    if args.json:
        out = res.to_dict()
        out["notes"] = notes
        print(json.dumps(out, indent=2))
        return 0
    params = ", ".join(f"{k} = {v:.6g}" for k, v in res.params.items()) or "-"
    print(f"law: {res.law} ({params}; SI units)")
    for n in notes:
        print(f"note: {n}")
    print("\n".join(line for line in res.table().splitlines()
                    if not line.startswith("warning: ")))
    _warn(res.warnings)
    return 0


def _run_thesis(args: argparse.Namespace) -> int:
    laws = [x.strip() for x in args.laws.split(",") if x.strip()]
    if not laws:
        raise InputError("--laws is empty; give law ids, e.g. thirion,savkoor")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        comp = thesis_comparison(laws=laws, dataset=args.data, tyre=_tyre(args))
    if args.json:
        print(json.dumps(comp.to_dict(), indent=2))
        return 0
    for label, f in comp.fits.items():
        print(f"fit {label}: " + ", ".join(
            f"{k} = {p.value:.6g} {p.unit}".rstrip()
            + (" (undetermined)" if k in f.non_identifiable else "")
            for k, p in f.params.items()) + f" (R^2 {f.metrics['r2']:.4f})")
    lines = comp.table().splitlines()
    print("\n".join(line for line in lines if not line.startswith("warning")))
    _warn([line.removeprefix("warning ") for line in lines if line.startswith("warning")])
    return 0


def _run_mf(args: argparse.Namespace) -> int:
    if args.coefficients:  # before reading the file: the listing evaluates no load
        refuse_unused(args, ("loads", "load_unit", *_steady_state_dests()),
                      "with --coefficients")
    mf = _mf_file(args)
    if args.coefficients:
        return _print_coefficients(mf, args.json)
    if _steady_state_given(args):
        return _print_steady_state(mf, args)
    loads = (parse_loads(args.loads, args.load_unit) if args.loads
             else np.array([0.5, 1.0, 1.5]) * mf.fnomin)
    summary = mf.summary(loads)
    if "source" in summary:
        summary["source"] = shown_source(summary["source"])
    if args.json:
        print(jsonio.dumps(summary))
        return 0
    _print_summary(mf, summary)
    return 0  # the warnings (outside the file's range, clamped) reach stderr once


def _print_summary(mf: Any, summary: dict[str, Any]) -> None:
    """The text of ``tyre mf``: per load, what :meth:`MagicFormula.summary` holds."""
    print(f"{mf.name}: Magic Formula {mf.version}, FNOMIN {mf.fnomin:g} N"
          + (f", inflation {mf.pressure / 1e6:.3g} MPa" if mf.pressure else ""))
    for n in summary["notes"]:
        print(f"note: {n}")
    moments = "trail_m" in summary
    print(f"{'Fz [kN]':>8}  {'mu_x peak':>9}  {'mu_y peak':>9}  {'Kx [kN]':>9}  "
          f"{'Ky [kN/rad]':>11}" + (f"  {'trail [mm]':>10}  {'Mz0 peak [N m]':>14}  "
                                     f"{'at [deg]':>8}" if moments else ""))
    for i, fz in enumerate(summary["loads_N"]):
        mark = "*" if summary["clamped"][i] else " "
        print(f"{fz / 1000:>8.4g}{mark} {summary['mu_x_peak'][i]:>9.4f}  "
              f"{summary['mu_y_peak'][i]:>9.4f}  {summary['K_x_N'][i] / 1000:>9.2f}  "
              f"{summary['K_y_N_per_rad'][i] / 1000:>11.2f}"
              + (f"  {summary['trail_m'][i] * 1000:>10.2f}  "
                 f"{summary['Mz0_peak_N_m'][i]:>14.1f}  "
                 f"{summary['Mz0_peak_alpha_deg'][i]:>8.2f}" if moments else ""))
    if any(summary["clamped"]):
        at = max(summary["loads_evaluated_N"]) / 1000
        print(f"*: clamped, evaluated at the file's FZMAX = {at:g} kN "
              "(loads_above_fzmax = clamp)")
    if moments:
        print("trail: pneumatic trail at zero slip; Mz0 peak: the pure-slip aligning moment "
              "of largest magnitude within +-20 deg, at the file's LONGVL")


def _steady_state_grid(mf: Any, args: argparse.Namespace) -> dict[str, Any]:
    """Every combination of the input values given (SI), one row each, as flat arrays."""
    given: dict[str, Any] = {}
    for name, inp in INPUTS.items():
        if name == "fz":
            given[name] = (parse_loads(args.loads, args.load_unit) if args.loads
                           else np.array([mf.fnomin]))
            continue
        text = getattr(args, name)
        if text is not None:
            flag = f"--{name.replace('_', '-')}"
            given[name] = np.asarray(parse_values(text, inp.quantity, option=flag,
                                                  unit=inp.display), dtype=float)
    n = int(np.prod([v.size for v in given.values()]))
    if n > MAX_STEADY_ROWS:
        raise InputError(f"{n} combinations of the values given: at most {MAX_STEADY_ROWS} "
                         "rows are evaluated at once")
    # the slip angle varies fastest: one sweep per combination of the others (instKya)
    order = sorted(given, key=lambda k: k == "alpha")
    rows = list(itertools.product(*(given[k] for k in order)))
    grid = {k: np.array([r[i] for r in rows], dtype=float) for i, k in enumerate(order)}
    return {**{k: None for k in INPUTS}, "kappa": 0.0, "alpha": 0.0, "gamma": 0.0, **grid}


def _print_steady_state(mf: Any, args: argparse.Namespace) -> int:
    """``tyre mf FILE --kappa ...``: every output of the library's table, per row."""
    names = None
    if args.outputs is not None:
        names = [x.strip() for x in args.outputs.split(",")]
        if "" in names and any(names):  # as every list option: an empty item is said
            raise InputError(f"--outputs {args.outputs!r}: item {names.index('') + 1} of the "
                             "list is empty; expected NAME,NAME, names separated by single "
                             "commas")
        names = [x for x in names if x]
        unknown = [x for x in names if x not in OUTPUTS]
        if unknown or not names:
            raise InputError(f"--outputs {args.outputs!r}: unknown output "
                             f"{', '.join(unknown) or '(none given)'}; the outputs are "
                             f"{', '.join(OUTPUTS)}")
    grid = _steady_state_grid(mf, args)
    res = evaluate(mf, grid["kappa"], grid["alpha"], grid["fz"], grid["gamma"],
                   grid["pressure"], grid["vx"], saturate=args.saturate, names=names,
                   phit=0.0 if grid["phit"] is None else grid["phit"], omega=grid["omega"],
                   turn_slip=args.turn_slip, limit_checks=not args.no_limit_checks)
    if args.json:
        out = {"name": mf.name, "source": shown_source(mf.source), "version": mf.version,
               **res.to_dict(), "notes": list(mf.notes)}
        print(jsonio.dumps(out))
        return 0
    print(f"{mf.name}: Magic Formula {mf.version}, FNOMIN {mf.fnomin:g} N; steady state "
          "(SI; 'clamped' names an input limited on the row: the warnings say which "
          "outputs are at the limit)")
    for n in mf.notes:
        print(f"note: {n}")
    _print_rows(res.to_dict())
    return 0  # the warnings reach stderr once, as every command's do


def _print_rows(table: dict[str, Any]) -> None:
    """The rows of a steady state as an aligned text table, units in the header."""
    cols = list(dict.fromkeys([*table["inputs"], *table["outputs"]]))  # omega: once, as
    # in the rows of the JSON (the wheel speed given is the one evaluated)
    units = {**table["inputs"], **table["outputs"]}
    head = [f"{c} [{units[c]['unit']}]" for c in cols] + ["clamped"]
    cells = [[f"{r[c]:.6g}" for c in cols] + [",".join(r["clamped"]) or "-"]
             for r in table["rows"]]
    width = [max(len(h), *(len(row[i]) for row in cells)) for i, h in enumerate(head)]
    print("  ".join(h.rjust(w) for h, w in zip(head, width)))
    for row in cells:
        print("  ".join(x.rjust(w) for x, w in zip(row, width)))


def _print_coefficients(mf: Any, as_json: bool) -> int:
    """``tyre mf --coefficients``: the file's values beside their declarations."""
    rows = mf.coefficient_listing()
    if as_json:
        print(json.dumps({"name": mf.name, "version": mf.version, "coefficients": rows},
                         indent=2))
        return 0
    print(f"{mf.name}: Magic Formula {mf.version}; '*' marks a default the file does not "
          "give, '-' an entry absent without a default")
    section = None
    for r in rows:
        if r["section"] != section:
            section = r["section"]
            print(f"[{section or 'unknown'}]")
        value = "-" if r["value"] is None else f"{r['value']:.6g}"
        mark = " " if r["given"] else "*"
        print(f"  {r['name']:<24}{value:>14}{mark} {str(r['unit'] or '1'):<9}{r['meaning']}")
    return 0


def _run_reduce(args: argparse.Namespace) -> int:
    loads = parse_loads(args.load, args.load_unit, "--load")
    if loads.size != 1:
        raise InputError("--load takes one load")
    if args.save:
        check_outputs([args.save], inputs=[args.file])
    mf = _mf_file(args)
    red = reduce_mf(mf, args.law, fz=float(loads[0]), side=args.side,
                    slip_max=args.slip_max, n=args.points)
    if not red.fit.success:  # as fit: a failed reduction is reported, not saved (exit 1)
        print(red.report())
        print(f"error: the reduction did not converge ({red.fit.message}); nothing saved",
              file=sys.stderr)
        return 1
    if args.save:
        red.fit.save(args.save)
    if args.json:
        print(jsonio.dumps(red.to_dict()))
    else:
        print(_said_once(red.report(), red.warnings, args))
        if args.save:
            print(f"saved: {args.save}")
    return 0


def _run_fit_mf(args: argparse.Namespace) -> int:
    # the library's one rule of options that do not apply, before anything is read
    refuse_not_applied(args.data, args.sign_convention, args.uncertainty,
                       {"resamples": args.boot, "jobs": args.boot_jobs, "seed": args.seed,
                        "sweeps": None})
    if args.data.count("-") > 1:
        raise UsageError("standard input ('-') can be given once among the DATA files")
    inputs = list(args.data) + ([args.template] if args.template else [])
    check_outputs([args.output, args.plot], inputs=inputs)
    check_tir_path(args.output)
    if args.plot:  # before the fit: a figure that cannot be drawn leaves no .tir behind
        check_figure_path(args.plot)

    with data_sources(args.data) as data:
        try:
            res = fit_mf(data, fittyp=args.fittyp, template=args.template,
                         sign_convention=args.sign_convention, uncertainty=args.uncertainty,
                         resamples=args.boot, seed=args.seed, jobs=args.boot_jobs)
        except FitError as exc:  # name standard input, not its private copy
            text = str(exc)
            for path in data:
                text = text.replace(path, shown_source(path))
            raise FitError(text) from None
        for path in data:  # the provenance the file states names what the user gave
            shown = shown_source(path)
            res.notes = [n.replace(path, shown) for n in res.notes]
            res.warnings = [n.replace(path, shown) for n in res.warnings]
        res.data.source = " + ".join(shown_source(p) for p in data)
    res.write(args.output)
    if args.plot:
        res.plot(args.plot)
    if args.json:
        print(jsonio.dumps(res.to_dict()))
        return 0
    print(_said_once(res.report(), res.warnings, args))
    print(f"written: {args.output}" + (f", {args.plot}" if args.plot else ""))
    return 0


def _run_prepare(args: argparse.Namespace) -> int:
    suffix = args.output.lower().rsplit(".", 1)[-1] if "." in args.output else ""
    if suffix not in ("csv", "tdx"):
        raise InputError("the sweeps are written as a tidy CSV (.csv) or a TYDEX file (.tdx): "
                         "give the output one of these suffixes", file=args.output)
    warmup = _quantity(args.warm_up, "time", "--warm-up") or 0.0
    check_outputs([args.output], dirs=[args.plots], inputs=[args.raw])
    with data_source(args.raw, "stdin.txt") as path:
        prepared = prepare_run(load_raw_run(path, sign_convention=args.sign_convention),
                               warmup=warmup)
        shown = shown_source(path)
        prepared.run.source = prepared.data.source = shown  # before the warnings name it
        data = prepared.data
        prepared.warnings += plausibility_warnings(data, float(np.median(data.fz)))
        provenance = [f"steady sweeps prepared by frictionlaws tyre prepare from {shown}",
                      *prepared.summary()[1:], *(f"note: {n}" for n in prepared.notes)]
        if suffix == "csv":
            write_tyre_csv(prepared.data, args.output, provenance)
        else:
            write_tydex(prepared.data, args.output, comments=provenance)
        plots = write_plots(prepared, args.plots) if args.plots else []
    if args.json:
        out = prepared.to_dict()
        out["written"] = [args.output, *map(str, plots)]
        print(jsonio.dumps(out))
        return 0
    print(_said_once(prepared.report(), prepared.warnings, args))
    print("written: " + ", ".join([args.output, *map(str, plots)]))
    return 0
