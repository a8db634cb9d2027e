"""The channels of tyre test files: what each quantity is, its names in TYDEX files and raw rig
runs, and the unit spellings rigs write.

One table per fact:

* :data:`KINDS`: the quantity kind (:data:`frictionlaws.base.units.QUANTITIES`) of every quantity a
  tyre test file holds (``fz``, ``kappa``, ``alpha``, ... and the rig's own: time, speed,
  wheel speed, radii, temperatures);
* :data:`TYDEX_CHANNELS`: TYDEX 1.3 channel names (W axes) and the quantity each gives;
* :data:`RAW_CHANNELS`: the channel names of raw rig runs as public tyre test programmes
  publish them (SAE axes) and the quantity each gives;
* :func:`unit_text`: a rig's unit spelling (``N-m``, ``Nm``, ``kph``, ``1/min``, ``deg C``,
  ``lb``, ``unitless``) in the unit grammar of :mod:`frictionlaws.units`;
* :func:`convert`: values in a file's unit to SI, refusing a unit of another dimension;
* :func:`read_lines`: the lines of a text file, bounded in size and line length.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ...base.errors import InputError
from ...base.limits import read_input
from ...base.outputs import check_input_file
from ...base.sanitize import split_lines
from ...base.units import parse_unit, to_si, unit_registry
from ...io import decode_text

__all__ = ["KINDS", "TYDEX_CHANNELS", "TYDEX_OTHER_AXES", "RAW_CHANNELS", "MEANINGS",
           "unit_text", "convert", "read_lines", "MAX_LINE_CHARS", "MAX_CORNERING_COEFFICIENT",
           "MAX_SLIP_COEFFICIENT", "MAX_CAMBER_STIFFNESS", "camber_settings_in_radians",
           "slip_coefficient"]

#: Largest plausible cornering coefficient K_y / F_z [1/rad] (tyres: about 5-40); the same
#: bound as the fit's check of its data.
MAX_CORNERING_COEFFICIENT = 60.0
#: Largest plausible longitudinal slip coefficient K_x / F_z [-] (tyres: about 10-40).
MAX_SLIP_COEFFICIENT = 150.0

#: Largest plausible camber stiffness, the slope of F_y / F_z on the camber near zero slip
#: angle [1/rad] (tyres: about 0.2-2): radians under a [deg] header make it 57 times larger.
MAX_CAMBER_STIFFNESS = 5.0
#: A camber setting is a whole degree within this [deg] (of the values read as radians).
_SETTING_TOL = 0.05
#: Largest camber a tyre runs at [rad] (30 degrees): smaller numbers under a [deg] header
#: may be radians.
_LARGEST_CAMBER = np.radians(30.0)
#: A small slip angle [rad]: where F_y / F_z is near linear in it (and in the camber).
_SMALL_ALPHA = 0.1

#: Quantity -> kind of :func:`frictionlaws.base.units.to_si` (the SI unit follows from it).
KINDS: dict[str, str] = {
    "fz": "F_N", "kappa": "s", "alpha": "angle", "gamma": "angle", "pressure": "p",
    "fx": "F_N", "fy": "F_N", "mz": "torque", "mx": "torque", "my": "torque",
    "time": "time", "speed": "v", "omega": "angular_velocity", "loaded_radius": "length",
    "effective_radius": "length", "slip_ratio_loaded": "s", "temperature": "T",
    "force_ratio": "s",
}

#: Quantity -> what it is (for notes and the guide).
MEANINGS: dict[str, str] = {
    "fz": "vertical load", "kappa": "slip ratio on the effective rolling radius (the Magic "
    "Formula's kappa)", "alpha": "slip angle", "gamma": "inclination (camber) angle",
    "pressure": "inflation pressure", "fx": "longitudinal force", "fy": "lateral force",
    "mz": "aligning moment", "mx": "overturning moment", "my": "rolling resistance moment",
    "time": "elapsed time", "speed": "road speed", "omega": "wheel speed",
    "loaded_radius": "loaded radius", "effective_radius": "effective rolling radius",
    "slip_ratio_loaded": "slip ratio on the loaded radius (the rig's control slip)",
    "temperature": "temperature", "force_ratio": "force over load",
}

#: TYDEX 1.3 channel (and constant) names in W axes -> quantity (None: known, not used).
TYDEX_CHANNELS: dict[str, str | None] = {
    "FZW": "fz", "FX": "fx", "FXW": "fx", "FXH": "fx", "FYW": "fy", "MZW": "mz",
    "MXW": "mx", "MYW": "my", "SLIPANGL": "alpha", "INCLANGL": "gamma", "LONGSLIP": "kappa",
    "INFLPRES": "pressure", "RUNTIME": "time", "LONGVEL": "speed", "WHROTSPD": "omega",
    "MEASNUMB": None, "NOMPRES": None, "FNOMIN": None, "LOADRADI": "loaded_radius",
    "EFFROLRA": "effective_radius", "AMBITEMP": "temperature", "TRCKTEMP": "temperature",
    "TYRETEMP": "temperature",
}

#: TYDEX force and moment channels in other axes than W (hub H, centre C), or without their
#: axis (FY, FZ, MZ): refused, naming the W-axis channel to give.
TYDEX_OTHER_AXES: dict[str, str] = {
    **{f"{q}{ax}": f"{q}W" for q in ("FY", "FZ", "MX", "MY", "MZ") for ax in ("H", "C")},
    "FXC": "FX", "FY": "FYW", "FZ": "FZW", "MX": "MXW", "MY": "MYW", "MZ": "MZW",
}

#: Raw rig-run channels as public tyre test programmes publish them (SAE axes) -> quantity
#: (None: read and not used).
RAW_CHANNELS: dict[str, str | None] = {
    "ET": "time", "V": "speed", "N": "omega", "SA": "alpha", "IA": "gamma",
    "RL": "loaded_radius", "RE": "effective_radius", "P": "pressure", "FX": "fx", "FY": "fy",
    "FZ": "fz", "MX": None, "MZ": "mz", "NFX": None, "NFY": None, "RST": None, "TSTI": None,
    "TSTC": "temperature", "TSTO": None, "AMBTMP": None, "SR": "slip_ratio_loaded",
    "SL": "kappa",
}

#: Unit spellings of rigs and TYDEX files -> the unit grammar's, per quantity kind (keys in
#: lower case).  ``Nm`` is a newton metre for a torque (the grammar reads it as nanometre);
#: ``1/min`` is revolutions per minute for a wheel speed (the grammar: one radian per minute).
_SPELLINGS: dict[str, dict[str, str]] = {
    "torque": {"nm": "N*m", "n-m": "N*m", "n.m": "N*m", "knm": "kN*m", "kn-m": "kN*m",
               "danm": "daN*m", "ft-lb": "ft*lbf", "lb-ft": "ft*lbf", "ft-lbf": "ft*lbf",
               "in-lb": "in*lbf", "lb-in": "in*lbf"},
    "F_N": {"lb": "lbf", "lbs": "lbf"},
    "angular_velocity": {"1/min": "rpm", "u/min": "rpm", "rev/min": "rpm", "min^-1": "rpm"},
    "T": {"deg c": "degC", "degc": "degC", "c": "degC", "°c": "degC", "deg f": "degF",
          "f": "degF"},
    "s": {"unitless": "-", "none": "-", "[-]": "-"},
    "v": {"kph": "km/h", "kmh": "km/h"},
}


def unit_text(unit: str, kind: str) -> str:
    """``unit`` in the unit grammar: a rig's spelling of ``kind`` translated, else unchanged.

    Parameters
    ----------
    unit : str
        The unit as the file writes it.
    kind : str
        The quantity kind (a value of :data:`KINDS`).

    Returns
    -------
    str
    """
    text = unit.strip()
    return _SPELLINGS.get(kind, {}).get(text.lower(), text)


def convert(values: Any, unit: str, quantity: str, *, file: str | None = None,
            column: str | None = None, row: int | None = None) -> np.ndarray:
    """``values`` in the file's ``unit`` as SI values of ``quantity``.

    Parameters
    ----------
    values : array-like
        Numbers in ``unit``.
    unit : str
        The file's unit (a rig's spelling is translated by :func:`unit_text`).
    quantity : str
        A key of :data:`KINDS`.
    file, column : str, optional
        Named in messages.
    row : int, optional
        The line that declares the unit, named in messages.

    Returns
    -------
    numpy.ndarray

    Raises
    ------
    InputError
        An unknown unit, one of another dimension, an angle without its unit or in a unit
        that is no angle (``%``, ``-``).
    """
    kind = KINDS[quantity]
    text = unit_text(unit, kind)
    try:
        if kind == "angle":
            if not text or text in ("-", "1"):
                raise InputError(f"an angle needs its unit (deg or rad); '{column}' has none",
                                 file=file, column=column, row=row)
            parsed = parse_unit(text, kind, column=column, file=file)
            root = unit_registry().get_root_units(parsed)[1]
            if str(root) != "radian":
                raise InputError(f"unit '{unit}' is not an angle (deg or rad)", file=file,
                                 column=column, row=row)
        return np.asarray(to_si(values, text, kind, column=column, file=file), dtype=float)
    except InputError as exc:
        if exc.row is None and row is not None:
            raise InputError(exc.bare_message, file=file, column=column, row=row) from None
        raise


#: Longest line of a tyre test text file [characters] (TYDEX lines have 80; a raw run with
#: a hundred channels some 2,000).
MAX_LINE_CHARS = 100_000


def read_lines(path: str | Path, what: str) -> tuple[list[str], list[str]]:
    """The lines of a text input file (bounded in size and line length) and the reading notes.

    Parameters
    ----------
    path : str or Path
        A regular file.
    what : str
        What the file is, for messages ("TYDEX file", "raw rig run").

    Returns
    -------
    lines : list of str
        Split at ``\\n``, ``\\r\\n`` and ``\\r`` only.
    notes : list of str
        The encoding note, when the file is not UTF-8.

    Raises
    ------
    InputError
        A missing, unreadable, binary or over-long file, or an over-long line.
    """
    source = str(path)
    check_input_file(path, what)
    text, note = decode_text(read_input(path, what, source), source, what)
    lines = split_lines(text)
    for number, line in enumerate(lines, start=1):
        if len(line) > MAX_LINE_CHARS:
            raise InputError(f"line longer than {MAX_LINE_CHARS} characters", file=source,
                             row=number)
    return lines, [note] if note else []


def slip_coefficient(force: np.ndarray, fz: np.ndarray, slip: np.ndarray,
                     share: float = 100.0) -> float:
    """A lower bound of the slip (or cornering) coefficient: the largest |F| / F_z over the
    largest |slip| (``tan(alpha)`` for the cornering one).  Above
    :data:`MAX_SLIP_COEFFICIENT` (:data:`MAX_CORNERING_COEFFICIENT`) no tyre has it: the
    slips are a unit too small (fractions under a percent header, radians under a degree
    header).  The one rule of the fit's checks and the raw run's.

    Parameters
    ----------
    force, fz, slip : numpy.ndarray
        The rows to look at (a slip that is not zero on some).
    share : float
        The percentile of |F| / F_z taken as its largest (below 100: spikes of a raw run's
        samples left out).

    Returns
    -------
    float
    """
    return float(np.percentile(np.abs(force / fz), share)) / float(np.max(np.abs(slip)))


def camber_settings_in_radians(gamma: np.ndarray, unit: str, fy: np.ndarray, fz: np.ndarray,
                               alpha: np.ndarray, pure: np.ndarray
                               ) -> tuple[str, bool, np.ndarray] | None:
    """Camber levels under a [deg] header so small that, read as radians, they are whole
    degrees (a rig's settings): radians under a degree header, told by the camber thrust.

    The levels are found among the values read as radians within :data:`_SETTING_TOL` of a
    whole degree (nine values in ten or more, each level on three or more, and on a
    twentieth of them, two levels or more).  The camber stiffness (the slope of F_y / F_z on
    the camber as read, fitted with a cornering slope and an offset over the ``pure`` rows
    within 0.1 rad of zero slip angle) then decides: above :data:`MAX_CAMBER_STIFFNESS` by
    two standard errors, the values are radians; below it by two, a tyre's (real levels
    that happen to be whole degrees when read as radians); between, or without F_y there,
    the levels are said but cannot be told.

    Parameters
    ----------
    gamma : numpy.ndarray
        The camber as read [rad].
    unit : str
        The unit of the camber column or channel.
    fy, fz, alpha : numpy.ndarray
        Lateral force and load [N] (NaN: not measured), slip angle [rad].
    pure : numpy.ndarray
        The rows near pure side slip (slip ratio near zero), boolean.

    Returns
    -------
    tuple or None
        None when the values are not such levels (or the unit is no degree); else the
        message (without its location), True when the values are radians (to refuse),
        False when that cannot be told (to warn), and the rows of the largest level.
    """
    if unit.strip().lower() not in ("deg", "degree", "degrees", "°"):
        return None
    written = np.degrees(gamma)  # the numbers as the file writes them
    if not 0 < float(np.max(np.abs(written))) <= _LARGEST_CAMBER:
        return None
    setting = np.round(np.degrees(written))  # [deg], were the numbers radians
    near = np.abs(np.degrees(written) - setting) <= _SETTING_TOL
    values, counts = np.unique(setting[near], return_counts=True)
    levels = values[counts >= max(3, 0.05 * gamma.size)] + 0.0  # no -0
    if near.mean() < 0.9 or levels.size < 2:
        return None
    top = near & (setting == levels[np.argmax(np.abs(levels))])
    head = (f"the camber takes the levels {', '.join(f'{np.radians(v):.3g}' for v in levels)}"
            f" deg, which read as radians are the whole degrees "
            f"{', '.join(f'{v:g}' for v in levels)} of a rig's settings")
    use = (near & np.isin(setting, levels) & pure & np.isfinite(fy)
           & (np.abs(alpha) <= 1.01 * _SMALL_ALPHA))
    k, se = _camber_stiffness(gamma[use], fy[use] / fz[use], np.tan(alpha[use]))
    if k - 2 * se > MAX_CAMBER_STIFFNESS:
        return (head + f", and Fy / Fz changes by {k:.3g} +- {se:.2g} per rad of camber as "
                "read (tyres: about 0.2-2): the values look like radians under a [deg] "
                "header (write 'gamma [rad]')", True, top)
    if k + 2 * se < MAX_CAMBER_STIFFNESS:
        return None
    said = ("no Fy near zero slip angle to tell them by their camber thrust" if np.isnan(k)
            else f"their camber thrust ({k:.3g} +- {se:.2g} per rad as read; tyres: about "
            "0.2-2) does not tell")
    return (f"{head}; {said}: if they are settings in radians, the header's unit is wrong "
            "(write 'gamma [rad]')", False, top)


def _camber_stiffness(gamma: np.ndarray, ratio: np.ndarray, tan_alpha: np.ndarray
                      ) -> tuple[float, float]:
    """|slope| of F_y / F_z (``ratio``) on ``gamma`` fitted with a slope on tan(alpha) and
    an offset, and its standard error; NaN without six rows or two cambers."""
    if gamma.size < 6 or np.ptp(gamma) == 0:
        return np.nan, np.nan
    design = np.column_stack([np.ones(gamma.size), tan_alpha, gamma])
    coef, *_ = np.linalg.lstsq(design, ratio, rcond=None)
    s2 = float(np.sum((ratio - design @ coef) ** 2)) / max(gamma.size - 3, 1)
    cov = s2 * np.linalg.pinv(design.T @ design)
    return abs(float(coef[2])), float(np.sqrt(max(float(cov[2, 2]), 0.0)))
