"""Persson's theory of rubber friction: material, surface and the friction integral.

* :mod:`.material`: a Prony-series rubber fitted to a DMA master curve, with
  its temperature shift (:func:`default_material` from the packaged data,
  :func:`material_from_csv` from a user's file).
* :mod:`.surface`: self-affine and measured roughness spectra C(q), and the
  1-D profile to isotropic 2-D conversion.
* :mod:`.theory`: the contact ratio P(q) and the friction coefficient
  mu(v, T, p) (fast vectorised quadrature).

The registry law ``persson`` (``frictionlaws/laws/persson.py``) wraps it.
"""

from .material import (
                       Material,
                       Shift,
                       default_material,
                       fit_prony,
                       material_from_csv,
                       material_from_master_curve,
)
from .surface import (
                       SelfAffine,
                       TabulatedPSD,
                       asphalt_like,
                       one_d_to_two_d,
                       psd_from_profile,
                       psd_from_profile_csv,
)
from .theory import contact_ratio, friction, loss_angular, modulus_sq_angular

__all__ = ["Material", "Shift", "default_material", "fit_prony", "material_from_csv",
           "material_from_master_curve", "SelfAffine", "TabulatedPSD", "asphalt_like",
           "one_d_to_two_d", "psd_from_profile", "psd_from_profile_csv", "contact_ratio",
           "friction", "loss_angular", "modulus_sq_angular"]
