"""Benchmark of tyre test data as it comes: a raw rig run and three TYDEX files to ``.tir``.

Data: a held-out tyre (the packaged MF 6.2 example with every longitudinal, lateral and
aligning coefficient moved by a factor drawn uniformly from 0.8-1.2, ``--seed``), measured by
:func:`frictionlaws.tyre.data.synthetic.synthetic_raw_run` (about 156,000 samples at 100 Hz:
4 loads, 3 cambers, 2 pressures, warm-up, lifts, ramps, continuous sweeps up and down,
slip-ratio sweeps at 0, +-4 and +-8 degrees, noise, drifting zero offsets, a 50 ms force lag,
SAE axes) and by :func:`~frictionlaws.tyre.data.synthetic.sweep_data` written as three TYDEX
files (lateral; longitudinal with the pressure in bar and the forces in daN with a factor
10; combined).  Each is fitted by ``frictionlaws tyre fit-mf ... --fittyp 62`` in one
command.

Baseline, in the same run: :func:`numpy.loadtxt` of the raw run's numbers (reading the text
alone, with no checks, units, axes or segmentation).

Printed: wall time of the reading and preparation against the baseline, of each fit, what
the segmentation dropped, and each fitted file's largest error against the noise-free truth
(pure F_x0, F_y0 and combined F_x, F_y as a share of the curve's peak, M_z of the peak
|M_z|) at every load, camber and pressure.

Run: ``python benchmarks/bench_tyre_data.py [--seed 31337] [--keep DIR]``.
"""

from __future__ import annotations

import argparse
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

from frictionlaws.base.errors import ExtrapolationWarning
from frictionlaws.cli import main
from frictionlaws.tyre import MagicFormula
from frictionlaws.tyre.data import load_raw_run, prepare_run, write_tydex
from frictionlaws.tyre.data.synthetic import RawRunSpec, sweep_data, synthetic_raw_run
from frictionlaws.tyre.synthetic_rig import moved_tyre, truth_errors

LOADS, CAMBERS, PRESSURES = (0.4, 0.8, 1.2, 1.6), (-3.0, 0.0, 3.0), (0.85, 1.1)
SPEC = RawRunSpec(loads=LOADS, cambers_deg=CAMBERS, pressures=PRESSURES, rate=100.0,
                  cycles=1, alpha_rate_deg=4.8, kappa_rate=0.15, warmup_s=40.0)


def held_out_tyre(seed: int) -> MagicFormula:
    """The MF 6.2 example with every P*, Q*, R*, S* coefficient moved by 0.8-1.2."""
    base = MagicFormula.from_file("MagicFormula62")
    rng = np.random.default_rng(seed)
    names = sorted(k for k, v in base.coefficients.items()
                   if k[:1] in "PQRS" and k[1:2].isalpha() and v != 0)
    return moved_tyre("MagicFormula62", dict(zip(names, rng.uniform(0.8, 1.2, len(names)))),
                      set_to={})


def _errors(truth: MagicFormula, tir: Path) -> dict[str, float]:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        return truth_errors(truth, MagicFormula.from_file(tir), loads=LOADS,
                            pressures=PRESSURES, cambers_deg=CAMBERS)


def _fit(files: list[Path], tir: Path) -> float:
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        code = main(["tyre", "fit-mf", *map(str, files), "--fittyp", "62", "-o", str(tir),
                     "--json"])
    if code:
        raise SystemExit(f"fit-mf exited with {code}")
    return time.perf_counter() - t0


def run(seed: int, folder: Path) -> None:
    import contextlib
    import io

    truth = held_out_tyre(seed)
    raw = synthetic_raw_run(truth, SPEC).write(folder / "held_out_run.dat")
    kw = dict(loads=LOADS, cambers_deg=CAMBERS, pressures=PRESSURES, n=41, seed=seed)
    tydex = [write_tydex(sweep_data(truth, "lateral", **kw), folder / "lateral.tdx"),
             write_tydex(sweep_data(truth, "longitudinal", **kw), folder / "longitudinal.tdx",
                         units={"pressure": "bar", "fx": "daN", "fy": "daN"},
                         factors={"fx": 10.0, "fy": 10.0}),
             write_tydex(sweep_data(truth, "combined", **kw), folder / "combined.tdx")]
    t0 = time.perf_counter()
    np.loadtxt(raw, skiprows=3)
    t_base = time.perf_counter() - t0
    t0 = time.perf_counter()
    prepared = prepare_run(load_raw_run(raw))
    t_prep = time.perf_counter() - t0
    print(f"raw run: {len(prepared.run)} samples; read and prepared in {t_prep:.2f} s "
          f"(baseline numpy.loadtxt {t_base:.2f} s, x{t_prep / t_base:.2f})")
    print("\n".join("  " + line for line in prepared.summary()[1:]))
    with contextlib.redirect_stdout(io.StringIO()):
        t_raw = _fit([raw], folder / "raw.tir")
        t_tdx = _fit(tydex, folder / "tydex.tir")
    for name, tir, seconds in (("raw run", folder / "raw.tir", t_raw),
                               ("3 TYDEX files", folder / "tydex.tir", t_tdx)):
        e = _errors(truth, tir)
        print(f"{name}: fit-mf {seconds:.1f} s; largest error, share of peak: "
              + ", ".join(f"{k} {100 * v:.2f} %" for k, v in e.items()))


def cli() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=31337)
    parser.add_argument("--keep", metavar="DIR", help="write the files here (else a "
                        "temporary folder)")
    args = parser.parse_args()
    if args.keep:
        Path(args.keep).mkdir(parents=True, exist_ok=True)
        run(args.seed, Path(args.keep))
        return
    with tempfile.TemporaryDirectory() as tmp:
        run(args.seed, Path(tmp))


if __name__ == "__main__":
    cli()
