"""Persson's theory of rubber friction: material, surface and the friction integral.

* :mod:`.material`: a Prony-series rubber fitted to a DMA master curve, with
  its temperature shift (:func:`default_material` from the packaged data,
  :func:`material_from_csv` from a user's file).
* :mod:`.surface`: self-affine and measured roughness spectra C(q), and the
  1-D profile to isotropic 2-D conversion.
* :mod:`.theory`: the contact ratio P(q) and the friction coefficient
  mu(v, T, p) (fast vectorised quadrature).
* :mod:`.flash`: the flash temperature (Persson 2006), the settings and closures.
* :mod:`.published`: the flash temperature's own figures on the packaged tread
  compound, and the published figures (of other rubbers) that are not compared.

The registry law ``persson`` (``frictionlaws/laws/persson.py``) wraps it.

The names below are imported on first use, so that discovering the registry's
laws (which declares ``persson``) loads none of these modules.
"""

from __future__ import annotations

from ..base.lazy import lazy_getattr

#: public name -> the submodule that defines it
_API = {
    "Material": "material",
    "Shift": "material",
    "default_material": "material",
    "fit_prony": "material",
    "material_from_csv": "material",
    "material_from_master_curve": "material",
    "havriliak_negami": "material",
    "tread_compound": "material",
    "SelfAffine": "surface",
    "TabulatedPSD": "surface",
    "asphalt_like": "surface",
    "check_roughness": "surface",
    "RoughnessWarning": "surface",
    "one_d_to_two_d": "surface",
    "psd_from_profile": "surface",
    "psd_from_profile_csv": "surface",
    "check_conditions": "theory",
    "contact_ratio": "theory",
    "flash_temperature": "theory",
    "Flash": "flash",
    "TREAD_THERMAL": "flash",
    "friction": "theory",
    "loss_angular": "theory",
    "modulus_sq_angular": "theory",
    "CLOSURES": "flash",
    "FlashFigures": "published",
    "flash_figures": "published",
}

__all__ = list(_API)


__getattr__ = lazy_getattr(__name__, _API)


def __dir__() -> list[str]:
    return sorted(__all__)
