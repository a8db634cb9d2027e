"""A raw rig run turned into steady sweeps: what a Magic Formula fit uses.

:func:`prepare_run` takes a :class:`~frictionlaws.tyre.data.raw_run.RawRun` (SI, ISO-W) and

1. finds the **lifts** (load below :data:`LIFT_SHARE` of the run's 95th-percentile load)
   and, while the tyre is lifted, the force channels' **zero offsets**, which are subtracted
   (interpolated in time between lifts; ``zero_offsets=False`` keeps the data as they are);
2. finds the **levels** of load, camber and pressure the rig steps through (values held for
   :data:`MIN_LEVEL_S` seconds or more, of the signals median-filtered over
   :data:`SMOOTH_S` s) and cuts the run into **conditions** where all three stay at one
   level; samples between levels are **transitions**, the first :data:`SETTLE_S` s of a
   condition **settling**, a condition shorter than :data:`MIN_CONDITION_S` s **short**;
   conditions at the start that begin before the tread is warm (its temperature within
   :data:`WARM_MARGIN_K` of its running value, :func:`_warm_from`) or that the run returns
   to later are the
   **warm-up** (so are the first ``warmup`` seconds, when given);
3. finds the **sweeps** in each condition: slip-angle levels held for :data:`MIN_HOLD_S` s
   or more carry slip-ratio sweeps (pure at zero slip angle, combined elsewhere); a hold
   without a slip-ratio sweep is a **dwell**; between the holds the slip angle sweeps (with
   the slip ratio steady: a lateral sweep) or steps; a sweep must run both ways, up and
   down in about equal parts (so that the force's lag behind the slip cancels), else it is
   **one-way** (a step of the slip angle between holds is one);
4. averages each sweep's samples in blocks, about :data:`BINS_PER_SWEEP` per pass, **up
   and down apart** (the direction is kept as a column), a block over a sharp curve of the
   aligning moment cut
   (:meth:`~frictionlaws.tyre.data.bins.SweepBins.split_curved`): one row per block of
   :data:`MIN_BLOCK` or more samples.

Everything dropped is counted by reason (samples and seconds) and reported; the rows keep
their sweep (``sweep``), direction (+1 up, -1 down), sample count and time.  A fit checks
them as it checks every data (units, signs, curves); so does ``tyre prepare``.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.ndimage import median_filter
from scipy.signal import savgol_filter

from ...base.errors import InputError
from ..mf.notices import collected
from .bins import (
    BINS_PER_SWEEP,
    MAX_LAG_S,
    MIN_BLOCK,
    SweepBins,
    blocks,
)
from .raw_run import RawRun
from .table import TyreData

__all__ = ["Segment", "PreparedRun", "prepare_run", "REASONS", "LIFT_SHARE", "SMOOTH_S",
           "MIN_LEVEL_S", "SETTLE_S", "MIN_CONDITION_S", "MIN_HOLD_S", "BINS_PER_SWEEP",
           "MIN_BLOCK", "MAX_LAG_S", "DERIVATIVE_S", "OFF_ROAD_SHARE",
           "FORCE_WEIGHT", "WARM_MARGIN_K", "WARM_SMOOTH_S",
           "KAPPA_SWEEP", "ALPHA_SWEEP"]

#: A sample is lifted when its load is below this share of the run's 95th-percentile load.
LIFT_SHARE = 0.1
#: While lifted, the forces are zero offsets where the load is below this share of the
#: run's 95th-percentile load (off the road, not touching it).
OFF_ROAD_SHARE = 0.02
#: The tread is warm within this of its running temperature [K].
WARM_MARGIN_K = 10.0
#: The median filter of the tread temperature for the warm-up [s].
WARM_SMOOTH_S = 10.0
#: The median filter of load, camber, pressure and slip angle [s].
SMOOTH_S = 1.0
#: A level of load, camber or pressure is held this long in all or more [s].
MIN_LEVEL_S = 3.0
#: Dropped at the start of every condition, after a step [s].
SETTLE_S = 1.0
#: Conditions shorter than this are dropped [s].
MIN_CONDITION_S = 3.0
#: A slip angle held this long carries slip-ratio sweeps [s].
MIN_HOLD_S = 1.0
#: The weight of each force and moment against the slip in the length along a sweep that
#: sizes the blocks (0: blocks of equal slip): the aligning moment's sharp peak near zero
#: slip angle gets short blocks.
FORCE_WEIGHT = {"fx": 0.3, "fy": 0.3, "mz": 1.0}
#: A slip-ratio sweep spans this much or more (2nd to 98th percentile) [-].
KAPPA_SWEEP = 0.02
#: A slip-angle sweep spans this much or more [rad].
ALPHA_SWEEP = math.radians(2.0)
#: The window of the time derivative of the forces for the lag [s].
DERIVATIVE_S = 0.04
#: Gaps between two pieces of one condition merged when shorter than this [s].
_MERGE_GAP_S = 2.0
#: Load levels: bin width (share of the reference load) and tolerance (share of the level).
_LOAD_BIN, _LOAD_TOL = 0.02, 0.08
_CAMBER_BIN, _CAMBER_TOL = math.radians(0.1), math.radians(0.4)
_PRESSURE_BIN, _PRESSURE_TOL = 0.005, 0.03
_ALPHA_BIN, _ALPHA_TOL = math.radians(0.1), math.radians(0.3)
_KAPPA_BIN, _KAPPA_TOL = 0.0005, 0.002

#: Why samples are dropped, in the order of the steps (code = index; 0: kept).
REASONS = ("kept", "lift", "transition", "settling", "short", "warm-up", "dwell", "one-way",
           "thin bin")


@dataclass
class Segment:
    """A stretch of the run: a kept sweep or what was dropped there, and its conditions.

    ``kind`` is ``"lateral"`` (slip-angle sweep) or ``"longitudinal"`` (slip-ratio sweep at
    ``alpha``) for a kept sweep, else the reason it was dropped (:data:`REASONS`).  Loads
    [N], angles [rad] and pressures [Pa] are NaN where they do not apply.
    """

    start: float
    end: float
    samples: int
    kind: str
    load: float = math.nan
    camber: float = math.nan
    pressure: float = math.nan
    alpha: float = math.nan
    sweep: int = -1
    rows: int = 0

    @property
    def kept(self) -> bool:
        """True for a sweep whose bins are in the data."""
        return self.kind in ("lateral", "longitudinal")

    def to_dict(self) -> dict[str, Any]:
        """JSON-able, SI units named in the keys."""
        return {"start_s": self.start, "end_s": self.end, "samples": self.samples,
                "kind": self.kind, "load_N": _finite(self.load),
                "camber_rad": _finite(self.camber), "pressure_Pa": _finite(self.pressure),
                "alpha_rad": _finite(self.alpha), "sweep": self.sweep, "rows": self.rows}


def _finite(v: float) -> float | None:
    return float(v) if math.isfinite(v) else None


@dataclass
class PreparedRun:
    """Steady sweeps of a raw run (module documentation) and what was dropped.

    ``status`` holds, per sample, the code of :data:`REASONS` (0: kept); ``lags`` the
    (sweep kind, lag [s]) found in each sweep kept; ``offsets`` the force channels' zero
    offsets measured while lifted (``"time"`` [s], ``"fx"``, ``"fy"`` [N], ``"mz"`` [N m]
    at each lift; empty without lifts or when not subtracted); ``warnings`` what the
    preparation warned of (a measured channel not used), also issued as Python warnings.
    """

    data: TyreData
    run: RawRun
    segments: list[Segment]
    status: np.ndarray
    levels: dict[str, np.ndarray]
    notes: list[str] = field(default_factory=list)
    rate: float = math.nan
    lags: list[tuple[str, float]] = field(default_factory=list)
    offsets: dict[str, np.ndarray] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)

    def dropped(self) -> dict[str, tuple[int, float]]:
        """Reason -> (samples, seconds) of what was dropped."""
        out = {}
        for code, reason in enumerate(REASONS[1:], start=1):
            n = int(np.sum(self.status == code))
            if n:
                out[reason] = (n, n / self.rate)
        return out

    def summary(self) -> list[str]:
        """The lines of the report: what was found, kept and dropped."""
        n = len(self.run)
        kept = int(np.sum(self.status == 0))
        sweeps = [s for s in self.segments if s.kept]
        lat = sum(s.kind == "lateral" for s in sweeps)
        lines = [f"raw run {self.run.source}: {n} samples at {self.rate:.4g} Hz "
                 f"({n / self.rate:.0f} s)",
                 f"levels: loads {_shown(self.levels['load'], 1e-3, 'kN')}; cambers "
                 f"{_shown(self.levels['camber'], 180 / math.pi, 'deg')}; pressures "
                 f"{_shown(self.levels['pressure'], 1e-3, 'kPa')}",
                 f"kept {kept} samples ({100 * kept / n:.1f} %) in {lat} slip-angle sweeps "
                 f"and {len(sweeps) - lat} slip-ratio sweeps: {len(self.data)} rows (blocks of "
                 f"{MIN_BLOCK} or more samples, about {BINS_PER_SWEEP} per pass, up and down "
                 "apart)"]
        for reason, (count, seconds) in self.dropped().items():
            lines.append(f"dropped {reason}: {count} samples ({seconds:.1f} s, "
                         f"{100 * count / n:.1f} %)")
        return lines + [f"warning: {w}" for w in self.warnings]

    def report(self) -> str:
        """Plain-text report: the summary, then the notes."""
        return "\n".join(self.summary() + [f"note: {t}" for t in self.notes])

    def to_dict(self) -> dict[str, Any]:
        """JSON-able summary (SI units in the keys)."""
        return {"source": self.run.source, "samples": len(self.run), "rate_Hz": self.rate,
                "rows": len(self.data), "kept_samples": int(np.sum(self.status == 0)),
                "dropped": {k: {"samples": c, "seconds": s}
                            for k, (c, s) in self.dropped().items()},
                "levels": {"load_N": self.levels["load"].tolist(),
                           "camber_rad": self.levels["camber"].tolist(),
                           "pressure_Pa": self.levels["pressure"].tolist()},
                "segments": [s.to_dict() for s in self.segments], "notes": list(self.notes),
                "warnings": list(self.warnings)}


def _shown(values: np.ndarray, scale: float, unit: str) -> str:
    if values.size == 0:
        return "none (not measured)"
    return ", ".join(f"{round(v * scale, 2) + 0.0:.3g}" for v in values) + f" {unit}"


# ------------------------------------------------------------------ helpers


def _runs(mask: np.ndarray) -> list[tuple[int, int]]:
    """(start, stop) of each stretch where ``mask`` is true."""
    edges = np.diff(np.concatenate([[0], mask.astype(np.int8), [0]]))
    return list(zip(np.flatnonzero(edges == 1).tolist(), np.flatnonzero(edges == -1).tolist()))


def _smooth(x: np.ndarray, size: int) -> np.ndarray:

    if size < 3 or not np.all(np.isfinite(x)):
        return x.copy()
    return np.asarray(median_filter(x, size=size | 1, mode="nearest"), dtype=float)


def _levels(x: np.ndarray, ok: np.ndarray, width: float, tol: Any, min_count: int
            ) -> tuple[np.ndarray, np.ndarray]:
    """Levels held by ``x`` (bins of ``width`` with ``min_count`` samples or more, next to
    each other merged) and each sample's level (-1: none within ``tol(level)``)."""
    label = np.full(x.size, -1)
    v = x[ok & np.isfinite(x)]
    if v.size == 0 or width <= 0:
        return np.array([]), label
    lo = float(v.min())
    width = max(width, (float(v.max()) - lo) / 100_000)
    idx = ((v - lo) / width).astype(int)
    counts = np.bincount(idx)
    sums = np.bincount(idx, weights=v)
    levels = np.array([sums[a:b].sum() / counts[a:b].sum()
                       for a, b in _runs(counts >= min_count)])
    if levels.size == 0:
        return levels, label
    near = np.abs(x[:, None] - levels[None, :])
    best = np.argmin(np.where(np.isfinite(near), near, np.inf), axis=1)
    within = near[np.arange(x.size), best] <= tol(levels[best])
    label[within & ok] = best[within & ok]
    return levels, label


@dataclass
class _Work:
    """The run's arrays while it is cut: status per sample, the rate, the segments."""

    run: RawRun
    q: dict[str, np.ndarray]
    rate: float
    status: np.ndarray
    segments: list[Segment] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    #: d/dt of the forces and moment (Savitzky-Golay over :data:`DERIVATIVE_S`).
    rates: dict[str, np.ndarray] = field(default_factory=dict)
    #: (sweep kind, lag found) of every sweep kept.
    lags: list[tuple[str, float]] = field(default_factory=list)
    lag: bool = True
    #: The zero offsets measured in lifts (:attr:`PreparedRun.offsets`).
    offsets: dict[str, np.ndarray] = field(default_factory=dict)

    def samples(self, seconds: float) -> int:
        return max(1, int(round(seconds * self.rate)))

    def drop(self, a: int, b: int, reason: str, **conditions: float) -> None:
        """Mark samples a..b dropped (where still kept) and record the stretch."""
        code = REASONS.index(reason)
        free = self.status[a:b] == 0
        self.status[a:b][free] = code
        if free.any():
            t = self.q["time"]
            self.segments.append(Segment(float(t[a]), float(t[b - 1]), int(free.sum()),
                                         reason, **conditions))  # type: ignore[arg-type]


def _rate(run: RawRun) -> float:
    dt = np.diff(run.quantities["time"])
    step = np.median(dt[dt > 0]) if np.any(dt > 0) else 0.0
    if not step > 0:
        raise InputError("the time channel does not advance: no sampling rate",
                         file=run.source, column=run.channels["time"])
    return float(1.0 / step)


# ------------------------------------------------------------------ the steps


def _lifts(w: _Work) -> np.ndarray:
    fz = w.q["fz"]
    lifted = fz < LIFT_SHARE * np.percentile(fz, 95)
    for a, b in _runs(lifted):
        w.drop(a, b, "lift")
    return lifted


def _zero_offsets(w: _Work, lifted: np.ndarray) -> None:
    """Subtract the forces measured while off the road (load below :data:`OFF_ROAD_SHARE`
    of the reference), interpolated between lifts."""
    t = w.q["time"]
    centres, values = [], []
    off = lifted & (w.q["fz"] < OFF_ROAD_SHARE * np.percentile(w.q["fz"], 95))
    for a, b in _runs(off):
        if b - a < w.samples(0.5):
            continue
        inner = slice(a + (b - a) // 5, b - (b - a) // 5)
        centres.append(float(np.mean(t[inner])))
        values.append([float(np.median(w.q[k][inner])) if k in w.q else 0.0
                       for k in ("fx", "fy", "mz")])
    if not centres:
        w.notes.append("no lift of 0.5 s or more: the force channels' zero offsets are not "
                       "measured, the forces are taken as they are")
        return
    table = np.array(values)
    w.offsets = {"time": np.array(centres), **{k: table[:, j] for j, k in
                                                enumerate(("fx", "fy", "mz")) if k in w.q}}
    said = []
    for j, (k, unit) in enumerate((("fx", "N"), ("fy", "N"), ("mz", "N m"))):
        if k in w.q:
            w.q[k] = w.q[k] - np.interp(t, centres, table[:, j])
            said.append(f"{k} {table[:, j].min():.3g}..{table[:, j].max():.3g} {unit}")
    w.notes.append(f"zero offsets measured in {len(centres)} lifts (the forces while the "
                   f"tyre is off the road) and subtracted: {', '.join(said)}")


def _conditions(w: _Work, lifted: np.ndarray) -> tuple[dict[str, np.ndarray], list]:
    """The levels and the stretches of one condition (merged across short gaps)."""
    q = w.q
    size = w.samples(SMOOTH_S)
    ok = ~lifted
    ref = float(np.percentile(q["fz"], 95))
    need = w.samples(MIN_LEVEL_S)
    fz_s, g_s, p_s = (_smooth(q[k], size) for k in ("fz", "gamma", "pressure"))
    loads, lab_l = _levels(fz_s, ok, _LOAD_BIN * ref,
                           lambda lv: np.maximum(_LOAD_TOL * lv, 2 * _LOAD_BIN * ref), need)
    cambers, lab_g = _levels(g_s, ok, _CAMBER_BIN, lambda lv: _CAMBER_TOL, need)
    measured = np.isfinite(q["pressure"]).any()
    pressures, lab_p = (_levels(p_s, ok, _PRESSURE_BIN * np.nanmedian(q["pressure"]),
                                lambda lv: _PRESSURE_TOL * lv, need) if measured
                        else (np.array([]), np.zeros(q["fz"].size, dtype=int)))
    at = ok & (lab_l >= 0) & (lab_g >= 0) & (lab_p >= 0)
    key = np.where(at, (lab_l * 1000 + lab_g) * 1000 + lab_p, -1)
    pieces: list[list[int]] = []
    gap = w.samples(_MERGE_GAP_S)
    for a, b in _runs(at):
        starts = np.flatnonzero(np.diff(np.concatenate([[-2], key[a:b]])) != 0) + a
        for s, e in zip(starts.tolist(), starts[1:].tolist() + [b]):
            if pieces and pieces[-1][2] == key[s] and s - pieces[-1][1] < gap:
                pieces[-1][1] = e
            else:
                pieces.append([s, e, int(key[s])])
    for a, b in _runs(~at & ~lifted):
        w.drop(a, b, "transition")
    levels = {"load": loads, "camber": cambers, "pressure": pressures}
    labels = {"load": lab_l, "camber": lab_g, "pressure": lab_p}
    return levels, [(a, b, k, {n: labels[n][a] for n in labels}) for a, b, k in pieces]


def _explicit_warmup(w: _Work, seconds: float) -> None:
    if seconds < 0 or not math.isfinite(seconds):
        raise InputError(f"the warm-up must be a time of 0 s or more, got {seconds:g} s")
    if seconds > 0:
        t = w.q["time"]
        n = int(np.searchsorted(t, t[0] + seconds)) if np.all(np.diff(t) >= 0) else int(
            np.sum(t < t[0] + seconds))
        w.drop(0, n, "warm-up")


def _condition_values(levels: dict[str, np.ndarray], lab: dict[str, int]) -> dict[str, float]:
    return {name: float(levels[name][lab[name]]) if levels[name].size else math.nan
            for name in ("load", "camber", "pressure")}


def _kept_conditions(w: _Work, pieces: list, levels: dict[str, np.ndarray]
                     ) -> list[tuple[int, int, dict[str, float]]]:
    """Warm-up, short and settling dropped; the rest of each condition."""
    long = []
    for a, b, key, lab in pieces:
        if b - a < w.samples(MIN_CONDITION_S):
            w.drop(a, b, "short", **_condition_values(levels, lab))
        else:
            long.append((a, b, key, lab))
    keys = [k for _, _, k, _ in long]
    warm = _warm_from(w)
    leading = True
    out = []
    for i, (a, b, key, lab) in enumerate(long):
        cond = _condition_values(levels, lab)
        leading = leading and (key in keys[i + 1:] or a < warm)
        if leading:
            w.drop(a, b, "warm-up", **cond)
        else:
            w.drop(a, min(b, a + w.samples(SETTLE_S)), "settling", **cond)
            out.append((a, b, cond))
    return out


def _warm_from(w: _Work) -> int:
    """The first sample at which the tread is warm: its temperature (median-filtered over
    :data:`WARM_SMOOTH_S` s, the heating of each sweep smoothed out) within
    :data:`WARM_MARGIN_K` of its running value, the 5th percentile over the run's second
    half (0 without a tread temperature channel, with a note)."""
    if "temperature" not in w.q:
        w.notes.append("no tread temperature channel (TSTC): the warm-up is taken as the "
                       "conditions at the start that the run returns to later")
        return 0
    t = _smooth(w.q["temperature"], w.samples(WARM_SMOOTH_S))
    loaded = w.status != REASONS.index("lift")
    half = np.arange(t.size) >= t.size // 2
    if not (loaded & half).any():
        return 0
    running = float(np.percentile(t[loaded & half], 5))
    warm = loaded & (t >= running - WARM_MARGIN_K)
    first = int(np.argmax(warm)) if warm.any() else 0
    if first:
        w.notes.append(f"the tread ({w.run.channels['temperature']}) reaches its running "
                       f"temperature ({running - 273.15:.0f} degC, within {WARM_MARGIN_K:g} K)"
                       f" at {w.q['time'][first]:.0f} s: conditions that start before are "
                       "the warm-up")
    return first


def _span(x: np.ndarray) -> float:
    return float(np.percentile(x, 98) - np.percentile(x, 2)) if x.size else 0.0


def _noise(x: np.ndarray) -> float:
    """The noise of a signal per sample, from its second differences (a ramp has none)."""
    if x.size < 3:
        return 0.0
    return float(1.4826 * np.median(np.abs(np.diff(x, 2))) / math.sqrt(6.0))


def _holds(w: _Work, x: np.ndarray, width: float, tol: float) -> np.ndarray:
    """Samples where ``x`` is held at a level for :data:`MIN_HOLD_S` or more, within four
    times its noise of the level (at most ``tol``: a hold must not reach into the ramps
    beside it; the signal median-filtered over 5 samples)."""
    tol = float(np.clip(4 * _noise(x), 0.1 * tol, tol))
    smooth = _smooth(x, 5)
    _, lab = _levels(smooth, np.ones(x.size, bool), width, lambda lv: tol,
                     w.samples(MIN_HOLD_S))
    held = lab >= 0
    for a, b in _runs(held):
        if b - a < w.samples(MIN_HOLD_S):
            held[a:b] = False
    return held


def _sweeps_of(w: _Work, a: int, b: int, cond: dict[str, float], rows: list) -> None:
    """The slip-ratio sweeps on held slip angles and the slip-angle sweeps between (a hold
    without a slip-ratio sweep at the end of a slip-angle sweep, a dwell at its turn, is
    dropped without cutting the sweep in two)."""
    idx = np.arange(a, b)[w.status[a:b] == 0]
    if idx.size == 0:
        return
    alpha, kappa = w.q["alpha"][idx], w.q["kappa"][idx]
    held = _holds(w, alpha, _ALPHA_BIN, _ALPHA_TOL)
    between: list[np.ndarray] = []  # positions of the stretch of slip-angle sweep being built
    for s, e in sorted(_runs(held) + _runs(~held)):
        if not held[s]:
            between.append(np.arange(s, e))
            continue
        level = float(np.median(alpha[s:e]))
        if _span(kappa[s:e]) >= KAPPA_SWEEP:
            _lateral(w, idx, between, cond, rows)
            between = []
            _longitudinal(w, idx[s:e], kappa[s:e], level, cond, rows)
        elif between and _at_turn(alpha, between[-1], level, ALPHA_SWEEP, _ALPHA_TOL):
            w.drop(idx[s], idx[e - 1] + 1, "dwell", alpha=level, **cond)
        else:
            _lateral(w, idx, between, cond, rows)
            between = []
            w.drop(idx[s], idx[e - 1] + 1, "dwell", alpha=level, **cond)
    _lateral(w, idx, between, cond, rows)


def _at_turn(x: np.ndarray, before: np.ndarray, level: float, span: float, tol: float
             ) -> bool:
    """True when a hold of ``x`` at ``level`` is where ``x``, sweeping over the positions
    ``before`` (by ``span`` or more), turned."""
    lo, hi = float(np.min(x[before])), float(np.max(x[before]))
    return hi - lo >= span and min(abs(level - lo), abs(level - hi)) <= 2 * tol


def _longitudinal(w: _Work, sub: np.ndarray, kappa: np.ndarray, level: float,
                  cond: dict[str, float], rows: list) -> None:
    """The slip-ratio sweeps of one held slip angle; its dwells dropped (one at a turn of
    the sweep does not cut it in two)."""
    still = _holds(w, kappa, _KAPPA_BIN, _KAPPA_TOL)
    group: list[np.ndarray] = []
    for c, d in sorted(_runs(still) + _runs(~still)):
        if not still[c]:
            group.append(np.arange(c, d))
            continue
        held = float(np.median(kappa[c:d]))
        if not (group and _at_turn(kappa, group[-1], held, KAPPA_SWEEP, _KAPPA_TOL)):
            _kappa_sweep(w, sub, kappa, group, level, cond, rows)
            group = []
        w.drop(sub[c], sub[d - 1] + 1, "dwell", alpha=level, **cond)
    _kappa_sweep(w, sub, kappa, group, level, cond, rows)


def _kappa_sweep(w: _Work, sub: np.ndarray, kappa: np.ndarray, group: list[np.ndarray],
                 level: float, cond: dict[str, float], rows: list) -> None:
    if not group:
        return
    at = np.concatenate(group)
    if _span(kappa[at]) >= KAPPA_SWEEP:
        _sweep(w, sub[at], "longitudinal", cond, level, rows)
    else:
        w.drop(sub[at[0]], sub[at[-1]] + 1, "dwell", alpha=level, **cond)


def _lateral(w: _Work, idx: np.ndarray, pieces: list[np.ndarray], cond: dict[str, float],
             rows: list) -> None:
    """A stretch of slip-angle sweep (its pieces joined across dwells at its turns)."""
    if not pieces:
        return
    at = np.concatenate(pieces)
    sub = idx[at]
    alpha, kappa = w.q["alpha"][sub], w.q["kappa"][sub]
    if _span(alpha) >= ALPHA_SWEEP and _span(kappa) < KAPPA_SWEEP:
        _sweep(w, sub, "lateral", cond, math.nan, rows)
    elif _span(alpha) < ALPHA_SWEEP and _span(kappa) < KAPPA_SWEEP:
        w.drop(sub[0], sub[-1] + 1, "dwell", **cond)
    else:
        w.drop(sub[0], sub[-1] + 1, "transition", **cond)


def _directions(x: np.ndarray, size: int) -> np.ndarray:
    """+1 where the smoothed ``x`` rises, -1 where it falls (a flat stretch: as before it)."""
    step = np.sign(np.gradient(_smooth(x, size)))
    nonzero = np.flatnonzero(step)
    if nonzero.size == 0:
        return np.ones(x.size)
    filled = step[nonzero][np.clip(np.searchsorted(nonzero, np.arange(x.size), "right") - 1,
                                   0, None)]
    return np.where(step != 0, step, filled)


def _sweep(w: _Work, sub: np.ndarray, kind: str, cond: dict[str, float], level: float,
           rows: list) -> None:
    """Average one sweep in blocks, up and down apart (module documentation), or drop it
    as one-way."""
    sub = _moving(w, sub, w.q["alpha" if kind == "lateral" else "kappa"][sub], level, cond)
    if sub.size < 2 * MIN_BLOCK:
        return
    x = w.q["alpha" if kind == "lateral" else "kappa"][sub]
    direction = _directions(x, w.samples(0.3))
    share = float(np.mean(direction > 0))
    if not 0.25 <= share <= 0.75:
        w.drop(sub[0], sub[-1] + 1, "one-way", alpha=level, **cond)
        return
    forces = [k for k in ("fx", "fy", "mz") if k in w.q]
    shaping = _shaping(w, sub, kind)
    block, piece = blocks(x, direction, [w.rates[k][sub] / w.rate for k in shaping],
                           [_range(w.q[k][sub]) / FORCE_WEIGHT.get(k, 1.0) for k in shaping])
    thin = block < 0
    w.status[sub[thin]] = REASONS.index("thin bin")
    b = SweepBins(block[~thin], x[~thin], direction[~thin], piece[~thin])
    kept = sub[~thin]
    main = "fy" if kind == "lateral" else "fx"
    tau = b.lag(w.q[main][kept], w.rates[main][kept]) if w.lag else 0.0
    w.lags.append((kind, tau))
    cut = [k for k in shaping if k == "mz"]  # the sharpest curve; the forces' correct well
    b = b.split_curved([w.q[k][kept] + tau * w.rates[k][kept] for k in cut],
                       [_range(w.q[k][sub]) for k in cut])
    means: dict[str, np.ndarray] = {
        k: b.mean(w.q[k][kept]) for k in ("fz", "kappa", "alpha", "gamma", "pressure", "time")
        if k in w.q}
    for k in forces:
        means[k] = b.curvature(b.mean(w.q[k][kept] + tau * w.rates[k][kept]))
    first = np.full(b.counts.size, np.iinfo(np.int64).max)
    np.minimum.at(first, b.inverse, w.run.lines[kept])
    label = len([s for s in w.segments if s.kept])
    n = int(b.counts.size)
    rows.append({**means, "rows": first, "samples": b.counts.astype(float),
                 "direction": b.direction, "sweep": np.full(n, float(label))})
    w.segments.append(Segment(float(w.q["time"][sub[0]]), float(w.q["time"][sub[-1]]),
                              kept.size, kind, alpha=level, sweep=label, rows=n, **cond))


def _range(f: np.ndarray) -> float:
    span = float(np.percentile(f, 98) - np.percentile(f, 2)) if f.size else 0.0
    return span if span > 0 and math.isfinite(span) else math.inf


def _moving(w: _Work, sub: np.ndarray, x: np.ndarray, level: float,
            cond: dict[str, float]) -> np.ndarray:
    """``sub`` without the still samples at its ends (a slip below a fifth of the sweep's
    median speed there, its slope over 0.1 s, for 3 samples or more: a dwell, dropped as
    such)."""
    size = max(5, w.samples(0.1) | 1)
    speed = (np.abs(savgol_filter(x, size, 1, deriv=1)) if x.size > size
             else np.abs(np.gradient(x)))
    steady = [(a, b) for a, b in _runs(speed > 0.2 * float(np.median(speed)))
              if b - a >= 3]  # moving for 3 samples or more: not one noisy sample
    if not steady:
        w.drop(sub[0], sub[-1] + 1, "dwell", alpha=level, **cond)
        return sub[:0]
    first, last = steady[0][0], steady[-1][1]
    if first:
        w.drop(sub[0], sub[first], "dwell", alpha=level, **cond)
    if last < sub.size:
        w.drop(sub[last], sub[-1] + 1, "dwell", alpha=level, **cond)
    return sub[first:last]


def _shaping(w: _Work, sub: np.ndarray, kind: str) -> list[str]:
    """The channels whose curves shape the blocks: the sweep's force, and the aligning
    moment of a slip-angle sweep or the lateral force of a slip-ratio sweep where they
    change (a channel that only carries noise would spread the blocks evenly)."""
    if kind == "lateral":
        return [k for k in ("fy", "mz") if k in w.q]
    out = ["fx"] if "fx" in w.q else []
    if "fy" in w.q and "fx" in w.q and _range(w.q["fy"][sub]) >= 0.2 * _range(w.q["fx"][sub]):
        out.append("fy")
    return out


def _data(w: _Work, rows: list) -> TyreData:
    """The binned rows as tyre data; a force its slip does not vary for is not kept (warned
    of, naming the slip channel and the rows)."""
    if not rows:
        raise InputError("no sweep was found in the run: no slip angle or slip ratio swept "
                         "up and down at a steady load (what was dropped: "
                         + _dropped_text(w) + ")", file=w.run.source)
    cat = {k: np.concatenate([r[k] for r in rows]) for k in rows[0]}
    n = cat["fz"].size
    nan = np.full(n, math.nan)
    data = TyreData(cat["fz"], cat["kappa"], cat["alpha"], cat["gamma"],
                    cat.get("pressure", nan), cat.get("fx", nan), cat.get("fy", nan),
                    cat["rows"].astype(int), w.run.source, [],
                    cat.get("mz", nan), w.run.unused, (), "iso",
                    {q: w.run.units[c] for q, c in w.run.channels.items()},
                    {k: cat[k] for k in ("sweep", "direction", "samples", "time")})
    unused = [(slip, forces) for slip, span, forces in
              (("kappa", KAPPA_SWEEP, ("fx",)), ("alpha", ALPHA_SWEEP, ("fy", "mz")))
              if np.ptp(getattr(data, slip)) < span
              and any(np.isfinite(getattr(data, f)).any() for f in forces)]
    for slip, forces in unused:  # (a run sweeps one slip at least, or has no rows)
        warnings.warn(_unswept(w, data, slip, forces), UserWarning, stacklevel=3)
    for _, forces in unused:
        for f in forces:
            setattr(data, f, nan.copy())
    data.validate()
    return data


def _unswept(w: _Work, data: TyreData, slip: str, forces: tuple[str, ...]) -> str:
    """Why the ``forces`` of a prepared run are not used: their slip's channel does not
    sweep on the rows kept (named, with its span, the rows and the channels not used)."""
    channel = w.run.channels.get(slip, f"none ({slip} = 0)")
    values = getattr(data, slip) * (180 / math.pi if slip == "alpha" else 1.0)
    unit = " deg" if slip == "alpha" else ""
    lo, hi = (round(float(f(values)), 9) + 0.0 for f in (np.min, np.max))
    what = "slip angle" if slip == "alpha" else "slip ratio"
    need = (f"{math.degrees(ALPHA_SWEEP):g} deg" if slip == "alpha" else f"{KAPPA_SWEEP:g}")
    given = [f"{f[0].upper()}{f[1:]} ({w.run.channels.get(f, f.upper())})"
             for f in forces if np.isfinite(getattr(data, f)).any()]
    return (f"the {what} channel {channel} stays within {lo:.3g}..{hi:.3g}{unit} on the "
            f"{len(data)} rows kept (lines {int(data.rows.min())}-{int(data.rows.max())} of "
            f"the run; a sweep spans {need} or more): {' and '.join(given)} "
            f"{'is' if len(given) == 1 else 'are'} not used, having no {what} to follow "
            "(a dead or stuck channel, or no such sweep in the run?)")


def _dropped_text(w: _Work) -> str:
    parts = []
    for code, reason in enumerate(REASONS[1:], start=1):
        n = int(np.sum(w.status == code))
        if n:
            parts.append(f"{reason} {n / w.rate:.1f} s")
    return ", ".join(parts) or "nothing"


def prepare_run(run: RawRun, *, warmup: float = 0.0, zero_offsets: bool = True,
                lag: bool = True) -> PreparedRun:
    """Turn a raw rig run into steady sweeps (module documentation).

    Parameters
    ----------
    run : RawRun
        The run in SI and ISO-W axes (:func:`~frictionlaws.tyre.data.raw_run.load_raw_run`).
    warmup : float
        Seconds at the start dropped as warm-up, beside the conditions the run returns to
        later (default 0).
    zero_offsets : bool
        Subtract the force channels' readings while lifted (default True).
    lag : bool
        Find each sweep's force lag and take it out (default True).

    Returns
    -------
    PreparedRun

    Raises
    ------
    InputError
        No sweep found (naming the file and what was dropped).
    """
    q = dict(run.quantities)
    w = _Work(run, q, _rate(run), np.zeros(len(run), dtype=np.int8), lag=lag)
    lifted = _lifts(w)
    if zero_offsets:
        _zero_offsets(w, lifted)
    _rates(w)
    _explicit_warmup(w, warmup)
    levels, pieces = _conditions(w, lifted)
    rows: list[dict[str, np.ndarray]] = []
    for a, b, cond in _kept_conditions(w, pieces, levels):
        _sweeps_of(w, a, b, cond, rows)
    w.segments.sort(key=lambda s: s.start)
    _level_notes(w, levels)
    _lag_notes(w)
    with collected() as unused:  # a channel not used: warned once, on every path
        data = _data(w, rows)
    notes = list(run.notes) + w.notes
    data.notes = list(notes)
    prepared = PreparedRun(data, run, w.segments, w.status, levels, notes, w.rate, w.lags,
                           w.offsets, unused)
    data.notes.append("prepared from a raw rig run: " + "; ".join(prepared.summary()[1:]))
    return prepared


def _rates(w: _Work) -> None:
    """d/dt of Fx, Fy, Mz: Savitzky-Golay (quadratic) over :data:`DERIVATIVE_S` s."""
    size = max(3, w.samples(DERIVATIVE_S) | 1)
    for k in ("fx", "fy", "mz"):
        if k in w.q:
            w.rates[k] = (savgol_filter(w.q[k], size, 2, deriv=1, delta=1.0 / w.rate)
                          if w.q[k].size > size else np.zeros(w.q[k].size))


def _lag_notes(w: _Work) -> None:
    if not w.lag:
        w.notes.append("the forces' lag behind the slip is not taken out: the up and the "
                       "down sweeps cancel it to first order")
        return
    said = []
    for kind in ("lateral", "longitudinal"):
        found = [tau for k, tau in w.lags if k == kind]
        if found:
            said.append(f"{kind} sweeps {1e3 * min(found):.0f}-{1e3 * max(found):.0f} ms")
    if said:
        w.notes.append("the forces' lag behind the slip, found in each sweep from its up and "
                       f"down halves ({', '.join(said)}), is taken out as a first-order lag "
                       "(F = F_measured + tau dF/dt)")


def _level_notes(w: _Work, levels: dict[str, np.ndarray]) -> None:
    """What a fit cannot get from these levels (one load, one camber, one pressure)."""
    for name, what in (("load", "the load dependence"), ("camber", "the camber terms"),
                       ("pressure", "the pressure terms")):
        if levels[name].size == 1:
            w.notes.append(f"one {name} level only: a fit cannot determine {what}")
