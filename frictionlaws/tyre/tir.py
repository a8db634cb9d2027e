"""Magic Formula property files at the import path of earlier releases.

They are read and written by :mod:`frictionlaws.tyre.mf.tir` (their content:
:mod:`frictionlaws.tyre.mf.property_file`); this module re-exports what
``frictionlaws.tyre.tir`` held so that code importing from here keeps working.
"""

from __future__ import annotations

from .mf.property_file import DIMENSIONAL, MF_KEYS, PropertyFile
from .mf.tir import (
    CHRONO_PROVENANCE,
    converted_header,
    format_tir,
    json_to_tir,
    read_json,
    read_property_file,
    read_tir,
    write_tir,
)

__all__ = ["PropertyFile", "read_property_file", "read_tir", "read_json", "write_tir",
           "format_tir", "json_to_tir", "converted_header", "CHRONO_PROVENANCE",
           "DIMENSIONAL", "MF_KEYS"]
