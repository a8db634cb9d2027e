"""Raw records -> friction coefficients per record -> a dataset per condition.

Manifest
    A CSV file with one row per record (paths relative to the manifest)::

        file,load [kg],surface,condition,mode
        records/steel_3kg_01.csv,3,steel,steel 3 kg 5 km/h,steady
        records/s120_2kg_01.csv,2,sandpaper 120,S120 2 kg,initial

    * ``file`` (required): the record CSV (see :mod:`.records`);
    * ``load`` (required) with its unit: a mass (``load [kg]``) is a dead
      weight, turned into a force with the rig's ``g``; a force
      (``load [N]``, ``load [kgf]``) is used as it is;
    * ``surface`` (required): the counter-surface;
    * ``condition`` (optional): records with the same label are repeats of one
      condition.  Without it, records are grouped by surface, mode, load and
      their measured disc and pin speeds (speeds closer than the rig's
      ``grouping.speed_step`` are the same condition);
    * ``mode`` (optional): ``steady`` (default) or ``initial`` (abrasive
      surfaces: only the first seconds of sliding are valid);
    * ``window_start``, ``window_end`` (optional, with a time unit, e.g.
      ``window_start [s]``): override the automatic window of that record
      (either or both; an empty cell keeps the automatic value);
    * ``direction`` (optional): ``signed`` (default: the speeds in the file
      carry their direction), ``counter`` (the file holds magnitudes; pin and
      disc counter-rotate) or ``same`` (magnitudes; same direction).

Per record
    filter the torque (zero-phase low-pass, :mod:`.signal`); subtract the
    system error and the internal torque at the current disc speed; friction
    force = torque / track radius; mu = force / normal load; find the window
    (or take the manifest's); the record's mu is the mean of the filtered mu
    over the window.  Sliding velocity ``v = r |w_pin - w_disc|`` and slip ratio
    ``s = |w_pin - w_disc| / max(|w_pin|, |w_disc|)`` (thesis Eq. 3-4) use the
    window means of the signed speeds, so a counter-rotating pin gives
    ``1 < s <= 2`` and a fixed pin ``s = 1``; contact pressure = load / area.

Per condition
    The record means of the usable records are averaged: ``mu`` (mean),
    ``mu_std`` (sample standard deviation, ddof = 1), ``n``, and the 95 %
    Student-t interval ``mu +/- t(0.975, n - 1) * mu_std / sqrt(n)``.  It
    covers the condition's true coefficient when the record means scatter
    normally about it (repeat-to-repeat scatter dominates the in-record noise).

Outlier rule
    ``[outliers] rule`` of the rig.  ``"pooled"`` (default): the
    record-to-record scatter, relative to each condition's median, is pooled
    robustly over the campaign's conditions and a record departing from its
    condition's median by more than a calibrated threshold in pooled-scatter
    units is dropped (conditions of 3 or more records; at most a minority of a
    condition; a good condition loses a record with probability at most
    ``alpha``); see :mod:`.outliers`.  It works at the rig's 3..7 repeats, where
    Grubbs cannot.  A campaign too small to pool a scatter falls back to
    Grubbs.  ``"grubbs"``: the two-sided Grubbs test on the record means of a
    condition with at least 4 usable records (so that 3 remain), significance
    ``alpha`` (default 0.01), applied once: the record with the largest
    ``G = |x - mean| / sd`` is dropped when ``G`` exceeds the critical value
    ``(n - 1) / sqrt(n) * sqrt(t^2 / (n - 2 + t^2))`` with ``t`` the
    ``1 - alpha / (2 n)`` quantile of Student's t with ``n - 2`` degrees of
    freedom.  ``"none"`` keeps every record.  A dropped record is reported with
    its statistic and threshold; the rule used, with its figures, is printed in
    the summary and written to the outputs' provenance.

Unusable records
    A missing or unreadable file, wrong columns or units, NaNs, a time base
    that is not uniform, a record shorter than ``min_duration``, no sliding,
    no steady window, no friction (mean mu below ``min_mu``), sensor saturation inside
    the window, or a bad manifest row: the record is reported with the reason
    (file, column, row) and the rest are processed.  Conditions with fewer than
    ``min_repeats`` (default 2) usable records are not written to the dataset
    and are listed in the summary.
"""

from __future__ import annotations

from .conditions import (
    GRUBBS_MIN,
    ConditionResult,
    grubbs,
    student_interval,
    summarise,
)
from .manifest import (
    DIRECTIONS,
    MODES,
    ManifestEntry,
    manifest_from_rows,
    read_manifest,
)
from .reduce import (
    CLIP_RUN,
    SATURATION_FRACTION,
    RecordResult,
    process_record,
)
from .results import (
    JSON_UNITS,
    ProcessedCampaign,
    write_tables,
)
from .run import (
    manifest_names,
    process_campaign,
    process_many,
    process_records,
)

__all__ = ["ManifestEntry", "RecordResult", "ConditionResult", "ProcessedCampaign", "read_manifest",
           "manifest_from_rows", "process_record", "process_campaign", "process_records",
           "process_many", "manifest_names", "write_tables", "grubbs", "student_interval",
           "SATURATION_FRACTION", "MODES", "DIRECTIONS", "CLIP_RUN", "GRUBBS_MIN", "summarise",
           "JSON_UNITS"]
