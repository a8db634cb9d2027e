"""The Magic Formula (PAC2002 / MF 5.2, MF 6.1, MF 6.2): one module per concern.

* :mod:`~frictionlaws.tyre.mf.declarations`: every coefficient declared once (section,
  versions, unit, meaning, default, bounds, fit stage); :mod:`~frictionlaws.tyre.mf.coefficients`:
  what is done with them (the checked view ``c.PCX1``, checks, fit stages, listing);
* :mod:`~frictionlaws.tyre.mf.parameters`: one tyre's parameters checked once
  (:class:`~frictionlaws.tyre.mf.parameters.MFParameters`), the view the equations read;
* the equations as plain functions of it: :mod:`~frictionlaws.tyre.mf.equations` (forces,
  combined slip), :mod:`~frictionlaws.tyre.mf.moments` (M_z, M_x, M_y),
  :mod:`~frictionlaws.tyre.mf.vertical` (radii, vertical stiffness, patch, relaxation);
* :mod:`~frictionlaws.tyre.mf.model`: :class:`MagicFormula`, which checks its inputs once
  and hands on to the equations;
* :mod:`~frictionlaws.tyre.mf.conditions` (the inputs of the steady state, checked) and
  :mod:`~frictionlaws.tyre.mf.outputs` (:data:`OUTPUTS`, the one table of outputs that
  :func:`steady_state`, the CLI, JSON and xarray loop over);
* :mod:`~frictionlaws.tyre.mf.notices`: the one path of the warnings;
* property files: :mod:`~frictionlaws.tyre.mf.property_file` (the content and what it says
  about the tyre) and :mod:`~frictionlaws.tyre.mf.tir` (reading and writing ``.tir`` and
  JSON, the packaged examples);
* :mod:`~frictionlaws.tyre.mf.fit`: the staged fit of a property file to test data.

The names below are imported on first use (:mod:`frictionlaws.tyre.mf.inputs`, read by the
CLI when it builds its parser, loads no numpy).
"""

from __future__ import annotations

from ...base.lazy import lazy_getattr

#: public name -> the submodule that defines it
_API = {
    "MagicFormula": "model",
    "MFCoefficients": "equations",
    "mf_curve": "equations",
    "MFFit": "fit.result",
    "fit_mf": "fit.staged",
    "PropertyFile": "property_file",
    "read_property_file": "tir",
    "write_tir": "tir",
    "json_to_tir": "tir",
    "OUTPUTS": "outputs",
    "steady_state": "outputs",
    "evaluate": "outputs",
    "INPUTS": "inputs",
    "DECLARED": "declarations",
    "Coefficient": "declarations",
}

__all__ = list(_API)


__getattr__ = lazy_getattr(__name__, _API)
