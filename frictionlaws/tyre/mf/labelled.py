"""xarray support of :class:`~frictionlaws.tyre.mf.model.MagicFormula` methods.

:func:`labelled` lets a method take :class:`xarray.DataArray` inputs and keep their
dimensions and coordinates; plain arrays and scalars take the fast path unchanged.
:func:`is_labelled` and :func:`refuse_plain` are the checks
:func:`~frictionlaws.tyre.mf.outputs.labelled_steady_state` shares.
"""

from __future__ import annotations

import functools
import inspect
from collections.abc import Callable
from typing import Any, TypeVar

import numpy as np

from ...base.errors import InputError
from ...law.evaluation import is_labelled

__all__ = ["labelled", "is_labelled", "refuse_plain"]

_F = TypeVar("_F", bound=Callable[..., Any])


def labelled(arrays: tuple[str, ...], *outputs: tuple[str, str, str]) -> Callable[[_F], _F]:
    """Let a method take :class:`xarray.DataArray` inputs and keep their dimensions.

    ``arrays`` are the method's array arguments; ``outputs`` give each result's
    (name, unit, long name).  When any of those arguments is a DataArray, the
    method runs through :func:`xarray.apply_ufunc` on the bare arrays: the
    result is a DataArray (a tuple of them for several outputs) with the
    broadcast dimensions and the coordinates of the inputs.  Otherwise the method
    runs as it is.
    """
    def wrap(method: _F) -> _F:
        signature = inspect.signature(method)

        @functools.wraps(method)
        def inner(self: Any, *args: Any, **kwargs: Any) -> Any:
            if not any(map(is_labelled, (*args, *kwargs.values()))):
                return method(self, *args, **kwargs)  # the fast path: no DataArray
            bound = signature.bind(self, *args, **kwargs)
            bound.apply_defaults()
            values = bound.arguments
            labelled = [n for n in arrays if is_labelled(values[n])]
            if not labelled:
                return method(self, *args, **kwargs)
            return _apply_labelled(method, self, values, arrays, labelled, outputs)

        return inner  # type: ignore[return-value]

    return wrap


def refuse_plain(values: dict[str, Any] | Any, labelled: list[str],
                 arrays: tuple[str, ...] | None = None) -> None:
    """Refuse plain arrays (not scalars) among ``arrays`` of ``values`` beside the
    DataArrays ``labelled``: they have no dimension names to broadcast by."""
    names = tuple(values) if arrays is None else arrays
    plain = [n for n in names if n not in labelled and values[n] is not None
             and np.ndim(values[n]) > 0]
    if plain:
        raise InputError(f"{', '.join(plain)} must be DataArrays too when "
                         f"{', '.join(labelled)} are (or scalars): plain arrays have no "
                         "dimension names to broadcast by")


def _apply_labelled(method: Callable[..., Any], mf: Any, values: dict[str, Any],
                    arrays: tuple[str, ...], labelled: list[str],
                    outputs: tuple[tuple[str, str, str], ...]) -> Any:
    """``method`` evaluated by :func:`xarray.apply_ufunc` over its DataArray arguments."""
    import xarray as xr

    refuse_plain(values, labelled, arrays)

    def bare(*data: Any) -> Any:
        kw = {k: v for k, v in values.items() if k != "self"}
        kw.update(zip(labelled, data, strict=True))
        shape = np.broadcast_shapes(*(np.shape(x) for x in data))
        out = method(mf, **kw)
        if len(outputs) == 1:
            return np.broadcast_to(np.asarray(out, dtype=float), shape).copy()
        return tuple(np.broadcast_to(np.asarray(o, dtype=float), shape).copy() for o in out)

    result = xr.apply_ufunc(bare, *(values[n] for n in labelled), dask="allowed",
                            output_core_dims=[[] for _ in outputs])
    named = [r.rename(name).assign_attrs(units=unit, long_name=long)
             for r, (name, unit, long) in zip(
                 result if len(outputs) > 1 else (result,), outputs, strict=True)]
    return named[0] if len(outputs) == 1 else tuple(named)
