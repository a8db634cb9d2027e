"""A law bound to parameter values: what a model, an export or a tyre needs of a law.

A :class:`BoundLaw` is to a :class:`~frictionlaws.law.Law` what a frozen
distribution is to a distribution family: the law, a complete set of parameter
and setting values (checked against their bounds once, when bound), where the
values came from (:class:`Source`: a preset, given values, a parameters file, a
fit to a dataset) and, when they come from a fit, the range of each variable the
fit saw, so that evaluation outside it warns of extrapolation.

Make one with :meth:`Law.freeze <frictionlaws.law.Law.freeze>`
(``get_law("thirion").freeze(preset="...")``), from a fit with
:attr:`FitResult.bound <frictionlaws.fitting.FitResult.bound>` (or
:func:`bound_from_result`), or from anything that carries a law and values with
:func:`as_bound`.  It evaluates like the law (vectorised, the same checks of the
variables and of mu), pickles (the law by its registered id) and is accepted by
:func:`~frictionlaws.fe_export.export` and
:class:`~frictionlaws.tyre.brush.BrushModel`.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np

from .errors import ExtrapolationWarning, InputError
from .law import VARIABLES, Law

__all__ = ["BoundLaw", "Source", "as_bound", "bound_from_result", "freeze", "outside_ranges"]

#: The kinds of :class:`Source`.
SOURCE_KINDS = ("values", "file", "fit")


@dataclass(frozen=True)
class Source:
    """Where the values of a :class:`BoundLaw` came from.

    Parameters
    ----------
    kind : {"values", "file", "fit"}
        ``values``: a preset and/or values given by the caller (or the defaults);
        ``file``: a parameters file; ``fit``: a fit to a dataset.
    preset : str, optional
        The preset used (``kind="values"``).
    given : tuple of str
        Names of the values given explicitly (over the preset or defaults).
    file : str, optional
        The parameters file (``kind="file"``).
    dataset : str, optional
        The dataset fitted (``kind="fit"``).
    detail : str
        A short statement about the origin (a fit's size and quality).
    data_file : str, optional
        The data file fitted, when known (``kind="fit"``): no output replaces it.
    """

    kind: str = "values"
    preset: str | None = None
    given: tuple[str, ...] = ()
    file: str | None = None
    dataset: str | None = None
    detail: str = ""
    data_file: str | None = field(default=None, compare=False)

    def __post_init__(self) -> None:
        if self.kind not in SOURCE_KINDS:
            raise InputError(f"source kind must be one of {', '.join(SOURCE_KINDS)}, "
                             f"got {self.kind!r}", option="source")

    def describe(self) -> str:
        """One line: ``preset 'x' with given values``, ``file fit.json``, ``fit to D (...)``."""
        if self.kind == "file":
            text = f"file {self.file}"
        elif self.kind == "fit":
            text = f"fit to {self.dataset}" if self.dataset else "fit result"
        else:
            parts = ([f"preset '{self.preset}'"] if self.preset else []) + (
                ["given values"] if self.given else [])
            text = " with ".join(parts) or "law defaults"
        return f"{text} ({self.detail})" if self.detail else text

    def to_dict(self) -> dict[str, Any]:
        """The source as JSON-able values."""
        return {"kind": self.kind, "preset": self.preset, "given": list(self.given),
                "file": self.file, "dataset": self.dataset, "detail": self.detail,
                "text": self.describe()}


@dataclass(frozen=True, eq=False)
class BoundLaw:
    """A law with fixed, checked parameter values, their source and fitted ranges.

    Build it with :func:`freeze`, :meth:`Law.freeze <frictionlaws.law.Law.freeze>`,
    :func:`bound_from_result` or :func:`as_bound` rather than directly; the
    constructor checks ``values`` (complete, finite, inside their bounds,
    admissible) with :meth:`Law.check_values <frictionlaws.law.Law.check_values>`.

    Parameters
    ----------
    law : Law
        The law.
    values : mapping
        Every parameter and setting of the law, SI.
    source : Source
        Where the values came from.
    fitted_ranges : mapping
        Variable -> (min, max) in SI of the data the values were fitted to
        (empty when not fitted).
    stderr : mapping
        Parameter -> standard error from a fit (only those a fit determined).
    fixed : tuple of str
        Parameters a fit held fixed.
    notes : tuple of str
        Warnings of the fit the values came from.
    converged : bool
        False when the values come from a fit that did not converge.
    undetermined : tuple of str
        Parameters the fit's data could not determine (their values are one arbitrary
        point of a flat valley of chi^2); an FE export refuses them.
    """

    law: Law
    values: dict[str, float]
    source: Source = field(default_factory=Source)
    fitted_ranges: dict[str, tuple[float, float]] = field(default_factory=dict)
    stderr: dict[str, float] = field(default_factory=dict)
    fixed: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()
    converged: bool = True
    undetermined: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if not isinstance(self.law, Law):
            raise InputError(f"law must be a Law, got {type(self.law).__name__}")
        values = {k: float(v) for k, v in dict(self.values).items()}
        expected = set(self.law.param_names) | {s.name for s in self.law.settings}
        missing, unknown = expected - set(values), set(values) - expected
        if missing or unknown:
            raise InputError(
                f"law '{self.law.id}': bound values must be every parameter and setting"
                + (f"; missing {', '.join(sorted(missing))}" if missing else "")
                + (f"; unknown {', '.join(sorted(unknown))}" if unknown else ""))
        self.law.check_values(values)
        object.__setattr__(self, "values", values)
        object.__setattr__(self, "fitted_ranges", _ranges(self.fitted_ranges))
        object.__setattr__(self, "stderr", {k: float(v) for k, v in self.stderr.items()})
        object.__setattr__(self, "fixed", tuple(self.fixed))
        object.__setattr__(self, "notes", tuple(self.notes))
        object.__setattr__(self, "undetermined", tuple(self.undetermined))

    # ------------------------------------------------------------ evaluation
    @property
    def variables(self) -> tuple[str, ...]:
        """The law's variables."""
        return self.law.variables

    @property
    def param_values(self) -> dict[str, float]:
        """Parameter values only (no settings)."""
        return {k: self.values[k] for k in self.law.param_names}

    def __call__(self, *, warn: bool = True, **variables: Any) -> Any:
        """Evaluate mu at the variables (SI, by keyword), as the law does.

        The variables are checked as by calling the law (non-finite values, a
        negative pressure, a slip ratio outside the domain...), and so is mu
        (finite; not negative for a sliding law).  With ``warn``, an
        :class:`~frictionlaws.errors.ExtrapolationWarning` says when a
        variable leaves the fitted range.

        Returns
        -------
        float or numpy.ndarray or pandas.Series
            As :meth:`Law.evaluate <frictionlaws.law.Law.evaluate>`.
        """
        variables = self.law.si_variables(variables)
        if warn:
            msgs = self.extrapolation(variables)
            if msgs:
                warnings.warn(f"law '{self.law.id}': " + "; ".join(msgs), ExtrapolationWarning,
                              stacklevel=2)
        return self.law.evaluate_checked(variables, self.values)

    def extrapolation(self, variables: Mapping[str, Any]) -> list[str]:
        """List the variables outside the range the values were fitted on.

        Parameters
        ----------
        variables : mapping
            Variable name -> values (SI).

        Returns
        -------
        list of str
            One message per variable outside its fitted range (none when not fitted).
        """
        return outside_ranges(self.law, self.fitted_ranges, variables)

    def bind(self) -> Any:
        """Return the law as a plain vectorised function of its variables.

        Returns
        -------
        callable
            :meth:`Law.bind <frictionlaws.law.Law.bind>` at these values: no checks,
            no warnings; variables positionally in :attr:`variables` order.
        """
        return self.law.bind(self.values)

    def derived(self) -> dict[str, float]:
        """Evaluate the law's derived quantities at these values.

        Returns
        -------
        dict
            Derived quantity name -> value (in its declared unit).
        """
        return self.law.derived_values(self.values)

    # ------------------------------------------------------------------ misc
    def to_dict(self) -> dict[str, Any]:
        """Describe the bound law as JSON-able values (SI, with units).

        Returns
        -------
        dict
            ``law``, ``values`` (value, unit, stderr), ``source``, ``fitted_ranges``,
            ``fixed``, ``notes``, ``converged`` and ``undetermined``.
        """
        units = {p.name: p.unit for p in self.law.params}
        units.update({s.name: s.unit for s in self.law.settings})
        return {"law": self.law.id,
                "values": {k: {"value": v, "unit": units.get(k, ""),
                               "stderr": self.stderr.get(k)} for k, v in self.values.items()},
                "source": self.source.to_dict(),
                "fitted_ranges": {k: {"min": lo, "max": hi, "unit": VARIABLES[k].unit}
                                  for k, (lo, hi) in self.fitted_ranges.items()},
                "fixed": list(self.fixed), "notes": list(self.notes),
                "converged": self.converged, "undetermined": list(self.undetermined)}

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, BoundLaw):
            return NotImplemented
        return (self.law is other.law and self.values == other.values
                and self.source == other.source and self.fitted_ranges == other.fitted_ranges)

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        values = ", ".join(f"{k}={v:.6g}" for k, v in self.param_values.items())
        extra = ""
        if set(self.fitted_ranges) & set(self.law.variables):
            extra = "; fitted on " + ", ".join(
                f"{k} {lo:.4g}..{hi:.4g} {VARIABLES[k].unit}".rstrip()
                for k, (lo, hi) in self.fitted_ranges.items() if k in self.law.variables)
        return f"<BoundLaw {self.law.id}({values}); from {self.source.describe()}{extra}>"


def outside_ranges(law: Law, ranges: Mapping[str, Any], variables: Mapping[str, Any]
                   ) -> list[str]:
    """Messages for the variables of ``law`` outside their fitted ``ranges`` (SI)."""
    msgs = []
    for k, (lo, hi) in ranges.items():
        if k in variables and k in law.variables:
            x = np.asarray(variables[k], float)
            if x.size and (np.min(x) < lo * (1 - 1e-9) - 1e-300
                           or np.max(x) > hi * (1 + 1e-9)):
                msgs.append(f"{k} outside the fitted range {lo:g}..{hi:g} "
                            f"{VARIABLES[k].unit}: extrapolation")
    return msgs


def _ranges(ranges: Mapping[str, Any]) -> dict[str, tuple[float, float]]:
    out = {}
    for k, r in dict(ranges or {}).items():
        if k not in VARIABLES:
            raise InputError(f"fitted range of unknown variable '{k}' (variables: "
                             f"{', '.join(VARIABLES)})")
        lo, hi = (float(x) for x in r)
        if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
            raise InputError(f"fitted range of {k} must be finite with min <= max, got {r!r}")
        out[k] = (lo, hi)
    return out


def freeze(law: Law | str, values: Mapping[str, float] | None = None, *,
           preset: str | None = None, source: Source | str | None = None) -> BoundLaw:
    """Bind ``law`` to a preset and/or values (the rest from defaults).

    Parameters
    ----------
    law : Law or str
        The law or its id/alias.
    values : mapping, optional
        Parameter (or setting) values in SI; they override the preset.
    preset : str, optional
        A named preset of the law.
    source : Source or str, optional
        Where the values came from; a string names a parameters file.  By
        default the preset and the names given.

    Returns
    -------
    BoundLaw

    Raises
    ------
    InputError
        An unknown law, preset or name, a missing parameter, or a value outside
        its bounds.
    """
    from .registry import get_law

    law_obj = get_law(law)
    resolved = law_obj.resolve(values, preset)
    if isinstance(source, str):
        source = Source("file", file=source)
    if source is None:
        source = Source("values", preset=preset, given=tuple(values or ()))
    return BoundLaw(law_obj, resolved, source)


class FitLike(Protocol):
    """What :func:`bound_from_result` reads of a fit result (a
    :class:`~frictionlaws.fitting.FitResult`), named here so that this module does not
    import the fitting package, which imports it."""

    @property
    def law(self) -> Law: ...  # read-only members: a dataclass field satisfies them
    @property
    def values(self) -> Mapping[str, float]: ...
    @property
    def params(self) -> Mapping[str, Any]: ...
    @property
    def metrics(self) -> Mapping[str, Any]: ...
    @property
    def data(self) -> Any: ...
    @property
    def warnings(self) -> Sequence[str]: ...
    @property
    def success(self) -> bool: ...
    @property
    def non_identifiable(self) -> Sequence[str]: ...


def bound_from_result(result: FitLike, source: Source | None = None, *,
                      dataset: str | None = None) -> BoundLaw:
    """The values of a fit result bound to its law, with the fitted data's ranges.

    Parameters
    ----------
    result : FitResult
        A fit (or a result read by :func:`~frictionlaws.fitting.load_result`).
    source : Source, optional
        Default: a fit to the result's dataset, with its size, R^2 and RMSE.
    dataset : str, optional
        How to name the dataset in the default source (default: the result's).

    Returns
    -------
    BoundLaw
    """
    data = result.data if isinstance(result.data, Mapping) else {}
    if source is None:
        m = result.metrics
        detail = ", ".join(
            f"{name} = {fmt.format(m[key])}" for name, key, fmt in
            (("n", "n", "{}"), ("R^2", "r2", "{:.4g}"), ("rmse", "rmse", "{:.3g}"))
            if isinstance(m.get(key), (int, float)) and math.isfinite(m[key]))
        source = Source("fit", dataset=dataset or data.get("name") or data.get("source"),
                        detail=detail, data_file=data.get("source") or None)
    return BoundLaw(
        result.law, dict(result.values), source, fitted_ranges=data.get("ranges") or {},
        stderr={k: p.stderr for k, p in result.params.items() if p.stderr is not None},
        fixed=tuple(k for k, p in result.params.items() if p.fixed),
        notes=tuple(result.warnings), converged=bool(result.success),
        undetermined=tuple(result.non_identifiable))


def as_bound(obj: Any, *, law: Law | str | None = None) -> BoundLaw:
    """A :class:`BoundLaw` from a bound law or a fit result (checked against ``law``).

    Parameters
    ----------
    obj : BoundLaw or FitResult
        What to bind.
    law : Law or str, optional
        The law the caller expects: an error when ``obj`` is of another law.

    Raises
    ------
    InputError
        When ``obj`` is neither, or of another law than ``law``.
    """
    if isinstance(obj, BoundLaw):
        bound = obj
    elif isinstance(getattr(obj, "law", None), Law) and hasattr(obj, "params") \
            and hasattr(obj, "metrics"):
        bound = bound_from_result(obj)
    else:
        raise InputError(f"expected a BoundLaw or a fit result, got {type(obj).__name__}")
    if law is not None:
        from .registry import get_law

        expected = get_law(law)
        if expected.id != bound.law.id:
            raise InputError(f"the parameters are for law '{bound.law.id}', not "
                             f"'{expected.id}'")
    return bound
