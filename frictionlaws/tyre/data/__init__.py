"""Tyre test data as it comes: tidy CSV tables, TYDEX files and raw rig runs.

Every reader gives :class:`TyreData` (SI units, ISO-W axes), which
:func:`frictionlaws.tyre.mf.fit.staged.fit_mf` fits:

* :func:`read_tyre_data`: a tidy CSV table with units in its headers
  (:mod:`~frictionlaws.tyre.data.table`; :func:`write_tyre_csv` writes one);
* :func:`read_tydex`: a TYDEX file (:mod:`~frictionlaws.tyre.data.tydex`; :func:`write_tydex`
  writes one, :func:`load_tydex` gives its sections);
* :func:`load_raw_run` and :func:`prepare_run`: a raw rig run, one row per sample, as public
  tyre test programmes publish them (:mod:`~frictionlaws.tyre.data.raw_run`), turned into
  steady sweeps with what was dropped reported (:mod:`~frictionlaws.tyre.data.segments`;
  :func:`write_plots` draws them);
* :func:`read_tyre_files`: one or several files of any of these formats, told apart by their
  content (:mod:`~frictionlaws.tyre.data.formats`), as one data set.

:mod:`~frictionlaws.tyre.data.synthetic` makes such files from a Magic Formula, with the
imperfections of a real rig, for checks and examples.
"""

from .formats import FORMATS, ReadFile, detect_format, read_tyre_file, read_tyre_files
from .plots import write_plots
from .raw_run import RawRun, load_raw_run
from .segments import PreparedRun, Segment, prepare_run
from .table import TyreData, join, read_tyre_data, write_tyre_csv
from .tydex import TydexFile, load_tydex, read_tydex, tydex_text, write_tydex

__all__ = ["TyreData", "read_tyre_data", "write_tyre_csv", "join", "TydexFile", "load_tydex",
           "read_tydex", "tydex_text", "write_tydex", "RawRun", "load_raw_run", "PreparedRun",
           "Segment", "prepare_run", "write_plots", "FORMATS", "ReadFile", "detect_format",
           "read_tyre_file", "read_tyre_files"]
