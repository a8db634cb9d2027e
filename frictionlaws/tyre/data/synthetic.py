"""Synthetic tyre test files from a Magic Formula: raw rig runs and TYDEX sweeps, for checks.

:func:`synthetic_raw_run` measures a known tyre the way a flat-track rig of the public test
programmes does and writes what such a rig writes (:mod:`~frictionlaws.tyre.data.raw_run`):
SAE axes, kph, rpm, cm, kPa, N, N-m, one row per sample.  It starts lifted, warms the tyre
up (sweeps at the nominal load, the grip rising from :data:`COLD_GRIP` as it warms), then
steps through pressures and cambers (each changed while the tyre is lifted) and loads
(ramped on the road); at each it sweeps the slip angle up and down continuously, then holds
slip angles (zero and :attr:`RawRunSpec.combined_deg`) and sweeps the slip ratio up and down
at each.  The forces lag the slips (first order, :attr:`RawRunSpec.lag` s), the load ripples,
the force channels carry zero offsets that drift, and every channel carries noise.  The
rig's slip on the loaded radius (``SR``) differs from the effective-radius slip (``SL``) as
on a real rig.  :attr:`SyntheticRun.phase` says what each sample is, for tests.

:func:`sweep_data` makes the rows of TYDEX-like sweep files (lateral, longitudinal, combined),
noisy, in SI and ISO-W axes, to be written with
:func:`~frictionlaws.tyre.data.tydex.write_tydex`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy.signal import lfilter

from ...base.errors import InputError
from ...base.outputs import atomic_write, check_outputs
from ..mf.model import MagicFormula
from .table import TyreData

__all__ = ["RawRunSpec", "SyntheticRun", "synthetic_raw_run", "sweep_data", "COLD_GRIP",
           "RAW_UNITS", "PHASES", "LIFTED_NOISE"]

#: The grip of the cold tyre at the start of the warm-up, as a share of the warm tyre's.
COLD_GRIP = 0.9
#: The noise of the force channels of a lifted tyre, a share of the lightest load's.
LIFTED_NOISE = 0.2
#: Channel -> unit written (SI as the public programmes publish).
RAW_UNITS = {"ET": "s", "V": "kph", "N": "rpm", "SA": "deg", "IA": "deg", "RL": "cm",
             "RE": "cm", "P": "kPa", "FX": "N", "FY": "N", "FZ": "N", "MX": "N-m",
             "MZ": "N-m", "NFX": "none", "NFY": "none", "RST": "degC", "TSTI": "degC",
             "TSTC": "degC", "TSTO": "degC", "AMBTMP": "degC", "SR": "none", "SL": "none"}
#: What a sample of a synthetic run is (:attr:`SyntheticRun.phase`).
PHASES = ("lift", "warm-up", "step", "hold", "lateral", "longitudinal")


@dataclass
class RawRunSpec:
    """The test a synthetic rig runs (multiples of the tyre's FNOMIN and nominal pressure)."""

    loads: Sequence[float] = (0.4, 0.8, 1.2, 1.6)
    cambers_deg: Sequence[float] = (-3.0, 0.0, 3.0)
    pressures: Sequence[float] = (0.85, 1.1)
    alpha_max_deg: float = 12.0
    kappa_max: float = 0.25
    combined_deg: Sequence[float] = (-8.0, -4.0, 4.0, 8.0)
    combined_kappa_max: float = 0.2
    #: Samples per second.
    rate: float = 100.0
    #: Sweep speeds [deg/s] and [1/s].
    alpha_rate_deg: float = 4.0
    kappa_rate: float = 0.1
    #: Up-and-down cycles per slip-angle sweep.
    cycles: int = 2
    #: Time constant of the forces' lag behind the slips [s].
    lag: float = 0.05
    #: Noise of the forces and moments, a share of each load's peak.
    noise: float = 0.008
    #: Zero offsets of Fx [N], Fy [N], Mz [N m] at the start and the end (a drift).
    offsets: tuple[tuple[float, float, float], tuple[float, float, float]] = (
        (12.0, -25.0, 1.5), (18.0, -40.0, 2.5))
    warmup_s: float = 40.0
    speed_kph: float = 40.0
    seed: int = 7
    #: The sign of the first half of every sweep (-1: down first) and a hold at its ends [s].
    first_sign: float = -1.0
    dwell_s: float = 0.0


@dataclass
class SyntheticRun:
    """A synthetic raw run: the channels as written (SAE, file units) and what each is."""

    channels: dict[str, np.ndarray]
    phase: np.ndarray
    spec: RawRunSpec
    truth: MagicFormula
    units: dict[str, str] = field(default_factory=lambda: dict(RAW_UNITS))

    def __len__(self) -> int:
        return int(self.phase.size)

    def text(self, delimiter: str = "\t", title: str | None = None) -> str:
        """The run as a raw-run file: a title line, the names and units rows, the samples."""
        names = list(self.channels)
        head = title or (f"synthetic raw run of {self.truth.name} (frictionlaws), "
                         f"{len(self)} samples at {self.spec.rate:g} Hz")
        out = [head, delimiter.join(names), delimiter.join(self.units[n] for n in names)]
        table = np.column_stack([self.channels[n] for n in names])
        out.extend(delimiter.join(f"{v:.6g}" for v in row) for row in table)
        return "\n".join(out) + "\n"

    def write(self, path: str | Path, delimiter: str = "\t") -> Path:
        """Write :meth:`text` to ``path`` (atomically, checked as an output)."""
        check_outputs([path])
        with atomic_write(path) as fh:
            fh.write(self.text(delimiter))
        return Path(path)


class _Timeline:
    """The commanded load, camber, pressure and slips, sample by sample."""

    def __init__(self, rate: float) -> None:
        self.rate = rate
        self.parts: list[dict[str, np.ndarray]] = []
        self.now = {"fz": 0.0, "gamma": 0.0, "p": 0.0, "alpha": 0.0, "kappa": 0.0}

    def add(self, seconds: float, phase: str, **ends: float) -> None:
        """Move linearly to ``ends`` over ``seconds`` (the others held)."""
        n = max(1, int(round(seconds * self.rate)))
        part = {k: np.linspace(v, ends.get(k, v), n + 1)[1:] for k, v in self.now.items()}
        part["phase"] = np.full(n, PHASES.index(phase))
        self.parts.append(part)
        self.now.update({k: float(part[k][-1]) for k in self.now})

    def sweep(self, name: str, top: float, speed: float, cycles: int, phase: str,
              first: float = -1.0, dwell: float = 0.0) -> None:
        """0 -> ``first`` top -> -``first`` top -> 0 (``cycles`` times) at ``speed`` per
        second, holding ``dwell`` seconds at each end."""
        start = self.now[name]
        for _ in range(cycles):
            for end in (start + first * top, start - first * top, start):
                self.add(abs(end - self.now[name]) / speed, phase, **{name: end})
                if dwell > 0 and end != start:
                    self.add(dwell, phase)

    def arrays(self) -> dict[str, np.ndarray]:
        return {k: np.concatenate([p[k] for p in self.parts]) for k in self.parts[0]}


def _condition(tl: _Timeline, spec: RawRunSpec, fz: float) -> None:
    """A load step, then the slip-angle sweeps and the slip-ratio sweeps at held angles."""
    tl.add(2.0, "step", fz=fz)
    tl.add(1.5, "hold")
    tl.sweep("alpha", math.radians(spec.alpha_max_deg), math.radians(spec.alpha_rate_deg),
             spec.cycles, "lateral", spec.first_sign, spec.dwell_s)
    for deg in (0.0, *spec.combined_deg):
        a = math.radians(deg)
        tl.add(max(0.5, abs(a - tl.now["alpha"]) / math.radians(spec.alpha_rate_deg)), "step",
               alpha=a)
        tl.add(1.5, "hold")
        top = spec.kappa_max if deg == 0 else spec.combined_kappa_max
        tl.sweep("kappa", top, spec.kappa_rate, 1, "longitudinal", spec.first_sign,
                 spec.dwell_s)
        tl.add(1.0, "hold")
    tl.add(max(0.5, abs(tl.now["alpha"]) / math.radians(spec.alpha_rate_deg)), "step",
           alpha=0.0)


def _timeline(truth: MagicFormula, spec: RawRunSpec) -> dict[str, np.ndarray]:
    fnom, p_nom = truth.fnomin, truth.nominal_pressure or 2.6e5
    tl = _Timeline(spec.rate)
    tl.now.update(p=p_nom * spec.pressures[0])
    tl.add(3.0, "lift")
    warm_load = fnom * min(spec.loads, key=lambda v: abs(v - 1.0))
    tl.add(2.0, "warm-up", fz=warm_load)
    while sum(p["phase"].size for p in tl.parts) < (3 + spec.warmup_s) * spec.rate:
        tl.sweep("alpha", math.radians(spec.alpha_max_deg), math.radians(spec.alpha_rate_deg),
                 1, "warm-up")
    tl.add(2.0, "lift", fz=0.0)
    for p in spec.pressures:
        for g in spec.cambers_deg:
            tl.add(3.0, "lift", fz=0.0)
            tl.add(3.0, "lift", p=p * p_nom, gamma=math.radians(g))
            for load in spec.loads:
                _condition(tl, spec, load * fnom)
    tl.add(3.0, "lift", fz=0.0)
    return tl.arrays()


def _lagged(x: np.ndarray, lag: float, rate: float) -> np.ndarray:
    """``x`` through a first-order lag of time constant ``lag`` [s]: tau dy/dt + y = x,
    solved exactly for ``x`` linear between samples."""
    if lag <= 0:
        return x
    a = math.exp(-1.0 / (lag * rate))
    b1 = lag * rate * (1 - a) - a
    b0 = 1 - a - b1
    out, _ = lfilter([b0, b1], [1, -a], x, zi=[(1 - b0) * x[0]])
    return np.asarray(out)


def _noise_scale(force: np.ndarray, level: np.ndarray) -> np.ndarray:
    """Each sample's noise scale: the largest |force| at its commanded load, interpolated
    between the loads held (a lifted tyre's: the lightest load's)."""
    values, counts = np.unique(level[level > 0], return_counts=True)
    held = values[counts >= max(3, int(0.05 * counts.max()))] if values.size else values
    if held.size == 0:
        return np.full(force.size, np.abs(force).max())
    peaks = np.array([np.abs(force[level == lv]).max() for lv in held])
    scale = np.interp(level, held, peaks)
    return np.where(level > 0, scale, LIFTED_NOISE * peaks.min())


def synthetic_raw_run(truth: MagicFormula, spec: RawRunSpec | None = None) -> SyntheticRun:
    """A raw rig run of ``truth`` (module documentation).

    Parameters
    ----------
    truth : MagicFormula
        The tyre measured.
    spec : RawRunSpec, optional
        The test (default :class:`RawRunSpec`).

    Returns
    -------
    SyntheticRun
    """
    spec = spec or RawRunSpec()
    rng = np.random.default_rng(spec.seed)
    c = _timeline(truth, spec)
    n = c["fz"].size
    t = np.arange(n) / spec.rate
    warm = np.where(c["phase"] == PHASES.index("warm-up"),
                    COLD_GRIP + (1 - COLD_GRIP) * np.clip(t / max(spec.warmup_s, 1e-9), 0, 1),
                    1.0)
    fz = c["fz"] * (1 + 0.01 * np.sin(2 * math.pi * t / 5.3))
    loaded = fz > 0
    v = spec.speed_kph / 3.6
    out = {k: np.zeros(n) for k in ("Fx", "Fy", "Mz", "Mx")}
    radii = {"Re": np.zeros(n), "Rl": np.zeros(n)}
    ss = truth.steady_state(c["kappa"][loaded], c["alpha"][loaded], fz[loaded],
                            c["gamma"][loaded], pressure=c["p"][loaded], vx=v)
    for k in out:
        out[k][loaded] = ss[k] * (warm[loaded] if k != "Mx" else 1.0)
    for k in radii:
        radii[k][loaded] = ss[k]
        radii[k][~loaded] = np.max(ss[k])
    return SyntheticRun(_channels(out, radii, c, fz, t, rng, spec), c["phase"], spec, truth)


def _channels(out: dict[str, np.ndarray], radii: dict[str, np.ndarray],
              c: dict[str, np.ndarray], fz: np.ndarray, t: np.ndarray,
              rng: np.random.Generator, spec: RawRunSpec) -> dict[str, np.ndarray]:
    """The written channels (SAE axes, file units) with lag, offsets and noise."""
    n = t.size
    share = t / t[-1]
    meas: dict[str, np.ndarray] = {}
    for j, k in enumerate(("Fx", "Fy", "Mz")):
        scale = spec.noise * _noise_scale(out[k], c["fz"])
        start, end = spec.offsets[0][j], spec.offsets[1][j]
        meas[k] = (_lagged(out[k], spec.lag, spec.rate) + start + (end - start) * share
                   + scale * rng.standard_normal(n))
    kappa = c["kappa"] + rng.normal(0, 5e-4, n)
    speed = spec.speed_kph + rng.normal(0, 0.1, n)
    fz_meas = fz + rng.normal(0, 0.003, n) * np.maximum(c["fz"], 200.0)
    omega = (1 + c["kappa"]) * (spec.speed_kph / 3.6) / radii["Re"]
    heat = 1 - np.exp(-3 * t / max(spec.warmup_s, 1.0))  # warm by the end of the warm-up
    temp = 25 + 30 * heat + 4 * np.abs(out["Fy"]) / np.maximum(fz, 1)
    ch = {"ET": t, "V": speed, "N": omega * 60 / (2 * math.pi) + rng.normal(0, 0.05, n),
          "SA": -np.degrees(c["alpha"]) + rng.normal(0, 0.03, n),
          "IA": np.degrees(c["gamma"]) + rng.normal(0, 0.02, n),
          "RL": 100 * radii["Rl"], "RE": 100 * radii["Re"],
          "P": c["p"] / 1e3 + rng.normal(0, 0.3, n), "FX": meas["Fx"], "FY": -meas["Fy"],
          "FZ": -fz_meas, "MX": _lagged(out["Mx"], spec.lag, spec.rate),
          "MZ": -meas["Mz"]}
    safe = np.where(np.abs(fz_meas) > 50, fz_meas, np.nan)
    ch["NFX"] = np.nan_to_num(meas["Fx"] / safe)
    ch["NFY"] = np.nan_to_num(meas["Fy"] / safe)
    ch.update({"RST": np.full(n, 30.0), "TSTI": temp - 2, "TSTC": temp, "TSTO": temp + 1.5,
               "AMBTMP": np.full(n, 24.0),
               "SR": (1 + kappa) * radii["Rl"] / radii["Re"] - 1, "SL": kappa})
    return ch


def sweep_data(truth: MagicFormula, kind: str, *, loads: Sequence[float] = (0.4, 0.8, 1.2,
               1.6), cambers_deg: Sequence[float] = (-3.0, 0.0, 3.0),
               pressures: Sequence[float] = (0.85, 1.1), n: int = 31,
               alpha_max_deg: float = 12.0, kappa_max: float = 0.25,
               combined_deg: Sequence[float] = (-8.0, -4.0, 4.0, 8.0),
               noise: float = 0.008, jitter: bool = True, seed: int = 11) -> TyreData:
    """Sweeps of ``truth`` of one kind, in SI and ISO-W axes (a TYDEX file's rows): noisy
    measurements, or (``noise=0, jitter=False``) the property file's evaluation on the grid.

    Parameters
    ----------
    truth : MagicFormula
    kind : {"lateral", "longitudinal", "combined"}
        Slip-angle sweeps at zero slip ratio; slip-ratio sweeps at zero slip angle; slip-ratio
        sweeps (to 0.8 ``kappa_max``) at the slip angles ``combined_deg``.
    loads, pressures : sequence of float
        Multiples of FNOMIN and of the nominal pressure.
    cambers_deg : sequence of float
    n : int
        Points per sweep direction (each sweep runs up and down).
    alpha_max_deg, kappa_max : float
    combined_deg : sequence of float
    noise : float
        Noise of the forces and moment, a share of each load's largest magnitude.
    jitter : bool
        Jitter the recorded slips (5e-4 in slip ratio, 0.03 deg) and the load (0.5 %) as a
        rig's are (default True).
    seed : int

    Returns
    -------
    TyreData
    """
    if kind not in ("lateral", "longitudinal", "combined"):
        raise InputError(f"kind must be lateral, longitudinal or combined, got {kind!r}")
    rng = np.random.default_rng(seed)
    p_nom = truth.nominal_pressure or 2.6e5
    blocks = []
    for fz in truth.fnomin * np.asarray(loads):
        for p in p_nom * np.asarray(pressures):
            for g in np.radians(cambers_deg):
                blocks.extend(_sweeps(kind, fz, p, g, n, alpha_max_deg, kappa_max,
                                      combined_deg, rng, 1.0 if jitter else 0.0))
    fz, kappa, alpha, gamma, pressure = (np.concatenate([b[i] for b in blocks])
                                         for i in range(5))
    out = truth.steady_state(kappa, alpha, fz, gamma, pressure=pressure)
    level = np.concatenate([np.full(b[0].size, b[0][0]) for b in blocks])
    noisy = {k: out[k] + noise * _noise_scale(out[k], level) * rng.standard_normal(fz.size)
             for k in ("Fx", "Fy", "Mz")}
    return TyreData.from_arrays(fz=fz, kappa=kappa, alpha=alpha, gamma=gamma,
                                pressure=pressure,
                                fx=noisy["Fx"] if kind != "lateral" else np.nan,
                                fy=noisy["Fy"] if kind != "longitudinal" else np.nan,
                                mz=noisy["Mz"] if kind != "longitudinal" else np.nan,
                                source=f"<synthetic {kind} sweeps>")


def _sweeps(kind: str, fz: float, p: float, g: float, n: int, alpha_max_deg: float,
            kappa_max: float, combined_deg: Sequence[float], rng: np.random.Generator,
            jitter: float) -> list[tuple[np.ndarray, ...]]:
    """The (fz, kappa, alpha, gamma, p) arrays of the sweeps at one condition."""
    up_down = np.concatenate([np.linspace(-1, 1, n), np.linspace(1, -1, n)])
    m = up_down.size
    load = fz * (1 + jitter * rng.normal(0, 0.005, m))
    dk, da = (jitter * rng.normal(0, s, m) for s in (5e-4, 0.03))
    if kind == "lateral":
        return [(load, dk, np.radians(alpha_max_deg * up_down + da), np.full(m, g),
                 np.full(m, p))]
    if kind == "longitudinal":
        return [(load, kappa_max * up_down + dk, np.radians(da), np.full(m, g), np.full(m, p))]
    return [(load, 0.8 * kappa_max * up_down + dk, np.radians(deg + da), np.full(m, g),
             np.full(m, p)) for deg in combined_deg]
