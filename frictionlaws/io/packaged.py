"""Packaged datasets and the one loader: :func:`load_dataset` for a packaged name, a file, a
frame or a mapping, :func:`list_datasets`, :func:`datasets_dir`.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..base.errors import InputError
from ..base.sanitize import split_lines

if TYPE_CHECKING:  # pandas is imported where a DataFrame is made or asked for
    import pandas as pd

from importlib import resources

from .building import _is_frame
from .columns import parse_mapping, parse_units
from .dataset import Dataset, _build
from .reading import Table, _table_from_frame, read_table

__all__ = ["datasets_dir", "list_datasets", "load_dataset"]


_PACKAGED_PREFIX = "packaged:"


def datasets_dir() -> Any:
    """The packaged datasets directory (an importlib.resources Traversable).

    The installed package ships them as ``frictionlaws._datasets``; in a
    source checkout (tests run from the clone) they are the top-level
    ``datasets/`` folder beside the package.
    """
    try:
        return resources.files("frictionlaws._datasets")
    except ModuleNotFoundError:  # a source checkout not (re)installed
        here = Path(__file__).resolve().parents[2] / "datasets"
        return here


def _packaged_names() -> list[str]:
    try:
        base = datasets_dir()
        return sorted(p.name[:-4] for p in base.iterdir() if p.name.endswith(".csv"))
    except (OSError, FileNotFoundError):  # pragma: no cover - broken install
        return []


def _header_info(text: str) -> tuple[str, str, int]:
    """Title (first comment line), provenance (all comment lines), data rows."""
    comments: list[str] = []
    count = -1
    for line in split_lines(text):
        s = line.strip()
        if s.startswith("#"):
            comments.append(s[2:] if s[1:2] == " " else s[1:])
        elif s:
            count += 1
    title = comments[0] if comments else ""
    return title, "\n".join(comments), max(count, 0)


def list_datasets() -> list[dict[str, Any]]:
    """List the packaged datasets.

    Returns
    -------
    list of dict
        One dict per packaged dataset, by name: ``name`` (what
        :func:`load_dataset` accepts), ``title`` (the first ``#`` line of the
        file), ``rows`` (the number of data lines) and ``provenance`` (the whole
        ``#`` comment block).
    """
    base = datasets_dir()
    out = []
    for name in _packaged_names():
        text = (base / f"{name}.csv").read_text(encoding="utf-8-sig")
        title, prov, rows = _header_info(text)
        out.append({"name": name, "title": title, "rows": rows, "provenance": prov})
    return out


# --------------------------------------------------------------------------- entry point
def load_dataset(
    name_or_path: str | os.PathLike[str] | pd.DataFrame | Mapping[str, Any] | Dataset,
    *,
    mapping: Mapping[str, str] | str | None = None,
    units: Mapping[str, str] | str | None = None,
    area: str | float | None = None,
) -> Dataset:
    """Load a dataset from a CSV file, a packaged dataset name or a DataFrame.

    Parameters
    ----------
    name_or_path : str, path, DataFrame, dict or Dataset
        A CSV path; the name of a packaged dataset (see :func:`list_datasets`,
        e.g. ``"thesis-steel"``); a DataFrame (its columns named as in a CSV file,
        each with its unit in the name or in ``units``: a column without a unit is
        refused, as in a file); a dict of columns (canonical or aliased names,
        SI where the name gives no unit); or a :class:`Dataset`, returned unchanged.
    mapping : dict or str, optional
        Canonical column -> the user's column, e.g. ``{"mu": "FC", "p": "CP"}``
        or ``"mu=FC,p=CP"``.
    units : dict or str, optional
        Units of columns whose header has none, e.g. ``{"p": "MPa"}`` or
        ``"p=MPa,v=m/s"``.
    area : str or float, optional
        Nominal contact area, ``"314.16 mm^2"`` or a float in m^2: when the
        data have a normal load ``F_N`` but no pressure, ``p = F_N / area``.

    Returns
    -------
    Dataset
        The data in canonical SI columns, with the units given, the provenance
        and notes of what the loader did (dropped rows, ignored columns,
        conversions); a :class:`Dataset` passed in is returned unchanged.

    Raises
    ------
    InputError
        For a missing, empty, binary or malformed file, an unknown or
        wrong-dimension unit, a missing ``mu`` column, a non-numeric cell, a
        negative pressure, load or friction coefficient, a bad mapping, or when
        no row is left after dropping rows with missing values.  The message
        names the file, column and row.
    """
    if isinstance(mapping, str):
        mapping = parse_mapping(mapping)
    if isinstance(units, str):
        units = parse_units(units)
    if isinstance(name_or_path, Dataset):
        if mapping or units or area is not None:
            raise InputError(
                f"dataset '{name_or_path.name}' is already loaded; mapping, units and area "
                "apply only when reading a file or a DataFrame"
            )
        return name_or_path
    if _is_frame(name_or_path) or isinstance(name_or_path, Mapping):
        table, name = _table_in_memory(name_or_path)
        return _build(table, name, mapping, units, area, None)
    if not isinstance(name_or_path, (str, os.PathLike)):
        raise InputError(
            f"cannot load a dataset from a {type(name_or_path).__name__}; expected a path, "
            "a packaged dataset name, a DataFrame or a Dataset"
        )
    table, name = _table_on_disk(os.fspath(name_or_path))
    prov = "\n".join(table.comments) or None
    return _build(table, name, mapping, units, area, prov)


def _table_in_memory(data: pd.DataFrame | Mapping[str, Any]) -> tuple[Table, str]:
    """A DataFrame or a dict of columns as a table, and the dataset's name."""
    if _is_frame(data):
        return _table_from_frame(data, "<DataFrame>"), "dataframe"
    import pandas as pd

    try:
        frame = pd.DataFrame({str(k): np.atleast_1d(v) for k, v in data.items()})
    except ValueError as exc:
        raise InputError(f"cannot build a table from the dict: {exc}") from None
    table = _table_from_frame(frame, "<dict>")
    table.si_by_default = True
    return table, "data"


def _table_on_disk(text: str) -> tuple[Table, str]:
    """A CSV file or a packaged dataset (``NAME`` or ``packaged:NAME``), and its name."""
    path = Path(text)
    if not path.exists() and text.startswith(_PACKAGED_PREFIX):
        bare = text[len(_PACKAGED_PREFIX):]
        if bare not in _packaged_names():
            raise InputError(
                f"no packaged dataset '{bare}' (packaged: {', '.join(_packaged_names())})")
        text = bare
        path = Path(text)
    if not path.exists() and text in _packaged_names():
        raw = (datasets_dir() / f"{text}.csv").read_bytes()
        return read_table(text, source=f"{_PACKAGED_PREFIX}{text}", raw=raw), text
    if not path.exists():
        raise InputError("file not found; expected a CSV file or the name of a packaged dataset "
                         f"({', '.join(_packaged_names()) or 'none'})", file=text)
    return read_table(path, source=text), path.stem

