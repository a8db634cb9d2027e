"""The Magic Formula model at the import path of earlier releases.

The Magic Formula lives in :mod:`frictionlaws.tyre.mf`; this module re-exports what
``frictionlaws.tyre.magic_formula`` held (:class:`~frictionlaws.tyre.mf.model.MagicFormula`
and its conventions) so that code importing from here keeps working.
"""

from __future__ import annotations

from .mf.equations import MFCoefficients, mf_curve
from .mf.model import MagicFormula
from .mf.parameters import (
    EQUATIONS,
    FRICTION_SCALINGS,
    LOADS_ABOVE_FZMAX,
    MF_VERSIONS,
    SLIP_ANGLE_INPUTS,
)
from .mf.tir import EXAMPLES, packaged_example

__all__ = ["MagicFormula", "MFCoefficients", "mf_curve", "MF_VERSIONS", "SLIP_ANGLE_INPUTS",
           "FRICTION_SCALINGS", "LOADS_ABOVE_FZMAX", "EQUATIONS", "EXAMPLES", "packaged_example"]
