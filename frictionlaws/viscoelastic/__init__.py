"""The viscoelastic room: rubber's dependence on temperature and rate.

* :mod:`~frictionlaws.viscoelastic.temperature`: the WLF shift factor, its presets and
  conversions, and a law made temperature-aware by shifting its velocity
  (:func:`~frictionlaws.viscoelastic.temperature.with_wlf`);
* :mod:`~frictionlaws.viscoelastic.mastercurve`: master curves built from frequency
  sweeps at several temperatures, and the WLF constants fitted to their shifts.

Import from the module that defines a name; this package imports none of them.
"""

__all__: list[str] = []
