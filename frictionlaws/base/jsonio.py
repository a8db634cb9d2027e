"""The one JSON encoder of frictionlaws: strict JSON, ``null`` for non-finite numbers.

Every JSON frictionlaws writes (``--json`` output, saved fit results, reports,
export tables) goes through :func:`dumps`, so a strict parser (one that refuses
``NaN`` and ``Infinity``) reads all of it.  Infinite *bounds* are the one place
where infinity carries meaning; they are written by :func:`bound_to_json` as
the strings ``"inf"``/``"-inf"`` and read back by :func:`bound_from_json`.
"""

from __future__ import annotations

import dataclasses
import json
import math
from collections.abc import Mapping
from pathlib import PurePath
from typing import Any

import numpy as np

from .limits import check_nesting, nesting_error

__all__ = ["to_jsonable", "dumps", "loads", "bound_to_json", "bound_from_json"]


def _number(x: float) -> float | None:
    return x if math.isfinite(x) else None


def to_jsonable(obj: Any) -> Any:
    """``obj`` as plain JSON types: non-finite floats become ``None``.

    Handles dicts (keys as strings), lists/tuples/sets, numpy scalars and
    arrays, dataclasses, paths and objects with a ``to_dict()`` method.
    """
    if obj is None or isinstance(obj, (str, bool)):
        return obj
    if isinstance(obj, (bool, np.bool_)):
        return bool(obj)
    if isinstance(obj, (int, np.integer)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        return _number(float(obj))
    if isinstance(obj, Mapping):
        return {str(k): to_jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple, set, frozenset)):
        return [to_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return [to_jsonable(v) for v in obj.tolist()]
    if isinstance(obj, PurePath):
        return str(obj)
    if hasattr(obj, "to_dict") and callable(obj.to_dict):
        return to_jsonable(obj.to_dict())
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return to_jsonable(dataclasses.asdict(obj))
    return str(obj)


def dumps(obj: Any, *, indent: int | None = 2) -> str:
    """Strict JSON text of ``obj`` (see :func:`to_jsonable`); never ``NaN``/``Infinity``."""
    return json.dumps(to_jsonable(obj), indent=indent, allow_nan=False)


def bound_to_json(x: float) -> float | str:
    """A parameter bound for JSON: ``"inf"``/``"-inf"`` for infinite bounds."""
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return float(x)


def bound_from_json(x: Any) -> float:
    """Inverse of :func:`bound_to_json` (``None`` is read as unbounded is *not* accepted)."""
    if isinstance(x, str) and x in ("inf", "-inf", "+inf"):
        return math.inf if not x.startswith("-") else -math.inf
    if isinstance(x, bool) or not isinstance(x, (int, float)):
        raise ValueError(f"a bound must be a number or 'inf'/'-inf', got {x!r}")
    return float(x)


def _no_duplicates(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, value in pairs:
        if key in out:
            raise ValueError(f"key '{key}' is given twice in one object; keep one")
        out[key] = value
    return out


def _no_constant(name: str) -> Any:
    raise ValueError(f"{name} is not a JSON number (strict JSON has no NaN or Infinity; "
                     "write null)")


#: Most digits of a JSON integer read (a count, a seed, a format version).
_MAX_INT_DIGITS = 40


def _finite_float(text: str) -> float:
    value = float(text)
    if not math.isfinite(value):
        raise ValueError(f"the number {text[:30]} overflows (beyond 1.8e308)")
    return value


def _bounded_int(text: str) -> int:
    if len(text.lstrip("-")) > _MAX_INT_DIGITS:
        raise ValueError(f"an integer of {len(text.lstrip('-'))} digits is beyond the limit "
                         f"of {_MAX_INT_DIGITS}")
    return int(text)


def loads(text: str) -> Any:
    """Parse strict JSON: the one JSON reader of input files.

    A key given twice in one object, ``NaN``/``Infinity``, a number that overflows
    (``1e999``) and an integer of more than 40 digits are refused (Python's parser keeps
    the last duplicate silently, accepts the constants and reads ``1e999`` as infinity).

    Parameters
    ----------
    text : str
        The JSON text.

    Returns
    -------
    Any
        The decoded document.

    Raises
    ------
    ValueError
        ``json.JSONDecodeError`` (with line and column), a duplicate key or constant, or
        nesting too deep for the parser.
    """
    try:
        doc = json.loads(text, object_pairs_hook=_no_duplicates, parse_constant=_no_constant,
                         parse_float=_finite_float, parse_int=_bounded_int)
    except RecursionError:  # e.g. 100000 nested arrays: not a parameter file
        raise nesting_error("JSON document") from None
    check_nesting(doc, "JSON document")
    return doc
