"""Fitting a Magic Formula property file to tyre test data, stage by stage.

* :mod:`~frictionlaws.tyre.mf.fit.staged`: :func:`fit_mf`, the staged fit;
* :mod:`~frictionlaws.tyre.mf.fit.pure`: the pure-slip stages (F_x0, F_y0);
* :mod:`~frictionlaws.tyre.mf.fit.stages`: the combined-slip, force and aligning-moment
  stages;
* :mod:`~frictionlaws.tyre.mf.fit.rows`: which rows are near pure slip, their load levels;
* :mod:`~frictionlaws.tyre.mf.fit.checks`: the data checked for units and curves first;
* :mod:`~frictionlaws.tyre.mf.fit.template`: the template and the property file written;
* :mod:`~frictionlaws.tyre.mf.fit.peak`: the peak friction kept physical, and said when
  the data do not reach it;
* :mod:`~frictionlaws.tyre.mf.fit.bootstrap`: the sweep bootstrap's standard errors;
* :mod:`~frictionlaws.tyre.mf.fit.result`: :class:`MFFit`;
* :mod:`~frictionlaws.tyre.mf.fit.plot`: its figure.
"""

from __future__ import annotations

from ....base.lazy import lazy_getattr

#: public name -> the submodule that defines it
_API = {
    "fit_mf": "staged",
    "FITTYPS": "staged",
    "MFFit": "result",
    "check_tir_path": "result",
    "UNCERTAINTIES": "result",
    "X_COEFFICIENTS": "pure",
    "Y_COEFFICIENTS": "pure",
}

__all__ = list(_API)


__getattr__ = lazy_getattr(__name__, _API)
