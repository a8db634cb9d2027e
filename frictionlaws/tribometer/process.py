"""Raw records -> friction coefficients per record -> a dataset per condition.

Manifest
    A CSV file with one row per record (paths relative to the manifest)::

        file,load [kg],surface,condition,mode
        records/steel_3kg_01.csv,3,steel,steel 3 kg 5 km/h,steady
        records/s120_2kg_01.csv,2,sandpaper 120,S120 2 kg,initial

    * ``file`` (required): the record CSV (see :mod:`.records`);
    * ``load`` (required) with its unit: a mass (``load [kg]``) is a dead
      weight, turned into a force with the rig's ``g``; a force
      (``load [N]``, ``load [kgf]``) is used as it is;
    * ``surface`` (required): the counter-surface;
    * ``condition`` (optional): records with the same label are repeats of one
      condition.  Without it, records are grouped by surface, mode, load and
      their measured disc and pin speeds (speeds closer than the rig's
      ``grouping.speed_step`` are the same condition);
    * ``mode`` (optional): ``steady`` (default) or ``initial`` (abrasive
      surfaces: only the first seconds of sliding are valid);
    * ``window_start``, ``window_end`` (optional, with a time unit, e.g.
      ``window_start [s]``): override the automatic window of that record
      (either or both; an empty cell keeps the automatic value);
    * ``direction`` (optional): ``signed`` (default: the speeds in the file
      carry their direction), ``counter`` (the file holds magnitudes; pin and
      disc counter-rotate) or ``same`` (magnitudes; same direction).

Per record
    filter the torque (zero-phase low-pass, :mod:`.signal`); subtract the
    system error and the internal torque at the current disc speed; friction
    force = torque / track radius; mu = force / normal load; find the window
    (or take the manifest's); the record's mu is the mean of the filtered mu
    over the window.  Sliding velocity ``v = r |w_pin - w_disc|`` and slip ratio
    ``s = |w_pin - w_disc| / max(|w_pin|, |w_disc|)`` (thesis Eq. 3-4) use the
    window means of the signed speeds, so a counter-rotating pin gives
    ``1 < s <= 2`` and a fixed pin ``s = 1``; contact pressure = load / area.

Per condition
    The record means of the usable records are averaged: ``mu`` (mean),
    ``mu_std`` (sample standard deviation, ddof = 1), ``n``, and the 95 %
    Student-t interval ``mu +/- t(0.975, n - 1) * mu_std / sqrt(n)``.  It
    covers the condition's true coefficient when the record means scatter
    normally about it (repeat-to-repeat scatter dominates the in-record noise).

Outlier rule
    ``[outliers] rule`` of the rig.  ``"pooled"`` (default): the
    record-to-record scatter, relative to each condition's median, is pooled
    robustly over the campaign's conditions and a record departing from its
    condition's median by more than a calibrated threshold in pooled-scatter
    units is dropped (conditions of 3 or more records; at most a minority of a
    condition; a good condition loses a record with probability at most
    ``alpha``); see :mod:`.outliers`.  It works at the rig's 3..7 repeats, where
    Grubbs cannot.  A campaign too small to pool a scatter falls back to
    Grubbs.  ``"grubbs"``: the two-sided Grubbs test on the record means of a
    condition with at least 4 usable records (so that 3 remain), significance
    ``alpha`` (default 0.01), applied once: the record with the largest
    ``G = |x - mean| / sd`` is dropped when ``G`` exceeds the critical value
    ``(n - 1) / sqrt(n) * sqrt(t^2 / (n - 2 + t^2))`` with ``t`` the
    ``1 - alpha / (2 n)`` quantile of Student's t with ``n - 2`` degrees of
    freedom.  ``"none"`` keeps every record.  A dropped record is reported with
    its statistic and threshold; the rule used, with its figures, is printed in
    the summary and written to the outputs' provenance.

Unusable records
    A missing or unreadable file, wrong columns or units, NaNs, a time base
    that is not uniform, a record shorter than ``min_duration``, no sliding,
    no steady window, no friction (mean mu below ``min_mu``), sensor saturation inside
    the window, or a bad manifest row: the record is reported with the reason
    (file, column, row) and the rest are processed.  Conditions with fewer than
    ``min_repeats`` (default 2) usable records are not written to the dataset
    and are listed in the summary.
"""

from __future__ import annotations

import math
import os
import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from .._workers import local_workers
from ..errors import InputError
from .records import Record, read_record, split_header
from .rig import RPM, Rig, RigError, check_cutoff
from .signal import NoWindow, Window, auto_cutoff, find_window, lowpass, speed_segment

__all__ = [
    "ManifestEntry",
    "RecordResult",
    "ConditionResult",
    "Campaign",
    "read_manifest",
    "manifest_from_rows",
    "process_record",
    "process_campaign",
    "process_records",
    "process_many",
    "manifest_names",
    "write_tables",
    "grubbs",
    "student_interval",
    "SATURATION_FRACTION",
]

#: A raw reading at this fraction of the sensor's full scale counts as saturated.
SATURATION_FRACTION = 0.995
#: Consecutive equal samples at the record's extreme that count as a flat-topped (clipped) signal.
CLIP_RUN = 20
MODES = ("steady", "initial")
#: The outlier test needs this many usable records (so that at least 3 remain).
GRUBBS_MIN = 4
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
    from ..io import read_table

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
    from ..numbers import parse_number

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
    from ..units import parse_unit, unit_registry

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
    from ..units import parse_unit, unit_registry

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


# --------------------------------------------------------------------------- per record
@dataclass
class RecordResult:
    """The outcome for one record.

    ``status`` is ``"used"``, ``"outlier"`` (usable but dropped by the outlier
    rule) or ``"unusable"`` (``reason`` says why).  Quantities in SI except
    where the name says otherwise.
    """

    file: str
    row: int
    surface: str
    mode: str
    load: float
    load_text: str
    condition: str = ""
    status: str = "unusable"
    reason: str = ""
    mu: float = math.nan
    mu_window_std: float = math.nan
    window_start: float = math.nan
    window_end: float = math.nan
    window_source: str = ""
    cutoff: float = math.nan
    cutoff_source: str = ""
    fs: float = math.nan
    duration: float = math.nan
    n_samples: int = 0
    p: float = math.nan
    v: float = math.nan
    s: float = math.nan
    disc_speed: float = math.nan
    pin_speed: float = math.nan
    grubbs_g: float = math.nan
    outlier_z: float = math.nan
    notes: list[str] = field(default_factory=list)
    explicit_condition: bool = False

    @property
    def usable(self) -> bool:
        return self.status in ("used", "outlier")


@dataclass
class _Signals:
    """Signals kept for a diagnostic plot."""

    time: np.ndarray
    raw: np.ndarray
    filtered: np.ndarray
    mu: np.ndarray
    window: Window | None
    segment: tuple[int, int] | None


def _apply_direction(rec: Record, direction: str) -> tuple[np.ndarray, np.ndarray]:
    disc = rec.disc_speed
    pin = rec.pin()
    if direction == "counter":
        return np.abs(disc), -np.abs(pin)
    if direction == "same":
        return np.abs(disc), np.abs(pin)
    return disc, pin


def _saturation(raw: np.ndarray, rig: Rig, sl: slice) -> tuple[int, str]:
    """Saturated samples in ``sl`` and a description (0, "" when none)."""
    if rig.torque_range is not None:
        lim = SATURATION_FRACTION * rig.torque_range
        sat = np.abs(raw[sl]) >= lim
        k = int(np.count_nonzero(sat))
        if k:
            return k, (f"{k} samples at or beyond {lim:.4g} N m (99.5 % of the sensor range "
                       f"{rig.torque_range:g} N m)")
    seg = raw[sl]
    if seg.size < CLIP_RUN:
        return 0, ""
    for extreme in (float(np.max(raw)), float(np.min(raw))):
        at = seg == extreme
        if np.count_nonzero(at) < CLIP_RUN:
            continue
        m = np.concatenate(([0], at.astype(np.int8), [0]))
        d = np.diff(m)
        runs = np.flatnonzero(d == -1) - np.flatnonzero(d == 1)
        longest = int(runs.max())
        if longest >= CLIP_RUN:
            return int(np.count_nonzero(at)), (
                f"the reading sticks at its extreme {extreme:.6g} N m for {longest} "
                "consecutive samples (clipped signal)")
    return 0, ""


def process_record(record: Record, entry: ManifestEntry, rig: Rig, *,
                   keep_signals: bool = False) -> RecordResult | tuple[RecordResult, Any]:
    """Process one record: filter, offsets, mu, window, v, s, p.

    Parameters
    ----------
    record : Record
        The raw record (SI).
    entry : ManifestEntry
        Its manifest row (load, mode, window override, direction).
    rig : Rig
        Geometry, offsets and settings.
    keep_signals : bool
        Also return the signals for a diagnostic plot.

    Returns
    -------
    RecordResult
        (and the signals when ``keep_signals``).  Problems with the record give
        ``status = "unusable"`` with the reason; nothing is raised for them.

    Raises
    ------
    RigError
        When a rig setting does not suit the record (a cut-off above its Nyquist
        frequency): the rig file is wrong, for every record alike.
    """
    res = _base_result(entry)
    box: dict[str, _Signals] = {}
    try:
        _process(record, entry, rig, res, box if keep_signals else None)
    except RigError:
        raise  # the rig does not suit the record: the rig file must change
    except (InputError, NoWindow) as exc:
        res.status = "unusable"
        res.reason = " ".join(str(exc).split())
    return (res, box.get("signals")) if keep_signals else res


def _base_result(entry: ManifestEntry) -> RecordResult:
    return RecordResult(file=entry.file, row=entry.row, surface=entry.surface, mode=entry.mode,
                        load=entry.load, load_text=entry.load_text,
                        condition=entry.condition or "",
                        explicit_condition=entry.condition is not None)


def _process(rec: Record, entry: ManifestEntry, rig: Rig, res: RecordResult,
             box: dict[str, _Signals] | None) -> None:
    st = rig.window
    res.n_samples = len(rec)
    res.fs = rec.fs
    res.duration = rec.duration
    if res.duration < st.min_duration:
        raise InputError(f"too short: {res.duration:.3g} s of data (min_duration "
                         f"{st.min_duration:g} s)", file=rec.source)
    disc, pin = _apply_direction(rec, entry.direction)
    mu, speeds = _friction(rec, rig, res, disc, pin, entry.load)
    if box is not None:  # kept for the diagnostic plot, even if no window is found
        box["signals"] = _Signals(rec.time, rec.torque, speeds[2], mu, None, None)
    win = _window(rec, entry, rig, res, mu, speeds[:2], box)
    if box is not None:
        box["signals"].window = win
    sl = win.slice()
    res.window_start, res.window_end = float(rec.time[win.start]), float(rec.time[win.stop - 1])
    _check_saturation(rec, rig, res, sl)
    vals = mu[sl]
    res.mu = float(np.mean(vals))
    res.mu_window_std = float(np.std(vals, ddof=1)) if vals.size > 1 else math.nan
    if not res.mu >= st.min_mu:
        raise NoWindow(f"no friction: mu = {res.mu:.3g} in the window is below min_mu = "
                       f"{st.min_mu:g}: pin not in contact, or offsets wrong?")
    _kinematics(res, rig, float(np.mean(disc[sl])), float(np.mean(pin[sl])), entry.load)
    res.status = "used"


def _friction(rec: Record, rig: Rig, res: RecordResult, disc: np.ndarray, pin: np.ndarray,
              load: float) -> tuple[np.ndarray, tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Filter the torque, subtract the offsets: mu, and (disc, pin, torque) filtered."""
    from scipy.ndimage import uniform_filter1d

    fs, raw = rec.fs, rec.torque
    if rig.filter.cutoff is None:
        info = auto_cutoff(raw, fs, rig.filter)
        res.cutoff, res.cutoff_source = info.cutoff, f"auto ({info.limited_by})"
    else:
        check_cutoff(rig, rig.filter.cutoff, fs, str(rec.source))
        res.cutoff, res.cutoff_source = rig.filter.cutoff, "rig"
    if not res.cutoff < 0.5 * fs:
        raise InputError(f"filter cut-off {res.cutoff:g} Hz is not below the Nyquist frequency "
                         f"{0.5 * fs:g} Hz of this record", file=rec.source)
    filtered = lowpass(raw, fs, res.cutoff, rig.filter.order)
    m = max(1, int(round(fs / res.cutoff)))
    disc_f = uniform_filter1d(disc, m, mode="nearest")
    pin_f = uniform_filter1d(pin, m, mode="nearest")
    friction = filtered - rig.system_error - rig.internal_torque(disc_f)
    return friction / (rig.track_radius * load), (disc_f, pin_f, filtered)


def _window(rec: Record, entry: ManifestEntry, rig: Rig, res: RecordResult, mu: np.ndarray,
            speeds: tuple[np.ndarray, np.ndarray], box: dict[str, _Signals] | None) -> Window:
    """The averaging window: automatic, from the manifest, or one end from each."""
    time, fs = rec.time, rec.fs
    ws, we = entry.window_start, entry.window_end
    for name, value in (("window_start", ws), ("window_end", we)):
        if value is not None and not (time[0] <= value <= time[-1]):
            raise InputError(f"{name} {value:g} s from the manifest (row {entry.row}) is "
                             f"outside the record ({time[0]:g} .. {time[-1]:g} s)",
                             file=rec.source)
    if ws is not None and we is not None:
        return _manifest_window(rec, entry, res, ws, we, None, (0, len(rec)))
    a, b, seg_notes = speed_segment(list(speeds), rig.window.speed_tolerance,
                                    step=max(1, int(fs // 200)))
    if box is not None:
        box["signals"].segment = (a, b)
    res.notes.extend(seg_notes)
    auto = find_window(mu, fs, (a, b), rig.window, entry.mode)
    res.notes.extend(auto.notes)
    if ws is None and we is None:
        res.window_source = "auto"
        return auto
    return _manifest_window(rec, entry, res, ws, we, auto, (a, b))


def _manifest_window(rec: Record, entry: ManifestEntry, res: RecordResult, ws: float | None,
                     we: float | None, auto: Window | None, segment: tuple[int, int]
                     ) -> Window:
    """The window with the manifest's ends (a missing end taken from ``auto``)."""
    s0 = int(np.searchsorted(rec.time, ws)) if ws is not None else None
    e0 = int(np.searchsorted(rec.time, we, side="right")) if we is not None else None
    if auto is not None:
        s0 = auto.start if s0 is None else s0
        e0 = auto.stop if e0 is None else e0
    assert s0 is not None and e0 is not None
    if e0 - s0 < 2:
        raise InputError(f"the window from the manifest (row {entry.row}) holds fewer than "
                         "2 samples", file=rec.source)
    res.window_source = ("manifest" if ws is not None and we is not None
                         else "manifest start" if ws is not None else "manifest end")
    return Window(s0, e0, segment, None, None, ())


def _check_saturation(rec: Record, rig: Rig, res: RecordResult, sl: slice) -> None:
    """Saturation inside the window makes the record unusable; outside it, a note."""
    k, what = _saturation(rec.torque, rig, sl)
    if k:
        unit = rec.units.get("torque")
        raise InputError(f"sensor saturation inside the window: {what}", file=rec.source,
                         column=f"torque [{unit}]" if unit else "torque")
    k_all, what_all = _saturation(rec.torque, rig, slice(None))
    if k_all:
        res.notes.append(f"sensor saturation outside the window: {what_all}")


def _kinematics(res: RecordResult, rig: Rig, wd: float, wp: float, load: float) -> None:
    """Sliding velocity, slip ratio and pressure from the window's mean speeds."""
    rel = abs(wp - wd)
    res.disc_speed, res.pin_speed = wd, wp
    res.v = rig.track_radius * rel
    top = max(abs(wp), abs(wd))
    res.s = rel / top if top > 0 else math.nan
    res.p = load / rig.contact_area
    rng = rig.internal_range_rpm()
    if rng is not None and not rng[0] * 0.999 <= abs(wd) / RPM <= rng[1] * 1.001:
        res.notes.append(f"disc speed {abs(wd) / RPM:.4g} rpm is outside the internal-torque "
                         f"table ({rng[0]:g} .. {rng[1]:g} rpm): its end value was used")


# --------------------------------------------------------------------------- statistics
def student_interval(values: Sequence[float] | np.ndarray, level: float = 0.95
                     ) -> tuple[float, float, float, float]:
    """Mean, sample standard deviation and Student-t interval of the mean.

    Returns
    -------
    mean, std, low, high : float
        ``std``, ``low`` and ``high`` are NaN for fewer than 2 values.
    """
    from scipy import stats

    x = np.asarray(values, dtype=float)
    n = x.size
    if n == 0:
        return math.nan, math.nan, math.nan, math.nan
    mean = float(np.mean(x))
    if n < 2:
        return mean, math.nan, math.nan, math.nan
    sd = float(np.std(x, ddof=1))
    half = float(stats.t.ppf(0.5 + level / 2.0, n - 1)) * sd / math.sqrt(n)
    return mean, sd, mean - half, mean + half


def grubbs(values: Sequence[float] | np.ndarray, alpha: float = 0.01
           ) -> tuple[int | None, float, float]:
    """Two-sided Grubbs test for a single outlier.

    Parameters
    ----------
    values : array-like
        At least 3 values.
    alpha : float
        Significance level.

    Returns
    -------
    index : int or None
        Position of the outlier, or None.
    G : float
        The statistic ``max |x - mean| / sd`` (NaN for fewer than 3 values).
    G_crit : float
        Its critical value at ``alpha``.
    """
    from scipy import stats

    x = np.asarray(values, dtype=float)
    n = x.size
    if n < 3:
        return None, math.nan, math.nan
    sd = float(np.std(x, ddof=1))
    t = float(stats.t.ppf(1.0 - alpha / (2.0 * n), n - 2))
    g_crit = (n - 1) / math.sqrt(n) * math.sqrt(t * t / (n - 2 + t * t))
    if sd == 0:
        return None, 0.0, g_crit
    dev = np.abs(x - np.mean(x)) / sd
    i = int(np.argmax(dev))
    g = float(dev[i])
    return (i if g > g_crit else None), g, g_crit


@dataclass
class ConditionResult:
    """Statistics of one condition (SI units)."""

    condition: str
    surface: str
    mode: str
    n: int
    mu: float
    mu_std: float
    ci95: tuple[float, float]
    p: float
    v: float
    s: float
    F_N: float
    disc_speed: float
    pin_speed: float
    load_text: str
    files: list[str] = field(default_factory=list)
    outliers: list[tuple[str, str]] = field(default_factory=list)
    unusable: list[tuple[str, str]] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    written: bool = True


def _clusters(values: np.ndarray, step: float) -> np.ndarray:
    """Labels of 1-D gap clusters: sorted values closer than ``step`` share a label."""
    order = np.argsort(values, kind="stable")
    labels = np.empty(values.size, dtype=int)
    k = 0
    for j, i in enumerate(order):
        if j and values[i] - values[order[j - 1]] > step:
            k += 1
        labels[i] = k
    return labels


def _auto_conditions(results: list[RecordResult], step: float) -> None:
    """Label records without a manifest condition by surface, mode, load and speeds."""
    groups: dict[tuple[str, str, float], list[RecordResult]] = {}
    for r in results:
        if r.explicit_condition or not math.isfinite(r.load):
            continue
        groups.setdefault((r.surface, r.mode, round(r.load, 9)), []).append(r)
    for members in groups.values():
        usable = [r for r in members if r.usable]
        if not usable:
            continue
        labels = _speed_clusters(usable, step)
        for recs in labels:
            d = float(np.mean([r.disc_speed for r in recs])) / RPM
            pp = float(np.mean([r.pin_speed for r in recs])) / RPM
            name = (f"{recs[0].surface} | {recs[0].load_text} | disc {d:.0f} rpm, "
                    f"pin {pp:.0f} rpm | {recs[0].mode}")
            for r in recs:
                r.condition = name
        if len(labels) == 1:  # an unusable record can only belong to the one condition
            for r in members:
                if not r.usable:
                    r.condition = labels[0][0].condition


def _speed_clusters(usable: list[RecordResult], step: float) -> list[list[RecordResult]]:
    """Records clustered by disc speed, then by pin speed (gaps wider than ``step``)."""
    disc = np.array([r.disc_speed for r in usable])
    pin = np.array([r.pin_speed for r in usable])
    ld = _clusters(disc, step)
    labels: dict[tuple[int, int], list[RecordResult]] = {}
    for c in np.unique(ld):
        idx = np.flatnonzero(ld == c)
        for k, i in zip(_clusters(pin[idx], step), idx, strict=True):
            labels.setdefault((int(c), int(k)), []).append(usable[i])
    return list(labels.values())


def _grubbs_condition(usable: list[RecordResult], alpha: float, label: str
                      ) -> list[RecordResult]:
    """Grubbs on one condition's usable records: the dropped record (status and reason set)."""
    if len(usable) < GRUBBS_MIN:
        return []
    mus = np.array([r.mu for r in usable])
    idx, g, g_crit = grubbs(mus, alpha)
    for r, gi in zip(usable, np.abs(mus - mus.mean()) / (mus.std(ddof=1) or 1.0), strict=True):
        r.grubbs_g = float(gi)
    if idx is None:
        return []
    bad = usable[idx]
    bad.status = "outlier"
    rest = np.delete(mus, idx)
    bad.reason = (f"outlier ({label}, alpha = {alpha:g}): mu = {bad.mu:.4g} vs "
                  f"{rest.mean():.4g} +/- {rest.std(ddof=1):.2g} of the other {rest.size} "
                  f"records; G = {g:.4f} > {g_crit:.4f}")
    return [bad]


def _pooled_conditions(groups: list[tuple[str, list[RecordResult]]], alpha: float
                       ) -> tuple[dict[str, list[RecordResult]], str] | None:
    """The pooled rule over the campaign; None when the scatter cannot be pooled."""
    from .outliers import pooled_outliers

    res = pooled_outliers([[r.mu for r in recs] for _, recs in groups], alpha)
    if not res.pooled:
        return None
    out: dict[str, list[RecordResult]] = {}
    for (name, recs), z, t, flagged in zip(groups, res.z, res.threshold, res.flagged,
                                           strict=True):
        for r, zi in zip(recs, z, strict=True):
            r.outlier_z = float(zi)
        if not flagged:
            continue
        med = float(np.median([r.mu for r in recs]))
        for j in flagged:
            bad = recs[j]
            bad.status = "outlier"
            bad.reason = (f"outlier (pooled scatter, alpha = {alpha:g}): mu = {bad.mu:.4g} is "
                          f"{100 * (bad.mu / med - 1):+.1f} % from the condition's median "
                          f"{med:.4g}, z = {bad.outlier_z:.2f} pooled scatters > threshold "
                          f"{t:.2f} for {len(recs)} records")
        out[name] = [recs[j] for j in flagged]
    sizes = sorted({len(recs) for _, recs in groups if len(recs) >= 3})
    thr = ", ".join(f"t_{n} = {t:.2f}" for n, t in zip(
        sizes, [next(t for (_, rr), t in zip(groups, res.threshold, strict=True)
                     if len(rr) == n) for n in sizes], strict=True))
    text = (f"pooled (a record departing from its condition's median by more than t_n "
            f"pooled relative scatters is dropped; scatter {100 * res.sigma:.3g} % pooled "
            f"robustly from {res.pool} deviations of the conditions with 3 or more records; "
            f"thresholds calibrated for a false-alarm probability <= {alpha:g} per condition: "
            f"{thr})")
    return out, text


def _outlier_decisions(groups: list[tuple[str, list[RecordResult]]], rig: Rig
                       ) -> tuple[dict[str, list[RecordResult]], str]:
    """Apply the rig's outlier rule: the dropped records per condition and the rule used."""
    rule, alpha = rig.outliers.rule, rig.outliers.alpha
    grubbs_text = (f"grubbs (two-sided Grubbs, alpha = {alpha:g}, once per condition of 4 or "
                   "more records)")
    if rule == "none":
        return {}, "none (every usable record kept)"
    if rule == "pooled":
        pooled = _pooled_conditions(groups, alpha)
        if pooled is not None:
            return pooled
        grubbs_text = (f"grubbs as the fallback of the pooled rule (too few repeats to pool a "
                       f"scatter: fewer than {_min_pool()} deviations from conditions of 3 or "
                       f"more records); two-sided, alpha = {alpha:g}, once per condition of 4 "
                       "or more records")
    label = "Grubbs" if rule == "grubbs" else "Grubbs, fallback of the pooled rule"
    out = {name: d for name, recs in groups if (d := _grubbs_condition(recs, alpha, label))}
    return out, grubbs_text


def _min_pool() -> int:
    from .outliers import MIN_POOL

    return MIN_POOL


def summarise(results: list[RecordResult], rig: Rig, *, min_repeats: int = 2
              ) -> tuple[list[ConditionResult], str]:
    """Group records into conditions, apply the outlier rule, compute the statistics.

    Sets ``status`` to ``"outlier"`` on records dropped by the rule.

    Parameters
    ----------
    results : list of RecordResult
        The processed records of one campaign (their ``condition`` is set here
        when the manifest gave none).
    rig : Rig
        The rig (outlier rule, speed step of the automatic grouping, contact area).
    min_repeats : int
        Conditions with fewer usable records are not written.

    Returns
    -------
    conditions : list of ConditionResult
        One per condition, in the order the conditions first appear.
    rule : str
        The outlier rule used, with its settings and figures (for reports).
    """
    _auto_conditions(results, rig.group_speed_step)
    by: dict[str, list[RecordResult]] = {}
    for r in results:
        if r.condition:
            by.setdefault(r.condition, []).append(r)
    decisions, rule_text = _outlier_decisions(
        [(k, [r for r in members if r.usable]) for k, members in by.items()], rig)
    out = [_condition(name, members, decisions.get(name, []), rig, min_repeats)
           for name, members in by.items()]
    return out, rule_text


def _condition(name: str, members: list[RecordResult], dropped: list[RecordResult], rig: Rig,
               min_repeats: int) -> ConditionResult:
    """The statistics of one condition, without the records the outlier rule dropped."""
    unusable = [(r.file, r.reason) for r in members if not r.usable]
    outliers = [(r.file, r.reason) for r in dropped]
    usable = [r for r in members if r.usable and all(r is not d for d in dropped)]
    first = members[0]
    if not usable:
        return ConditionResult(name, first.surface, first.mode, 0, math.nan, math.nan,
                               (math.nan, math.nan), math.nan, math.nan, math.nan, first.load,
                               math.nan, math.nan, first.load_text, [], outliers, unusable,
                               ["no usable record"], written=False)
    mean, sd, lo, hi = student_interval([r.mu for r in usable])
    notes = _mixed_notes(name, usable)
    mixed = bool(notes)
    vs = np.array([r.v for r in usable])
    if vs.size > 1 and np.ptp(vs) > max(0.05 * np.mean(vs), rig.group_speed_step
                                        * rig.track_radius):
        notes.append(f"sliding velocities differ between records ({vs.min():.3g} .. "
                     f"{vs.max():.3g} m/s); the mean is used")
    if len(usable) < min_repeats:
        notes.append(f"{len(usable)} usable record(s), fewer than min_repeats = "
                     f"{min_repeats}: not written to the dataset")
    F = float(np.mean([r.load for r in usable]))
    surfaces = sorted({r.surface for r in usable})
    return ConditionResult(
        condition=name, surface="/".join(surfaces), mode=usable[0].mode, n=len(usable),
        mu=mean, mu_std=sd, ci95=(lo, hi), p=F / rig.contact_area, v=float(np.mean(vs)),
        s=float(np.mean([r.s for r in usable])), F_N=F,
        disc_speed=float(np.mean([r.disc_speed for r in usable])),
        pin_speed=float(np.mean([r.pin_speed for r in usable])),
        load_text=usable[0].load_text, files=[r.file for r in usable], outliers=outliers,
        unusable=unusable, notes=notes, written=len(usable) >= min_repeats and not mixed)


def _mixed_notes(name: str, usable: list[RecordResult]) -> list[str]:
    """One condition is one surface, one load, one mode: a note when records differ."""
    mixed = []
    if len({round(r.load, 9) for r in usable}) > 1:
        mixed.append(f"loads ({', '.join(sorted({r.load_text for r in usable}))})")
    surfaces = {r.surface for r in usable}
    if len(surfaces) > 1:
        mixed.append(f"surfaces ({', '.join(sorted(surfaces))})")
    modes = {r.mode for r in usable}
    if len(modes) > 1:
        mixed.append(f"modes ({', '.join(sorted(modes))})")
    if not mixed:
        return []
    return [f"records of different {' and '.join(mixed)} share the condition label "
            f"'{name}': not written (give each its own condition)"]


# --------------------------------------------------------------------------- campaign
@dataclass
class Campaign:
    """The result of processing a campaign: per record, per condition, and notes."""

    records: list[RecordResult]
    conditions: list[ConditionResult]
    rig: Rig
    source: str = "<memory>"
    notes: list[str] = field(default_factory=list)
    min_repeats: int = 2
    outlier_rule: str = ""

    @property
    def used(self) -> list[RecordResult]:
        return [r for r in self.records if r.status == "used"]

    @property
    def outliers(self) -> list[RecordResult]:
        return [r for r in self.records if r.status == "outlier"]

    @property
    def unusable(self) -> list[RecordResult]:
        return [r for r in self.records if r.status == "unusable"]

    def record_files(self) -> list[Path]:
        """The record files the manifest names, resolved (paths are relative to it).

        Returns
        -------
        list of pathlib.Path
            One per record with a file name; empty for records held in memory.
        """
        if self.source == "<memory>":
            return []
        base = Path(self.source).resolve().parent
        return [(base / r.file).resolve() for r in self.records if r.file]

    def dataset_frame(self) -> Any:
        """The per-condition dataset with display-unit headers (what ``write_dataset`` writes).

        Columns: ``condition``, ``surface``, ``mu``, ``mu_std``, ``mu_ci95_low``,
        ``mu_ci95_high``, ``n``, ``p [MPa]``, ``v [m/s]``, ``s``, ``F_N [N]``,
        ``mode``, ``disc_speed [rpm]``, ``pin_speed [rpm]``, ``n_outliers``,
        ``n_unusable``.  Only conditions with at least ``min_repeats`` usable
        records.
        """
        import pandas as pd

        rows = []
        for c in self.conditions:
            if not c.written:
                continue
            rows.append({
                "condition": c.condition, "surface": c.surface, "mu": c.mu,
                "mu_std": c.mu_std, "mu_ci95_low": c.ci95[0], "mu_ci95_high": c.ci95[1],
                "n": c.n, "p [MPa]": c.p / 1e6, "v [m/s]": c.v, "s": c.s, "F_N [N]": c.F_N,
                "mode": c.mode, "disc_speed [rpm]": c.disc_speed / RPM,
                "pin_speed [rpm]": c.pin_speed / RPM, "n_outliers": len(c.outliers),
                "n_unusable": len(c.unusable)})
        cols = ["condition", "surface", "mu", "mu_std", "mu_ci95_low", "mu_ci95_high", "n",
                "p [MPa]", "v [m/s]", "s", "F_N [N]", "mode", "disc_speed [rpm]",
                "pin_speed [rpm]", "n_outliers", "n_unusable"]
        return pd.DataFrame(rows, columns=cols)

    def dataset(self) -> Any:
        """The dataset as a :class:`frictionlaws.io.Dataset` (SI), ready for ``fit``."""
        from ..io import load_dataset

        f = self.dataset_frame()
        if f.empty:
            raise InputError("no condition has enough usable records for a dataset",
                             file=self.source)
        frame = {"mu": f["mu"].to_numpy(), "p": f["p [MPa]"].to_numpy() * 1e6,
                 "v": f["v [m/s]"].to_numpy(), "s": f["s"].to_numpy(),
                 "F_N": f["F_N [N]"].to_numpy(), "mu_std": f["mu_std"].to_numpy(),
                 "n": f["n"].to_numpy(), "surface": f["surface"].to_numpy()}
        ds = load_dataset(frame)
        ds.name = Path(self.source).stem if self.source != "<memory>" else "processed"
        ds.notes.extend(self.summary_lines(short=True))
        return ds

    def records_frame(self) -> Any:
        """The per-record table (display-unit headers)."""
        import pandas as pd

        rows = []
        for r in self.records:
            rows.append({
                "file": r.file, "manifest_row": r.row, "condition": r.condition,
                "surface": r.surface, "mode": r.mode, "status": r.status, "reason": r.reason,
                "mu": r.mu, "mu_window_std": r.mu_window_std, "load": r.load_text,
                "F_N [N]": r.load, "p [MPa]": r.p / 1e6, "v [m/s]": r.v, "s": r.s,
                "disc_speed [rpm]": r.disc_speed / RPM, "pin_speed [rpm]": r.pin_speed / RPM,
                "window_start [s]": r.window_start, "window_end [s]": r.window_end,
                "window_source": r.window_source, "cutoff [Hz]": r.cutoff,
                "cutoff_source": r.cutoff_source, "fs [Hz]": r.fs, "duration [s]": r.duration,
                "samples": r.n_samples, "grubbs_G": r.grubbs_g,
                "outlier_z": r.outlier_z, "notes": "; ".join(r.notes)})
        return pd.DataFrame(rows)

    def _provenance(self) -> list[str]:
        n = len(self.records)
        return [
            f"Processed by frictionlaws process from manifest {self.source} with rig "
            f"{self.rig.source}",
            f"{n} records: {len(self.used)} used, {len(self.outliers)} outliers dropped, "
            f"{len(self.unusable)} unusable (see the per-record table)",
            "mu: mean of the record means of a condition; mu_std: their sample standard "
            "deviation; mu_ci95_low/high: 95 % Student-t interval of the mean; n: records used",
            f"outlier rule: {self.outlier_rule or self.rig.outliers.rule}",
        ]

    def write_dataset(self, path: str | os.PathLike[str]) -> Path:
        """Write the dataset CSV (foundation schema, units in headers, provenance as ``#``)."""
        return write_tables([(path, self.dataset_text())])[0]

    def write_records(self, path: str | os.PathLike[str]) -> Path:
        """Write the per-record table as CSV."""
        return write_tables([(path, self.records_text())])[0]

    def dataset_text(self) -> str:
        """The dataset CSV that :meth:`write_dataset` writes, as text."""
        return _csv_text(self.dataset_frame(), self._provenance())

    def records_text(self) -> str:
        """The per-record CSV that :meth:`write_records` writes, as text."""
        prov = self._provenance()
        return _csv_text(self.records_frame(), prov[:2] + prov[3:])

    def summary_lines(self, *, short: bool = False) -> list[str]:
        """Return the lines of the summary.

        Parameters
        ----------
        short : bool
            Only the counts, the rule and one line per unusable or dropped record
            (the form kept in a dataset's notes).

        Returns
        -------
        list of str
            Counts, the outlier rule, unusable records, outliers, conditions not
            written, notes of conditions and records.
        """
        written = [c for c in self.conditions if c.written]
        lines = [f"{len(self.records)} records: {len(self.used)} used, "
                 f"{len(self.outliers)} dropped as outliers, {len(self.unusable)} unusable; "
                 f"{len(written)} conditions in the dataset",
                 f"outlier rule: {self.outlier_rule or self.rig.outliers.rule}"]
        if short:
            lines += [f"unusable record {r.file}: {r.reason}" for r in self.unusable]
            lines += [f"outlier {r.file} ({r.condition}): {r.reason}" for r in self.outliers]
            return lines
        return lines + self._record_lines() + self._condition_lines() + self._note_lines()

    def _record_lines(self) -> list[str]:
        lines = []
        if self.unusable:
            lines.append("unusable records:")
            lines += [f"  {r.file}: {r.reason}" for r in self.unusable]
        if self.outliers:
            lines.append("outliers dropped:")
            lines += [f"  {r.file} [{r.condition}]: {r.reason}" for r in self.outliers]
        unassigned = [r for r in self.unusable if not r.condition]
        if unassigned:
            lines.append(f"{len(unassigned)} unusable record(s) could not be assigned to a "
                         "condition (no 'condition' column and no measured speeds)")
        return lines

    def _condition_lines(self) -> list[str]:
        lines = []
        not_written = [c for c in self.conditions if not c.written]
        if not_written:
            lines.append("conditions not in the dataset:")
            lines += [f"  {c.condition}: {'; '.join(c.notes)}" for c in not_written]
        other = [(c.condition, note) for c in self.conditions if c.written for note in c.notes]
        if other:
            lines.append("condition notes:")
            lines += [f"  {name}: {note}" for name, note in other]
        return lines

    def _note_lines(self) -> list[str]:
        lines = []
        rec_notes = [(r.file, n) for r in self.records for n in r.notes
                     if not n.startswith("window ends")]
        if rec_notes:
            lines.append(f"record notes ({len(rec_notes)}):")
            lines += [f"  {f}: {n}" for f, n in rec_notes[:20]]
            if len(rec_notes) > 20:
                lines.append(f"  ... {len(rec_notes) - 20} more in the per-record table")
        return lines + [f"note: {n}" for n in self.notes]

    def summary(self) -> str:
        """Return the summary as text (:meth:`summary_lines` joined).

        Returns
        -------
        str
            One line per item of :meth:`summary_lines`.
        """
        return "\n".join(self.summary_lines())

    def to_dict(self) -> dict[str, Any]:
        """Return the campaign as JSON-able data in SI units.

        Returns
        -------
        dict
            ``manifest``, ``rig``, ``min_repeats``, ``outlier_rule``, ``counts``
            (records, used, outliers, unusable, conditions written), ``units``
            (the SI unit of every quantity below), ``conditions`` (one dict per
            condition: statistics, whether it is in the dataset, its records and
            notes), ``records`` (one dict per record: status, reason, mu, window,
            filter, speeds) and ``notes``.  Missing numbers are NaN (written as
            ``null`` by :func:`frictionlaws.jsonio.dumps`).
        """
        return {
            "manifest": self.source, "rig": self.rig.source, "min_repeats": self.min_repeats,
            "outlier_rule": self.outlier_rule or self.rig.outliers.rule,
            "counts": {"records": len(self.records), "used": len(self.used),
                       "outliers": len(self.outliers), "unusable": len(self.unusable),
                       "conditions_written": sum(c.written for c in self.conditions)},
            "units": dict(JSON_UNITS),
            "conditions": [_condition_dict(c) for c in self.conditions],
            "records": [_record_dict(r) for r in self.records],
            "notes": list(self.notes)}


#: SI unit of each quantity in :meth:`Campaign.to_dict` (``1``: dimensionless).
JSON_UNITS = {"mu": "1", "mu_std": "1", "mu_ci95": "1", "mu_window_std": "1", "p": "Pa",
              "v": "m/s", "s": "1", "F_N": "N", "load": "N", "disc_speed": "rad/s",
              "pin_speed": "rad/s", "window_start": "s", "window_end": "s", "cutoff": "Hz",
              "fs": "Hz", "duration": "s"}


def _condition_dict(c: ConditionResult) -> dict[str, Any]:
    return {"condition": c.condition, "surface": c.surface, "mode": c.mode,
            "written": c.written, "n": c.n, "mu": c.mu, "mu_std": c.mu_std,
            "mu_ci95": list(c.ci95), "p": c.p, "v": c.v, "s": c.s, "F_N": c.F_N,
            "disc_speed": c.disc_speed, "pin_speed": c.pin_speed, "load_text": c.load_text,
            "files": list(c.files),
            "outliers": [{"file": f, "reason": why} for f, why in c.outliers],
            "unusable": [{"file": f, "reason": why} for f, why in c.unusable],
            "notes": list(c.notes)}


def _record_dict(r: RecordResult) -> dict[str, Any]:
    return {"file": r.file, "manifest_row": r.row, "condition": r.condition,
            "surface": r.surface, "mode": r.mode, "status": r.status, "reason": r.reason,
            "mu": r.mu, "mu_window_std": r.mu_window_std, "load": r.load,
            "load_text": r.load_text, "p": r.p, "v": r.v, "s": r.s,
            "disc_speed": r.disc_speed, "pin_speed": r.pin_speed,
            "window_start": r.window_start, "window_end": r.window_end,
            "window_source": r.window_source, "cutoff": r.cutoff,
            "cutoff_source": r.cutoff_source, "fs": r.fs, "duration": r.duration,
            "samples": r.n_samples, "grubbs_G": r.grubbs_g, "outlier_z": r.outlier_z,
            "notes": list(r.notes)}


def _fmt(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, (float, np.floating)):
        return "" if not math.isfinite(float(value)) else format(float(value), ".10g")
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    return str(value)


def _csv_text(frame: Any, comments: list[str]) -> str:
    import csv
    import io

    from ..sanitize import comment_lines, csv_cell

    buf = io.StringIO()
    for line in comment_lines(comments):
        buf.write(line + "\n")
    w = csv.writer(buf, lineterminator="\n")
    w.writerow([csv_cell(c) for c in frame.columns])
    for row in frame.itertuples(index=False):
        w.writerow([csv_cell(v) if isinstance(v, str) else _fmt(v) for v in row])
    return buf.getvalue()


def write_tables(tables: Sequence[tuple[str | os.PathLike[str], str]]) -> list[Path]:
    """Write several text files together: all of them or, on any failure, none.

    Each file is written to a temporary file beside its target; the temporary
    files are renamed into place only when every one has been written.

    Parameters
    ----------
    tables : sequence of (path, text)
        The files and their contents.

    Returns
    -------
    list of pathlib.Path
        The paths written, in the order given.

    Raises
    ------
    InputError
        When a directory is missing, or a target is an input or a directory;
        nothing is written then.
    """
    import contextlib

    from ..outputs import atomic_write

    paths = [Path(p) for p, _ in tables]
    for out in paths:
        if str(out.parent) and not out.parent.exists():
            raise InputError("the output directory does not exist", file=str(out))
    with contextlib.ExitStack() as stack:
        for out, (_, text) in zip(paths, tables, strict=True):
            stack.enter_context(atomic_write(out, newline="")).write(text)
    return paths


# --------------------------------------------------------------------------- drivers
@dataclass(frozen=True)
class _Chunk:
    """Records to process in one unit of work: plain, picklable data only."""

    rig: Rig
    entries: tuple[ManifestEntry, ...]
    plots: tuple[str | None, ...]


def _run_chunk(chunk: _Chunk) -> list[RecordResult]:
    """Read and process the records of a chunk (a worker's unit of work)."""
    return [_handle(e, chunk.rig, plots, None)
            for e, plots in zip(chunk.entries, chunk.plots, strict=True)]


def _handle(entry: ManifestEntry, rig: Rig, plots: str | None,
            record: Record | None) -> RecordResult:
    if entry.error:
        res = _base_result(entry)
        res.reason = entry.error
        return res
    try:
        rec = record if record is not None else read_record(entry.path, source=entry.file)
        if record is not None:
            rec.check()
    except InputError as exc:
        res = _base_result(entry)
        res.reason = " ".join(str(exc).split())
        return res
    if plots is None:
        return process_record(rec, entry, rig)  # type: ignore[return-value]
    res, sig = process_record(rec, entry, rig, keep_signals=True)  # type: ignore[misc]
    from .plots import plot_record

    try:
        plot_record(Path(plots), res, rec, sig)
    except Exception as exc:  # noqa: BLE001 - a failed plot must not lose the record
        res.notes.append(f"diagnostic plot failed: {type(exc).__name__}: {exc}")
    return res


def _progress(total: int, progress: bool | None, desc: str) -> Any:
    from tqdm import tqdm

    return tqdm(total=total, disable=None if progress is None else not progress,
                unit="record", desc=desc, file=sys.stderr, leave=False)


def _workers(jobs: int | None) -> int:
    """``jobs`` as the campaign runner takes it: None or 0 (one per CPU) become -1."""
    return -1 if jobs is None or jobs == 0 else jobs


def _run_files(work: list[tuple[ManifestEntry, str | None]], rig: Rig, jobs: int | None,
               scheduler: str | None, progress: bool | None) -> list[RecordResult]:
    """Process records read from files, on the campaign runner (serial, joblib or Dask).

    The results are in the order of ``work`` and do not depend on how the work ran.
    """
    from ..campaign import SCHEDULER_ENV, _check_jobs, iter_parallel

    jobs = _workers(jobs)
    _check_jobs(jobs)
    remote = bool(scheduler or os.environ.get(SCHEDULER_ENV))
    workers = local_workers(jobs)
    if not remote and len(work) < 2 * workers:  # too few records to be worth a pool
        jobs = 1
    # one record per item: the campaign runner batches the items into tasks itself
    chunks = (_Chunk(rig, (e,), (p,)) for e, p in work)
    results: list[RecordResult] = []
    bar = _progress(len(work), progress, "processing")
    try:
        for part in iter_parallel(_run_chunk, chunks, jobs=jobs, scheduler=scheduler,
                                  total=len(work)):
            results.extend(part)
            bar.update(len(part))
    finally:
        bar.close()
    return results


def _run_memory(entries: list[ManifestEntry], rig: Rig, records: Sequence[Record],
                progress: bool | None, plots: str | None) -> list[RecordResult]:
    """Process records held in memory, in this process."""
    results: list[RecordResult] = []
    bar = _progress(len(entries), progress, "processing")
    try:
        for entry, rec in zip(entries, records, strict=True):
            results.append(_handle(entry, rig, plots, rec))
            bar.update(1)
    finally:
        bar.close()
    return results


def _check_min_repeats(min_repeats: int) -> None:
    if min_repeats < 2:
        raise InputError(f"min_repeats must be at least 2 (a standard deviation needs two "
                         f"records), got {min_repeats}")


def process_campaign(
    manifest: str | os.PathLike[str],
    rig: Rig | str | os.PathLike[str],
    *,
    jobs: int | None = 1,
    progress: bool | None = None,
    plots: str | os.PathLike[str] | None = None,
    min_repeats: int = 2,
    scheduler: str | None = None,
) -> Campaign:
    """Process every record of a manifest into per-record and per-condition results.

    Parameters
    ----------
    manifest : str or path
        The manifest CSV (format in the module docstring).
    rig : Rig or path
        A :class:`Rig` or the path of its TOML description.
    jobs : int, optional
        Worker processes: 1 (default) serial, N > 1 that many, ``-1``, ``0`` or
        ``None`` one per CPU.  Results do not depend on it.
    progress : bool, optional
        Show a progress bar on stderr; ``None`` (default): only when stderr is a
        terminal.
    plots : str or path, optional
        Directory for diagnostic plots (created); matplotlib is imported only then.
    min_repeats : int
        Conditions with fewer usable records are not written to the dataset
        (at least 2: a standard deviation needs two).
    scheduler : str, optional
        A Dask scheduler address: the records are processed on that cluster (see
        :func:`frictionlaws.campaign.iter_parallel`; the record files must be
        readable by its workers).

    Returns
    -------
    Campaign
        The per-record results, the conditions with their statistics, the notes
        and the outlier rule used.

    Raises
    ------
    InputError
        For a bad manifest or rig (problems of single records are reported in
        the results instead).
    """
    return process_many([manifest], rig, jobs=jobs, progress=progress, plots=plots,
                        min_repeats=min_repeats, scheduler=scheduler, plot_dirs="flat")[0]


def process_many(
    manifests: Sequence[str | os.PathLike[str]],
    rig: Rig | str | os.PathLike[str],
    *,
    jobs: int | None = 1,
    progress: bool | None = None,
    plots: str | os.PathLike[str] | None = None,
    min_repeats: int = 2,
    scheduler: str | None = None,
    plot_dirs: str = "per-manifest",
) -> list[Campaign]:
    """Process several manifests with one rig: one :class:`Campaign` per manifest.

    Every manifest is read and checked before any record is processed.  The
    records of all manifests are then processed as one stream of work, serially,
    on local processes (``jobs``) or on a Dask cluster (``scheduler``), the way
    :func:`frictionlaws.campaign.fit_many` runs many datasets; each manifest's
    conditions and outlier rule are then computed from its own records only, so
    each result equals :func:`process_campaign` of that manifest alone.

    Parameters
    ----------
    manifests : sequence of str or path
        The manifest CSVs; the same file may not be given twice.
    rig : Rig or path
        The rig of every manifest.
    jobs : int, optional
        Worker processes, as in :func:`process_campaign`.
    progress : bool, optional
        Progress bar on stderr (``None``: only on a terminal).
    plots : str or path, optional
        Directory for diagnostic plots.
    min_repeats : int
        As in :func:`process_campaign`, for every manifest.
    scheduler : str, optional
        A Dask scheduler address, as in :func:`process_campaign`.
    plot_dirs : {"per-manifest", "flat"}
        ``per-manifest`` (default): each manifest's plots go to a subdirectory
        named by :func:`manifest_names`; ``flat``: all in ``plots`` (one manifest).

    Returns
    -------
    list of Campaign
        In the order of ``manifests``.

    Raises
    ------
    InputError
        For a bad rig, a manifest given twice, or a bad manifest (naming it);
        nothing is processed then.
    """
    if not isinstance(rig, Rig):
        from .rig import load_rig

        rig = load_rig(rig)
    _check_min_repeats(min_repeats)
    names = manifest_names(manifests)
    read = [read_manifest(m, rig) for m in manifests]
    dirs = _plot_dirs(plots, names, plot_dirs)
    work = [(e, d) for (entries, _), d in zip(read, dirs, strict=True) for e in entries]
    results = iter(_run_files(work, rig, jobs, scheduler, progress))
    camps = []
    for m, (entries, notes), d in zip(manifests, read, dirs, strict=True):
        mine = [next(results) for _ in entries]
        camps.append(_campaign(mine, rig, os.fspath(m), notes, min_repeats, d))
    return camps


def _campaign(results: list[RecordResult], rig: Rig, source: str, notes: list[str],
              min_repeats: int, plots_dir: str | None) -> Campaign:
    conditions, rule = summarise(results, rig, min_repeats=min_repeats)
    camp = Campaign(results, conditions, rig, source, notes, min_repeats, rule)
    if plots_dir is not None:
        _summary_plot(camp, plots_dir)
    return camp


def _plot_dirs(plots: str | os.PathLike[str] | None, names: list[str], layout: str
               ) -> list[str | None]:
    if layout not in ("per-manifest", "flat"):
        raise InputError(f"plot_dirs must be 'per-manifest' or 'flat', got {layout!r}")
    if plots is None:
        return [None] * len(names)
    if layout == "flat":
        if len(names) > 1:
            raise InputError("several manifests need a plot directory each: use "
                             "plot_dirs='per-manifest'")
        return [_plots_dir(plots)]
    return [_plots_dir(Path(plots) / name) for name in names]


def manifest_names(manifests: Sequence[str | os.PathLike[str]]) -> list[str]:
    """Give manifests short, distinct names for their outputs.

    The name is the file stem, or parent and stem when two stems are the same
    (``week1/manifest.csv`` -> ``week1_manifest``).

    Parameters
    ----------
    manifests : sequence of str or path
        The manifest files.

    Returns
    -------
    list of str
        One name per manifest, in order; used for output files and plot folders.

    Raises
    ------
    InputError
        When no manifest is given, one is given twice (the same file, also
        through a link), or two names still collide (naming both files).
    """
    if not manifests:
        raise InputError("no manifest given")
    paths = [Path(m) for m in manifests]
    _refuse_repeats(paths)
    stems = [p.stem for p in paths]
    names = [f"{p.resolve().parent.name}_{p.stem}" if stems.count(p.stem) > 1 else p.stem
             for p in paths]
    seen: dict[str, Path] = {}
    for name, p in zip(names, paths, strict=True):
        key = name.casefold()  # outputs may land on a case-insensitive file system
        if key in seen:
            raise InputError(f"manifests '{seen[key]}' and '{p}' would write outputs of the "
                             f"same name '{name}': rename one, or process them separately",
                             file=str(p))
        seen[key] = p
    return names


def _refuse_repeats(paths: list[Path]) -> None:
    """A manifest given twice (same path, or the same file through a link) is refused."""
    for i, p in enumerate(paths):
        for q in paths[:i]:
            same = os.path.realpath(p) == os.path.realpath(q)
            if not same and p.exists() and q.exists():
                same = os.path.samefile(p, q)
            if same:
                raise InputError(f"the manifest is given twice ('{q}' and '{p}'); give it "
                                 "once", file=str(p))


def process_records(
    records: Sequence[Record],
    manifest: Sequence[Mapping[str, Any]] | Sequence[ManifestEntry],
    rig: Rig,
    *,
    progress: bool | None = False,
    plots: str | os.PathLike[str] | None = None,
    min_repeats: int = 2,
) -> Campaign:
    """Process records held in memory (e.g. from :mod:`.synthetic`), one manifest row each.

    ``manifest`` holds dicts with the manifest's columns (``file``,
    ``load [kg]``, ``surface``, ``condition``, ``mode``...) or ready
    :class:`ManifestEntry` objects; ``file`` only names the record.
    """
    if len(records) != len(manifest):
        raise InputError(f"{len(records)} records but {len(manifest)} manifest rows")
    _check_min_repeats(min_repeats)
    notes: list[str] = []
    if manifest and all(isinstance(m, ManifestEntry) for m in manifest):
        entries = [m for m in manifest if isinstance(m, ManifestEntry)]
    else:
        rows = [m for m in manifest if isinstance(m, Mapping)]
        if len(rows) != len(manifest):
            raise InputError("manifest rows must all be dicts or all be ManifestEntry objects")
        entries, notes = manifest_from_rows(rows, rig)
    entries = [replace(e, path="") for e in entries]
    plots_dir = _plots_dir(plots)
    results = _run_memory(entries, rig, records, progress, plots_dir)
    return _campaign(results, rig, "<memory>", notes, min_repeats, plots_dir)


def _plots_dir(plots: str | os.PathLike[str] | None) -> str | None:
    if plots is None:
        return None
    from ..io import output_dir

    return str(output_dir(os.fspath(plots), "plots directory"))


def _summary_plot(camp: Campaign, plots_dir: str) -> None:
    from .plots import plot_conditions

    try:
        plot_conditions(Path(plots_dir) / "conditions.png", camp)
    except Exception as exc:  # noqa: BLE001 - report, do not lose the processing
        camp.notes.append(f"summary plot failed: {type(exc).__name__}: {exc}")
