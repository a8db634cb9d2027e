"""Friction laws inside tyre models.

* :class:`BrushModel` / :class:`BrushTyre`: a steady-state brush tyre whose
  local friction limit is any sliding law mu(p, v) (lateral F_y(alpha),
  longitudinal F_x(kappa), cornering stiffness against load);
* :func:`thesis_comparison`: the source thesis' cornering experiment (constant
  mu against friction fitted to its tribometer data) beside its Table 6-2;
* :class:`MagicFormula`: the PAC2002 / MF 5.2 and MF 6.1/6.2 forces, moments and
  other steady-state outputs from ADAMS ``.tir`` or JSON property files
  (:func:`read_property_file`), whose coefficients are declared (unit, meaning,
  default, bounds, fit stage) in :mod:`~frictionlaws.tyre.mf.declarations`; the Magic
  Formula's room is :mod:`frictionlaws.tyre.mf`;
* :func:`reduce_mf`: fit a simple slip law (``pacejka``, ``burckhardt``) to a
  Magic Formula curve at one load;
* :func:`fit_mf`: fit a Magic Formula property file to tyre test data
  (:func:`read_tyre_data`) and write it as ``.tir``;
* :func:`transient_slip`: the forces over time of a tyre whose slips relax over the
  relaxation lengths (MF-Tyre's first-order transient model).

Units are SI everywhere (N, m, Pa, m/s, rad).

The names below are imported on first use, so that importing a module of the package
(the CLI reads :data:`frictionlaws.tyre.mf.inputs.INPUTS` when it builds its parser) loads
none of the others.
"""

from ..base.lazy import lazy_getattr

#: public name -> the submodule that defines it
_API = {
    "BrushModel": "brush",
    "BrushTyre": "brush",
    "CorneringResult": "brush",
    "MagicFormula": "mf.model",
    "MFCoefficients": "mf.equations",
    "MFFit": "mf.fit.result",
    "fit_mf": "mf.fit.staged",
    "TyreData": "data.table",
    "read_tyre_data": "data.table",
    "PropertyFile": "mf.property_file",
    "read_property_file": "mf.tir",
    "write_tir": "mf.tir",
    "TransientSlip": "transient",
    "transient_slip": "transient",
    "Reduction": "reduce",
    "reduce_mf": "reduce",
    "equivalent_pacejka": "reduce",
    "mf_slip_curve": "reduce",
    "TABLE_6_2": "thesis",
    "ThesisComparison": "thesis",
    "thesis_comparison": "thesis",
    "thesis_ratios": "thesis",
}

__all__ = list(_API)


__getattr__ = lazy_getattr(__name__, _API)
