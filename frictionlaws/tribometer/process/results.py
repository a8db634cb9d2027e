"""The processed campaign (:class:`ProcessedCampaign`): records and conditions as tables with
units, the dataset CSV with its provenance, JSON, and :func:`write_tables`.
"""

from __future__ import annotations

import contextlib
import csv
import io
import math
import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ...base.errors import InputError
from ...base.outputs import atomic_write
from ...base.sanitize import comment_lines, csv_cell
from ...io import load_dataset
from ..rig import RPM, Rig
from .conditions import ConditionResult
from .reduce import RecordResult

__all__ = ["ProcessedCampaign", "JSON_UNITS", "write_tables"]


# --------------------------------------------------------------------------- campaign
@dataclass
class ProcessedCampaign:
    """The result of processing a campaign: per record, per condition, and notes."""

    records: list[RecordResult]
    conditions: list[ConditionResult]
    rig: Rig
    source: str = "<memory>"
    notes: list[str] = field(default_factory=list)
    min_repeats: int = 2
    outlier_rule: str = ""

    @property
    def used(self) -> list[RecordResult]:
        return [r for r in self.records if r.status == "used"]

    @property
    def outliers(self) -> list[RecordResult]:
        return [r for r in self.records if r.status == "outlier"]

    @property
    def unusable(self) -> list[RecordResult]:
        return [r for r in self.records if r.status == "unusable"]

    def record_files(self) -> list[Path]:
        """The record files the manifest names, resolved (paths are relative to it).

        Returns
        -------
        list of pathlib.Path
            One per record with a file name; empty for records held in memory.
        """
        if self.source == "<memory>":
            return []
        base = Path(self.source).resolve().parent
        return [(base / r.file).resolve() for r in self.records if r.file]

    def dataset_frame(self) -> Any:
        """The per-condition dataset with display-unit headers (what ``write_dataset`` writes).

        Columns: ``condition``, ``surface``, ``mu``, ``mu_std``, ``mu_ci95_low``,
        ``mu_ci95_high``, ``n``, ``p [MPa]``, ``v [m/s]``, ``s``, ``F_N [N]``,
        ``mode``, ``disc_speed [rpm]``, ``pin_speed [rpm]``, ``n_outliers``,
        ``n_unusable``.  Only conditions with at least ``min_repeats`` usable
        records.
        """
        import pandas as pd

        rows = []
        for c in self.conditions:
            if not c.written:
                continue
            rows.append({
                "condition": c.condition, "surface": c.surface, "mu": c.mu,
                "mu_std": c.mu_std, "mu_ci95_low": c.ci95[0], "mu_ci95_high": c.ci95[1],
                "n": c.n, "p [MPa]": c.p / 1e6, "v [m/s]": c.v, "s": c.s, "F_N [N]": c.F_N,
                "mode": c.mode, "disc_speed [rpm]": c.disc_speed / RPM,
                "pin_speed [rpm]": c.pin_speed / RPM, "n_outliers": len(c.outliers),
                "n_unusable": len(c.unusable)})
        cols = ["condition", "surface", "mu", "mu_std", "mu_ci95_low", "mu_ci95_high", "n",
                "p [MPa]", "v [m/s]", "s", "F_N [N]", "mode", "disc_speed [rpm]",
                "pin_speed [rpm]", "n_outliers", "n_unusable"]
        return pd.DataFrame(rows, columns=cols)

    def dataset(self) -> Any:
        """The dataset as a :class:`frictionlaws.io.Dataset` (SI), ready for ``fit``."""
        f = self.dataset_frame()
        if f.empty:
            raise InputError("no condition has enough usable records for a dataset",
                             file=self.source)
        frame = {"mu": f["mu"].to_numpy(), "p": f["p [MPa]"].to_numpy() * 1e6,
                 "v": f["v [m/s]"].to_numpy(), "s": f["s"].to_numpy(),
                 "F_N": f["F_N [N]"].to_numpy(), "mu_std": f["mu_std"].to_numpy(),
                 "n": f["n"].to_numpy(), "surface": f["surface"].to_numpy()}
        ds = load_dataset(frame)
        ds.name = Path(self.source).stem if self.source != "<memory>" else "processed"
        ds.notes.extend(self.summary_lines(short=True))
        return ds

    def records_frame(self) -> Any:
        """The per-record table (display-unit headers)."""
        import pandas as pd

        rows = []
        for r in self.records:
            rows.append({
                "file": r.file, "manifest_row": r.row, "condition": r.condition,
                "surface": r.surface, "mode": r.mode, "status": r.status, "reason": r.reason,
                "mu": r.mu, "mu_window_std": r.mu_window_std, "load": r.load_text,
                "F_N [N]": r.load, "p [MPa]": r.p / 1e6, "v [m/s]": r.v, "s": r.s,
                "disc_speed [rpm]": r.disc_speed / RPM, "pin_speed [rpm]": r.pin_speed / RPM,
                "window_start [s]": r.window_start, "window_end [s]": r.window_end,
                "window_source": r.window_source, "cutoff [Hz]": r.cutoff,
                "cutoff_source": r.cutoff_source, "fs [Hz]": r.fs, "duration [s]": r.duration,
                "samples": r.n_samples, "grubbs_G": r.grubbs_g,
                "outlier_z": r.outlier_z, "notes": "; ".join(r.notes)})
        return pd.DataFrame(rows)

    def _provenance(self) -> list[str]:
        n = len(self.records)
        return [
            f"Processed by frictionlaws process from manifest {self.source} with rig "
            f"{self.rig.source}",
            f"{n} records: {len(self.used)} used, {len(self.outliers)} outliers dropped, "
            f"{len(self.unusable)} unusable (see the per-record table)",
            "mu: mean of the record means of a condition; mu_std: their sample standard "
            "deviation; mu_ci95_low/high: 95 % Student-t interval of the mean; n: records used",
            f"outlier rule: {self.outlier_rule or self.rig.outliers.rule}",
        ]

    def write_dataset(self, path: str | os.PathLike[str]) -> Path:
        """Write the dataset CSV (foundation schema, units in headers, provenance as ``#``)."""
        return write_tables([(path, self.dataset_text())])[0]

    def write_records(self, path: str | os.PathLike[str]) -> Path:
        """Write the per-record table as CSV."""
        return write_tables([(path, self.records_text())])[0]

    def dataset_text(self) -> str:
        """The dataset CSV that :meth:`write_dataset` writes, as text."""
        return _csv_text(self.dataset_frame(), self._provenance())

    def records_text(self) -> str:
        """The per-record CSV that :meth:`write_records` writes, as text."""
        prov = self._provenance()
        return _csv_text(self.records_frame(), prov[:2] + prov[3:])

    def summary_lines(self, *, short: bool = False) -> list[str]:
        """Return the lines of the summary.

        Parameters
        ----------
        short : bool
            Only the counts, the rule and one line per unusable or dropped record
            (the form kept in a dataset's notes).

        Returns
        -------
        list of str
            Counts, the outlier rule, unusable records, outliers, conditions not
            written, notes of conditions and records.
        """
        written = [c for c in self.conditions if c.written]
        lines = [f"{len(self.records)} records: {len(self.used)} used, "
                 f"{len(self.outliers)} dropped as outliers, {len(self.unusable)} unusable; "
                 f"{len(written)} conditions in the dataset",
                 f"outlier rule: {self.outlier_rule or self.rig.outliers.rule}"]
        if short:
            lines += [f"unusable record {r.file}: {r.reason}" for r in self.unusable]
            lines += [f"outlier {r.file} ({r.condition}): {r.reason}" for r in self.outliers]
            return lines
        return lines + self._record_lines() + self._condition_lines() + self._note_lines()

    def _record_lines(self) -> list[str]:
        lines = []
        if self.unusable:
            lines.append("unusable records:")
            lines += [f"  {r.file}: {r.reason}" for r in self.unusable]
        if self.outliers:
            lines.append("outliers dropped:")
            lines += [f"  {r.file} [{r.condition}]: {r.reason}" for r in self.outliers]
        unassigned = [r for r in self.unusable if not r.condition]
        if unassigned:
            lines.append(f"{len(unassigned)} unusable record(s) could not be assigned to a "
                         "condition (no 'condition' column and no measured speeds)")
        return lines

    def _condition_lines(self) -> list[str]:
        lines = []
        not_written = [c for c in self.conditions if not c.written]
        if not_written:
            lines.append("conditions not in the dataset:")
            lines += [f"  {c.condition}: {'; '.join(c.notes)}" for c in not_written]
        other = [(c.condition, note) for c in self.conditions if c.written for note in c.notes]
        if other:
            lines.append("condition notes:")
            lines += [f"  {name}: {note}" for name, note in other]
        return lines

    def _note_lines(self) -> list[str]:
        lines = []
        rec_notes = [(r.file, n) for r in self.records for n in r.notes
                     if not n.startswith("window ends")]
        if rec_notes:
            lines.append(f"record notes ({len(rec_notes)}):")
            lines += [f"  {f}: {n}" for f, n in rec_notes[:20]]
            if len(rec_notes) > 20:
                lines.append(f"  ... {len(rec_notes) - 20} more in the per-record table")
        return lines + [f"note: {n}" for n in self.notes]

    def summary(self) -> str:
        """Return the summary as text (:meth:`summary_lines` joined).

        Returns
        -------
        str
            One line per item of :meth:`summary_lines`.
        """
        return "\n".join(self.summary_lines())

    def to_dict(self) -> dict[str, Any]:
        """Return the campaign as JSON-able data in SI units.

        Returns
        -------
        dict
            ``manifest``, ``rig``, ``min_repeats``, ``outlier_rule``, ``counts``
            (records, used, outliers, unusable, conditions written), ``units``
            (the SI unit of every quantity below), ``conditions`` (one dict per
            condition: statistics, whether it is in the dataset, its records and
            notes), ``records`` (one dict per record: status, reason, mu, window,
            filter, speeds) and ``notes``.  Missing numbers are NaN (written as
            ``null`` by :func:`frictionlaws.base.jsonio.dumps`).
        """
        return {
            "manifest": self.source, "rig": self.rig.source, "min_repeats": self.min_repeats,
            "outlier_rule": self.outlier_rule or self.rig.outliers.rule,
            "counts": {"records": len(self.records), "used": len(self.used),
                       "outliers": len(self.outliers), "unusable": len(self.unusable),
                       "conditions_written": sum(c.written for c in self.conditions)},
            "units": dict(JSON_UNITS),
            "conditions": [_condition_dict(c) for c in self.conditions],
            "records": [_record_dict(r) for r in self.records],
            "notes": list(self.notes)}


#: SI unit of each quantity in :meth:`ProcessedCampaign.to_dict` (``1``: dimensionless).
JSON_UNITS = {"mu": "1", "mu_std": "1", "mu_ci95": "1", "mu_window_std": "1", "p": "Pa",
              "v": "m/s", "s": "1", "F_N": "N", "load": "N", "disc_speed": "rad/s",
              "pin_speed": "rad/s", "window_start": "s", "window_end": "s", "cutoff": "Hz",
              "fs": "Hz", "duration": "s"}


def _condition_dict(c: ConditionResult) -> dict[str, Any]:
    return {"condition": c.condition, "surface": c.surface, "mode": c.mode,
            "written": c.written, "n": c.n, "mu": c.mu, "mu_std": c.mu_std,
            "mu_ci95": list(c.ci95), "p": c.p, "v": c.v, "s": c.s, "F_N": c.F_N,
            "disc_speed": c.disc_speed, "pin_speed": c.pin_speed, "load_text": c.load_text,
            "files": list(c.files),
            "outliers": [{"file": f, "reason": why} for f, why in c.outliers],
            "unusable": [{"file": f, "reason": why} for f, why in c.unusable],
            "notes": list(c.notes)}


def _record_dict(r: RecordResult) -> dict[str, Any]:
    return {"file": r.file, "manifest_row": r.row, "condition": r.condition,
            "surface": r.surface, "mode": r.mode, "status": r.status, "reason": r.reason,
            "mu": r.mu, "mu_window_std": r.mu_window_std, "load": r.load,
            "load_text": r.load_text, "p": r.p, "v": r.v, "s": r.s,
            "disc_speed": r.disc_speed, "pin_speed": r.pin_speed,
            "window_start": r.window_start, "window_end": r.window_end,
            "window_source": r.window_source, "cutoff": r.cutoff,
            "cutoff_source": r.cutoff_source, "fs": r.fs, "duration": r.duration,
            "samples": r.n_samples, "grubbs_G": r.grubbs_g, "outlier_z": r.outlier_z,
            "notes": list(r.notes)}


def _fmt(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, (float, np.floating)):
        return "" if not math.isfinite(float(value)) else format(float(value), ".10g")
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    return str(value)


def _csv_text(frame: Any, comments: list[str]) -> str:
    buf = io.StringIO()
    for line in comment_lines(comments):
        buf.write(line + "\n")
    w = csv.writer(buf, lineterminator="\n")
    w.writerow([csv_cell(c) for c in frame.columns])
    for row in frame.itertuples(index=False):
        w.writerow([csv_cell(v) if isinstance(v, str) else _fmt(v) for v in row])
    return buf.getvalue()


def write_tables(tables: Sequence[tuple[str | os.PathLike[str], str]]) -> list[Path]:
    """Write several text files together: all of them or, on any failure, none.

    Each file is written to a temporary file beside its target; the temporary
    files are renamed into place only when every one has been written.

    Parameters
    ----------
    tables : sequence of (path, text)
        The files and their contents.

    Returns
    -------
    list of pathlib.Path
        The paths written, in the order given.

    Raises
    ------
    InputError
        When a directory is missing, or a target is an input or a directory;
        nothing is written then.
    """
    paths = [Path(p) for p, _ in tables]
    for out in paths:
        if str(out.parent) and not out.parent.exists():
            raise InputError("the output directory does not exist", file=str(out))
    with contextlib.ExitStack() as stack:
        for out, (_, text) in zip(paths, tables, strict=True):
            stack.enter_context(atomic_write(out, newline="")).write(text)
    return paths

