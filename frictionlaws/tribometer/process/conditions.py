"""Repeats to conditions: speed clusters, Grubbs' outlier test, Student intervals, pooled
conditions (:func:`summarise`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from ..outliers import MIN_POOL, pooled_outliers
from ..rig import RPM, Rig
from .reduce import RecordResult

__all__ = ["GRUBBS_MIN", "student_interval", "grubbs", "ConditionResult", "summarise"]


#: The outlier test needs this many usable records (so that at least 3 remain).
GRUBBS_MIN = 4


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

