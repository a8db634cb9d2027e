"""Friction laws inside tyre models.

* :class:`BrushModel` / :class:`BrushTyre`: a steady-state brush tyre whose
  local friction limit is any sliding law mu(p, v) (lateral F_y(alpha),
  longitudinal F_x(kappa), cornering stiffness against load);
* :func:`thesis_comparison`: the source thesis' cornering experiment (constant
  mu against friction fitted to its tribometer data) beside its Table 6-2;
* :class:`MagicFormula`: the PAC2002 / MF 5.2 and MF 6.1/6.2 pure-slip forces
  from ADAMS ``.tir`` or JSON property files (:func:`read_property_file`), whose
  coefficients are declared (unit, meaning, default, bounds) in
  :mod:`~frictionlaws.tyre.mf_coefficients`;
* :func:`reduce_mf`: fit a simple slip law (``pacejka``, ``burckhardt``) to a
  Magic Formula curve at one load;
* :func:`fit_mf`: fit a Magic Formula property file to tyre test data
  (:func:`read_tyre_data`) and write it as ``.tir``;
* :func:`transient_slip`: the forces over time of a tyre whose slips relax over the
  relaxation lengths (MF-Tyre's first-order transient model).

Units are SI everywhere (N, m, Pa, m/s, rad).
"""

from .brush import BrushModel, BrushTyre, CorneringResult
from .fit_mf import MFFit, fit_mf
from .magic_formula import MagicFormula, MFCoefficients
from .reduce import Reduction, equivalent_pacejka, mf_slip_curve, reduce_mf
from .thesis import TABLE_6_2, ThesisComparison, thesis_comparison, thesis_ratios
from .tir import PropertyFile, read_property_file, write_tir
from .transient import TransientSlip, transient_slip
from .tyre_data import TyreData, read_tyre_data

__all__ = [
    "BrushModel",
    "BrushTyre",
    "CorneringResult",
    "MagicFormula",
    "MFCoefficients",
    "MFFit",
    "fit_mf",
    "TyreData",
    "read_tyre_data",
    "PropertyFile",
    "read_property_file",
    "write_tir",
    "TransientSlip",
    "transient_slip",
    "Reduction",
    "reduce_mf",
    "equivalent_pacejka",
    "mf_slip_curve",
    "TABLE_6_2",
    "ThesisComparison",
    "thesis_comparison",
    "thesis_ratios",
]
