"""Export a law to finite-element codes: tables, keyword cards and user subroutines.

:func:`export` writes a law, with its parameters, in the model's unit system,
to one of :data:`FORMATS`, the one table of formats (:mod:`.formats`: each a writer and
its entry, read by the API, the command line and the docs):

* tables the solver interpolates (``csv``, ``json``, ``abaqus`` ``*FRICTION``,
  ``lsdyna`` ``*DEFINE_TABLE``, ``ansys`` ``TB,FRIC``), on grids whose
  interpolation error is measured (and, with ``tol``, bounded) the way the
  solver interpolates: multilinear, end values held (:mod:`.grid`);
* closed forms the solver has built in (``abaqus-decay``, LS-DYNA FS/FD/DC,
  Radioss Ifric 1 and 4), written only when exact (:mod:`.exact`), or for
  Radioss fitted over the box with the approximation error stated;
* Abaqus user subroutines generated from the symbolic form (:mod:`.fortran`).

Every file starts with a header: law, parameters with units, unit system, box,
the maximum interpolation error and where it occurs, and what the solver does
outside the box.

The function is also ``frictionlaws.export``; this package is named
``fe_export`` so that the two never shadow each other.
"""

from .api import ExportResult, export, make_specs, parse_range
from .formats import FORMATS, OPTIONS, ExportFormat, FormatOption
from .grid import AxisSpec, Grid, GridError
from .systems import SYSTEMS, UnitSystem, unit_system

__all__ = ["export", "ExportResult", "FORMATS", "OPTIONS", "ExportFormat", "FormatOption",
           "AxisSpec", "Grid", "GridError", "UnitSystem", "unit_system", "SYSTEMS",
           "parse_range", "make_specs"]
