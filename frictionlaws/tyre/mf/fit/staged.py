"""Fit the Magic Formula (forces and aligning moment) to tyre test data; write a property file.

The staged fit: :func:`fit_mf` runs the stages (pure-slip forces,
:mod:`~frictionlaws.tyre.mf.fit.pure`; the later stages,
:mod:`~frictionlaws.tyre.mf.fit.stages`) on the rows the data give
(:mod:`~frictionlaws.tyre.mf.fit.rows`), after the checks of the data
(:mod:`~frictionlaws.tyre.mf.fit.checks`) and of the template
(:mod:`~frictionlaws.tyre.mf.fit.template`); the sweep bootstrap is
:mod:`~frictionlaws.tyre.mf.fit.bootstrap`, the result :class:`~.result.MFFit` with its
figure (:mod:`~frictionlaws.tyre.mf.fit.plot`).

:func:`fit_mf` fits the coefficient groups of MF 5.2, 6.1 or 6.2 to measured forces
and aligning moments (:class:`~frictionlaws.tyre.data.table.TyreData`) in stages: the
pure-slip forces F_x0, F_y0 as below, then the combined-slip weighting functions, the
forces refined together on every row, the aligning moment M_z0 and combined M_z
(:mod:`frictionlaws.tyre.mf.fit.stages`).  The pure-slip forces are fitted in three
steps (:mod:`frictionlaws.tyre.mf.fit.pure`):

1. **per-load curves**: at each load (at the nominal pressure and the smallest
   camber measured) a Magic Formula curve ``D sin(C arctan(B x - E (B x -
   arctan(B x)))) + S_V`` with ``x = slip + S_H`` is fitted alone;
2. **load dependence** (regressions of mu, K, E, S_H, S_V of the per-load curves
   on ``dfz``) gives the starting values of the load coefficients; the pressure
   and camber coefficients are then fitted with those held;
3. **global refinement** of every coefficient the data span, on all pure-slip
   points at once (:func:`scipy.optimize.least_squares`); standard errors from
   the Jacobian, ``SE = sqrt(diag(s^2 (J^T J)^-1))``.

Coefficients the data cannot determine (a pressure term with one pressure, a
camber term with one camber, a curvature in load with fewer than three loads,
an asymmetry with one sign of slip, or a direction of the Jacobian with no
information) are left at the template's value and named in the notes; a coefficient along a
direction the data do not inform whose template value would spoil the fit is held
at its fitted value instead (standard error infinite, named in the notes).  The
pure-slip steps start from the rows near pure slip (cross slip within
:data:`~frictionlaws.tyre.mf.fit.stages.ALPHA_PURE` = 1 deg or
:data:`~frictionlaws.tyre.mf.fit.stages.KAPPA_PURE` = 0.01, robust to rig jitter); the
later stages use every row with the combined-slip model at the slips recorded.  The
slip angle enters as tan(alpha), the library's default convention, and the file
written says so.  Data whose slips, angles or loads look like another unit than
declared are refused first (:mod:`frictionlaws.tyre.mf.fit.checks`).

The peak friction coefficient stays within a physical range during the fit, and
data that stop before the peak give a warning (the peak is extrapolated), not a
refusal; see :mod:`frictionlaws.tyre.mf.fit.peak`.
"""


from __future__ import annotations

import math
import time
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ....base.errors import Argument, ExtrapolationWarning, FitError, InputError
from ...data.formats import read_tyre_files
from ...data.table import TyreData
from ..coefficients import fit_bounds
from ..model import MagicFormula
from ..notices import collected
from ..property_file import FITTYP_VERSIONS, PropertyFile
from ..tir import format_tir, read_tir
from .bootstrap import DEFAULT_RESAMPLES, check_can_resample, check_options, sweep_bootstrap
from .checks import repeated_rows
from .peak import FittingModel, peak_message, unreached_peaks
from .pure import direction_errors, fit_direction
from .result import UNCERTAINTIES, MFFit
from .rows import select_direction
from .stages import group_of, later_stages
from .template import build_file, model_from_template, template_file

__all__ = ["fit_mf", "FITTYPS", "BOOTSTRAP_OPTIONS", "refuse_not_applied"]

#: FITTYP -> Magic Formula version (of the property files: one table).
FITTYPS = FITTYP_VERSIONS
#: The options of the sweep bootstrap with their defaults (``uncertainty="sweeps"``).
BOOTSTRAP_OPTIONS: dict[str, Any] = {"resamples": DEFAULT_RESAMPLES, "jobs": 1, "seed": 0,
                                     "sweeps": None}


def fit_mf(data: TyreData | str | Path | Sequence[str | Path], *, fittyp: int = 61,
           template: str | Path | PropertyFile | None = None,
           sign_convention: str | None = None, uncertainty: str = "asymptotic",
           resamples: int | None = None, seed: int | None = None, jobs: int | None = None,
           sweeps: Sequence[Any] | np.ndarray | None = None) -> MFFit:
    """Fit the Magic Formula to tyre test data, stage by stage (module docstring).

    Parameters
    ----------
    data : TyreData, str, Path or sequence of them
        The measurements, or files of any tyre test format (:mod:`frictionlaws.tyre.data`).
    fittyp : {5, 6, 21, 61, 62}
        FITTYP of the file written: 5, 6 or 21 for MF 5.2 / PAC2002, 61 for MF 6.1,
        62 for MF 6.2.
    template : path, PropertyFile or packaged example name, optional
        Property file providing FNOMIN, the nominal pressure, the other sections
        and the values of coefficients the data cannot determine (default: the
        packaged example of the version).
    sign_convention : {"iso", "sae"}, optional
        Axes of the measurement when ``data`` are files (default: each format's; ISO for
        CSV and TYDEX, SAE for raw rig runs); refused with
        :class:`~frictionlaws.tyre.tyre_data.TyreData`, which are in ISO axes already.
    uncertainty : {"asymptotic", "sweeps"}
        How the standard errors are made.  ``"asymptotic"`` (the default, no extra
        cost): from the Jacobian of each stage, ``s^2 (J^T J)^-1``, which assumes
        independent residuals and is too small when a sweep's residuals share an
        offset.  ``"sweeps"``: the sweep bootstrap
        (:mod:`frictionlaws.tyre.mf.fit.bootstrap`), which resamples whole sweeps
        and refits the final stages from the point estimate; it costs about
        ``resamples`` times the final stages.
    resamples, seed, jobs : int, optional
        For ``uncertainty="sweeps"``: resamples (default 100), their seed (default 0)
        and worker processes (default 1; :func:`frictionlaws.parallel.run_parallel`).
    sweeps : array-like, optional
        For ``uncertainty="sweeps"``: a sweep label per row; default: the data's own
        (``data.extra``), else from the row order
        (:func:`~frictionlaws.tyre.mf.fit.bootstrap.find_sweeps`).  These four are refused
        with another ``uncertainty`` (:data:`BOOTSTRAP_OPTIONS`: an option that does not
        apply is refused, on every path).

    Returns
    -------
    MFFit

    Raises
    ------
    InputError
        Unknown FITTYP, unreadable data or template.
    FitError
        Too few pure-slip points.
    """
    given = dict(resamples=resamples, jobs=jobs, seed=seed, sweeps=sweeps)
    with collected() as raised:  # every warning of the fit, once: the file's, JSON's, text's
        fitted = _fitted(data, fittyp, template, sign_convention, uncertainty, given)
    fitted.warnings = raised
    return fitted


def _fitted(data: TyreData | str | Path | Sequence[str | Path], fittyp: int,
            template: str | Path | PropertyFile | None, sign_convention: str | None,
            uncertainty: str, given: dict[str, Any]) -> MFFit:
    """:func:`fit_mf`'s work; its warnings are issued (:func:`fit_mf` collects them)."""
    t0 = time.perf_counter()
    data, boot = _checked_inputs(data, fittyp, sign_convention, uncertainty, given)
    version = FITTYPS[fittyp]
    tpl = template_file(template, version)
    notes = list(data.notes)
    notes.extend(filter(None, [repeated_rows(data)]))
    tpl_coeffs, p_nom, p_fit, mf = model_from_template(tpl, data, version, notes)
    values, stderr, undetermined, stages, errors, warns = _fit_directions(
        mf, data, version, tpl_coeffs, p_fit, notes)
    later = later_stages(mf, data, version, tpl_coeffs, p_fit, values, stderr, fit_bounds())
    values, stderr, undetermined = _with_later(later, undetermined, errors, notes)
    if not values:
        raise FitError(f"{data.source}: nothing could be fitted (no coefficient is "
                       "determined by these rows); no file written")
    notes.extend(_undetermined_notes(undetermined, stderr, tpl_coeffs))
    pf = build_file(tpl, fittyp, values, p_nom, data, notes, mf.fnomin)
    asymptotic = dict(stderr)
    method = UNCERTAINTIES["asymptotic"]
    if uncertainty == "sweeps":
        stderr, method = _bootstrap(mf, data, values, stderr, p_fit, {**boot,
                                                                      "warnings_out": warns})
    fitted = _finish(pf, version, values, stderr, undetermined, errors, stages, data,
                     t0, notes)
    fitted.uncertainty, fitted.stderr_asymptotic = method, asymptotic
    fitted.warnings = warns
    for text in warns:
        warnings.warn(text, ExtrapolationWarning, stacklevel=2)
    return fitted


def refuse_not_applied(data: Any, sign_convention: str | None, uncertainty: str,
                        given: dict[str, Any]) -> None:
    """Refuse options given that do not apply (the one rule of fit-mf's options: an option
    that cannot change the fit is refused, naming it, on every path; the command line calls
    this before it reads anything).

    Parameters
    ----------
    data : TyreData, str or Path
        The data (``sign_convention`` applies to a file only).
    sign_convention : str or None
        As given (None: not given).
    uncertainty : str
        How the standard errors are made.
    given : dict
        ``resamples``, ``jobs``, ``seed``, ``sweeps`` as given (None: not given), in the
        order they are named.

    Raises
    ------
    InputError
        Naming each option that does not apply.
    """
    unused = [k for k, v in given.items() if v is not None]
    if uncertainty != "sweeps" and unused:
        parts: list[str | Argument] = []
        for i, k in enumerate(unused):
            parts += [", " if i else "", Argument(k)]
        raise InputError([*parts, f" {'is' if len(unused) == 1 else 'are'} not used with ",
                          Argument("uncertainty", uncertainty), " (for ",
                          Argument("uncertainty", "sweeps"), " only); remove "
                          f"{'it' if len(unused) == 1 else 'them'}"])
    if isinstance(data, TyreData) and sign_convention is not None:
        raise InputError([Argument("sign_convention", sign_convention), " is not used: it "
                          "applies to a data file read here, and TyreData are in ISO axes "
                          "already (read_tyre_data(path, sign_convention=...) converts); "
                          "remove it"])


def _with_later(later: Any, undetermined: list[str], errors: dict, notes: list[str]
                ) -> tuple[dict[str, float], dict[str, float], list[str]]:
    """The values, standard errors and undetermined coefficients after the later stages
    (their errors and notes added to ``errors`` and ``notes``)."""
    errors.update(later.errors)
    notes.extend(later.notes)
    kept = [k for k in undetermined if k not in later.values]
    return later.values, later.stderr, kept + [k for k in later.undetermined
                                               if k not in undetermined]


def _checked_inputs(data: TyreData | str | Path | Sequence[str | Path], fittyp: int,
                    sign_convention: str | None, uncertainty: str, given: dict[str, Any]
                    ) -> tuple[TyreData, dict[str, Any]]:
    """The data (read when a file) and the bootstrap's options (``given``, with their
    defaults), after the options are checked (before any fit)."""
    refuse_not_applied(data, sign_convention, uncertainty, given)
    boot = {k: BOOTSTRAP_OPTIONS[k] if v is None else v for k, v in given.items()}
    if uncertainty not in UNCERTAINTIES:
        raise InputError(f"uncertainty {uncertainty!r} is not known; expected one of "
                         f"{', '.join(UNCERTAINTIES)}")
    if fittyp not in FITTYPS:
        raise InputError(f"FITTYP {fittyp!r} is not fitted here; expected one of "
                         f"{', '.join(str(k) for k in FITTYPS)}")
    if not isinstance(data, TyreData):
        files = [data] if isinstance(data, (str, Path)) else list(data)
        data, _ = read_tyre_files(files, sign_convention=sign_convention)
    if boot["sweeps"] is None and "sweep" in data.extra:
        boot["sweeps"] = data.extra["sweep"]
    if uncertainty == "sweeps":
        check_options(boot["resamples"], boot["jobs"], boot["sweeps"], len(data))
        check_can_resample(data, boot["sweeps"])  # resamples that cannot vary: refused
    return data, boot


def _undetermined_notes(undetermined: list[str], stderr: dict[str, float],
                        template: dict[str, float]) -> list[str]:
    """The notes naming the coefficients left at the template, those the template lacks
    too (not written: their declared default applies) and those held."""
    out = []
    kept = [k for k in undetermined if k in template]
    absent = [k for k in undetermined if k not in template]
    if kept:
        out.append("not determined by the data, left at the template's value: "
                   + ", ".join(kept))
    if absent:
        out.append("not determined by the data and not in the template: not written, so "
                   "their declared default applies: " + ", ".join(absent))
    held = [k for k, se in stderr.items() if se == math.inf]
    if held:
        out.append("not determined by the data, and the template's value does not suit "
                   "them: held at the fitted value (standard error infinite): "
                   + ", ".join(held))
    return out


def _bootstrap(mf: FittingModel, data: TyreData, values: dict[str, float],
               stderr: dict[str, float], p_fit: float | None, options: dict[str, Any]
               ) -> tuple[dict[str, float], str]:
    """The sweep bootstrap's standard errors of every coefficient with a finite one (the
    others keep theirs) and its description."""
    groups: dict[str, list[str]] = {}
    for k in values:
        if math.isfinite(stderr.get(k, math.inf)):
            groups.setdefault(group_of(k), []).append(k)
    boot, method = sweep_bootstrap(mf, data, groups, p_fit, fit_bounds(), **options)
    return {**stderr, **boot}, method


def _fit_directions(mf: FittingModel, data: TyreData, version: str,
                    template: dict[str, float], p_fit: float | None, notes: list[str]
                    ) -> tuple[dict[str, float], dict[str, float], list[str], dict, dict,
                               list[str]]:
    """Fit F_x0 then F_y0: values, standard errors, undetermined coefficients, stage-1
    curves, errors and warnings (peaks the data do not reach)."""
    values: dict[str, float] = {}
    stderr: dict[str, float] = {}
    undetermined: list[str] = []
    stages: dict[str, list[dict[str, float]]] = {}
    errors: dict[str, dict[str, float]] = {}
    warns: list[str] = []
    for name in ("x", "y"):
        d = select_direction(data, name, p_fit)
        if d is None:
            notes.append(f"no pure-slip F{name}0 points: the F{name}0 coefficients are the "
                         "template's")
            continue
        v, se, und, curves = fit_direction(mf, d, data, version, template)
        values.update(v)
        stderr.update(se)
        undetermined.extend(und)
        stages[name] = curves
        errors[name] = direction_errors(mf, d)
        ref = d.reference
        unreached = unreached_peaks(mf, name, d.slip[ref], d.fz[ref], d.gamma[ref],
                                    d.dpi[ref], d.load_labels[ref], d.loads)
        if unreached:
            warns.append(peak_message(name, unreached, [k for k in v if k[:2] == "PD"]))
    return values, stderr, undetermined, stages, errors, warns


def _finish(pf: PropertyFile, version: str, values: dict[str, float],
            stderr: dict[str, float], undetermined: list[str], errors: dict, stages: dict,
            data: TyreData, t0: float, notes: list[str]) -> MFFit:
    """Check that the written text reads back as the fitted model; assemble the result."""
    text = format_tir(pf)
    back = read_tir(text, source="<fitted .tir>")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        model = MagicFormula.from_property_file(back)
    if model.version != version:
        raise FitError(f"the written file reads back as MF {model.version}, not {version}")
    return MFFit(version=version, property_file=pf, model=model, values=values,
                 stderr=stderr, undetermined=undetermined, errors=errors, stages=stages,
                 data=data, seconds=time.perf_counter() - t0, notes=notes)
