"""Tyre test data: moved to :mod:`frictionlaws.tyre.data` (the data formats of the tyre side).

This module keeps the old import path working; new code imports from
:mod:`frictionlaws.tyre.data`.
"""

from __future__ import annotations

from .data.table import COLUMNS, SIGN_CONVENTIONS, TyreData, read_tyre_data

__all__ = ["TyreData", "read_tyre_data", "SIGN_CONVENTIONS", "COLUMNS"]
