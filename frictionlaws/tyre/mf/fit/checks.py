"""Plausibility of tyre test data before a Magic Formula is fitted to them.

A unit slip in a header (a slip ratio in percent written as a fraction, slip angles in
radians under a ``[deg]`` header, loads in kN under ``[N]``) gives numbers that a fit
accepts and turns into a confident, wrong property file.  :func:`check_plausible`
refuses such data, naming the file, column, row and the unit the values look like.

First the data must be able to determine what is asked of them: a force whose slip is
constant (``Fx`` without a varying slip ratio, ``Fy`` or ``Mz`` without a varying slip
angle) is refused, naming the columns not read; so is a force with no trend on its slip
(all zero, or noise: a correlation with the slip below :data:`MIN_CURVE_CORRELATION`
on the rows near pure slip within 0.1 of zero slip, where a tyre's force rises with it),
and an ``Fy`` with the sign of the slip angle on most rows beyond 2 degrees (in ISO-W axes
a positive slip angle gives a negative ``Fy``: the data are in SAE axes, or a column's
sign is flipped).

The unit tests are physical bounds, not statistics of the data set:

* **slip ratio**: below -1 the wheel would turn backwards; above 1 with the
  longitudinal force staying below half the load (a slip coefficient
  ``max|F_x| / (F_z max|kappa|)`` under 0.5) the values are percent; a slip
  coefficient above :data:`MAX_SLIP_COEFFICIENT` (150; tyres have 10-40) means
  fractions under a percent header; a slope of ``F_x / F_z`` on the slip ratio below
  :data:`MIN_SLIP_SLOPE` (0.5) over the rows near pure slip within 0.1 of zero means
  percent written as fractions (a sweep of a few percent that never exceeds 1);
* **slip angle**: a cornering coefficient ``max|F_y| / (F_z max|tan alpha|)`` above
  :data:`MAX_CORNERING_COEFFICIENT` (60 per rad; tyres have about 5-40) means radians
  under a degree header; a slope of ``F_y / F_z`` on ``tan(alpha)`` below
  :data:`MIN_CORNERING_SLOPE` (0.75 per rad) within 0.1 rad of zero means degrees under
  a ``[rad]`` header (small angles, below 90 "radians");
* **load**: a force above :data:`MAX_FORCE_RATIO` (5) times the load on its row, or a
  median load below FNOMIN / 100 or above 100 FNOMIN, means kN given as N (or N as kN);
* **camber**: beyond :data:`MAX_CAMBER` (30 deg) the values are degrees under a ``[rad]``
  header (or, under another unit's header, impossible);
* **pressure**: a median pressure below a fifth or above five times the template's
  nominal pressure means kPa as Pa, bar as kPa or the like;
* **aligning moment**: |M_z| above F_z times the unloaded radius (a trail longer than the
  tyre's radius) means N mm under an ``[N m]`` header.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import replace
from typing import Any

import numpy as np

from ....base.errors import Argument, InputError
from ...data.channels import (
    MAX_CAMBER_STIFFNESS,
    MAX_CORNERING_COEFFICIENT,
    MAX_SLIP_COEFFICIENT,
    camber_settings_in_radians,
    slip_coefficient,
)
from ...data.table import COLUMNS, TyreData
from ..notices import collected
from .stages import ALPHA_PURE, KAPPA_PURE, load_levels

__all__ = ["check_plausible", "plausibility_warnings", "repeated_rows", "MAX_SLIP_COEFFICIENT",
           "MAX_CORNERING_COEFFICIENT", "MAX_FORCE_RATIO", "MIN_SLIP_SLOPE", "MIN_CORNERING_SLOPE",
           "MIN_CURVE_CORRELATION", "MAX_FILES_SLOPE_RATIO", "MAX_PEAK_RATIO",
           "LOW_PEAK_FRICTION", "PEAK_SLIPS", "MAX_CAMBER_STIFFNESS", "RISING_SHARE",
           "rising_side"]

#: Smallest plausible slope of F_x / F_z on the slip ratio within 0.1 of zero [-] (tyres:
#: 10-40; on ice, a peak of 0.1 at a slip of 0.1 still gives 1).
MIN_SLIP_SLOPE = 0.5
#: Smallest plausible slope of F_y / F_z on tan(alpha) within 0.1 rad of zero [1/rad]
#: (tyres: 5-40; on ice, a peak of 0.1 at 0.1 rad still gives 1).
MIN_CORNERING_SLOPE = 0.75
#: Largest ratio of two files' slopes near zero slip (of F_x / F_z on kappa, F_y / F_z on
#: tan(alpha)) for one tyre [-]: loads and pressures change them by less than 2, sweeps
#: of another reach (the fit over the window) by up to about 2.
MAX_FILES_SLOPE_RATIO = 5.0
#: A usual tyre's slopes near zero slip of F_x / F_z on kappa and F_y / F_z on tan(alpha).
_TYPICAL_SLOPES = (20.0, 14.0)
#: Half-width of the slip window near zero where the slopes are taken [-, rad].
_SMALL_SLIP = 0.1
#: Largest plausible |F_x| or |F_y| over F_z on one row (peak friction is below 4).
MAX_FORCE_RATIO = 5.0
#: Largest plausible camber [rad] (30 degrees).
MAX_CAMBER = math.radians(30.0)
#: Slip ratio and slip angle [rad] a pure-slip sweep must reach for its largest |F| / F_z to
#: stand for the tyre's peak friction (every tyre is near its peak there: within some 30 %).
PEAK_SLIPS = (0.1, math.radians(8.0))
#: Largest ratio of one tyre's peak friction in one direction to the other's (F_x / F_z to
#: F_y / F_z) [-]: tyres have 0.7-1.5, on any road; a force in daN under an [N] header is
#: 10 off.
MAX_PEAK_RATIO = 3.0
#: Below this peak friction [-] (dry roads: 0.8-1.3; wet: 0.4-0.8; snow: 0.2-0.4; ice:
#: 0.05-0.2) the force is warned of: on ice it is real, else in daN under an [N] header.
LOW_PEAK_FRICTION = 0.2
#: Smallest |correlation| of F_x / F_z with the slip ratio (F_y / F_z with tan(alpha)) for
#: a force that follows its slip (a tyre's, even on ice: above 0.5; noise: near 0).
MIN_CURVE_CORRELATION = 0.3
#: Slip angle beyond which F_y has the opposite sign of alpha in ISO-W axes [rad]
#: (camber thrust and ply steer can outweigh smaller angles).
_SIGN_ANGLE = math.radians(2.0)
#: Slip angles where M_z opposes F_y (a positive trail, before the moment turns over) [rad],
#: on the rows where F_y still rises (:func:`rising_side`).
_MZ_SIGN_ANGLES = (math.radians(1.0), math.radians(4.0))
#: Share of its load level's peak |F_y| up to which the side force still rises with the slip
#: angle and the pneumatic trail is positive: the aligning moment turns over near the peak
#: of F_y, at 2-3 deg on a dry road but below 1 deg on ice (a Magic Formula tyre with its
#: friction scaled to 0.2 has M_z of the sign of F_y from 1.5 deg on).
RISING_SHARE = 0.8


def check_plausible(data: TyreData, fnomin: float, nominal_pressure: float | None = None,
                    radius: float | None = None) -> None:
    """Refuse data whose slips, angles, loads, pressures or moments are in another unit.

    Parameters
    ----------
    data : TyreData
        The measurements (SI, ISO axes).
    fnomin : float
        The template's nominal load [N].
    nominal_pressure : float, optional
        The template's nominal pressure [Pa] (pressures unchecked without it).
    radius : float, optional
        The template's unloaded radius [m] (M_z unchecked without it).

    Raises
    ------
    InputError
        Naming the file, column and row, and the unit the values look like.
    """
    parts = _files_of(data)
    for part in parts:  # each file's rows first: the refusal names that file
        _check_rows(part, fnomin, nominal_pressure, radius)
    _check_files_agree(parts)
    _check_slip_columns(data)
    _check_rows(data, fnomin, nominal_pressure, radius)


def plausibility_warnings(data: TyreData, fnomin: float) -> list[str]:
    """:func:`check_plausible` on data without a template (the load checked against
    ``fnomin``), returning what it warns of (issued too, once each): for a path that
    reports its own warnings, as ``tyre prepare`` does.

    Parameters
    ----------
    data : TyreData
    fnomin : float
        The load the loads are checked against [N].

    Returns
    -------
    list of str
    """
    with collected() as raised:
        check_plausible(data, fnomin)
    return raised


def _files_of(data: TyreData) -> list[TyreData]:
    """The rows of each file of several joined, each named by its file (none for one)."""
    if len(data.files) < 2 or "file" not in data.extra:
        return []
    return [replace(data.subset(data.extra["file"] == i), source=name, files=())
            for i, name in enumerate(data.files)]


def _check_rows(data: TyreData, fnomin: float, p_nom: float | None,
                radius: float | None) -> None:
    """The checks of :func:`check_plausible` but the slip columns' (which the files
    joined answer together: one file may hold the Fx sweeps, another the Fy sweeps)."""
    _check_curves(data, ("Fx", "Fy"))
    _check_fy_sign(data)
    # one force in another unit than the other: named before the loads' and slopes' checks
    # (which see a force 10 off as a load in kN, or a flat slope as degrees under [rad])
    _check_peak_friction(data)
    _check_loads(data, fnomin)
    _check_kappa(data)
    _check_alpha(data)
    _check_small_slip_slopes(data)
    _check_others(data, p_nom, radius)
    _check_curves(data, ("Mz",))  # after the slip angles' unit: radians as degrees flatten Mz
    _check_mz_sign(data)


def _check_others(data: TyreData, p_nom: float | None, radius: float | None) -> None:
    """Camber, pressure and aligning moment against their physical ranges."""
    _check_camber(data)
    _check_camber_settings(data)
    p = data.pressure[np.isfinite(data.pressure)]
    if p_nom is not None and p.size:
        median = float(np.median(p))
        if not p_nom / 5 <= median <= 5 * p_nom:
            raise InputError(
                f"the median pressure {median:g} Pa is far from the template's nominal "
                f"{p_nom:g} Pa: the values look like another unit (kPa as Pa, bar as kPa?)",
                column="pressure",
                **_at(data, np.isfinite(data.pressure), data.pressure - median))
    if radius is not None:
        arm = np.where(np.isfinite(data.mz), np.abs(data.mz) / data.fz, 0.0)
        if (arm > radius).any():
            raise InputError(
                f"|Mz| is {arm.max():.3g} m times the load on this row, more than the tyre's "
                f"radius {radius:g} m: the moments look like N mm under an [N m] header",
                column="Mz", **_at(data, arm > radius, arm))


def _check_slip_columns(data: TyreData) -> None:
    """Refuse a force whose slip does not vary (no slip column, or a constant one)."""
    for slip, forces, what in (("kappa", ("fx",), "slip-ratio"),
                               ("alpha", ("fy", "mz"), "slip-angle")):
        values = getattr(data, slip)
        given = [f for f in forces if np.isfinite(getattr(data, f)).any()]
        if not given or np.ptp(values) > 0:
            continue
        names = " and ".join(f[0].upper() + f[1:] for f in given)
        why = (f"no {what} column" if slip in data.missing else "the column is constant")
        hint = (f"columns not used: {', '.join(data.unused)}; a {what} column is named "
                f"{', '.join(COLUMNS[slip][1])} (any case) with its unit in brackets"
                if data.unused else f"measure a {what} sweep, or remove the {names} column")
        raise InputError(
            f"{names} given but {slip} is {float(values[0]):g} on every row ({why}): "
            f"{names} cannot be fitted without a {what} that varies; {hint}",
            file=data.source, column=slip)


def _check_curves(data: TyreData, names: tuple[str, ...]) -> None:
    """Refuse F_x, F_y or M_z (of ``names``) with no trend on its slip (all zero, or noise
    only)."""
    for name, force, slip, pure in (
            ("Fx", data.fx, data.kappa, np.abs(data.alpha) <= ALPHA_PURE),
            ("Fy", data.fy, np.tan(data.alpha), np.abs(data.kappa) <= KAPPA_PURE),
            ("Mz", data.mz, np.tan(data.alpha), np.abs(data.kappa) <= KAPPA_PURE)):
        if name not in names:
            continue
        use = np.isfinite(force) & (slip != 0)
        for narrower in (pure, np.abs(slip) <= 1.01 * _SMALL_SLIP):  # where F rises with slip
            if (use & narrower).sum() >= 5 and np.ptp(slip[use & narrower]) > 0:
                use &= narrower
        if name == "Mz":  # M_z follows the slip only while F_y rises (it turns over after)
            rising = use & rising_side(data)
            if rising.sum() >= 5 and np.ptp(slip[rising]) > 0:
                use = rising
            elif not (use.any() and np.ptp(force[use]) == 0):
                continue  # too few such rows: only an M_z that never changes is told
        if use.sum() < 3 or np.ptp(slip[use]) == 0:
            continue
        ratio = force[use] / data.fz[use]
        r = 0.0 if np.ptp(ratio) == 0 else float(np.corrcoef(ratio, slip[use])[0, 1])
        if abs(r) < MIN_CURVE_CORRELATION:
            top = float(np.max(np.abs(ratio)))
            raise InputError(
                f"{name} carries no curve to fit: on {int(use.sum())} rows its ratio to Fz "
                f"(at most {top:.3g}) has no trend on the slip (correlation {r:.2f}; a "
                f"tyre's force follows its slip with at least {MIN_CURVE_CORRELATION:g}): "
                "zero or noise only; check the column, or remove it", column=name,
                **_at(data, use, np.where(use, force, 0.0)))


def _check_fy_sign(data: TyreData) -> None:
    """Refuse F_y with the sign of alpha on most rows beyond 2 degrees (not ISO-W)."""
    use = (np.isfinite(data.fy) & (np.abs(data.alpha) > _SIGN_ANGLE)
           & (np.abs(data.kappa) <= KAPPA_PURE) & (data.fy != 0))
    if use.sum() < 5:
        use = np.isfinite(data.fy) & (np.abs(data.alpha) > _SIGN_ANGLE) & (data.fy != 0)
    same = int((np.sign(data.fy[use]) == np.sign(data.alpha[use])).sum())
    if use.sum() < 5 or 2 * same <= use.sum():
        return
    head = (f"Fy has the sign of the slip angle on {same} of {int(use.sum())} rows with "
            "|alpha| > 2 deg")
    if data.sign_convention == "sae":
        parts: list[str | Argument] = [
            head + " after the conversion from SAE axes (Fy and alpha negated); in ISO-W "
            "axes a positive slip angle gives a negative Fy: the data look like ISO-W axes "
            "already (give ", Argument("sign_convention", "iso"), ", the default) or a "
            "column of flipped sign (negate Fy, or alpha)"]
    else:
        parts = [head + ", taken in ISO-W axes where a positive slip angle gives a negative "
                 "Fy: the data look like SAE axes (give ", Argument("sign_convention", "sae"),
                 ") or a column of flipped sign (negate Fy, or alpha)"]
    raise InputError(parts, column="Fy",
                     **_at(data, use, np.where(use, data.fy, 0.0)))


def _check_mz_sign(data: TyreData) -> None:
    """Refuse M_z with the sign of F_y on most rows near pure side slip at 1-4 degrees."""
    lo, hi = _MZ_SIGN_ANGLES
    # pure side slip only: with a slip ratio, F_x's moment arm can turn M_z over
    use = ((np.abs(data.alpha) >= lo) & (np.abs(data.alpha) <= hi) & rising_side(data)
           & np.isfinite(data.mz) & (data.mz != 0) & (data.fy != 0))
    same = int((np.sign(data.mz[use]) == np.sign(data.fy[use])).sum())
    if use.sum() < 5 or 2 * same <= use.sum():
        return
    raise InputError(
        f"Mz has the sign of Fy on {same} of {int(use.sum())} rows with |alpha| of 1-4 deg: "
        "near pure side slip the aligning moment opposes the side force (a positive "
        "pneumatic trail, Mz and Fy of opposite signs, in ISO-W as in SAE axes); the sign "
        "of Mz looks reversed: a channel of flipped sign (negate Mz, or Fy) or axes that "
        "flip Mz alone", column="Mz", **_at(data, use, np.where(use, data.mz, 0.0)))


def rising_side(data: TyreData) -> np.ndarray:
    """The rows near pure side slip where F_y still rises with the slip angle: below the
    slip angle of its load level's peak |F_y| and below :data:`RISING_SHARE` of that peak
    (where the pneumatic trail is positive and M_z opposes F_y, on any road).

    Parameters
    ----------
    data : TyreData

    Returns
    -------
    numpy.ndarray
        A mask of the rows.
    """
    pure = (np.abs(data.kappa) <= KAPPA_PURE) & np.isfinite(data.fy) & np.isfinite(data.fz)
    out = np.zeros(len(data.fy), dtype=bool)
    if not pure.any():
        return out
    levels = load_levels(data.fz[pure])
    idx = np.flatnonzero(pure)
    for lv in np.unique(levels):
        rows = idx[levels == lv]
        mag = np.abs(data.fy[rows])
        top = int(np.argmax(mag))
        out[rows] = ((np.abs(data.alpha[rows]) < abs(float(data.alpha[rows[top]])))
                     & (mag <= RISING_SHARE * mag[top]))
    return out


def _check_camber(data: TyreData) -> None:
    """Camber beyond 30 deg: degrees under a [rad] header, or (in another unit) impossible."""
    wide = np.abs(data.gamma) > MAX_CAMBER
    if not wide.any():
        return
    top = math.degrees(float(np.abs(data.gamma).max()))
    if data.units.get("gamma", "rad").strip().lower() in ("rad", "radian", "radians"):
        why = "beyond 30 deg the values look like degrees under a [rad] header"
    else:
        why = ("no tyre runs beyond 30 deg (at 90 deg the wheel lies on its side): check the "
               "camber column")
    raise InputError(f"camber {top:.3g} deg is impossible: {why}", column="gamma",
                     **_at(data, wide, data.gamma))


def _check_camber_settings(data: TyreData) -> None:
    """Camber settings in radians under a [deg] header
    (:func:`~frictionlaws.tyre.data.channels.camber_settings_in_radians`): refused when the
    camber thrust says so, else warned of."""
    found = camber_settings_in_radians(data.gamma, data.units.get("gamma", ""), data.fy,
                                       data.fz, data.alpha,
                                       np.abs(data.kappa) <= KAPPA_PURE)
    if found is None:
        return
    text, decisive, top = found
    error = InputError(text, column="gamma", **_at(data, top, data.gamma))
    if decisive:
        raise error
    warnings.warn(str(error), UserWarning, stacklevel=2)


def _check_peak_friction(data: TyreData) -> None:
    """The largest |F_x| / F_z and |F_y| / F_z of sweeps that reach the tyre's peak
    (:data:`PEAK_SLIPS`): more than :data:`MAX_PEAK_RATIO` apart, one of the two forces is
    in another unit (refused, naming first the one whose peak is farther from a dry road's
    1, and the other's opposite slip); below :data:`LOW_PEAK_FRICTION`, a force is on ice
    or in daN under an [N] header (warned)."""
    peaks = []
    for name, force, slip, pure, reach in (
            ("Fx", data.fx, data.kappa, np.abs(data.alpha) <= ALPHA_PURE, PEAK_SLIPS[0]),
            ("Fy", data.fy, data.alpha, np.abs(data.kappa) <= KAPPA_PURE, PEAK_SLIPS[1])):
        use = pure & np.isfinite(force)
        if use.any() and float(np.max(np.abs(slip[use]))) >= reach:
            ratio = np.where(use, np.abs(force) / data.fz, 0.0)
            # the peak of the twentieth of the rows highest: a spike on a row is no peak
            top = float(np.sort(ratio[use])[-max(1, int(np.ceil(0.05 * use.sum())))])
            peaks.append((name, top, _at(data, use & (ratio == top), ratio)))
    if len(peaks) == 2 and not (1 / MAX_PEAK_RATIO <= peaks[0][1] / peaks[1][1]
                                <= MAX_PEAK_RATIO):
        (name, mu, at), (other, mu_other, _) = sorted(peaks,
                                                      key=lambda p: -abs(math.log(p[1])))
        low = mu < mu_other
        raise InputError(
            f"|{name}| / Fz peaks at {mu:.3g} but |{other}| / Fz at {mu_other:.3g}, a factor "
            f"{max(mu, mu_other) / min(mu, mu_other):.3g} apart (one tyre's peaks differ by "
            f"less than {MAX_PEAK_RATIO:g}, on any road): the {name} column looks like "
            f"another unit than its header says ({'daN under [N]' if low else 'N under [daN]'}"
            f"; or {other} in {'N under [daN]' if low else 'daN under [N]'})",
            column=name, **at)
    for name, mu, at in peaks:
        if mu < LOW_PEAK_FRICTION:
            warnings.warn(str(InputError(
                f"|{name}| / Fz peaks at {mu:.3g} (tyres reach 0.8-1.3 on a dry road, 0.2-0.8 "
                "wet or on snow; less only on ice): unless measured on ice, the column looks "
                "like daN under an [N] header", column=name, **at)), UserWarning, stacklevel=2)


def _at(data: TyreData, mask: np.ndarray, values: np.ndarray) -> dict[str, Any]:
    """File and source row of the largest |value| among ``mask`` (of several files joined:
    the one file holding that row)."""
    idx = np.flatnonzero(mask)
    file, row = data.where(int(idx[int(np.argmax(np.abs(values[idx])))]))
    return {"file": file, "row": row}


def _check_loads(data: TyreData, fnomin: float) -> None:
    for name, force in (("Fx", data.fx), ("Fy", data.fy)):
        ratio = np.where(np.isfinite(force), np.abs(force) / data.fz, 0.0)
        if ratio.max() > MAX_FORCE_RATIO:
            at = _at(data, ratio > MAX_FORCE_RATIO, ratio)
            # most rows too high: the loads' unit; a few: those force cells
            most = np.mean(ratio[np.isfinite(force)] > MAX_FORCE_RATIO) > 0.5
            raise InputError(
                f"|{name}| is {ratio.max():.3g} times the load Fz on this row (a tyre's "
                f"friction stays below 4): the loads look like kN given as N (or {name} in "
                "another unit than its header says)",
                column="Fz" if most else name, **at)
    median = float(np.median(data.fz))
    if not fnomin / 100 <= median <= 100 * fnomin:
        likely = "kN given as N" if median < fnomin else "N given as kN (or N*1000)"
        raise InputError(
            f"the median load {median:g} N is far from the template's FNOMIN {fnomin:g} N: "
            f"the loads look like {likely}", column="Fz",
            **_at(data, np.ones(len(data), bool), data.fz - median))


def _check_kappa(data: TyreData) -> None:
    k = data.kappa
    if (k < -1 - 1e-9).any():
        raise InputError(
            f"slip ratio {k.min():g}: below -1 the wheel turns backwards; the values look "
            "like percent given as a fraction (write 'kappa [%]')", column="kappa",
            **_at(data, k < -1 - 1e-9, k))
    use = np.isfinite(data.fx) & (np.abs(k) > 0)
    if not use.any():
        return
    coef = slip_coefficient(data.fx[use], data.fz[use], k[use])
    if np.max(np.abs(k[use])) > 1 and coef < 0.5:
        raise InputError(
            f"slip ratios up to {np.max(np.abs(k[use])):g} while |Fx| stays below "
            f"{coef * np.max(np.abs(k[use])):.2g} Fz: the values look like percent given as "
            "a fraction (write 'kappa [%]')", column="kappa",
            **_at(data, use, k))
    if coef > MAX_SLIP_COEFFICIENT:
        raise InputError(
            f"|Fx| reaches {coef * np.max(np.abs(k[use])):.2g} Fz at slip ratios of at most "
            f"{np.max(np.abs(k[use])):.3g}: a slip coefficient of at least {coef:.0f} (tyres "
            "have 10-40); the slip ratios look like fractions under a percent header",
            column="kappa", **_at(data, use, k))


def _check_alpha(data: TyreData) -> None:
    a = np.tan(data.alpha)
    use = np.isfinite(data.fy) & (np.abs(a) > 0)
    if not use.any() or np.ptp(a[use]) == 0:  # a constant slip angle: refused as such
        return
    top = float(np.max(np.abs(a[use])))
    coef = slip_coefficient(data.fy[use], data.fz[use], a[use])
    if coef > MAX_CORNERING_COEFFICIENT:
        raise InputError(
            f"|Fy| reaches {coef * top:.2g} Fz at slip angles of at most "
            f"{math.degrees(math.atan(top)):.3g} deg: a cornering coefficient of at least "
            f"{coef:.0f} per rad (tyres have about 5-40); the slip angles look like radians "
            "under a [deg] header", column="alpha",
            **_at(data, use, a))


def _slope_near_zero(slip: np.ndarray, force: np.ndarray, fz: np.ndarray,
                     pure: np.ndarray) -> tuple[float, np.ndarray]:
    """|slope| of force / F_z on ``slip`` over the pure-slip rows within the window (1 %
    wider: tan(0.1 rad) and rounded decimal slips are inside), and
    the rows used (NaN when fewer than three rows or one slip value)."""
    use = pure & np.isfinite(force) & (np.abs(slip) <= 1.01 * _SMALL_SLIP)
    if use.sum() < 3 or np.ptp(slip[use]) <= 0 or not (np.abs(slip[use]) > 0).any():
        return math.nan, use
    return abs(float(np.polyfit(slip[use], force[use] / fz[use], 1)[0])), use


def _slopes(data: TyreData) -> tuple[tuple[float, np.ndarray], tuple[float, np.ndarray]]:
    """The slopes near zero slip of F_x / F_z on kappa and F_y / F_z on tan(alpha), each
    with its rows (:func:`_slope_near_zero`)."""
    return (_slope_near_zero(data.kappa, data.fx, data.fz, np.abs(data.alpha) <= ALPHA_PURE),
            _slope_near_zero(np.tan(data.alpha), data.fy, data.fz,
                             np.abs(data.kappa) <= KAPPA_PURE))


def _check_files_agree(parts: list[TyreData]) -> None:
    """Refuse files whose slopes near zero slip differ by more than a tyre's do (a force
    column of one file in another unit: daN as N)."""
    found = [(_slopes(p), p) for p in parts]
    for i, (name, what) in enumerate((("Fx", "unit slip ratio"), ("Fy", "rad of slip angle"))):
        typical = _TYPICAL_SLOPES[i]
        given = [(f[i][0], f[i][1], p) for f, p in found if f[i][0] > 0]  # NaN: not given
        if len(given) < 2:
            continue
        lo, hi = min(g[0] for g in given), max(g[0] for g in given)
        if hi <= MAX_FILES_SLOPE_RATIO * lo:
            continue
        # the file at fault: the slope farthest from a usual tyre's; compared with the nearest
        k, use, part = max(given, key=lambda g: abs(math.log(g[0] / typical)))
        k_ok, _, other = min(given, key=lambda g: abs(math.log(g[0] / typical)))
        force = getattr(part, name.lower())
        raise InputError(
            f"{name} / Fz changes by {k:.3g} per {what} near zero slip in this file but "
            f"by {k_ok:.3g} in '{other.source}', a factor {hi / lo:.3g} apart (one tyre's "
            f"differ by less than {MAX_FILES_SLOPE_RATIO:g} across loads and pressures): "
            f"the {name} column of this file looks like another unit than its header says "
            "(daN as N?)", column=name, **_at(part, use, np.where(use, force, 0.0)))


def _check_small_slip_slopes(data: TyreData) -> None:
    """Slopes near zero slip far below any tyre's: percent as fractions, degrees as rad."""
    (kx, use), (ky, use_y) = _slopes(data)
    if kx < MIN_SLIP_SLOPE:
        raise InputError(
            f"Fx / Fz rises by only {kx:.3g} per unit slip ratio near zero slip (tyres have "
            "10-40): the slip ratios look like percent given as a fraction (write "
            "'kappa [%]')", column="kappa", **_at(data, use, data.kappa))
    a = np.tan(data.alpha)
    if ky < MIN_CORNERING_SLOPE:
        raise InputError(
            f"Fy / Fz changes by only {ky:.3g} per rad of slip angle near zero (tyres have "
            "about 5-40): the slip angles look like degrees under a [rad] header",
            column="alpha", **_at(data, use_y, a))


def repeated_rows(data: TyreData) -> str | None:
    """A note when rows repeat another row exactly (every column), else None.

    Measured rows with noise never repeat to the last digit: repeats are a file given
    twice or rows copied.  They are fitted as given (the point estimate is that of the
    rows counted with their repeats), but the asymptotic standard errors then count
    them as independent measurements and shrink."""
    table = np.stack([data.fz, data.kappa, data.alpha, data.gamma, data.pressure,
                      data.fx, data.fy, data.mz], axis=1)
    table = np.where(np.isnan(table), np.inf, table)  # NaN (not measured) equals NaN here
    unique = np.unique(table, axis=0).shape[0]
    if unique == len(data):
        return None
    return (f"{len(data) - unique} of {len(data)} rows repeat another row exactly (every "
            "column): they are fitted as given, each counted as a measurement, so the "
            "asymptotic standard errors are too small by about the square root of the "
            "repeats (remove the copies, or use uncertainty='sweeps')")
