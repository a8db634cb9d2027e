"""One raw record to one friction coefficient: direction, saturation, the friction signal, the
steady or initial window, kinematics (:func:`process_record`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...base.errors import InputError
from ..records import Record
from ..rig import RPM, Rig, RigError, check_cutoff
from ..signal import NoWindow, Window, auto_cutoff, find_window, lowpass, speed_segment
from .manifest import ManifestEntry

__all__ = ["SATURATION_FRACTION", "CLIP_RUN", "RecordResult", "process_record"]


#: A raw reading at this fraction of the sensor's full scale counts as saturated.
SATURATION_FRACTION = 0.995


#: Consecutive equal samples at the record's extreme that count as a flat-topped (clipped) signal.
CLIP_RUN = 20


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

