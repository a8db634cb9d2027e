"""The export entry point: :func:`export` any law to any supported format."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..base.errors import Argument, InputError
from ..base.numbers import parse_integer, parse_number
from ..base.outputs import check_outputs, write_text_atomic
from ..base.units import parse_quantity, si_magnitude
from ..law import VARIABLES, Law
from ..law.bound import BoundLaw, as_bound, freeze
from .formats import FORMATS, OPTIONS, formats_taking
from .fortran import check_source_name
from .grid import MAX_ROWS, AxisSpec, Grid
from .job import Job, Written
from .systems import UnitSystem, unit_system

__all__ = ["export", "ExportResult", "FORMATS", "OPTIONS", "check_options", "parse_range",
           "make_specs"]


def check_options(options: Mapping[str, Any] | None, format: str | None = None
                  ) -> dict[str, int]:
    """Check format options against :data:`OPTIONS`, with the defaults of those not given.

    Parameters
    ----------
    options : mapping or None
        Option name -> value.
    format : str, optional
        The format written: an option it does not take is refused, never ignored.

    Returns
    -------
    dict
        Every option of ``format`` (all of them without one) as ints, the given ones and
        the defaults of the others.

    Raises
    ------
    InputError
        An unknown name, one the format does not take, or a value that is not a whole
        number in its range.
    """
    taken = {o.name for o in FORMATS[format].options} if format in FORMATS else set(OPTIONS)
    out = {name: OPTIONS[name].default for name in taken}
    for name, value in (options or {}).items():
        if name not in OPTIONS:
            raise InputError(f"unknown export option '{name}'; options: {', '.join(OPTIONS)}",
                             option="options")
        if name not in taken:
            raise InputError(f"export option {name} does not apply to format {format} "
                             f"(it is an option of {', '.join(formats_taking(name))})",
                             option="options")
        opt = OPTIONS[name]
        ok = (not isinstance(value, bool) and isinstance(value, (int, np.integer))
              and opt.lo <= value <= opt.hi)
        if not ok:
            raise InputError(f"export option {name} must be a whole number from {opt.lo} to "
                             f"{opt.hi}, got {value!r}", option="options")
        out[name] = int(value)
    return out


@dataclass
class ExportResult:
    """What :func:`export` wrote.

    Attributes
    ----------
    format : str
        The export format.
    text : str
        The file content.
    path : str or None
        Where it was written (None when not written).
    law : str
        Law id.
    units : str
        Unit system name.
    rows : int or None
        Table rows, None for formula exports.
    exact : bool
        True when the file reproduces the law exactly (no interpolation).
    max_error : float or None
        Largest ``|mu_file - mu_law|`` in the box (interpolation or approximation).
    error_at : dict
        Where it occurs, in the model's units.
    rms_error : float or None
        Root mean square error over the check sample.
    warnings : list of str
        Extrapolation and other warnings (also in the file's header).
    summary : list of str
        Lines for the user.
    details : dict
        Format-specific facts (coefficients, ids...).
    grid : Grid or None
        The grid written, breakpoints in SI.
    """

    format: str
    text: str
    path: str | None
    law: str
    units: str
    rows: int | None
    exact: bool
    max_error: float | None
    error_at: dict[str, float] = field(default_factory=dict)
    rms_error: float | None = None
    warnings: list[str] = field(default_factory=list)
    summary: list[str] = field(default_factory=list)
    details: dict[str, Any] = field(default_factory=dict)
    grid: Grid | None = None

    def to_dict(self) -> dict[str, Any]:
        """What was written and its error, as JSON-able values (the file's text left out).

        Errors are in mu (dimensionless); ``error_at`` and ``grid`` breakpoints are in
        the export's unit system (``units``).
        """
        return {"format": self.format, "path": self.path, "law": self.law,
                "units": self.units, "rows": self.rows, "exact": self.exact,
                "max_error": self.max_error, "rms_error": self.rms_error,
                "error_at": dict(self.error_at), "warnings": list(self.warnings),
                "summary": list(self.summary), "details": self.details}

    def report(self) -> str:
        """A few lines for the command line."""
        where = f"{self.path}" if self.path else "(not written)"
        lines = [f"wrote {where}: {self.format}, law {self.law}, units {self.units}"]
        lines += [f"  {s}" for s in self.summary]
        lines += [f"  warning: {w}" for w in self.warnings]
        return "\n".join(lines)


# ------------------------------------------------------------------ ranges


def _check_range(var: str, lo: float, hi: float) -> None:
    if var in ("p", "v", "F_N") and lo < 0:
        raise InputError(f"range of {var} ({VARIABLES[var].meaning}) must not be negative, "
                         f"got MIN {lo:g} {VARIABLES[var].unit} (SI)", option=f"box.{var}")
    if var == "T" and lo <= 0:
        raise InputError(f"range of T must be above 0 K, got MIN {lo:g} K (SI)",
                         option="box.T")


#: An example range per variable: bare numbers in the export's unit system, or with units.
_RANGE_EXAMPLES = {"p": "0.01:0.5:20 (in the unit system) or 10kPa:0.5MPa:20",
                   "v": "0:2:21 or 1e-3m/s:10m/s:30", "T": "253.15:353.15:5 or 20degC:80degC:7",
                   "F_N": "10:500:12 or 1N:1kN", "s": "0:1:41"}


def _range_bound(var: str, s: str, text: str, system: UnitSystem) -> float:
    """One bound of a range: a number in the unit system or a quantity with its unit."""
    s = s.strip()
    if not s:
        raise InputError(f"'{text}': empty bound; expected MIN:MAX[:N], e.g. "
                         f"{_RANGE_EXAMPLES[var]}", option=f"box.{var}")
    try:
        x = parse_number(s)  # the one number parser: no 1_000, no nan, no overflow
    except ValueError:
        try:
            return parse_quantity(s, var, what=var)
        except InputError as exc:
            raise InputError(f"'{text}': {exc.bare_message}", option=f"box.{var}") from None
    with np.errstate(over="ignore", invalid="ignore"):
        value = float(np.asarray(system.to_si(var, x), dtype=float))
    if not (math.isfinite(x) and math.isfinite(value)):
        raise InputError(f"'{text}': bounds must be finite (in SI too)", option=f"box.{var}")
    return value


def parse_range(var: str, text: str, units: UnitSystem | str | None = None,
                spacing: str = "auto") -> AxisSpec:
    """Parse ``MIN:MAX[:N]`` for variable ``var``.

    Bare numbers are in ``units`` (the export's unit system); a bound may carry
    its own unit, e.g. ``"10kPa:0.5MPa:20"`` or ``"20degC:80degC"``.  This is the
    one range grammar of the package (``N`` points, both ends included).

    Raises
    ------
    InputError
        With ``option="box.<var>"``, the text and an example, when malformed.
    """
    system = unit_system(units)
    parts = str(text).split(":")
    if len(parts) not in (2, 3):
        raise InputError(f"'{text}': expected MIN:MAX or MIN:MAX:N, e.g. "
                         f"{_RANGE_EXAMPLES[var]}", option=f"box.{var}")
    lo, hi = (_range_bound(var, x, text, system) for x in parts[:2])
    n = None
    if len(parts) == 3:
        count = parts[2].strip()
        try:  # the one number parser: no 1_0, no non-ASCII digits
            n = parse_integer(count, lo=0, hi=999_999_999)
        except ValueError:
            raise InputError(f"'{text}': N must be a whole number of points, got "
                             f"'{count[:20]}'", option=f"box.{var}") from None
    _check_range(var, lo, hi)
    return AxisSpec(var, lo, hi, n, spacing)


def _check_spacing(spacing: Mapping[str, str]) -> None:
    for k, s in spacing.items():
        if k not in VARIABLES:
            raise InputError(f"spacing for unknown variable '{k}' (variables: "
                             f"{', '.join(VARIABLES)})", option="spacing")
        if s not in ("lin", "log", "auto"):
            raise InputError(f"spacing of {k} must be lin or log, got '{s}'", option="spacing")


def _axis(var: str, spec: Any, units: UnitSystem, spacing: str) -> AxisSpec:
    """One entry of a box: an AxisSpec, ``"MIN:MAX[:N]"`` text or ``(min, max[, n])``."""
    if isinstance(spec, AxisSpec):
        return spec
    if isinstance(spec, str):
        return parse_range(var, spec, units, spacing)
    seq = list(spec)
    if len(seq) not in (2, 3):
        raise InputError(f"expected (min, max) or (min, max, n), got {spec!r}",
                         option=f"box.{var}")
    lo, hi = (parse_quantity(si_magnitude(x, VARIABLES[var].unit, f"box['{var}']"), var,
                             what=f"box['{var}']") for x in seq[:2])
    n = None
    if len(seq) == 3 and seq[2] is not None:
        if int(seq[2]) != seq[2]:
            raise InputError(f"n must be a whole number, got {seq[2]!r}", option=f"box.{var}")
        n = int(seq[2])
    _check_range(var, lo, hi)
    return AxisSpec(var, lo, hi, n, spacing)


def make_specs(box: Mapping[str, Any] | None, units: UnitSystem,
               spacing: Mapping[str, str] | None = None) -> dict[str, AxisSpec]:
    """Ranges from an API ``box``: SI tuples ``(min, max[, n])``, quantity strings, text."""
    spacing = dict(spacing or {})
    _check_spacing(spacing)
    out: dict[str, AxisSpec] = {}
    for var, spec in (box or {}).items():
        if var not in VARIABLES:
            raise InputError(f"unknown variable '{var}' (variables: {', '.join(VARIABLES)})",
                             option="box")
        out[var] = _axis(var, spec, units, spacing.get(var, "auto"))
    for var in spacing:
        if var not in out:
            raise InputError(f"spacing given for {var} but no range", option=f"box.{var}")
    return out


# ------------------------------------------------------------------ export


def _bound(law: Law | BoundLaw | str | None, params: Any, preset: str | None) -> BoundLaw:
    """The law and its values: a BoundLaw given as ``law`` or ``params``, or bound here."""
    if isinstance(law, BoundLaw):
        if params is not None or preset is not None:
            raise InputError("a bound law carries its values: give no params or preset with "
                             "it", option="params")
        return law
    if params is not None and not isinstance(params, Mapping):
        if preset is not None:
            raise InputError("give either a fit result (or bound law) or a preset, not both",
                             option="preset")
        return as_bound(params, law=law)
    if law is None:
        raise InputError("no law given")
    return freeze(law, params, preset=preset)


def _check_format(format: str, tol: float | None) -> None:
    if format not in FORMATS:
        raise InputError(f"unknown export format '{format}'; formats: {', '.join(FORMATS)}")
    if tol is not None and (isinstance(tol, bool) or not (
            isinstance(tol, (int, float)) and math.isfinite(tol) and tol > 0)):
        raise InputError(f"tolerance must be a positive number, got {tol!r}")


def _job(bound: BoundLaw, format: str, specs: dict[str, AxisSpec], system: UnitSystem, *,
         tol: float | None, max_rows: int, source: str | None,
         options: Mapping[str, Any] | None) -> Job:
    """The export job, with the warnings the bound values carry."""
    law_obj = bound.law
    unused = [v for v in specs if v not in law_obj.variables]
    if unused:  # a range the law cannot use is an error, not ignored
        raise InputError(f"law '{law_obj.id}' does not depend on {', '.join(unused)} (its "
                         f"variables: {', '.join(law_obj.variables) or 'none'}); remove the "
                         "range", option=f"box.{unused[0]}")
    job = Job(law=law_obj, values=dict(bound.values), fmt=format, units=system, specs=specs,
              tol=tol, max_rows=int(max_rows), source=source or bound.source.describe(),
              fit=bound, options=check_options(options, format))
    job.warnings += [f"fit: {w}" for w in bound.notes]
    if not bound.converged:
        job.warnings.append("fit: the optimiser did not converge")
    return job


def _inputs_of(bound: BoundLaw) -> list[str]:
    """The files the bound values came from: the fitted data file, the params file."""
    src = bound.source
    return [f for f in (src.data_file, src.file) if f]


def _check_path(path: str | Path | None, bound: BoundLaw, fmt: str) -> None:
    """Check the export's path before any work (the same check as :func:`_write`).

    A Fortran format's file must also have a name compilers read as fixed form.
    """
    if path is not None and str(path) != "-":
        if FORMATS[fmt].source_code:
            check_source_name(str(path))

        check_outputs([path], inputs=_inputs_of(bound), what="export file")


def _write(path: str | Path | None, text: str, inputs: list[str]) -> str | None:
    """Write the export atomically, never over ``inputs`` nor a file read in this process.

    Returns the path written, or None for no path (or ``"-"``).
    """
    if path is None or str(path) == "-":
        return None

    p = Path(path)
    check_outputs([p], inputs=inputs, what="export file")
    try:
        write_text_atomic(p, text)
    except OSError as exc:
        raise InputError(f"cannot write the export: {exc.strerror}", file=str(p)) from None
    return str(p)


def export(law: Law | BoundLaw | str | None, params: Any = None, format: str = "csv",
           box: Mapping[str, Any] | None = None, *, preset: str | None = None,
           units: str | UnitSystem = "SI", tol: float | None = None,
           spacing: Mapping[str, str] | None = None, path: str | Path | None = None,
           max_rows: int = MAX_ROWS, source: str | None = None,
           options: Mapping[str, Any] | None = None) -> ExportResult:
    """Export a law to a finite-element code's input, a table or a user subroutine.

    Parameters
    ----------
    law : Law or BoundLaw or str or None
        The law (id or alias), or a :class:`~frictionlaws.law.bound.BoundLaw`
        (``law.freeze(...)``, ``result.bound``) that carries its values, their
        source and fitted ranges; may be None when ``params`` is a bound law or
        a fit result.
    params : mapping or BoundLaw or FitResult, optional
        Parameter values (SI), a bound law, or a
        :class:`~frictionlaws.fitting.FitResult` (also from
        :func:`~frictionlaws.fitting.load_result`); missing values come from
        ``preset`` or the defaults of optional parameters.
    format : str
        One of :data:`~frictionlaws.fe_export.formats.FORMATS` (``csv``, ``abaqus``,
        ``lsdyna``, ``radioss``...).
    box : mapping, optional
        Variable -> ``(min, max)`` or ``(min, max, n)`` in SI (numbers) or as
        quantity strings (``("10 kPa", "0.5 MPa", 20)``), or ``"MIN:MAX[:N]"``
        text in the ``units`` system.  Needed for the table formats (every
        variable the law uses) and the Radioss fit.
    preset : str, optional
        A named preset of the law.
    units : str or UnitSystem
        Unit system of the file: ``"SI"`` (Pa, m/s, K, N), ``"mm-N-s"``
        (MPa, mm/s, K, N), ``"mm-kg-ms"`` (GPa, m/s, K, kN), optionally with
        overrides such as ``"mm-N-s,T=degC"``.
    tol : float, optional
        Largest interpolation error allowed in mu: the grid is refined until
        the solver's interpolation meets it everywhere in the box.  Without
        ``tol``, a box giving a count for every variable is used as it is;
        otherwise the grid is adaptive with tol 1e-3.
    spacing : mapping, optional
        Variable -> ``"lin"`` or ``"log"`` (default: log when min > 0 and
        max/min >= 100, else lin).
    path : str or Path, optional
        Write the file there, atomically; never over the fitted data, the params
        file or a file read in this process (:mod:`frictionlaws.base.outputs`).
    max_rows : int
        Largest table allowed.
    source : str, optional
        How the parameters were obtained (written in the header; default: the
        bound law's :class:`~frictionlaws.law.bound.Source`).
    options : mapping, optional
        Format options (ids of the solver's cards) of ``format``, see
        :data:`~frictionlaws.fe_export.formats.OPTIONS`; the others take their defaults.

    Returns
    -------
    ExportResult
        The text, where it was written, and the error statement.

    Raises
    ------
    InputError
        Unknown format, bad box, a law needing a variable without a range, or
        a format that cannot represent the law (``abaqus-decay``; variables a
        solver does not support).
    """
    _check_format(format, tol)
    bound = _bound(law, params, preset)
    _check_determined(bound)
    _check_path(path, bound, format)
    system = unit_system(units)
    job = _job(bound, format, make_specs(box, system, spacing), system, tol=tol,
               max_rows=max_rows, source=source, options=options)
    written = FORMATS[format].writer(_checked(job, format))
    return _result(job, written, _write(path, written.text, _inputs_of(bound)))


def _checked(job: Job, format: str) -> Job:
    """The job after the checks of its box that come before any writing, with warnings."""
    entry = FORMATS[format]
    job.check_corners(entry.needs_box)
    if entry.needs_box:
        job.domain_warnings()
    if not entry.needs_box or entry.formula_card:
        # tables check their own box while the grid is built
        job.check_formula_box(code=entry.source_code)
    if entry.source_code:
        job.floor_warnings()
    return job


def _check_determined(bound: BoundLaw) -> None:
    """Refuse values a fit could not determine: every mu written from them is arbitrary."""
    if not bound.undetermined:
        return
    names = ", ".join(bound.undetermined)
    raise InputError([
        f"law '{bound.law.id}': the data of {bound.source.describe()} cannot determine "
        f"{names}: their values are one arbitrary point of a flat valley of chi^2, and so "
        "would be the mu written from them outside the measured points; hold them in the "
        "fit (", Argument("fix", f"{bound.undetermined[0]}=VALUE"), ") or fit data that vary "
        "what they act through"])


def _result(job: Job, written: Written, path: str | None) -> ExportResult:
    """What was written, with its error located in the model's units."""
    err = written.error
    error_at = {}
    if err is not None:
        error_at = {k: float(np.asarray(job.units.to_model(k, v)))
                    for k, v in err.where.items()}
    return ExportResult(
        format=job.fmt, text=written.text, path=path, law=job.law.id, units=job.units.name,
        rows=written.rows, exact=written.exact,
        max_error=(0.0 if written.exact else (err.max_abs if err is not None else None)),
        error_at=error_at, rms_error=None if err is None else err.rms,
        warnings=list(job.warnings), summary=list(written.summary),
        details=dict(written.details), grid=written.grid)
