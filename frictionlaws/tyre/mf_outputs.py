"""The Magic Formula's steady-state outputs at the import path of earlier releases.

They live in :mod:`frictionlaws.tyre.mf.outputs`; this module re-exports what
``frictionlaws.tyre.mf_outputs`` held so that code importing from here keeps working.
"""

from __future__ import annotations

from .mf.outputs import OUTPUTS, aligning_moment, aligning_summary, steady_state

__all__ = ["steady_state", "aligning_moment", "aligning_summary", "OUTPUTS"]
