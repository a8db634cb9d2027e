"""Raw rig runs: tyre test time series as public tyre test programmes publish them.

A raw run is text with one row per sample (50-100 Hz), tab, comma or space separated,
after an optional title line or two: a row of channel names, a row of their units, then
the samples::

    ET    V     N     SA    IA    RL    RE    P     FX    FY    FZ    MX    MZ    SR    SL ...
    s     kph   rpm   deg   deg   cm    cm    kPa   N     N     N     N-m   N-m   none  none
    0.00  40.1  ...

The channels (:data:`~frictionlaws.tyre.data.channels.RAW_CHANNELS`): ``ET`` elapsed time,
``V`` road speed, ``N`` wheel speed, ``SA`` slip angle, ``IA`` inclination (camber), ``RL``
loaded and ``RE`` effective rolling radius, ``P`` inflation pressure, ``FX``, ``FY``, ``FZ``
forces, ``MX``, ``MZ`` moments, ``SR`` and ``SL`` slip ratios, ``NFX``, ``NFY`` the forces
over the load, ``TSTI``, ``TSTC``, ``TSTO`` tread surface temperatures (inner, centre,
outer), ``RST`` road and ``AMBTMP`` ambient temperature.  The axes are SAE (z down: the
load is negative, and a positive slip angle gives a positive lateral force); they are
turned into the ISO-W axes of a property file (``sign_convention``).

The slip ratio is chosen by its meaning: ``SL``, the slip ratio on the effective rolling
radius (zero at free rolling), is the Magic Formula's kappa; ``SR`` is the rig's control
slip on the loaded radius, which is offset by some percent (``RL / RE - 1`` at free
rolling).  Without ``SL`` kappa is computed from ``N``, ``RE`` and ``V`` (``omega R_e / V -
1``); only without those is ``SR`` read, and the notes say which was taken.

Units are those of the units row, through the rig spellings of
:func:`~frictionlaws.tyre.data.channels.unit_text` (``kph``, ``N-m``, ``none``, ``lb``,
``ft-lb``, ``psi``, ``in``, ``deg C``...) and :func:`frictionlaws.base.units.to_si`.  Every number
read goes through :func:`frictionlaws.base.numbers.parse_number`.  Refused, naming the file, line
and channel: no names and units rows, two channels of one name, a channel used without a
unit, a row with another number of cells, a number that is not one, a load in SAE axes
declared ISO (or the reverse), slip angles or cambers beyond what a tyre sees (degrees under
a ``rad`` unit).  :func:`~frictionlaws.tyre.data.segments.prepare_run` turns a raw run into
steady sweeps.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...base.errors import Argument, InputError
from ...base.numbers import parse_number
from ..mf.parameters import check_pressure
from .channels import (
    KINDS,
    MAX_CORNERING_COEFFICIENT,
    MAX_SLIP_COEFFICIENT,
    MEANINGS,
    RAW_CHANNELS,
    camber_settings_in_radians,
    convert,
    read_lines,
    slip_coefficient,
)
from .table import check_sign_convention, to_iso_axes
from .tydex import is_tydex

__all__ = ["RawRun", "load_raw_run", "raw_layout", "MAX_SAMPLES", "RAW_DELIMITERS", "MIN_RIG_LOAD",
           "MIN_SWEPT_SLIP", "PLAUSIBLE_RATE", "GAP_STEPS",
           "REQUIRED_CHANNELS"]

#: Most samples of a raw run read (a day at 50 Hz is 4.3 million).
MAX_SAMPLES = 5_000_000
#: Delimiters of a raw run, as named in messages.
RAW_DELIMITERS = {"\t": "tab", ",": "comma", None: "spaces"}
#: Known channels a names row must hold to be taken as one (with FZ among them).
_MIN_KNOWN = 4
#: Lines searched for the names row.
_HEAD_LINES = 50
#: The quantities a raw run needs beside the load: a slip and a force.
_LARGEST_CAMBER = math.radians(30.0)


@dataclass
class RawRun:
    """A raw rig run in SI and ISO-W axes: one array per quantity, one value per sample.

    ``quantities`` maps a quantity of :data:`~frictionlaws.tyre.data.channels.KINDS`
    (``time``, ``fz``, ``fx``, ``fy``, ``mz``, ``alpha``, ``gamma``, ``pressure``, ``kappa``,
    ``speed``, ``omega``, radii, ``temperature``) to its values; ``channels`` the quantity to
    the file's channel name; ``units`` a channel to the unit written; ``lines`` the file
    line of each sample.
    """

    source: str
    quantities: dict[str, np.ndarray]
    channels: dict[str, str]
    units: dict[str, str]
    lines: np.ndarray
    sign_convention: str
    notes: list[str] = field(default_factory=list)
    title: list[str] = field(default_factory=list)
    unused: tuple[str, ...] = ()

    def __len__(self) -> int:
        return int(self.lines.size)


def _split(line: str, delimiter: str | None) -> list[str]:
    return [c.strip() for c in line.split(delimiter)] if delimiter else line.split()


def _delimiter(line: str) -> str | None:
    return "\t" if "\t" in line else "," if "," in line else None


def raw_layout(lines: Sequence[str]) -> tuple[int, int, str | None] | None:
    """Where a raw run's names and units rows are, and its delimiter; None if not a raw run.

    Parameters
    ----------
    lines : sequence of str
        The file's lines.

    Returns
    -------
    tuple or None
        ``(names line index, units line index, delimiter)`` (0-based; delimiter ``None``
        for spaces).
    """
    head = [(i, line) for i, line in enumerate(lines[:_HEAD_LINES]) if line.strip()]
    for k, (i, line) in enumerate(head[:-1]):
        delimiter = _delimiter(line)
        names = [c.upper() for c in _split(line, delimiter)]
        known = [c for c in names if c in RAW_CHANNELS]
        if "FZ" not in names or len(known) < _MIN_KNOWN:
            continue
        j, units = head[k + 1]
        cells = _split(units, delimiter)
        if cells and not all(_is_number(c) for c in cells if c):
            return i, j, delimiter
    return None


def _is_number(text: str) -> bool:
    try:
        parse_number(text)
    except ValueError:
        return False
    return True


def _units_row(names: list[str], cells: list[str], delimiter: str | None, source: str,
               line: int) -> list[str]:
    """One unit per channel: a units row split at spaces may split ``deg C``; joined."""
    if len(cells) > len(names) and delimiter is None:
        joined: list[str] = []
        for c in cells:
            if joined and c.upper() in ("C", "F") and joined[-1].lower() == "deg":
                joined[-1] = f"deg {c}"
            else:
                joined.append(c)
        cells = joined
    if len(cells) != len(names):
        raise InputError(f"the units row has {len(cells)} cells, the names row "
                         f"{len(names)} (delimiter: {RAW_DELIMITERS[delimiter]})",
                         file=source, row=line)
    return cells


def _columns(names: list[str], source: str, line: int) -> dict[str, int]:
    """Quantity -> column of the channels used; a channel named twice refused."""
    seen: dict[str, int] = {}
    for j, name in enumerate(names):
        if name in seen:
            raise InputError(f"channel {name} is named twice (columns {seen[name] + 1} and "
                             f"{j + 1})", file=source, column=name, row=line)
        seen[name] = j
    out: dict[str, int] = {}
    for name, j in seen.items():
        q = RAW_CHANNELS.get(name)
        if q is not None and q not in out:
            out[q] = j
    return out


def _read_samples(lines: Sequence[str], start: int, names: list[str], wanted: list[int],
                  delimiter: str | None, source: str) -> tuple[np.ndarray, np.ndarray]:
    """The numbers of the wanted columns of every sample row, and their line numbers."""
    rows = [i for i in range(start, len(lines)) if lines[i].strip()]
    if not rows:
        raise InputError("no sample rows after the names and units rows", file=source)
    if len(rows) > MAX_SAMPLES:
        raise InputError(f"{len(rows)} samples, more than the limit of {MAX_SAMPLES}; split "
                         "the run", file=source)
    values = np.empty((len(rows), len(wanted)))
    for r, i in enumerate(rows):
        cells = _split(lines[i], delimiter)
        if len(cells) != len(names):
            raise InputError(f"{len(cells)} cells on this row, {len(names)} channels named "
                             f"(delimiter: {RAW_DELIMITERS[delimiter]}; a truncated row?)",
                             file=source, row=i + 1)
        for k, j in enumerate(wanted):
            try:
                values[r, k] = parse_number(cells[j])
            except ValueError as exc:
                raise InputError(str(exc), file=source, column=names[j], row=i + 1) from None
    return values, np.asarray(rows) + 1


#: The smallest load a rig holds a tyre at [N]: below it, the tyre is off the road.
MIN_RIG_LOAD = 100.0
#: Slips whose largest magnitude stays below this (rad or slip ratio; 0.11 deg) are the
#: rig's jitter about zero: too small to check a unit by.
MIN_SWEPT_SLIP = 0.002
#: Sampling rates a rig records a raw run at [Hz].
PLAUSIBLE_RATE = (2.0, 5000.0)
#: A step in time longer than this many sampling steps is a gap (noted).
GAP_STEPS = 10
#: The channels a raw run must have: quantity -> the usual name.
REQUIRED_CHANNELS = {"fz": "FZ", "time": "ET", "alpha": "SA", "fx": "FX", "fy": "FY"}


def load_raw_run(path: str | Path, *, sign_convention: str = "sae") -> RawRun:
    """Read a raw rig run (module documentation) into SI and ISO-W axes.

    Parameters
    ----------
    path : str or Path
        The file.
    sign_convention : {"sae", "iso"}
        The axes of the run (default SAE, as the public test programmes publish).

    Returns
    -------
    RawRun

    Raises
    ------
    InputError
        Naming the file, line and channel of what cannot be read.
    """
    check_sign_convention(sign_convention)
    source = str(path)
    lines, notes = read_lines(path, "raw rig run")
    layout = raw_layout(lines)
    if layout is None and is_tydex(lines):
        raise InputError("a TYDEX file (it opens with **HEADER), not a raw rig run: its rows "
                         "are steady measurements, which fit-mf reads as they are",
                         file=source)
    if layout is None:
        raise InputError("no row of channel names (FZ with SA, SL, FX, FY ...) followed by a "
                         "row of units in the first lines: not a raw rig run", file=source)
    i_names, i_units, delimiter = layout
    names = [c.upper() for c in _split(lines[i_names], delimiter)]
    units = _units_row(names, _split(lines[i_units], delimiter), delimiter, source,
                       i_units + 1)
    cols = _columns(names, source, i_names + 1)
    for q, name in REQUIRED_CHANNELS.items():
        if q not in cols:
            raise InputError(f"no {name} channel (the {MEANINGS[q]}): a raw run needs "
                             f"{', '.join(REQUIRED_CHANNELS.values())}", file=source,
                             row=i_names + 1)
    order = sorted(cols, key=cols.__getitem__)
    values, rows = _read_samples(lines, i_units + 1, names, [cols[q] for q in order],
                                 delimiter, source)
    quantities = {q: _si(values[:, k], q, names[cols[q]], units[cols[q]], source, i_units + 1)
                  for k, q in enumerate(order)}
    title = [lines[i].strip() for i in range(i_names) if lines[i].strip()]
    run = RawRun(source, quantities, {q: names[cols[q]] for q in cols},
                 dict(zip(names, units)), rows, sign_convention, notes, title,
                 tuple(n for j, n in enumerate(names) if j not in cols.values()))
    _check_time(run)
    _kappa(run)
    run.notes.append(to_iso_axes(run.quantities, sign_convention))
    loaded = _loaded(run)
    _check_axes(run, loaded)
    _check_angles(run)
    _check_units(run, loaded & (run.quantities["fz"] > 0))
    return run


def _check_time(run: RawRun) -> None:
    """Samples in time order, each once, at a rate a rig records at; gaps noted."""
    t = run.quantities["time"]
    name = run.channels["time"]
    dt = np.diff(t)
    back = np.flatnonzero(~(dt > 0))
    if back.size:
        i = int(back[0]) + 1
        raise InputError(f"the time does not advance here ({t[i]:.6g} s after {t[i - 1]:.6g} "
                         f"s; {back.size} such step(s) in all): the samples must be in time "
                         "order, each once (rows repeated, shuffled or runs joined?)",
                         file=run.source, column=name, row=int(run.lines[i]))
    if not dt.size:
        return
    rate = 1.0 / float(np.median(dt))
    lo, hi = PLAUSIBLE_RATE
    if not lo <= rate <= hi:
        raise InputError(f"a sampling rate of {rate:.4g} Hz (rigs record at {lo:g}-{hi:g} Hz): "
                         f"the time's unit '{run.units.get(name, '')}' looks wrong by a factor",
                         file=run.source, column=name)
    gaps = np.flatnonzero(dt > GAP_STEPS / rate)
    if gaps.size:
        i = int(gaps[0])
        run.notes.append(f"{gaps.size} gap(s) in the time ({name}), the first of "
                         f"{dt[i]:.3g} s after line {int(run.lines[i])}: no samples there")


def _si(values: np.ndarray, q: str, name: str, unit: str, source: str, line: int
        ) -> np.ndarray:
    if not unit and KINDS[q] != "s":
        raise InputError(f"channel {name} has no unit in the units row", file=source,
                         column=name, row=line)
    si = convert(values, unit, q, file=source, column=name, row=line)
    if not np.all(np.isfinite(si)):
        raise InputError("value is not finite in SI", file=source, column=name, row=line)
    return si


def _kappa(run: RawRun) -> None:
    """The Magic Formula's kappa chosen by meaning (module documentation), said in a note."""
    q = run.quantities
    has = {k for k in ("kappa", "omega", "effective_radius", "speed", "slip_ratio_loaded")
           if k in q}
    sr = run.channels.get("slip_ratio_loaded")
    if "kappa" in has:
        run.notes.append(f"kappa is {run.channels['kappa']}, the slip ratio on the effective "
                         "rolling radius (the Magic Formula's)"
                         + (f"; {sr}, the rig's slip on the loaded radius, is not used"
                            if sr else ""))
    elif {"omega", "effective_radius", "speed"} <= has:
        speed = q["speed"]
        if np.any(np.abs(speed) < 0.5):
            i = int(np.argmax(np.abs(speed) < 0.5))
            raise InputError("kappa would be computed from the wheel speed, but the road "
                             "speed is below 0.5 m/s here", file=run.source,
                             column=run.channels["speed"], row=int(run.lines[i]))
        q["kappa"] = q["omega"] * q["effective_radius"] / speed - 1.0
        run.notes.append("kappa computed as omega R_e / V - 1 from "
                         + ", ".join(run.channels[k] for k in ("omega", "effective_radius",
                                                               "speed"))
                         + " (no SL channel, the slip ratio on the effective radius)")
    elif sr:
        q["kappa"] = q["slip_ratio_loaded"]
        run.notes.append(f"kappa is {sr}, the rig's slip ratio on the loaded radius: the Magic "
                         "Formula's kappa is on the effective rolling radius (SL), which the "
                         "file lacks; the two differ by some percent (RL / RE - 1 at free "
                         "rolling)")
    else:
        q["kappa"] = np.zeros(len(run))
        run.notes.append("no slip ratio channel (SL, SR, or N with RE and V): kappa = 0")
    for name, default, what in (("gamma", 0.0, "camber (IA)"),
                                ("pressure", math.nan, "pressure (P)")):
        if name not in q:
            q[name] = np.full(len(run), default)
            run.notes.append(f"no {what} channel: "
                             + ("camber = 0" if name == "gamma" else "not measured"))


def _loaded(run: RawRun) -> np.ndarray:
    """The samples that carry a load (:data:`MIN_RIG_LOAD` or more, and a tenth of the
    run's 95th-percentile |load|): what the checks of the axes and units look at."""
    fz = run.quantities["fz"]
    loaded = np.abs(fz) > max(0.1 * np.percentile(np.abs(fz), 95), MIN_RIG_LOAD)
    if not loaded.any():
        raise InputError(f"no sample carries a load of {MIN_RIG_LOAD:g} N or more (the "
                         f"largest |{run.channels['fz']}| is {np.max(np.abs(fz)):.3g} N): "
                         "the tyre is lifted throughout, or the run was cut before it was "
                         "loaded", file=run.source, column=run.channels["fz"])
    return loaded


def _check_axes(run: RawRun, loaded: np.ndarray) -> None:
    """Loads of the other sign than the axes declared: the other convention, said."""
    fz = run.quantities["fz"]
    if np.mean(fz[loaded] < 0) > 0.5:
        other = "iso" if run.sign_convention == "sae" else "sae"
        said = ("SAE loads are negative in the file and were negated, so these were "
                "positive: ISO-W axes" if run.sign_convention == "sae" else
                "ISO-W loads are positive; these are negative: SAE axes")
        i = int(np.argmax(loaded & (fz < 0)))
        raise InputError([f"the load is negative on most loaded samples after the "
                          f"conversion to ISO-W ({said}; give ",
                          Argument("sign_convention", other), ")"], file=run.source,
                         column=run.channels["fz"], row=int(run.lines[i]))


def _check_angles(run: RawRun) -> None:
    """Slip angles beyond 90 degrees or cambers beyond 30: degrees under ``rad``."""
    for q, limit, what in (("alpha", math.pi / 2, "slip angle beyond 90 degrees"),
                           ("gamma", _LARGEST_CAMBER, "camber beyond 30 degrees")):
        if q not in run.channels:
            continue
        bad = np.abs(run.quantities[q]) > limit
        if bad.any():
            name = run.channels[q]
            raise InputError(f"{what} (unit '{run.units[name]}'): degrees under a radian "
                             "unit?", file=run.source, column=name,
                             row=int(run.lines[np.argmax(bad)]))


def _refuse_unit(run: RawRun, q: str, message: str, where: np.ndarray) -> None:
    name = run.channels.get(q, q.upper())
    raise InputError(f"{message} (unit '{run.units.get(name, '')}')", file=run.source,
                     column=name, row=int(run.lines[int(np.argmax(where))]))


def _check_units(run: RawRun, loaded: np.ndarray) -> None:
    """Slips, forces and moments of the ``loaded`` samples (ISO-W: loads positive) against
    what tyres do (the bounds of a fit's checks): a unit that is wrong by a factor would
    otherwise shrink or blow up the sweeps."""
    q = run.quantities
    fz = q["fz"]
    kappa, tan_a = q["kappa"], np.tan(q["alpha"])
    if np.mean(np.abs(kappa[loaded]) > 1) > 0.01:
        _refuse_unit(run, "kappa", "slip ratios beyond -1..1: percent given as fractions?",
                     loaded & (np.abs(kappa) > 1))
    for force, slip, other, limit, what in (
            ("fy", tan_a, np.abs(kappa) < 0.01, MAX_CORNERING_COEFFICIENT,
             "a cornering coefficient of {c:.0f} per rad (tyres have 5-40): the slip angles "
             "look like radians under a degree unit"),
            ("fx", kappa, np.abs(q["alpha"]) < math.radians(1.0), MAX_SLIP_COEFFICIENT,
             "a slip coefficient of {c:.0f} (tyres have 10-40): the slip ratios look like "
             "fractions under a percent unit")):
        use = loaded & other & (np.abs(slip) > 1e-6)
        # slips within the jitter, or held (a channel stuck at a value): the ratio would be
        # the force offsets over a tiny slip, or a sweep's forces over a slip that is not its
        if (force in q and use.sum() > 10 and np.max(np.abs(slip[use])) >= MIN_SWEPT_SLIP
                and np.ptp(slip[use]) >= MIN_SWEPT_SLIP):
            coef = slip_coefficient(q[force][use], fz[use], slip[use], share=99.9)
            if coef > limit:
                _refuse_unit(run, "alpha" if force == "fy" else "kappa", what.format(c=coef),
                             use)
    _check_loads_and_moments(run, loaded)
    _check_pressure(run, loaded)
    _check_camber_settings(run, loaded)


def _check_camber_settings(run: RawRun, loaded: np.ndarray) -> None:
    """Camber settings in radians under a degree unit
    (:func:`~frictionlaws.tyre.data.channels.camber_settings_in_radians`, on the loaded
    samples): refused when the camber thrust says so, else warned of."""
    q = run.quantities
    if "gamma" not in run.channels or "fy" not in q:
        return
    name = run.channels["gamma"]
    found = camber_settings_in_radians(q["gamma"][loaded], run.units.get(name, ""),
                                       q["fy"][loaded], q["fz"][loaded], q["alpha"][loaded],
                                       np.abs(q["kappa"][loaded]) <= 0.01)
    if found is None:
        return
    text, decisive, top = found
    error = InputError(text.replace("'gamma [rad]'", f"'rad' in {name}'s unit"),
                       file=run.source, column=name,
                       row=int(run.lines[loaded][np.argmax(top)]))
    if decisive:
        raise error
    warnings.warn(str(error), UserWarning, stacklevel=3)


def _check_pressure(run: RawRun, loaded: np.ndarray) -> None:
    """The median inflation pressure of the loaded samples where tyres run
    (:func:`~frictionlaws.tyre.mf.parameters.check_pressure`): else the unit is off by a
    factor (kPa under MPa, bar under kPa, ...); the row named is the first loaded one."""
    p = run.quantities.get("pressure")
    if p is None or not np.isfinite(p[loaded]).any():
        return
    name = run.channels["pressure"]
    measured = loaded & np.isfinite(p)
    check_pressure(float(np.median(p[measured])), "a median inflation pressure of",
                   file=run.source, column=name, rows=[int(run.lines[np.argmax(measured)])],
                   unit=run.units.get(name, ""))


def _check_loads_and_moments(run: RawRun, loaded: np.ndarray) -> None:
    """Forces of a few percent of the load at most (a load unit too large), or moments
    beyond the load times the loaded radius (N mm as N m)."""
    q = run.quantities
    fz = q["fz"][loaded]
    forces = [np.abs(q[k][loaded]) for k in ("fx", "fy") if k in q]
    if forces and float(np.percentile(np.max(forces, axis=0) / fz, 99)) < 0.02:
        _refuse_unit(run, "fz", "the forces stay below 2 % of the load: the load looks "
                                "larger than it is (kN under N?)", loaded)
    if "mz" in q and "loaded_radius" in q:
        arm = np.abs(q["mz"][loaded]) / fz
        radius = q["loaded_radius"][loaded]
        if float(np.percentile(arm / radius, 99)) > 1:
            _refuse_unit(run, "mz", "|MZ| exceeds the load times the loaded radius: the "
                                    "moments look like N mm under N m", loaded)
