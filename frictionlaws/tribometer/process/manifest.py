"""The manifest: which raw record was measured under which load, surface, condition, mode and
window, read from a CSV file or rows, with the file, column and row of anything refused.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ...base.errors import InputError
from ...base.numbers import parse_number
from ...base.units import parse_unit, unit_registry
from ...io import read_table
from ..records import split_header
from ..rig import Rig

__all__ = ["MODES", "DIRECTIONS", "ManifestEntry", "read_manifest", "manifest_from_rows"]


MODES = ("steady", "initial")


DIRECTIONS = ("signed", "counter", "same")


# --------------------------------------------------------------------------- manifest
@dataclass(frozen=True)
class ManifestEntry:
    """One manifest row, checked.

    ``error`` is set (and the record reported unusable) when the row itself is bad.
    """

    row: int
    file: str
    path: str
    load: float  # N
    load_text: str
    surface: str
    condition: str | None = None
    mode: str = "steady"
    window_start: float | None = None
    window_end: float | None = None
    direction: str = "signed"
    error: str | None = None


_MANIFEST_COLUMNS = {"file", "load", "surface", "condition", "mode", "window_start",
                     "window_end", "direction"}


def _norm(name: str) -> str:
    return "_".join(name.strip().lower().replace("-", " ").split())


def read_manifest(path: str | os.PathLike[str], rig: Rig) -> tuple[list[ManifestEntry],
                                                                     list[str]]:
    """Read and check a manifest CSV (format in the module docstring).

    Returns
    -------
    entries : list of ManifestEntry
        One per data row; rows with a problem carry ``error``.
    notes : list of str
        Remarks (ignored columns...).

    Raises
    ------
    InputError
        When the file is missing or malformed, a required column is missing, or
        a column's unit is wrong: problems that concern every row.
    """
    src = os.fspath(path)
    headers, columns, rows = _read_table(src)
    base = Path(src).resolve().parent
    return _entries(headers, columns, rows, src, base, rig)


def _read_table(src: str) -> tuple[list[str], list[list[str]], list[int]]:
    """Cells of the manifest (the one table reader): headers, columns, row numbers."""
    table = read_table(src, header_hint="'file,load [kg],surface'", what="manifest file")
    return table.headers, table.columns, table.rows


def manifest_from_rows(rows: Sequence[Mapping[str, Any]], rig: Rig, *,
                       base: str | os.PathLike[str] = ".", source: str = "<manifest>"
                       ) -> tuple[list[ManifestEntry], list[str]]:
    """Check manifest rows given as dicts (column header -> value), as :func:`read_manifest`."""
    if not rows:
        raise InputError("the manifest has no rows", file=source)
    headers: list[str] = []
    for r in rows:
        for k in r:
            if k not in headers:
                headers.append(str(k))
    columns = [[r.get(h, "") for r in rows] for h in headers]
    return _entries(headers, columns, list(range(2, len(rows) + 2)), source, Path(base), rig)


def _number(text: str) -> float:
    """A manifest cell as a number: the one number parser (a decimal comma allowed)."""
    return parse_number(text, decimal_comma="," in text)


def _cell(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, float) and math.isnan(value):
        return ""
    return str(value).strip()


@dataclass(frozen=True)
class _Layout:
    """Where each manifest column is and how its cells convert to SI."""

    headers: list[str]
    found: dict[str, int]
    src: str
    base: Path
    load_unit: str
    load_factor: float  # N per unit of the load column
    win_factor: dict[str, float]  # s per unit of window_start / window_end

    def header(self, key: str) -> str:
        return self.headers[self.found[key]]


def _locate_columns(headers: list[str], src: str
                    ) -> tuple[dict[str, int], dict[str, str | None], list[str]]:
    """Column index and unit of each manifest column; the headers that are ignored."""
    found: dict[str, int] = {}
    units: dict[str, str | None] = {}
    ignored: list[str] = []
    for j, h in enumerate(headers):
        name, unit = split_header(h)
        key = _norm(name)
        key = "load" if key == "f_n" else key
        if key not in _MANIFEST_COLUMNS:
            if h.strip():
                ignored.append(h)
            continue
        if key in found:
            raise InputError(f"two columns give '{key}' ('{headers[found[key]]}' and '{h}')",
                             file=src, column=h)
        found[key] = j
        units[key] = unit
    for key in ("file", "load", "surface"):
        if key not in found:
            example = {"file": "file", "load": "load [kg]", "surface": "surface"}[key]
            raise InputError(
                f"manifest has no '{key}' column; expected columns file, load [kg] (or "
                f"load [N]), surface and optionally condition, mode, window_start [s], "
                f"window_end [s], direction (e.g. '{example}'; found: "
                f"{', '.join(headers) or 'none'})", file=src)
    return found, units, ignored


def _load_factor(unit: str | None, header: str, rig: Rig, src: str) -> tuple[float, bool]:
    """Newtons per unit of the load column, and whether the column holds masses."""
    if not unit:
        raise InputError("the load column has no unit; write 'load [kg]' for dead weights or "
                         "'load [N]' for a force", file=src, column=header)
    parsed = parse_unit(unit, "F_N", column=header, file=src)
    ureg = unit_registry()
    if parsed.dimensionality == ureg.kilogram.dimensionality:
        return float(ureg.Quantity(1.0, parsed).to("kg").magnitude) * rig.g, True
    return float(ureg.Quantity(1.0, parsed).to("N").magnitude), False


def _window_factors(found: dict[str, int], units: dict[str, str | None],
                    headers: list[str], src: str) -> dict[str, float]:
    """Seconds per unit of the window columns present."""
    out: dict[str, float] = {}
    for key in ("window_start", "window_end"):
        if key not in found:
            continue
        u, h = units[key], headers[found[key]]
        if not u:
            raise InputError(f"the {key} column has no unit; write '{key} [s]'",
                             file=src, column=h)
        q = unit_registry().Quantity(1.0, parse_unit(u, "time", column=h, file=src))
        out[key] = float(q.to("s").magnitude)
    return out


def _entries(headers: list[str], columns: list[list[Any]], rows: list[int], src: str,
             base: Path, rig: Rig) -> tuple[list[ManifestEntry], list[str]]:
    found, units, ignored = _locate_columns(headers, src)
    load_h = headers[found["load"]]
    factor, is_mass = _load_factor(units["load"], load_h, rig, src)
    layout = _Layout(headers, found, src, base, str(units["load"]), factor,
                     _window_factors(found, units, headers, src))
    notes = []
    if ignored:
        notes.append(f"manifest columns ignored: {', '.join(ignored)}")
    if is_mass:
        notes.append(f"loads given as a mass ('{load_h}') are dead weights: F_N = m * g with "
                     f"g = {rig.g:g} m/s^2 from the rig")
    seen: dict[str, int] = {}
    entries = []
    for i, row in enumerate(rows):
        cells = {key: _cell(columns[j][i]) for key, j in found.items()}
        entries.append(_entry(cells, row, layout, seen))
    return entries, notes


def _entry(cells: dict[str, str], row: int, layout: _Layout, seen: dict[str, int]
           ) -> ManifestEntry:
    """One manifest row checked; its problems are collected into ``error``."""
    def get(key: str) -> str:
        return cells.get(key, "")

    errors: list[str] = []
    load = _row_load(get("load"), layout, errors)
    file = get("file")
    for key in ("file", "surface"):
        if not get(key):
            errors.append(f"column '{key}' is empty")
    mode = _choice(get("mode"), "mode", MODES, errors)
    direction = _choice(get("direction"), "direction", DIRECTIONS, errors)
    ws = _row_window("window_start", get("window_start"), layout, errors)
    we = _row_window("window_end", get("window_end"), layout, errors)
    if ws is not None and we is not None and not we > ws:
        errors.append(f"window_end ({we:g} s) must be after window_start ({ws:g} s)")
    path = str((layout.base / file).resolve()) if file else ""
    if path in seen:
        errors.append(f"file listed twice (also in manifest row {seen[path]})")
    elif path:
        seen[path] = row
    error = f"manifest '{layout.src}' row {row}: " + "; ".join(errors) if errors else None
    return ManifestEntry(
        row=row, file=file, path=path, load=load,
        load_text=f"{get('load')} {layout.load_unit}".strip(), surface=get("surface"),
        condition=get("condition") or None, mode=mode, window_start=ws, window_end=we,
        direction=direction, error=error)


def _row_load(text: str, layout: _Layout, errors: list[str]) -> float:
    """The load of one row in N (NaN with an error when it is not a positive number)."""
    header = layout.header("load")
    try:
        load = _number(text) * layout.load_factor
    except ValueError as exc:
        errors.append(f"column '{header}': load {exc}")
        return math.nan
    if not (load > 0 and math.isfinite(load)):
        errors.append(f"column '{header}': load must be > 0, got '{text}'")
    return load


def _choice(cell: str, key: str, allowed: tuple[str, ...], errors: list[str]) -> str:
    """A cell that must be one of ``allowed`` (empty: the first); bad: an error, the first."""
    value = cell.lower() or allowed[0]
    if value in allowed:
        return value
    errors.append(f"column '{key}': '{cell}' is not one of {', '.join(allowed)}")
    return allowed[0]


def _row_window(key: str, cell: str, layout: _Layout, errors: list[str]) -> float | None:
    """A window end from the manifest in s, or None when the cell is empty (or bad)."""
    if not cell:
        return None
    try:
        return _number(cell) * layout.win_factor[key]
    except ValueError as exc:
        errors.append(f"column '{layout.header(key)}': {exc}")
        return None

