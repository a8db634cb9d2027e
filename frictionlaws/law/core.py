"""The :class:`Law` users build and the registry holds, and a law bound to values.

:class:`Law` is assembled from its rooms: the declaration and its parameters
(:mod:`~frictionlaws.law.parameters`), the checks of its variables, floors and domain
(:mod:`~frictionlaws.law.domain`), evaluation (:mod:`~frictionlaws.law.evaluation`) and
the formula as text (:mod:`~frictionlaws.law.text`); here it gains what hands it on,
the frozen form (:meth:`Law.freeze`), the lmfit model and Jupyter's HTML
(:mod:`~frictionlaws.law.interop`) and pickling by registered id.

:class:`BoundLaw` is to a law what a frozen distribution is to a distribution family
(:mod:`frictionlaws.law.bound` has the ways to make one: by law id, from a fit result); it is
defined beside :class:`Law` because each refers to the other.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..base.errors import ExtrapolationWarning, InputError
from .declaration import VARIABLES
from .evaluation import LawEvaluation
from .interop import law_html, lmfit_model
from .text import LawText

__all__ = ["Law", "BoundLaw", "Source", "SOURCE_KINDS", "outside_ranges", "set_lookup"]


@dataclass(eq=False)
class Law(LawEvaluation, LawText):
    """One friction law, declared once.

    Parameters
    ----------
    id : str
        Registry id (lower case, hyphenated), e.g. ``"thirion"``.
    title : str
        Human name, e.g. ``"Thirion (pressure saturation)"``.
    family : {"sliding", "slip"}
        Sliding-velocity laws (tribometer, rubber) or slip-ratio laws (tyre).
    variables : tuple of str
        Variables the formula uses, keys of :data:`VARIABLES`.
    params : tuple of Param
        Fitted parameters, in formula order.
    formula : callable
        ``formula(m, **kw)`` with ``m`` a math namespace and ``kw`` the
        variables, parameters and settings by name.
    settings : tuple of Setting
        Fixed reference scales.
    floors : dict
        Variable name -> floor value applied before the formula (``v`` is also
        taken as ``|v|``).
    presets : dict
        Preset name -> parameter dict.
    domain : dict
        Variable name -> (low, high) in SI where the law is valid or was
        measured; outside it the law is an extrapolation.
    typical : dict
        Variable name -> (low, high) in SI: the range to plot or tabulate by
        default (falls back to the domain, then to :data:`VARIABLES`).
    references : tuple of str
        Bibliographic references.
    evidence : str
        Evidence tag(s), e.g. ``"C"`` or ``"S, I"`` (see ``laws.md``).
    guess : callable, optional
        ``guess(data) -> dict`` returning initial values from a mapping with
        ``"mu"`` and the variables as numpy arrays.
    derived : tuple of Derived
        Derived quantities.
    admissible : callable, optional
        ``admissible(params) -> str | None``: a message when a parameter set is
        not admissible (e.g. a denominator that can vanish).
    linear : bool
        True when the law is linear in its parameters (closed-form fit).
    aliases : tuple of str
        Other names the registry accepts.
    optional_variables : dict
        Variable name -> (parameter name, neutral value): the variable may be
        left out when that parameter has its neutral value, where the variable
        drops out of the formula (Burckhardt's vehicle speed ``v`` with
        ``c4 = 0``).  Evaluation without it, fits to data without it (the
        parameter is then fixed at its neutral value), comparison and export
        follow from this one entry.
    variable_meanings : dict
        Variable name -> what the variable is *in this law* when it differs
        from the generic meaning in :data:`VARIABLES` (Burckhardt's ``v`` is the
        vehicle speed, not the sliding velocity).
    strict_domain : bool
        The law means nothing outside :attr:`domain` (a polynomial valid only over
        its measured box, a pre-peak slip law): ``law(...)`` refuses variables outside
        it, fits and exports say so.  Otherwise the domain only marks extrapolation.
    description : str
        A paragraph shown by ``show`` and the docs.
    notes : str
        Caveats and traps.
    """

    def freeze(self, values: Mapping[str, float] | None = None, preset: str | None = None,
               *, source: Source | str | None = None) -> BoundLaw:
        """Bind this law to a preset and/or values, like a frozen scipy distribution.

        Parameters
        ----------
        values : mapping, optional
            Parameter (or setting) values in SI, over the preset.
        preset : str, optional
            A named preset of the law.
        source : Source or str, optional
            Where the values came from; a string names a parameters file.  By default
            the preset and the names given.

        Returns
        -------
        BoundLaw
            E.g. ``law.freeze(preset="x")(p=1e5)``.
        """
        resolved = self.resolve(values, preset)
        if isinstance(source, str):
            source = Source("file", file=source)
        if source is None:
            source = Source("values", preset=preset, given=tuple(values or ()))
        return BoundLaw(self, resolved, source)

    def __repr__(self) -> str:
        return f"<Law {self.id!r}: {self.title}>"

    def __reduce__(self) -> tuple[Any, tuple[str]]:
        """Pickle a registered law by its id (formulas need not be picklable)."""
        lookup = _LOOKUP.get("law")
        try:
            registered = lookup(self.id) if lookup is not None else None
        except InputError:
            registered = None
        if lookup is None or registered is not self:
            raise TypeError(f"law '{self.id}' is not registered: register it to pickle it")
        return (lookup, (self.id,))

    def _repr_html_(self) -> str:
        return law_html(self)

    def lmfit_model(self, values: Mapping[str, float] | None = None) -> Any:
        """Return the law as an :class:`lmfit.Model`.

        See :func:`frictionlaws.law.interop.lmfit_model`.

        Parameters
        ----------
        values : mapping, optional
            Start values (defaults: the declared ones).

        Returns
        -------
        lmfit.Model
            The model with the declared bounds as parameter hints.
        """
        return lmfit_model(self, values=values)


#: How a law id is looked up again (set by :mod:`frictionlaws.law.registry` when it loads,
#: so that this module does not import the registry).
_LOOKUP: dict[str, Callable[[str], Law]] = {}


def set_lookup(lookup: Callable[[str], Law]) -> None:
    """Install the function that finds a registered law by id (for pickling)."""
    _LOOKUP["law"] = lookup


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

    Build it with :meth:`Law.freeze`, :func:`~frictionlaws.law.bound.freeze`,
    :func:`~frictionlaws.law.bound.bound_from_result` or :func:`~frictionlaws.law.bound.as_bound`
    rather than directly; the constructor checks ``values`` (complete, finite, inside
    their bounds, admissible) with :meth:`Law.check_values <frictionlaws.law.Law.check_values>`.

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
        :class:`~frictionlaws.base.errors.ExtrapolationWarning` says when a
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
