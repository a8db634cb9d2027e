"""The rig description: geometry, offsets and processing settings, read from TOML.

A rig file describes one tribometer and how its records are processed.  Every
dimensional value is a string with its unit, parsed with pint through
:mod:`frictionlaws.base.units`, so ``"40 mm"`` and ``"0.04 m"`` mean the same::

    track_radius = "40 mm"        # mean radius of the pin track
    pin_diameter = "20 mm"        # or: contact_area = "314.16 mm^2"
    system_error = "0.3 N*m"      # constant torque offset (hanging-weight test)
    g = "9.8 m/s^2"               # turns a dead weight in kg into a load
    torque_range = "10 N*m"       # optional: sensor full scale (saturation check)

    [internal_torque]             # optional: no-contact torque vs disc speed
    disc_speed_rpm = [0, 100, 331, 663]
    torque_Nm = [0.11, 0.06, 0.06, 0.12]

    [filter]
    cutoff = "auto"               # or a frequency, e.g. "20 Hz"
    order = 4

    [window]                      # steady-window detection (defaults shown)
    min_duration = "3 s"
    min_window = "2 s"
    speed_tolerance = 0.05
    smooth = "0.5 s"
    level_tolerance = 0.03
    noise_factor = 4.0
    start_tolerance = 0.01
    settle = "0.5 s"
    end_margin = "0.5 s"
    initial_delay = "1 s"
    initial_duration = "3 s"
    min_mu = 0.02

    [outliers]
    rule = "pooled"               # or "grubbs" or "none"
    alpha = 0.01

    [grouping]
    speed_step = "10 rpm"

Unknown keys are an error (a typo must not silently fall back to a default).  Every
dimensional value must lie in its plausible range (:data:`RANGES`: a track radius of
1 mm..2 m, g of 9.7..9.9 m/s^2...), so a unit slip such as ``"40 km"`` is refused
naming the key, the value and the range; a filter cut-off must also lie below the
Nyquist frequency of every record (checked as each record is processed).
The meaning of each setting is documented on :class:`FilterSettings`,
:class:`WindowSettings`, :class:`OutlierSettings` and :class:`Rig`.
"""

from __future__ import annotations

import math
import os
import sys
from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Any

import numpy as np

if sys.version_info >= (3, 11):
    import tomllib
else:  # Python 3.10: the same parser, published as tomli
    import tomli as tomllib

from ..base.errors import InputError
from ..base.limits import check_nesting, nesting_error, read_input
from ..base.numbers import parse_number
from ..base.outputs import check_input_file
from ..base.units import parse_quantity
from .records import angular_unit_factor

__all__ = [
    "FilterSettings",
    "WindowSettings",
    "OutlierSettings",
    "Rig",
    "load_rig",
    "rig_from_dict",
    "RPM",
    "PlausibleRange",
    "RANGES",
    "RigError",
    "check_cutoff",
]

#: One revolution per minute in rad/s.
RPM = 2.0 * math.pi / 60.0


@dataclass(frozen=True)
class FilterSettings:
    """Zero-phase low-pass filter applied to every signal of a record.

    Attributes
    ----------
    cutoff : float or None
        Cut-off frequency [Hz]; ``None`` means automatic, from the spectrum of
        the torque signal (see :func:`frictionlaws.tribometer.signal.auto_cutoff`).
    order : int
        Order of the Butterworth prototype.  It is applied forwards and
        backwards (``scipy.signal.sosfiltfilt``), so the effective order is
        twice this and the phase shift is zero.
    auto_min, auto_max : float
        Bounds of an automatic cut-off [Hz]; ``auto_max`` of 0 means a quarter
        of the sampling rate.
    auto_snr : float
        The automatic cut-off is where the torque spectrum falls to within this
        factor of the broadband noise floor.
    """

    cutoff: float | None = None
    order: int = 4
    auto_min: float = 1.0
    auto_max: float = 0.0
    auto_snr: float = 10.0


@dataclass(frozen=True)
class WindowSettings:
    """How the steady sliding window is found (times in s, fractions in 1).

    Attributes
    ----------
    min_duration : float
        Records shorter than this are unusable ("too short").
    min_window : float
        A detected window shorter than this means "no steady window".
    speed_tolerance : float
        The motors count as running at speed while each moving speed channel
        is within this fraction of its plateau value.
    smooth : float
        Length of the moving average used to compare the filtered friction
        signal with its steady level.
    level_tolerance : float
        Relative band around the steady level that counts as steady (the band
        is never narrower than ``noise_factor`` robust standard deviations of
        the smoothed signal).
    noise_factor : float
        See ``level_tolerance``.
    start_tolerance : float
        Tighter relative band the start-up peak must have decayed into before
        the window starts (also never narrower than the noise band), so that
        its tail does not bias the mean.
    settle : float
        Extra time skipped after the start-up peak has fallen into that band.
    end_margin : float
        Time dropped before the motors leave their plateau speed.
    initial_delay : float
        ``initial`` mode: the window starts this long after the motors reach
        speed (skips the start-up transient).
    initial_duration : float
        ``initial`` mode: length of the window (abrasive surfaces: only the
        first seconds of sliding are valid).
    min_mu : float
        A window whose mean friction coefficient is below this (or not clearly
        above the noise) means "no friction": the pin is not in contact or the
        offsets are wrong.
    """

    min_duration: float = 3.0
    min_window: float = 2.0
    speed_tolerance: float = 0.05
    smooth: float = 0.5
    level_tolerance: float = 0.03
    noise_factor: float = 4.0
    start_tolerance: float = 0.01
    settle: float = 0.5
    end_margin: float = 0.5
    initial_delay: float = 1.0
    initial_duration: float = 3.0
    min_mu: float = 0.02


@dataclass(frozen=True)
class OutlierSettings:
    """The outlier rule applied to the record means of each condition.

    Attributes
    ----------
    rule : {"pooled", "grubbs", "none"}
        ``"pooled"`` (default): the record-to-record scatter is pooled robustly
        over the campaign's conditions (relative to each condition's median) and
        a record departing from its condition's median by more than a threshold
        in pooled-scatter units is dropped (conditions of 3 or more records;
        :mod:`frictionlaws.tribometer.outliers`).  It detects a +30 % record
        among 4 repeats with 2 % scatter almost always, where Grubbs does a
        third of the time.  A campaign too small to pool a scatter falls back
        to Grubbs, with a note.  ``"grubbs"``: the two-sided Grubbs test at
        significance ``alpha``, applied once per condition (at most one record
        dropped) and only when the condition has at least 4 usable records.
        ``"none"``: keep all.
    alpha : float
        Pooled rule: the largest probability that a condition without an
        outlier loses a record (the thresholds are calibrated for it).  Grubbs:
        its significance level.  The default 0.01 drops a good record in at
        most 1 % of normal conditions; 0.05 detects outliers more often but
        lowers the coverage of the confidence intervals.
    """

    rule: str = "pooled"
    alpha: float = 0.01


class RigError(InputError):
    """A rig setting that does not suit a record (a filter cut-off above its Nyquist
    frequency): the rig is wrong, not the record, so processing stops (never a
    record marked unusable)."""


@dataclass(frozen=True)
class PlausibleRange:
    """The range a rig quantity of any real tribometer lies in (SI), and how to show it.

    A value outside is almost always a unit slip (``"40 km"`` for ``"40 mm"``) or a
    typing error, which would otherwise surface only as "no usable record".

    Parameters
    ----------
    lo, hi : float
        The plausible range, ends included [SI unit of the quantity].
    unit : str
        The unit the range is shown in.
    scale : float
        That unit in SI (``1e-3`` for mm).
    why : str
        What bounds the range, for the message.
    """

    lo: float
    hi: float
    unit: str
    scale: float
    why: str

    def check(self, name: str, value: float, raw: Any, src: str) -> float:
        """Return ``value`` if it lies in the range, else refuse it.

        Parameters
        ----------
        name : str
            The key in the rig file (``"track_radius"``, ``"filter.auto_min"``).
        value : float
            Its value in SI.
        raw : object
            The value as written in the file (shown in the message).
        src : str
            The rig file.

        Returns
        -------
        float
            ``value``.

        Raises
        ------
        InputError
            Naming the file, the key, the value with its unit and the range.
        """
        if self.lo <= value <= self.hi:
            return value
        raise InputError(f"'{name}' = {raw!r} ({value / self.scale:.6g} {self.unit}) is outside "
                         f"the plausible range {self.lo / self.scale:g}..{self.hi / self.scale:g} "
                         f"{self.unit} ({self.why})", file=src)


#: The plausible range of every dimensional rig quantity, by its key in the rig file.
#: ``filter.cutoff`` is also checked against each record's Nyquist frequency when the
#: record is processed (:func:`check_cutoff`).
RANGES: dict[str, PlausibleRange] = {
    "track_radius": PlausibleRange(1e-3, 2.0, "mm", 1e-3,
                                   "a pin track, from a micro-tribometer to a road wheel"),
    "pin_diameter": PlausibleRange(1e-4, 0.5, "mm", 1e-3, "a pin or a rubber block"),
    "contact_area": PlausibleRange(1e-8, 0.1, "mm^2", 1e-6,
                                   "a pin tip up to a whole tyre contact patch"),
    "system_error": PlausibleRange(-1e3, 1e3, "N*m", 1.0,
                                   "a torque offset, far below any sensor's full scale"),
    "g": PlausibleRange(9.7, 9.9, "m/s^2", 1.0,
                        "gravity anywhere on the Earth's surface is 9.76..9.84 m/s^2"),
    "torque_range": PlausibleRange(1e-3, 1e5, "N*m", 1.0, "torque sensors' full scales"),
    "filter.cutoff": PlausibleRange(1e-3, 1e6, "Hz", 1.0, "a low-pass cut-off, also "
                                    "below half the sampling rate of each record"),
    "filter.auto_min": PlausibleRange(1e-3, 1e6, "Hz", 1.0, "a low-pass cut-off"),
    "filter.auto_max": PlausibleRange(0.0, 1e6, "Hz", 1.0,
                                      "a low-pass cut-off; 0 means a quarter of the "
                                      "sampling rate"),
    **{f"window.{name}": PlausibleRange(0.0, 86400.0, "s", 1.0, "at most a day")
       for name in ("min_duration", "min_window", "smooth", "settle", "end_margin",
                    "initial_delay", "initial_duration")},
    "grouping.speed_step": PlausibleRange(0.01 * RPM, 1e4 * RPM, "rpm", RPM,
                                          "a difference of disc or pin speeds"),
}


def check_cutoff(rig: Rig, cutoff: float, fs: float, record: str) -> None:
    """Refuse a rig cut-off at or above the Nyquist frequency of a record.

    Parameters
    ----------
    rig : Rig
        The rig (its ``source`` is named).
    cutoff : float
        The rig's cut-off [Hz].
    fs : float
        The record's sampling rate [Hz].
    record : str
        The record, named in the message.

    Raises
    ------
    RigError
        When ``cutoff >= fs / 2``: the rig, not the record, must change.
    """
    nyquist = 0.5 * fs
    if not 0 < cutoff < nyquist:
        raise RigError(f"'filter.cutoff' = {cutoff:g} Hz is not below the Nyquist frequency "
                       f"{nyquist:g} Hz of record '{record}' (sampled at {fs:g} Hz); expected "
                       f"0 < cutoff < {nyquist:g} Hz", file=rig.source)


@dataclass(frozen=True)
class Rig:
    """A pin-on-disc tribometer and the settings used to process its records.

    Attributes
    ----------
    track_radius : float
        Mean radius of the pin track [m]: friction force = torque / radius and
        sliding velocity = radius * relative angular speed.
    contact_area : float
        Nominal contact area of the pin [m^2]: pressure = load / area.
    system_error : float
        Constant torque offset of the sensor [N m], subtracted from every
        reading (from the hanging-weight test).
    g : float
        Gravity [m/s^2] used for loads given as a mass (dead weights).
    internal_speed : numpy.ndarray or None
        Disc speeds of the internal-torque table [rad/s], increasing.
    internal_torque_table : numpy.ndarray or None
        No-contact torque at those speeds [N m] (system error excluded).
    torque_range : float or None
        Sensor full scale [N m]; readings at 99.5 % of it count as saturated.
    filter, window, outliers : settings
        See :class:`FilterSettings`, :class:`WindowSettings`, :class:`OutlierSettings`.
    group_speed_step : float
        Without a ``condition`` column, records whose disc and pin speeds differ
        by less than this [rad/s] belong to the same condition.
    source : str
        Where the description came from.
    """

    track_radius: float = 0.040
    contact_area: float = math.pi * 0.010**2
    system_error: float = 0.0
    g: float = 9.8
    internal_speed: np.ndarray | None = None
    internal_torque_table: np.ndarray | None = None
    torque_range: float | None = None
    filter: FilterSettings = field(default_factory=FilterSettings)
    window: WindowSettings = field(default_factory=WindowSettings)
    outliers: OutlierSettings = field(default_factory=OutlierSettings)
    group_speed_step: float = 10.0 * RPM
    source: str = "<defaults>"

    def internal_torque(self, disc_speed: Any) -> np.ndarray:
        """The no-contact torque [N m] at ``disc_speed`` [rad/s] (by |speed|).

        Linear interpolation in the table; outside it the end values are held
        (see :meth:`internal_range_rpm` to warn about that).  Zero when the rig
        has no table.
        """
        w = np.abs(np.asarray(disc_speed, dtype=float))
        if self.internal_speed is None or self.internal_torque_table is None:
            return np.zeros_like(w)
        return np.interp(w, self.internal_speed, self.internal_torque_table)

    def internal_range_rpm(self) -> tuple[float, float] | None:
        """The disc-speed range covered by the internal-torque table [rpm]."""
        if self.internal_speed is None:
            return None
        return float(self.internal_speed[0] / RPM), float(self.internal_speed[-1] / RPM)

    def to_toml(self) -> str:
        """The rig as TOML text that :func:`load_rig` reads back to the same values."""
        f, w, o = self.filter, self.window, self.outliers
        lines = [
            f'track_radius = "{self.track_radius * 1e3:.10g} mm"',
            f'contact_area = "{self.contact_area * 1e6:.10g} mm^2"',
            f'system_error = "{self.system_error:.10g} N*m"',
            f'g = "{self.g:.10g} m/s^2"',
        ]
        if self.torque_range is not None:
            lines.append(f'torque_range = "{self.torque_range:.10g} N*m"')
        if self.internal_speed is not None and self.internal_torque_table is not None:
            rpm = ", ".join(f"{x / RPM:.10g}" for x in self.internal_speed)
            tq = ", ".join(f"{x:.10g}" for x in self.internal_torque_table)
            lines += ["", "[internal_torque]", f"disc_speed_rpm = [{rpm}]",
                      f"torque_Nm = [{tq}]"]
        cutoff = '"auto"' if f.cutoff is None else f'"{f.cutoff:.10g} Hz"'
        lines += ["", "[filter]", f"cutoff = {cutoff}", f"order = {f.order}",
                  f'auto_min = "{f.auto_min:.10g} Hz"', f'auto_max = "{f.auto_max:.10g} Hz"',
                  f"auto_snr = {f.auto_snr:.10g}"]
        lines += ["", "[window]"]
        for fl in fields(WindowSettings):
            val = getattr(w, fl.name)
            if fl.name in _WINDOW_FRACTIONS:
                lines.append(f"{fl.name} = {val:.10g}")
            else:
                lines.append(f'{fl.name} = "{val:.10g} s"')
        lines += ["", "[outliers]", f'rule = "{o.rule}"', f"alpha = {o.alpha:.10g}"]
        lines += ["", "[grouping]", f'speed_step = "{self.group_speed_step / RPM:.10g} rpm"']
        return "\n".join(lines) + "\n"

    def describe(self) -> dict[str, Any]:
        """The rig in display units (JSON-able), for reports."""
        return {
            "source": self.source,
            "track_radius [mm]": self.track_radius * 1e3,
            "contact_area [mm^2]": self.contact_area * 1e6,
            "system_error [N m]": self.system_error,
            "g [m/s^2]": self.g,
            "torque_range [N m]": self.torque_range,
            "internal_torque": None if self.internal_speed is None else {
                "disc_speed [rpm]": (self.internal_speed / RPM).tolist(),
                "torque [N m]": np.asarray(self.internal_torque_table).tolist()},
            "filter cutoff [Hz]": "auto" if self.filter.cutoff is None else self.filter.cutoff,
            "outlier rule": self.outliers.rule,
            "outlier alpha": self.outliers.alpha,
        }


#: The outlier rules a rig may name.
OUTLIER_RULES = ("pooled", "grubbs", "none")
_WINDOW_FRACTIONS = {"speed_tolerance", "level_tolerance", "noise_factor", "min_mu",
                     "start_tolerance"}
_TOP_KEYS = {"track_radius", "pin_diameter", "contact_area", "system_error", "g",
             "torque_range", "internal_torque", "filter", "window", "outliers", "grouping",
             "name", "description"}


def load_rig(path: str | os.PathLike[str]) -> Rig:
    """Read a rig description from a TOML file.

    Parameters
    ----------
    path : str or path
        The TOML file (format in the module docstring).

    Returns
    -------
    Rig
        The rig geometry and calibration in SI (track radius [m], contact area
        [m^2], torques [N m], disc speeds [rad/s]) and its processing settings,
        with ``source`` set to ``path``.

    Raises
    ------
    InputError
        For a missing or malformed file, an unknown key, a value without a unit
        or with the wrong dimension, or an inconsistent internal-torque table.
    """
    if not isinstance(path, (str, os.PathLike)):
        raise InputError(f"load_rig takes the path of a TOML file, got {type(path).__name__}"
                         " (build a rig from a mapping with rig_from_dict)")
    src = os.fspath(path)
    p = Path(src)
    if not p.exists():
        raise InputError("rig file not found; expected a TOML rig description", file=src)
    if p.is_dir():
        raise InputError("is a directory; expected a TOML rig description", file=src)
    check_input_file(p, "rig file")  # no FIFO; registered as read, never overwritten
    raw = read_input(p, "rig file", src)  # bounded in size
    try:
        data = tomllib.loads(raw.decode("utf-8-sig"))
    except UnicodeDecodeError:
        raise InputError("is not a UTF-8 text file; expected a TOML rig description",
                         file=src) from None
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"is not valid TOML: {exc}", file=src) from None
    except RecursionError:  # arrays or inline tables nested thousands deep
        raise nesting_error("rig file", src) from None
    check_nesting(data, "rig file", src)
    return rig_from_dict(data, source=src)


def _quantity(table: Mapping[str, Any], key: str, kind: str, src: str, prefix: str = "",
              default: Any = None, required: bool = False, sign: str = "positive") -> Any:
    name = f"{prefix}{key}"
    if key not in table:
        if required:
            raise InputError(f"missing '{name}' (e.g. {name} = \"{_EXAMPLE[kind]}\")", file=src)
        return default
    raw = table[key]
    if isinstance(raw, bool) or not isinstance(raw, (str, int, float)):
        raise InputError(f"'{name}' must be a string with a unit, e.g. "
                         f"{name} = \"{_EXAMPLE[kind]}\"", file=src)
    if isinstance(raw, (int, float)) and raw != 0:
        raise InputError(f"'{name} = {raw}' has no unit; write e.g. "
                         f"{name} = \"{_EXAMPLE[kind]}\"", file=src)
    value = parse_quantity(raw, kind, what=f"'{name}'", file=src)
    if sign == "positive" and not value > 0:
        raise InputError(f"'{name}' must be > 0, got {raw!r}", file=src)
    if sign == "nonneg" and value < 0:
        raise InputError(f"'{name}' must be >= 0, got {raw!r}", file=src)
    return RANGES[name].check(name, value, raw, src) if name in RANGES else value


_EXAMPLE = {"length": "40 mm", "area": "314.16 mm^2", "torque": "0.3 N*m",
            "time": "0.5 s", "frequency": "20 Hz", "angular_velocity": "10 rpm"}


def _acceleration(raw: Any, name: str, src: str) -> float:
    if isinstance(raw, bool) or not isinstance(raw, str):
        raise InputError(f"'{name}' must be a string with a unit, e.g. {name} = \"9.8 m/s^2\"",
                         file=src)
    value = parse_quantity(raw, "acceleration", what=f"'{name}'", file=src)
    if not value > 0 or not math.isfinite(value):
        raise InputError(f"'{name}' must be > 0, got {raw!r}", file=src)
    return RANGES[name].check(name, value, raw, src)


def _number(table: Mapping[str, Any], key: str, src: str, prefix: str, default: float,
            lo: float, hi: float) -> float:
    if key not in table:
        return default
    raw = table[key]
    if isinstance(raw, bool) or not isinstance(raw, (int, float)):
        raise InputError(f"'{prefix}{key}' must be a number, got {raw!r}", file=src)
    if not (lo <= float(raw) <= hi):
        raise InputError(f"'{prefix}{key}' = {raw} is outside {lo:g}..{hi:g}", file=src)
    return float(raw)


def _check_keys(table: Any, allowed: set[str], src: str, where: str) -> None:
    if not isinstance(table, Mapping):
        raise InputError(f"'{where}' must be a table, e.g. [{where}]", file=src)
    unknown = sorted(set(table) - allowed)
    if unknown:
        place = f"[{where}]" if where else "the top level"
        raise InputError(
            f"unknown key{'s' if len(unknown) > 1 else ''} "
            f"{', '.join(repr(u) for u in unknown)} in {place}"
            f"; expected {', '.join(sorted(allowed))}",
            file=src,
        )


def rig_from_dict(data: Mapping[str, Any], *, source: str = "<dict>") -> Rig:
    """Build a :class:`Rig` from a parsed TOML table (see :func:`load_rig`)."""
    src = source
    _check_keys(data, _TOP_KEYS, src, "")
    radius = _quantity(data, "track_radius", "length", src, required=True)
    area = _contact_area(data, src)
    system_error = _quantity(data, "system_error", "torque", src, default=0.0,
                             sign="any")
    g = _acceleration(data["g"], "g", src) if "g" in data else 9.8
    torque_range = _quantity(data, "torque_range", "torque", src)
    speeds, table = (_internal_torque(data["internal_torque"], src)
                     if "internal_torque" in data else (None, None))
    filt = _filter_settings(data["filter"], src) if "filter" in data else FilterSettings()
    win = _window_settings(data["window"], src) if "window" in data else WindowSettings()
    out = (_outlier_settings(data["outliers"], src) if "outliers" in data
           else OutlierSettings())
    step = 10.0 * RPM
    if "grouping" in data:
        gt = data["grouping"]
        _check_keys(gt, {"speed_step"}, src, "grouping")
        step = _angular(gt, "speed_step", src, "grouping.", step)

    return Rig(track_radius=radius, contact_area=area, system_error=system_error, g=g,
               internal_speed=speeds, internal_torque_table=table, torque_range=torque_range,
               filter=filt, window=win, outliers=out, group_speed_step=step, source=src)


def _contact_area(data: Mapping[str, Any], src: str) -> float:
    """The pin's contact area [m^2], from ``contact_area`` or ``pin_diameter`` (one of them)."""
    if "contact_area" in data and "pin_diameter" in data:
        raise InputError("give either 'pin_diameter' or 'contact_area', not both", file=src)
    if "contact_area" in data:
        return _quantity(data, "contact_area", "area", src)
    if "pin_diameter" in data:
        d = _quantity(data, "pin_diameter", "length", src)
        return math.pi * d * d / 4.0
    raise InputError("missing 'pin_diameter' (e.g. pin_diameter = \"20 mm\") or "
                     "'contact_area' (e.g. contact_area = \"314.16 mm^2\")", file=src)


def _internal_torque(it: Mapping[str, Any], src: str) -> tuple[np.ndarray, np.ndarray]:
    """The ``[internal_torque]`` table: disc speeds [rad/s] (ascending) and torques [N m]."""
    _check_keys(it, {"disc_speed_rpm", "torque_Nm"}, src, "internal_torque")
    for key in ("disc_speed_rpm", "torque_Nm"):
        if key not in it:
            raise InputError(f"[internal_torque] needs '{key}' (a list of numbers)",
                             file=src)
    try:
        rpm = np.asarray(it["disc_speed_rpm"], dtype=float)
        tq = np.asarray(it["torque_Nm"], dtype=float)
    except (TypeError, ValueError):
        raise InputError("[internal_torque]: disc_speed_rpm and torque_Nm must be lists "
                         "of numbers", file=src) from None
    if rpm.ndim != 1 or tq.ndim != 1 or rpm.size == 0 or rpm.size != tq.size:
        raise InputError(
            f"[internal_torque]: disc_speed_rpm ({rpm.size} values) and torque_Nm "
            f"({tq.size} values) must be non-empty lists of the same length", file=src)
    if not (np.all(np.isfinite(rpm)) and np.all(np.isfinite(tq))):
        raise InputError("[internal_torque]: values must be finite numbers", file=src)
    if np.any(rpm < 0):
        raise InputError("[internal_torque]: disc_speed_rpm must be >= 0 (speeds are "
                         "looked up by magnitude)", file=src)
    order = np.argsort(rpm, kind="stable")
    rpm, tq = rpm[order], tq[order]
    if np.any(np.diff(rpm) == 0):
        raise InputError("[internal_torque]: disc_speed_rpm has a repeated value",
                         file=src)
    return rpm * RPM, tq


def _filter_settings(ft: Mapping[str, Any], src: str) -> FilterSettings:
    """The ``[filter]`` table (cutoff ``"auto"`` or a frequency, order 1..10)."""
    _check_keys(ft, {"cutoff", "order", "auto_min", "auto_max", "auto_snr"}, src, "filter")
    cutoff: float | None = None
    raw = ft.get("cutoff", "auto")
    if not (isinstance(raw, str) and raw.strip().lower() == "auto"):
        cutoff = _quantity(ft, "cutoff", "frequency", src, prefix="filter.")
    order = ft.get("order", 4)
    if isinstance(order, bool) or not isinstance(order, int) or not 1 <= order <= 10:
        raise InputError(f"'filter.order' must be an integer 1..10, got {order!r}",
                         file=src)
    return FilterSettings(
        cutoff=cutoff, order=order,
        auto_min=_quantity(ft, "auto_min", "frequency", src, prefix="filter.",
                           default=1.0),
        auto_max=_quantity(ft, "auto_max", "frequency", src, prefix="filter.",
                           default=0.0, sign="nonneg"),
        auto_snr=_number(ft, "auto_snr", src, "filter.", 10.0, 1.0, 1e6),
    )


def _window_settings(wt: Mapping[str, Any], src: str) -> WindowSettings:
    """The ``[window]`` table: fractions as numbers, durations as times."""
    names = {f.name for f in fields(WindowSettings)}
    _check_keys(wt, names, src, "window")
    kw: dict[str, float] = {}
    for name in names:
        if name not in wt:
            continue
        if name in _WINDOW_FRACTIONS:
            hi = 100.0 if name in ("noise_factor", "min_mu") else 1.0
            kw[name] = _number(wt, name, src, "window.", 0.0, 0.0, hi)
        else:
            kw[name] = _quantity(wt, name, "time", src, prefix="window.", sign="nonneg")
    return WindowSettings(**kw)


def _outlier_settings(ot: Mapping[str, Any], src: str) -> OutlierSettings:
    """The ``[outliers]`` table: the rule and its significance level."""
    _check_keys(ot, {"rule", "alpha"}, src, "outliers")
    rule = str(ot.get("rule", "pooled")).strip().lower()
    if rule not in OUTLIER_RULES:
        raise InputError(f"'outliers.rule' = {ot.get('rule')!r}; expected one of "
                         f"{', '.join(OUTLIER_RULES)}", file=src)
    return OutlierSettings(rule=rule, alpha=_number(ot, "alpha", src, "outliers.", 0.01,
                                                    1e-6, 0.5))


def _angular(table: Mapping[str, Any], key: str, src: str, prefix: str, default: float) -> float:
    if key not in table:
        return default

    raw = table[key]
    if not isinstance(raw, str):
        raise InputError(f"'{prefix}{key}' must be a string with a unit, e.g. \"10 rpm\"",
                         file=src)
    parts = raw.strip().split(None, 1)

    try:
        number = parse_number(parts[0])  # the one number parser (no 1_0, no overflow)
    except (ValueError, IndexError):
        raise InputError(f"'{prefix}{key} = \"{raw}\"' is not a number with a unit; "
                         "expected e.g. \"10 rpm\"", file=src) from None
    if len(parts) < 2:
        raise InputError(f"'{prefix}{key} = \"{raw}\"' has no unit; expected e.g. \"10 rpm\"",
                         file=src)
    value = number * angular_unit_factor(parts[1], column=f"{prefix}{key}", file=src)
    if not value > 0:
        raise InputError(f"'{prefix}{key}' must be > 0", file=src)
    return RANGES[prefix + key].check(prefix + key, value, raw, src)
