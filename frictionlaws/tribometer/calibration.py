"""Calibration of the rig's offsets: system error and internal torque.

System error (hanging-weight test)
    Known masses hang from a rope wound on the disc (radius ``r``), so the
    shaft carries the known torque ``m g r``; the sensor reads
    ``reading = known + system_error``.  :func:`system_error_from_weights`
    estimates the offset as the mean of ``reading - known`` with its Student-t
    95 % interval, and checks the constant-offset model by a straight-line fit
    of reading against known torque: a slope that differs significantly from 1
    is reported (a gain error is not an offset).  The thesis used 1..4 kg,
    3 repeats each, and found 0.3 N m.

Internal torque (no-contact runs)
    With the pin lifted, the reading is ``system_error + internal(|w_disc|)``
    (bearings, seals, belt).  :func:`internal_torque_from_runs` bins the
    samples of each run by disc speed, averages each bin per run and then
    across runs (each run weighs the same), and returns the curve as the
    ``[internal_torque]`` table of the rig file.  The thesis averaged 4 runs.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..base.errors import InputError
from ..base.units import parse_quantity, parse_unit, unit_registry
from .records import Record, read_record
from .rig import RPM, Rig

__all__ = [
    "SystemErrorCalibration",
    "system_error_from_weights",
    "InternalTorqueCurve",
    "internal_torque_from_runs",
]


@dataclass(frozen=True)
class SystemErrorCalibration:
    """Result of a hanging-weight calibration (torques in N m).

    Attributes
    ----------
    offset : float
        The system error: mean of ``reading - known``.
    std : float
        Standard deviation of ``reading - known`` (ddof = 1).
    ci95 : tuple of float
        95 % Student-t interval of ``offset``.
    n : int
        Number of readings.
    slope, slope_stderr, intercept : float
        Straight line ``reading = intercept + slope * known``.
    known, reading : numpy.ndarray
        The data.
    warnings : list of str
        Problems found (gain differs from 1, too few loads...).
    """

    offset: float
    std: float
    ci95: tuple[float, float]
    n: int
    slope: float
    slope_stderr: float
    intercept: float
    known: np.ndarray
    reading: np.ndarray
    warnings: list[str] = field(default_factory=list)

    def to_toml(self) -> str:
        """The line of the rig file: ``system_error = "0.3 N*m"``."""
        return f'system_error = "{self.offset:.6g} N*m"'

    def apply(self, rig: Rig) -> Rig:
        """A copy of ``rig`` with this system error."""
        return replace(rig, system_error=self.offset)

    def report(self) -> str:
        """Human-readable summary."""
        lines = [
            f"system error = {self.offset:.4g} N m (95 % CI {self.ci95[0]:.4g} .. "
            f"{self.ci95[1]:.4g}; std {self.std:.3g}; n = {self.n})",
            f"reading = {self.intercept:.4g} + {self.slope:.4g} * known torque "
            f"(slope standard error {self.slope_stderr:.2g})",
        ]
        lines += [f"warning: {w}" for w in self.warnings]
        return "\n".join(lines)


def _length(value: str | float, what: str) -> float:
    v = parse_quantity(value, "length", what=what)
    if not v > 0:
        raise InputError(f"{what} must be > 0, got {value!r}")
    return v


def system_error_from_weights(
    masses: Sequence[float] | np.ndarray,
    readings: Sequence[float] | np.ndarray,
    *,
    radius: str | float,
    g: float = 9.8,
    mass_unit: str = "kg",
    torque_unit: str = "N*m",
    gain_tolerance: float = 0.01,
) -> SystemErrorCalibration:
    """Estimate the system error from a hanging-weight test.

    Parameters
    ----------
    masses : array-like
        Hanging masses, one per reading (in ``mass_unit``).
    readings : array-like
        Steady torque readings with each mass (in ``torque_unit``).
    radius : str or float
        Radius at which the rope pulls, ``"40 mm"`` or a float in m.
    g : float
        Gravity [m/s^2] (the thesis used 9.8).
    mass_unit, torque_unit : str
        Units of the inputs (pint).
    gain_tolerance : float
        A slope further than this from 1, and significantly so (beyond its
        95 % interval), is reported as a gain error.

    Returns
    -------
    SystemErrorCalibration

    Raises
    ------
    InputError
        Different lengths, fewer than 2 readings, non-finite values, masses
        that are not positive, or wrong units.
    """
    from scipy import stats

    m_kg, r = _weights_si(masses, readings, mass_unit, torque_unit)
    rad = _length(radius, "radius")
    if not (g > 0 and math.isfinite(g)):
        raise InputError(f"g must be > 0, got {g!r}")
    known = m_kg * g * rad
    diff = r - known
    n = diff.size
    offset = float(np.mean(diff))
    sd = float(np.std(diff, ddof=1))
    t = float(stats.t.ppf(0.975, n - 1))
    half = t * sd / math.sqrt(n)
    slope, slope_se, intercept, warnings = _gain_check(known, r, gain_tolerance)
    return SystemErrorCalibration(offset, sd, (offset - half, offset + half), n, slope,
                                  slope_se, intercept, known, r, warnings)


def _weights_si(masses: Sequence[float] | np.ndarray, readings: Sequence[float] | np.ndarray,
                mass_unit: str, torque_unit: str) -> tuple[np.ndarray, np.ndarray]:
    """Checked hanging masses [kg] and torque readings [N m] of a hanging-weight test."""
    m = np.asarray(masses, dtype=float).ravel()
    r = np.asarray(readings, dtype=float).ravel()
    if m.size != r.size:
        raise InputError(f"{m.size} masses but {r.size} readings; give one reading per mass")
    if m.size < 2:
        raise InputError("need at least 2 readings for a system error with an interval")
    if not (np.all(np.isfinite(m)) and np.all(np.isfinite(r))):
        raise InputError("masses and readings must be finite numbers")
    if np.any(m <= 0):
        raise InputError(f"masses must be > 0, got {m[m <= 0][0]:g} {mass_unit}")
    ureg = unit_registry()
    mu_ = parse_unit(mass_unit, "F_N", column="mass_unit")
    if mu_.dimensionality != ureg.kilogram.dimensionality:
        raise InputError(f"mass_unit '{mass_unit}' is not a mass unit (e.g. kg, g)")
    m_kg = m * float(ureg.Quantity(1.0, mu_).to("kg").magnitude)
    tq = float(ureg.Quantity(1.0, parse_unit(torque_unit, "torque")).to("N*m").magnitude)
    return m_kg, r * tq


def _gain_check(known: np.ndarray, r: np.ndarray,
                gain_tolerance: float) -> tuple[float, float, float, list[str]]:
    """Slope, its standard error and intercept of reading vs known torque, with warnings."""
    from scipy import stats

    n = known.size
    warnings: list[str] = []
    if np.unique(known).size < 2:
        warnings.append("all readings use the same mass: the gain (slope) cannot be checked; "
                        "use several masses (the thesis used 1..4 kg)")
        return math.nan, math.nan, math.nan, warnings
    fit = stats.linregress(known, r)
    slope, slope_se, intercept = float(fit.slope), float(fit.stderr), float(fit.intercept)
    tq_ = float(stats.t.ppf(0.975, n - 2)) if n > 2 else math.inf
    if abs(slope - 1.0) > gain_tolerance and abs(slope - 1.0) > tq_ * slope_se:
        warnings.append(
            f"the reading grows {slope:.4g} times as fast as the known torque (slope "
            f"differs from 1 beyond its 95 % interval): the sensor has a gain error, "
            "which a constant system error does not correct; recalibrate the sensor")
    return slope, slope_se, intercept, warnings


@dataclass(frozen=True)
class InternalTorqueCurve:
    """Internal (no-contact) torque against disc speed.

    Attributes
    ----------
    speed_rpm : numpy.ndarray
        Mean |disc speed| of each speed bin [rpm], increasing.
    torque : numpy.ndarray
        Mean internal torque in each bin [N m] (system error removed).
    std : numpy.ndarray
        Standard deviation of the run means in each bin [N m] (NaN with one run).
    runs : numpy.ndarray
        Number of runs that contribute to each bin.
    n_runs : int
        Number of runs.
    """

    speed_rpm: np.ndarray
    torque: np.ndarray
    std: np.ndarray
    runs: np.ndarray
    n_runs: int

    def __call__(self, speed_rpm: Any) -> np.ndarray:
        """Interpolated internal torque [N m] at |speed| [rpm]."""
        return np.interp(np.abs(np.asarray(speed_rpm, dtype=float)), self.speed_rpm,
                         self.torque)

    def to_toml(self) -> str:
        """The ``[internal_torque]`` table of the rig file."""
        rpm = ", ".join(f"{x:.6g}" for x in self.speed_rpm)
        tq = ", ".join(f"{x:.6g}" for x in self.torque)
        return f"[internal_torque]\ndisc_speed_rpm = [{rpm}]\ntorque_Nm = [{tq}]\n"

    def apply(self, rig: Rig) -> Rig:
        """A copy of ``rig`` using this curve."""
        return replace(rig, internal_speed=self.speed_rpm * RPM,
                       internal_torque_table=self.torque.copy())


def internal_torque_from_runs(
    runs: Sequence[Record | str | os.PathLike[str]],
    *,
    system_error: float,
    speed_step: float = 25.0,
    min_samples: int = 50,
) -> InternalTorqueCurve:
    """Internal torque curve from no-contact runs (records or record CSV paths).

    Parameters
    ----------
    runs : sequence of Record or path
        Runs with the pin lifted, covering the disc speeds of interest.
    system_error : float
        The system error [N m], subtracted from the readings.
    speed_step : float
        Width of the speed bins [rpm]; bins are centred on multiples of it.
    min_samples : int
        A run contributes to a bin only with at least this many samples there.

    Returns
    -------
    InternalTorqueCurve

    Raises
    ------
    InputError
        No runs, unreadable runs, or no bin with enough samples.
    """
    if not runs:
        raise InputError("no no-contact runs given")
    if not speed_step > 0:
        raise InputError(f"speed_step must be > 0 rpm, got {speed_step!r}")
    per_bin: dict[int, list[tuple[float, float]]] = {}
    for run in runs:
        rec = run if isinstance(run, Record) else read_record(run)
        rec.check()
        rpm = np.abs(rec.disc_speed) / RPM
        torque = rec.torque - system_error
        k = np.rint(rpm / speed_step).astype(np.int64)
        order = np.argsort(k, kind="stable")
        ks, starts, counts = np.unique(k[order], return_index=True, return_counts=True)
        for kk, s0, c in zip(ks, starts, counts, strict=True):
            if c < min_samples:
                continue
            idx = order[s0:s0 + c]
            per_bin.setdefault(int(kk), []).append((float(np.mean(rpm[idx])),
                                                     float(np.mean(torque[idx]))))
    if not per_bin:
        raise InputError(f"no speed bin holds {min_samples} samples of any run; use longer "
                         "runs or a wider speed_step")
    keys = sorted(per_bin)
    speed = np.array([np.mean([s for s, _ in per_bin[k]]) for k in keys])
    torque = np.array([np.mean([t for _, t in per_bin[k]]) for k in keys])
    std = np.array([np.std([t for _, t in per_bin[k]], ddof=1) if len(per_bin[k]) > 1
                    else math.nan for k in keys])
    count = np.array([len(per_bin[k]) for k in keys])
    return InternalTorqueCurve(speed, torque, std, count, len(runs))
