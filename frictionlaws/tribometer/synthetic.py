"""Synthetic raw records and campaigns with a known friction coefficient.

Used by the tests, the benchmark and the docs.  A synthetic record mimics the
phases of a real pin-on-disc test (thesis chapter 4):

1. the pin is loaded, the motors are off: the reading is the sensor offset;
2. the first motor starts (speed ramp) and the friction torque rises;
3. a start-up peak ``mu * (1 + peak)`` decays with time constant ``peak_tau``
   (with a rotating pin: the disc runs first with a small friction
   ``pre_fraction * mu``, and the peak comes when the pin motor starts);
4. steady sliding at ``mu``, with a per-revolution ripple;
5. the motors stop (the rotating pin first) and the friction torque vanishes.

On top of the friction torque ``mu * F_N * r`` the reading carries the rig's
offsets (the system error and the internal torque at the current disc speed,
from the rig description, plus an optional ``offset_error`` the calibration
does not know about), white noise, mains hum, and a rig vibration at a natural
frequency that is excited while the motors run.  Readings beyond the sensor's
``torque_range`` are clipped, as a saturated sensor does.

In ``initial`` mode (abrasive surfaces) the reading decays after
``debris_onset`` seconds of full sliding, so only the first seconds hold the
true value.

Each record of a condition gets its own coefficient,
``mu_record = mu * (1 + repeat_sd * N(0, 1))``: repeat-to-repeat scatter, so
that a condition's mean estimates ``mu`` and its Student-t interval has
something real to cover.
"""

from __future__ import annotations

import csv
import math
import os
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from ..base.outputs import check_unique_names
from ..parallel import run_parallel
from .records import Record, write_record
from .rig import RPM, Rig

__all__ = [
    "RecordSpec",
    "ConditionSpec",
    "generate_record",
    "synthetic_rig",
    "internal_torque_truth",
    "make_campaign",
    "campaign_truth",
    "campaign_records",
    "thesis_conditions",
    "hanging_weight_readings",
    "no_contact_run",
    "CampaignTruth",
]


def internal_torque_truth(rpm: Any) -> np.ndarray:
    """A plausible internal (no-contact) torque curve [N m] vs |disc speed| [rpm].

    High at break-away, a dip after start-up, a rise near the top speed, as the
    thesis describes its calibration curve.
    """
    n = np.abs(np.asarray(rpm, dtype=float))
    return 0.05 + 0.06 * np.exp(-n / 50.0) + 0.08 * (n / 700.0) ** 3


#: Disc speeds [rpm] of the internal-torque table of :func:`synthetic_rig`.
INTERNAL_RPM = (0.0, 25.0, 50.0, 100.0, 150.0, 200.0, 300.0, 400.0, 500.0, 600.0, 700.0)


def synthetic_rig(**overrides: Any) -> Rig:
    """The thesis rig: r = 40 mm, 20 mm pin, system error 0.3 N m, g = 9.8, 10 N m sensor.

    The internal torque table samples :func:`internal_torque_truth`.  Keyword
    arguments replace fields of the :class:`~frictionlaws.tribometer.rig.Rig`.
    """
    rpm = np.asarray(INTERNAL_RPM)
    rig = Rig(track_radius=0.040, contact_area=math.pi * 0.010**2, system_error=0.3, g=9.8,
              internal_speed=rpm * RPM, internal_torque_table=internal_torque_truth(rpm),
              torque_range=10.0, source="synthetic")
    return replace(rig, **overrides) if overrides else rig


@dataclass(frozen=True)
class RecordSpec:
    """What a synthetic record contains.

    Attributes
    ----------
    mu : float
        Steady friction coefficient of this record.
    load : float
        Normal load [N].
    disc_rpm, pin_rpm : float
        Signed plateau speeds [rpm] (opposite signs: counter-rotating); 0 for a
        fixed disc or pin.
    mode : {"steady", "initial"}
        ``initial``: the reading decays after ``debris_onset`` (abrasive surface).
    duration, fs : float
        Record length [s] and sampling rate [Hz].
    t_start, t_stop : float
        First motor on / off [s].
    t_second : float
        Delay of the second motor after the first (and before it on stopping) [s].
    ramp : float
        Speed ramp time of the motors [s].
    peak, peak_tau : float
        Start-up peak height (relative to ``mu``) and decay time [s].
    pre_fraction : float
        Friction while only the first motor runs (rotating pin), relative to mu.
    ripple : float
        Per-revolution ripple amplitude relative to the friction torque.
    noise : float
        White noise standard deviation [N m].
    hum, hum_freq : float
        Mains hum amplitude [N m] and frequency [Hz].
    vibration, vib_freq : float
        Rig vibration amplitude [N m] (while the motors run) and natural frequency [Hz].
    offset_error : float
        Offset in the reading not in the rig's calibration [N m].
    debris_onset, debris_drop, debris_tau : float
        ``initial`` mode: decay starts after this much full sliding [s], relative
        drop, decay time [s].
    speed_noise : float
        Standard deviation of the speed readings [rpm].
    """

    mu: float
    load: float
    disc_rpm: float = 331.0
    pin_rpm: float = 0.0
    mode: str = "steady"
    duration: float = 30.0
    fs: float = 1000.0
    t_start: float = 4.0
    t_stop: float = 26.0
    t_second: float = 2.0
    ramp: float = 0.5
    peak: float = 0.4
    peak_tau: float = 0.8
    pre_fraction: float = 0.2
    ripple: float = 0.03
    noise: float = 0.02
    hum: float = 0.02
    hum_freq: float = 50.0
    vibration: float = 0.05
    vib_freq: float = 37.0
    offset_error: float = 0.0
    debris_onset: float = 5.0
    debris_drop: float = 0.3
    debris_tau: float = 3.0
    speed_noise: float = 0.5


def _profile(t: np.ndarray, on: float, off: float, ramp: float) -> np.ndarray:
    """0..1 motor speed profile: linear ramps up at ``on`` and down at ``off``."""
    up = np.clip((t - on) / ramp, 0.0, 1.0)
    down = np.clip((off - t) / ramp, 0.0, 1.0)
    return np.minimum(up, down)


def generate_record(spec: RecordSpec, rig: Rig, rng: np.random.Generator | int | None = None,
                    *, source: str = "<synthetic>") -> Record:
    """Generate one raw record (see the module docstring for the signal model).

    Parameters
    ----------
    spec : RecordSpec
        What the record contains.
    rig : Rig
        Geometry and offsets (system error, internal torque, sensor range).
    rng : numpy.random.Generator or int, optional
        Random source (or seed).
    source : str
        Name of the record.

    Returns
    -------
    Record
        Signals in SI (torque in N m, speeds in rad/s); ``pin_speed`` is None
        when ``spec.pin_rpm`` is 0.
    """
    rng = np.random.default_rng(rng)
    n = int(round(spec.duration * spec.fs))
    t = np.arange(n) / spec.fs
    disc_on = spec.disc_rpm != 0
    pin_on = spec.pin_rpm != 0
    if not (disc_on or pin_on):
        raise ValueError("a record needs a moving disc or pin")
    two = disc_on and pin_on
    first = _profile(t, spec.t_start, spec.t_stop, spec.ramp)
    second = (_profile(t, spec.t_start + spec.t_second, spec.t_stop - spec.t_second, spec.ramp)
              if two else first)
    disc_prof = first if disc_on else np.zeros(n)
    pin_prof = (second if two else first) if pin_on else np.zeros(n)
    w_disc = spec.disc_rpm * RPM * disc_prof
    w_pin = spec.pin_rpm * RPM * pin_prof
    # friction coefficient vs time
    t_full = (spec.t_start + spec.t_second if two else spec.t_start) + spec.ramp
    decay = np.where(t >= t_full, np.exp(-np.maximum(t - t_full, 0.0) / spec.peak_tau), 1.0)
    level = second * (1.0 + spec.peak * decay)
    if two:
        level = level + spec.pre_fraction * first * (1.0 - second)
    if spec.mode == "initial":
        td = t_full + spec.debris_onset
        level = level * np.where(
            t > td, 1.0 - spec.debris_drop * (1.0 - np.exp(-(t - td) / spec.debris_tau)), 1.0)
    rel_rpm = abs(spec.pin_rpm - spec.disc_rpm) if two else abs(spec.disc_rpm or spec.pin_rpm)
    f_rev = rel_rpm / 60.0
    ripple = 1.0 + spec.ripple * second * np.sin(2 * np.pi * f_rev * t + rng.uniform(0, 6.3))
    torque_fric = spec.mu * spec.load * rig.track_radius * level * ripple
    running = np.maximum(first, second)
    reading = (rig.system_error + spec.offset_error + rig.internal_torque(w_disc) + torque_fric
               + spec.noise * rng.standard_normal(n)
               + spec.hum * np.sin(2 * np.pi * spec.hum_freq * t + rng.uniform(0, 6.3))
               + spec.vibration * running
               * np.sin(2 * np.pi * spec.vib_freq * t + rng.uniform(0, 6.3)))
    if rig.torque_range is not None:
        np.clip(reading, -rig.torque_range, rig.torque_range, out=reading)
    sn = spec.speed_noise * RPM
    disc = w_disc + (sn * rng.standard_normal(n) if disc_on else 0.0)
    pin = (w_pin + sn * rng.standard_normal(n)) if pin_on else None
    return Record(t, reading, disc, pin, source=source,
                  units={"time": "s", "torque": "N m", "disc_speed": "rpm", "pin_speed": "rpm"})


@dataclass(frozen=True)
class ConditionSpec:
    """A test condition of a synthetic campaign.

    Attributes
    ----------
    name : str
        Condition label (written to the manifest's ``condition`` column).
    surface : str
        Counter-surface.
    load_kg : float
        Dead weight [kg]; the load is ``load_kg * rig.g``.
    mu : float
        True friction coefficient of the condition.
    repeats : int
        Number of records.
    disc_rpm, pin_rpm : float
        Signed speeds [rpm].
    mode : {"steady", "initial"}
    repeat_sd : float
        Relative repeat-to-repeat scatter of the record coefficients.

    Records of ``initial``-mode conditions get a short start-up peak
    (``peak_tau = 0.3 s``) unless ``record_kwargs`` sets one.
    """

    name: str
    surface: str
    load_kg: float
    mu: float
    repeats: int = 5
    disc_rpm: float = 331.0
    pin_rpm: float = 0.0
    mode: str = "steady"
    repeat_sd: float = 0.02


@dataclass
class CampaignTruth:
    """What a synthetic campaign contains: the true values, per record and condition."""

    directory: Path | None
    manifest: Path | None
    rig_file: Path | None
    records: list[dict[str, Any]] = field(default_factory=list)
    conditions: list[ConditionSpec] = field(default_factory=list)

    def condition_mu(self) -> dict[str, float]:
        """Condition name -> true mu."""
        return {c.name: c.mu for c in self.conditions}

    def record_mu(self) -> dict[str, float]:
        """Record file -> the coefficient that record was generated with."""
        return {r["file"]: r["mu_record"] for r in self.records}


def _record_specs(conditions: Sequence[ConditionSpec], rig: Rig, seed: int,
                  record_kwargs: dict[str, Any] | None) -> list[tuple[ConditionSpec, RecordSpec,
                                                                       int, str]]:
    rng = np.random.default_rng(seed)
    out = []
    kw = dict(record_kwargs or {})
    k = 0
    for c in conditions:
        for i in range(c.repeats):
            mu_r = c.mu * (1.0 + c.repeat_sd * rng.standard_normal())
            jitter = dict(t_start=kw.get("t_start", 4.0) + rng.uniform(-1.0, 1.0),
                          t_stop=kw.get("t_stop", 26.0) + rng.uniform(-1.0, 1.0))
            extra = {key: v for key, v in kw.items() if key not in ("t_start", "t_stop")}
            if "duration" in extra and "t_stop" not in kw:
                d = extra["duration"]
                jitter = dict(t_start=0.13 * d + rng.uniform(-0.03, 0.03) * d,
                              t_stop=0.87 * d + rng.uniform(-0.03, 0.03) * d)
            if c.mode == "initial" and "peak_tau" not in extra:
                extra["peak_tau"] = 0.3  # abrasive surfaces: a short start-up peak
            spec = RecordSpec(mu=mu_r, load=c.load_kg * rig.g, disc_rpm=c.disc_rpm,
                              pin_rpm=c.pin_rpm, mode=c.mode, **{**jitter, **extra})
            name = f"{_slug(c.name)}_{i + 1:02d}.csv"
            out.append((c, spec, int(rng.integers(2**31)), name))
            k += 1
    return out


def _slug(text: str) -> str:
    keep = [ch if ch.isalnum() or ch in "-." else "_" for ch in text.strip()]
    return "".join(keep).strip("_") or "record"


def campaign_records(conditions: Sequence[ConditionSpec], rig: Rig | None = None, *,
                     seed: int = 0, record_kwargs: dict[str, Any] | None = None
                     ) -> tuple[list[Record], list[dict[str, Any]], CampaignTruth]:
    """Generate a campaign in memory (no files): records, manifest rows and truth.

    Returns
    -------
    records : list of Record
    manifest : list of dict
        One row per record: ``file``, ``load [kg]``, ``surface``,
        ``condition``, ``mode`` (what :func:`make_campaign` writes).
    truth : CampaignTruth
    """
    rig = rig or synthetic_rig()
    records, rows = [], []
    truth = CampaignTruth(None, None, None, conditions=list(conditions))
    for c, spec, rseed, name in _record_specs(conditions, rig, seed, record_kwargs):
        records.append(generate_record(spec, rig, rseed, source=name))
        rows.append({"file": name, "load [kg]": c.load_kg, "surface": c.surface,
                     "condition": c.name, "mode": c.mode})
        truth.records.append({"file": name, "condition": c.name, "mu_record": spec.mu,
                              "mu_condition": c.mu, **{k: v for k, v in asdict(spec).items()
                                                       if k != "mu"}})
    return records, rows, truth


def campaign_truth(directory: str | os.PathLike[str], conditions: Sequence[ConditionSpec], *,
                   rig: Rig | None = None, seed: int = 0,
                   record_kwargs: dict[str, Any] | None = None) -> CampaignTruth:
    """The truth of the campaign :func:`make_campaign` writes with the same arguments.

    Nothing is generated or written: use it to check a campaign written earlier.
    """
    rig = rig or synthetic_rig()
    root = Path(directory)
    truth = CampaignTruth(root, root / "manifest.csv", root / "rig.toml",
                          conditions=list(conditions))
    for c, spec, _, name in _record_specs(conditions, rig, seed, record_kwargs):
        truth.records.append({"file": f"records/{name}", "condition": c.name,
                              "mu_record": spec.mu, "mu_condition": c.mu})
    return truth


def _write_one(args: tuple[str, RecordSpec, int, Rig, str]) -> None:
    path, spec, rseed, rig, name = args
    write_record(path, generate_record(spec, rig, rseed, source=name))


def make_campaign(
    directory: str | os.PathLike[str],
    conditions: Sequence[ConditionSpec],
    *,
    rig: Rig | None = None,
    seed: int = 0,
    record_kwargs: dict[str, Any] | None = None,
    jobs: int = 1,
) -> CampaignTruth:
    """Write a synthetic campaign: ``rig.toml``, ``manifest.csv`` and ``records/*.csv``.

    Parameters
    ----------
    directory : str or path
        Created if needed.
    conditions : sequence of ConditionSpec
        The test conditions.
    rig : Rig, optional
        Default :func:`synthetic_rig`.
    seed : int
        Seed of everything random.
    record_kwargs : dict, optional
        Fields of :class:`RecordSpec` applied to every record (e.g.
        ``{"duration": 10.0}``).
    jobs : int
        Worker processes used to write the files.

    Returns
    -------
    CampaignTruth
    """
    rig = rig or synthetic_rig()
    root = Path(directory)
    specs = _record_specs(conditions, rig, seed, record_kwargs)
    check_unique_names([(f"condition '{c.name}'", name) for c, _, _, name in specs],
                       what="records")  # one file per record, before any is written
    (root / "records").mkdir(parents=True, exist_ok=True)
    rig_file = root / "rig.toml"
    rig_file.write_text("# synthetic rig (frictionlaws.tribometer.synthetic)\n" + rig.to_toml(),
                        encoding="utf-8")
    tasks = [(str(root / "records" / name), spec, rseed, rig, name)
             for _, spec, rseed, name in specs]

    run_parallel(_write_one, tasks, jobs=jobs if len(tasks) > 8 else 1)
    rows = [["file", "load [kg]", "surface", "condition", "mode"]]
    rows += [[f"records/{name}", f"{c.load_kg:g}", c.surface, c.name, c.mode]
             for c, _, _, name in specs]
    truth = campaign_truth(root, conditions, rig=rig, seed=seed, record_kwargs=record_kwargs)
    assert truth.manifest is not None
    with truth.manifest.open("w", encoding="utf-8", newline="") as out:
        csv.writer(out, lineterminator="\n").writerows(rows)  # quotes a name with a comma
    return truth


#: Valid test counts of the thesis campaign (Table 4-2), with the speeds used here.
THESIS_GROUPS: tuple[tuple[str, str, int, float, float, str, float], ...] = (
    # label, surface, records, disc rpm, pin rpm, mode, mu factor
    ("steel fixed disc", "steel", 167, 0.0, 331.0, "steady", 1.0),
    ("steel 5 km/h", "steel", 169, 331.0, -120.0, "steady", 1.05),
    ("steel 10 km/h", "steel", 174, 663.0, -120.0, "steady", 1.08),
    ("steel same direction", "steel", 82, 331.0, 500.0, "steady", 1.02),
    ("glass", "glass", 120, 331.0, -120.0, "steady", 1.1),
    ("sandpaper 120 fixed disc", "sandpaper 120", 27, 0.0, 331.0, "initial", 0.65),
    ("sandpaper 120 5 km/h", "sandpaper 120", 31, 331.0, -120.0, "initial", 0.68),
    ("sandpaper 120 10 km/h", "sandpaper 120", 30, 663.0, -120.0, "initial", 0.7),
    ("sandpaper 400", "sandpaper 400", 43, 331.0, -120.0, "initial", 0.8),
)


def _mu_of_pressure(p_mpa: float) -> float:
    """A decreasing-then-level mu(p) resembling the thesis' steel data."""
    return 1.1 + 4.4 * math.exp(-p_mpa / 0.04)


def thesis_conditions(seed: int = 0) -> list[ConditionSpec]:
    """Conditions of a campaign the size of the thesis' (843 records, Table 4-2).

    Each group of Table 4-2 is split into loads of 1..8 kg with 3..7 repeats
    (2..3 on sandpaper) so that the record counts match the table exactly.
    """
    rng = np.random.default_rng(seed)
    out: list[ConditionSpec] = []
    loads = (1.0, 2.0, 3.0, 3.5, 4.0, 4.5, 5.0, 5.5, 6.0, 7.0, 8.0)
    area_mm2 = math.pi * 100.0
    for label, surface, count, disc, pin, mode, factor in THESIS_GROUPS:
        lo, hi = (2, 3) if mode == "initial" else (3, 7)
        left, k = count, 0
        while left > 0:
            reps = int(rng.integers(lo, hi + 1))
            if left - reps < lo and left - reps != 0:
                reps = left if left <= hi else left - lo
            reps = min(reps, left)
            load = loads[k % len(loads)]
            p_mpa = load * 9.8 / area_mm2
            mu = factor * _mu_of_pressure(p_mpa)
            sd = 0.06 if surface == "glass" else 0.03
            out.append(ConditionSpec(f"{label} {load:g} kg #{k // len(loads) + 1}", surface,
                                     load, round(mu, 4), reps, disc, pin, mode, sd))
            left -= reps
            k += 1
    return out


def hanging_weight_readings(masses: Sequence[float], *, radius: float = 0.040,
                            system_error: float = 0.3, g: float = 9.8, noise: float = 0.005,
                            gain: float = 1.0, rng: np.random.Generator | int | None = None
                            ) -> np.ndarray:
    """Torque readings [N m] of a hanging-weight calibration (mass ``m`` on a rope at ``radius``).

    ``reading = gain * m * g * radius + system_error + noise``.
    """
    rng = np.random.default_rng(rng)
    m = np.asarray(masses, dtype=float)
    return gain * m * g * radius + system_error + noise * rng.standard_normal(m.size)


def no_contact_run(rig: Rig, *, max_rpm: float = 700.0, duration: float = 40.0,
                   fs: float = 1000.0, noise: float = 0.01,
                   curve: Any = internal_torque_truth, rng: np.random.Generator | int | None = None,
                   source: str = "<no-contact>") -> Record:
    """A no-contact calibration run: the disc sweeps 0 -> ``max_rpm`` -> 0, no pin.

    The reading is ``system_error + curve(|rpm|) + noise``.
    """
    rng = np.random.default_rng(rng)
    n = int(round(duration * fs))
    t = np.arange(n) / fs
    rpm = max_rpm * (1.0 - np.abs(2.0 * t / duration - 1.0))
    reading = rig.system_error + curve(rpm) + noise * rng.standard_normal(n)
    return Record(t, reading, rpm * RPM, None, source=source,
                  units={"time": "s", "torque": "N m", "disc_speed": "rpm"})
