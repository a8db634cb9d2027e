"""The example files the README and the getting-started guide use, written to a folder.

:func:`write_example_files` (CLI ``frictionlaws examples DIR``) writes small, synthetic
tables and a synthetic tribometer campaign, each generated from a stated law with stated
values and noise (a ``# synthetic: ...`` comment heads every table, and ``EXAMPLES.txt``
lists them), so that every command of the README's "A first look" runs as written:

==================  =============================================================
``my.csv``          your own columns: ``FC`` (mu), ``CP`` (p, MPa), ``DV`` (v, m/s),
                    no units in the header (``--map``/``--units`` demonstration)
``campaign.csv``    three counter-surfaces (``surface`` column), p in MPa
``temps.csv``       three temperatures (``T [degC]``), one Thirion ``b`` in common
``runs.csv``        three repeated runs (``run`` column), for standard input
``data/``           two test days on two surfaces, one file each (a directory of datasets)
``tyre_data.csv``   pure-slip forces of the packaged ``MagicFormula61`` tyre, 1 % noise
``manifest.csv``,   a small raw tribometer campaign (torque records) from
``rig.toml``,       :func:`frictionlaws.tribometer.synthetic.make_campaign`
``records/``
==================  =============================================================

The values are reproducible: the same ``seed`` writes the same files.  Nothing is
written over an existing file: the call is refused, naming it, before any work.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from .base.errors import InputError
from .base.outputs import atomic_dir
from .tribometer.synthetic import ConditionSpec, make_campaign
from .tyre import MagicFormula

__all__ = ["EXAMPLE_FILES", "write_example_files"]

#: The files and directories :func:`write_example_files` creates, relative to its folder.
EXAMPLE_FILES = ("EXAMPLES.txt", "my.csv", "campaign.csv", "temps.csv", "runs.csv", "data",
                 "tyre_data.csv", "manifest.csv", "rig.toml", "records")

#: Pressures [MPa] of the example tables (the range of the thesis' steel-disc data).
_PRESSURES = (0.03, 0.06, 0.09, 0.12, 0.16, 0.2, 0.25)
#: Relative scatter (standard deviation) of the example friction coefficients.
_SCATTER = 0.03


def _thirion_mu(rng: np.random.Generator, a: float, b_mpa: float, p_mpa: np.ndarray
                ) -> np.ndarray:
    """Thirion's ``1/mu = a + b p`` (b in 1/MPa) with relative Gaussian scatter."""
    mu = 1.0 / (a + b_mpa * p_mpa)
    return mu * (1.0 + _SCATTER * rng.standard_normal(p_mpa.shape))


def _table(header: Sequence[str], columns: Sequence[Sequence[object]], note: str) -> str:
    """CSV text with a ``# synthetic`` comment line; numbers to 4 significant figures."""
    def cell(x: object) -> str:
        return f"{x:.4g}" if isinstance(x, float | np.floating) else str(x)

    lines = [f"# synthetic: {note}", ",".join(header)]
    lines += [",".join(cell(c) for c in row) for row in zip(*columns)]
    return "\n".join(lines) + "\n"


def _grouped(rng: np.random.Generator, groups: Mapping[Any, tuple[float, float]],
             repeats: int) -> tuple[list[object], list[float], list[float]]:
    """Rows of a Thirion table per group: (group labels, p [MPa], mu)."""
    keys: list[object] = []
    ps: list[float] = []
    mus: list[float] = []
    p = np.repeat(np.asarray(_PRESSURES), repeats)
    for key, (a, b) in groups.items():
        keys += [key] * p.size
        ps += [float(x) for x in p]
        mus += [float(x) for x in _thirion_mu(rng, a, b, p)]
    return keys, ps, mus


_SURFACES = {"steel": (0.25, 3.5), "glass": (0.2, 3.0), "concrete": (0.45, 1.8)}
_TEMPS = {20: (0.25, 3.0), 40: (0.32, 3.0), 60: (0.4, 3.0)}


def _describe(groups: Mapping[Any, tuple[float, float]], unit: str = "") -> str:
    return "; ".join(f"{k}{unit}: a = {a:g}, b = {b:g} 1/MPa" for k, (a, b) in groups.items())


def _sliding_tables(rng: np.random.Generator) -> dict[str, str]:
    """The friction tables: my.csv, campaign.csv, temps.csv, runs.csv and data/day*.csv."""
    out: dict[str, str] = {}
    law = f"Thirion 1/mu = a + b p with {_SCATTER:.0%} relative scatter"
    p = np.tile(np.asarray(_PRESSURES), 3)
    v = np.repeat([0.1, 0.5, 1.0], len(_PRESSURES))
    out["my.csv"] = _table(("FC", "CP", "DV"), (list(_thirion_mu(rng, 0.28, 3.2, p)),
                                                list(map(float, p)), list(map(float, v))),
                           f"{law}, a = 0.28, b = 3.2 1/MPa; FC = mu, CP = p in MPa, "
                           "DV = sliding speed in m/s (no units in the header)")
    keys, ps, mus = _grouped(rng, _SURFACES, 2)
    out["campaign.csv"] = _table(("surface", "p [MPa]", "mu"), (keys, ps, mus),
                                 f"{law}; {_describe(_SURFACES)}")
    keys, ps, mus = _grouped(rng, _TEMPS, 2)
    out["temps.csv"] = _table(("T [degC]", "p [MPa]", "mu"), (keys, ps, mus),
                              f"{law}; b common; {_describe(_TEMPS, ' degC')}")
    keys, ps, mus = _grouped(rng, {1: (0.25, 3.5), 2: (0.25, 3.5), 3: (0.25, 3.5)}, 1)
    out["runs.csv"] = _table(("run", "p [MPa]", "mu"), (keys, ps, mus),
                             f"{law}, a = 0.25, b = 3.5 1/MPa; three repeated runs")
    for day in (1, 2):
        for surface in ("steel", "glass"):
            one = {surface: _SURFACES[surface]}
            keys, ps, mus = _grouped(rng, one, 1)
            out[f"data/day{day}_{surface}.csv"] = _table(
                ("surface", "p [MPa]", "mu"), (keys, ps, mus),
                f"{law}; test day {day}; {_describe(one)}")
    return out


def _tyre_table(rng: np.random.Generator) -> str:
    """Pure-slip Fx and Fy of the packaged MagicFormula61 tyre with 1 % noise."""
    mf = MagicFormula.from_file("MagicFormula61")
    p0 = mf.nominal_pressure or 2.6e5
    kappa = np.linspace(-0.3, 0.3, 21)
    alpha = np.radians(np.linspace(-12.0, 12.0, 21))
    rows: list[tuple[float, ...]] = []
    for fz in mf.fnomin * np.array([0.5, 1.0, 1.5]):
        for p in (0.9 * p0, 1.1 * p0):
            for g in (0.0, 0.05):
                fx = mf.fx0(kappa, fz, g, pressure=p)
                fy = mf.fy0(alpha, fz, g, pressure=p)
                fx = fx + 0.01 * np.abs(fx).max() * rng.standard_normal(fx.shape)
                fy = fy + 0.01 * np.abs(fy).max() * rng.standard_normal(fy.shape)
                common = (fz / 1e3, np.degrees(g), p / 1e3)
                rows += [(common[0], float(k), 0.0, common[1], common[2], float(x), np.nan)
                         for k, x in zip(kappa, fx)]
                rows += [(common[0], 0.0, float(np.degrees(a)), common[1], common[2], np.nan,
                          float(y)) for a, y in zip(alpha, fy)]
    header = ("Fz [kN]", "kappa [-]", "alpha [deg]", "gamma [deg]", "pressure [kPa]",
              "Fx [N]", "Fy [N]")
    lines = ["# synthetic: pure-slip forces of the packaged MagicFormula61 property file, "
             "3 loads x 2 pressures x 2 cambers, noise 1 % of each curve's peak",
             ",".join(header)]
    lines += [",".join("" if np.isnan(x) else f"{x:.6g}" for x in row) for row in rows]
    return "\n".join(lines) + "\n"


def _campaign(folder: Path, seed: int) -> None:
    """A raw tribometer campaign: two surfaces x three loads x three records of 12 s."""
    conditions = [ConditionSpec(f"{surface} {load:g} kg", surface, load,
                                round(1.0 / (a + b * load * 9.8 / 314.16), 3), repeats=3)
                  for surface, (a, b) in (("steel", _SURFACES["steel"]),
                                          ("glass", _SURFACES["glass"]))
                  for load in (2.0, 4.0, 6.0)]
    make_campaign(folder, conditions, seed=seed, record_kwargs={"duration": 12.0})


_NOTE = """\
Example files written by frictionlaws (frictionlaws examples DIR, or
frictionlaws.example_files.write_example_files), seed {seed}.  Every value is synthetic:
generated from the law and values stated in each table's first line, with random scatter.

my.csv          your own column names: FC = mu, CP = p [MPa], DV = v [m/s], no units
campaign.csv    three counter-surfaces (column 'surface')
temps.csv       three temperatures in degC, one Thirion b in common
runs.csv        three repeated runs (column 'run')
data/           two test days on two surfaces, one file each
tyre_data.csv   pure-slip tyre forces from the packaged MagicFormula61 file
manifest.csv    a raw tribometer campaign: records/*.csv (time, torque, speeds),
rig.toml        the rig description, and the manifest listing loads and surfaces
"""


def write_example_files(directory: str | os.PathLike[str], *, seed: int = 0) -> list[Path]:
    """Write the README's example files into ``directory`` (created if needed).

    Parameters
    ----------
    directory : str or path
        The folder.  It may exist; none of :data:`EXAMPLE_FILES` may exist in it.
    seed : int
        Seed of the random scatter (the same seed writes the same files).

    Returns
    -------
    list of Path
        The files and directories written, in the order of :data:`EXAMPLE_FILES`.

    Raises
    ------
    InputError
        When one of the files or directories already exists (nothing is written), or
        the seed is not a whole number from 0 to 2**32 - 1.
    """
    if isinstance(seed, bool) or not isinstance(seed, int | np.integer) \
            or not 0 <= int(seed) < 2**32:
        raise InputError(f"seed must be a whole number from 0 to {2**32 - 1}, got {seed!r}",
                         option="seed")
    root = Path(directory)
    taken = [name for name in EXAMPLE_FILES if os.path.lexists(root / name)]
    if taken:
        raise InputError(f"{', '.join(taken)} already exist(s) there; the example files "
                         "are never written over existing ones (choose an empty folder)",
                         file=str(root))
    rng = np.random.default_rng(seed)
    with atomic_dir(root) as tmp:
        (tmp / "data").mkdir()
        for name, text in _sliding_tables(rng).items():
            (tmp / name).write_text(text, encoding="utf-8")
        (tmp / "tyre_data.csv").write_text(_tyre_table(rng), encoding="utf-8")
        _campaign(tmp, seed)
        (tmp / "EXAMPLES.txt").write_text(_NOTE.format(seed=seed), encoding="utf-8")
    return [root / name for name in EXAMPLE_FILES]
