"""Datasets: read tribometer tables in the user's columns and units, into SI.

A dataset is a table with one friction coefficient per row and the conditions
it was measured at.  The canonical columns are

=========== ============================== ======================= =====
column      meaning                        unit in the file        SI
=========== ============================== ======================= =====
``mu``      friction coefficient           none (or ``-``)         ``-``
``p``       contact pressure               required, e.g. ``MPa``  Pa
``v``       sliding velocity               required, e.g. ``m/s``  m/s
``T``       temperature                    required, e.g. ``degC`` K
``F_N``     normal load                    required, e.g. ``N``,   N
                                           ``kgf``, ``kg``
``s``       slip ratio                     none, ``-`` or ``%``    ``-``
``mu_std``  std. deviation of replicate mu none                    ``-``
``n``       number of replicates           none                    ``-``
``surface`` counter-surface (text)         ``-``                   ``-``
=========== ============================== ======================= =====

Units go in the header in square brackets (``p [MPa]``), or through the
``units`` argument (``units="p=MPa"``) for files whose header has none.  Column
names may be aliases (``cof``, ``pressure``, ``speed``, ``load``...) or be
mapped explicitly (``mapping="mu=FC,p=CP,v=DV"``).  The full schema, the rules for
what is an error and what is a reported drop, and the provenance of the
packaged datasets are in ``datasets/README.md``.

Every problem with the user's input raises :class:`~frictionlaws.base.errors.InputError`
naming the file, the column and the row (the line number a text editor or
spreadsheet shows; the header of a file without comments is row 1).  Rows are
never dropped silently: each drop is written to :attr:`Dataset.notes`.

The other rooms read their own tables (a rig's records and manifests, a tyre's test data,
a material's sweeps) with this room's one reader and rules: :func:`read_table` (the
encoding, delimiter and lines of a file, as a :class:`Table`), :func:`detect_delimiter`,
:func:`split_header` (``"p [MPa]"`` -> name and unit), :func:`column_for` (a name through
the aliases), :func:`to_float` and :func:`column_numbers` (the numbers of a cell and of a
column, refused with file, column and row).
"""

from __future__ import annotations

from .building import (
    column_numbers,
    to_float,
)
from .columns import (
    ALIASES,
    CANONICAL,
    MISSING_TOKENS,
    TEXT_COLUMNS,
    VARIABLE_COLUMNS,
    canonical_name,
    column_for,
    parse_mapping,
    parse_units,
)
from .dataset import (
    Dataset,
    dataset_html,
)
from .packaged import (
    datasets_dir,
    list_datasets,
    load_dataset,
)
from .reading import (
    Table,
    decode_text,
    detect_delimiter,
    output_dir,
    read_table,
    refuse_nul,
    split_header,
)

__all__ = ["CANONICAL", "VARIABLE_COLUMNS", "ALIASES", "Dataset", "load_dataset", "list_datasets",
           "datasets_dir", "output_dir", "parse_mapping", "parse_units", "canonical_name",
           "column_for", "TEXT_COLUMNS", "MISSING_TOKENS", "Table", "refuse_nul",
           "decode_text", "detect_delimiter", "read_table", "split_header", "to_float",
           "column_numbers", "dataset_html"]
