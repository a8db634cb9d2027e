"""Tribometer processing: raw torque records to friction datasets with intervals.

The pipeline, module by module:

* :mod:`.rig` - the rig description (TOML with units in the values);
* :mod:`.records` - raw record CSVs (units in the headers), validation;
* :mod:`.signal` - zero-phase low-pass filter, automatic cut-off, steady window;
* :mod:`.process` - manifest, per-record and per-condition processing, the
  outlier rule, the dataset and per-record tables;
* :mod:`.calibration` - system error (hanging weights) and internal torque
  (no-contact runs);
* :mod:`.synthetic` - synthetic records and campaigns with a known mu;
* :mod:`.plots` - diagnostic plots.

Typical use::

    from frictionlaws.tribometer import process_campaign
    camp = process_campaign("manifest.csv", "rig.toml")
    camp.write_dataset("steel.csv")
    print(camp.summary())
"""

from __future__ import annotations

from .calibration import (
    InternalTorqueCurve,
    SystemErrorCalibration,
    internal_torque_from_runs,
    system_error_from_weights,
)
from .outliers import outlier_power, pooled_outliers
from .process import (
    ConditionResult,
    ManifestEntry,
    ProcessedCampaign,
    RecordResult,
    grubbs,
    process_campaign,
    process_many,
    process_record,
    process_records,
    read_manifest,
    student_interval,
)
from .records import Record, read_record, write_record
from .rig import Rig, load_rig, rig_from_dict

__all__ = [
    "ProcessedCampaign",
    "ConditionResult",
    "InternalTorqueCurve",
    "ManifestEntry",
    "Record",
    "RecordResult",
    "Rig",
    "SystemErrorCalibration",
    "grubbs",
    "internal_torque_from_runs",
    "load_rig",
    "outlier_power",
    "pooled_outliers",
    "process_campaign",
    "process_many",
    "process_record",
    "process_records",
    "read_manifest",
    "read_record",
    "rig_from_dict",
    "student_interval",
    "system_error_from_weights",
    "write_record",
]
