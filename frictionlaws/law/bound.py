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

The classes are defined beside :class:`~frictionlaws.law.Law` (in
:mod:`frictionlaws.law.core`, as each refers to the other); this module adds the ways
to make one that look a law up by name or read a fit result.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any, Protocol

from ..base.errors import InputError
from . import Law
from .core import SOURCE_KINDS, BoundLaw, Source, outside_ranges
from .registry import get_law

__all__ = ["BoundLaw", "Source", "SOURCE_KINDS", "as_bound", "bound_from_result", "freeze",
           "outside_ranges"]


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
    return get_law(law).freeze(values, preset, source=source)


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
        expected = get_law(law)
        if expected.id != bound.law.id:
            raise InputError(f"the parameters are for law '{bound.law.id}', not "
                             f"'{expected.id}'")
    return bound
