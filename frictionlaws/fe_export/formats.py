"""The export formats, one entry each: what :func:`~frictionlaws.fe_export.export` writes,
and what the command line (``frictionlaws export --format`` with its choices, the format
flags and the help), the docs' table of formats and the tests read.

Adding a format is a writer and one entry:

* the writer is a function ``writer(job) -> Written`` in a module of this room (given the
  :class:`~frictionlaws.fe_export.job.Job`: the law, its values, the unit system, the box
  and the options; it returns the text and what to tell the user,
  :class:`~frictionlaws.fe_export.job.Written`), solver-specific text going through the
  format's sanitiser (:mod:`frictionlaws.base.sanitize`);
* the entry is an :class:`ExportFormat` in :data:`FORMATS`: its name, one line for the help,
  the docs' description, whether it needs a box of ranges, and the whole-number options it
  takes (:class:`FormatOption`: ids of the solver's cards; each becomes an
  ``options={...}`` key of the API, listed in :data:`OPTIONS`, and a flag of the command
  line, ``ansys_mat`` -> ``--ansys-mat``).

Nothing else names the formats.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass

from .abaqus import write_abaqus, write_abaqus_decay, write_abaqus_subroutine
from .ansys import write_ansys
from .job import Job, Written
from .lsdyna import write_lsdyna
from .opensees import write_opensees
from .radioss import write_radioss
from .tables import write_csv, write_json

__all__ = ["FormatOption", "ExportFormat", "FORMATS", "OPTIONS", "formats_taking"]


@dataclass(frozen=True)
class FormatOption:
    """A whole-number option of a format (an id of the solver's cards).

    Attributes
    ----------
    name : str
        Its key in ``export(options={...})``, prefixed by the solver (``ansys_mat``).
    lo, hi : int
        The whole numbers it may take (both included).
    default : int
        The value written when it is not given.
    meaning : str
        What it is, for the help and the docs.
    metavar : str
        Its value's name in the command line's help.
    """

    name: str
    lo: int
    hi: int
    default: int
    meaning: str
    metavar: str = "ID"


@dataclass(frozen=True)
class ExportFormat:
    """An export format: its writer and what the command line, the API and the docs read.

    Attributes
    ----------
    name : str
        The format's name (``format=`` of :func:`~frictionlaws.fe_export.export`).
    writer : callable
        ``writer(job) -> Written``: the file's text for an export job.
    line : str
        One line for ``frictionlaws export --help``.
    description : str
        What is written, for the docs' table of formats (reStructuredText).
    needs_box : bool
        True when the format tabulates the law over a box of ranges.
    options : tuple of FormatOption
        The whole-number options it takes.
    formula_card : bool
        True for a table format that writes the solver's own formula instead when the law
        has its form (the law is then checked over the box, where the solver evaluates it).
    source_code : bool
        True for a user subroutine: its file must be named for a compiler, the law is
        checked over its whole domain, and the floors it applies are stated.
    """

    name: str
    writer: Callable[[Job], Written]
    line: str
    description: str
    needs_box: bool = True
    options: tuple[FormatOption, ...] = ()
    formula_card: bool = False
    source_code: bool = False


#: An id of a keyword card: positive, and fits the solvers' 10-column integer fields.
_ID = (1, 99_999_999)
_SUBROUTINE = ("Fortran user subroutine {} that evaluates the law itself, with its "
               "derivatives; compiled with the analysis (``abaqus job=... user=...``)")

#: Every export format, in the order the help and the docs list them.
FORMATS: dict[str, ExportFormat] = {f.name: f for f in (
    ExportFormat("csv", write_csv, "grid of mu, CSV with units in the header",
                 "the grid of μ with units in the header, for any other tool"),
    ExportFormat("json", write_json, "grid of mu, JSON with units",
                 "the grid of μ with its units and breakpoints, as JSON"),
    ExportFormat("abaqus", write_abaqus,
                 "Abaqus *FRICTION table (mu, slip rate, pressure, temperature, fields)",
                 "``*FRICTION`` data lines: μ, slip rate, contact pressure, temperature, in "
                 "Abaqus' order (slip rate fastest, every block with the same slip-rate "
                 "values)"),
    ExportFormat("abaqus-decay", write_abaqus_decay,
                 "Abaqus *FRICTION, EXPONENTIAL DECAY (exact laws only)",
                 "``*FRICTION, EXPONENTIAL DECAY``; only for laws that are exactly of that "
                 "form", needs_box=False),
    ExportFormat("lsdyna", write_lsdyna,
                 "LS-DYNA FS/FD/DC card when exact, else FS=2 *DEFINE_TABLE",
                 "the FS/FD/DC contact card when the law is exactly exponential decay, "
                 "otherwise ``FS = 2`` with a ``*DEFINE_TABLE`` of curves", formula_card=True,
                 options=(
                     FormatOption("lsdyna_ssid", *_ID, 1, "LS-DYNA contact card 1: SSID"),
                     FormatOption("lsdyna_msid", *_ID, 2, "LS-DYNA contact card 1: MSID"),
                     FormatOption("lsdyna_sstyp", 0, 9, 3, "LS-DYNA contact card 1: SSTYP",
                                  "TYPE"),
                     FormatOption("lsdyna_mstyp", 0, 9, 3, "LS-DYNA contact card 1: MSTYP",
                                  "TYPE"),
                     FormatOption("lsdyna_table_id", *_ID, 1000,
                                  "LS-DYNA *DEFINE_TABLE id (its curves follow: ID+1, ...)"),
                 )),
    ExportFormat("ansys", write_ansys, "Ansys TB,FRIC with TBFIELD NPRES/SLRV/TEMP",
                 "``TB,FRIC`` with ``TBFIELD`` ``NPRES`` (pressure), ``SLRV`` (sliding "
                 "velocity), ``TEMP``",
                 options=(FormatOption("ansys_mat", *_ID, 1, "Ansys material id", "MAT"),)),
    ExportFormat("radioss", write_radioss,
                 "OpenRadioss /FRICTION Ifric 1/4, exact or fitted over the box",
                 "OpenRadioss ``/FRICTION`` Ifric 1 (the quadratic p-v law) or 4 (exponential "
                 "decay): exact when the law is of that form, otherwise fitted over the box "
                 "with the approximation error stated", formula_card=True,
                 options=(FormatOption("radioss_id", *_ID, 1, "Radioss /FRICTION id"),)),
    ExportFormat("abaqus-fric-coef", write_abaqus_subroutine,
                 "Fortran FRIC_COEF (Abaqus/Standard), mu and derivatives",
                 _SUBROUTINE.format("``FRIC_COEF`` (Abaqus/Standard)"), needs_box=False,
                 source_code=True),
    ExportFormat("abaqus-vfric-coef", write_abaqus_subroutine,
                 "Fortran VFRIC_COEF (Abaqus/Explicit), mu and derivatives",
                 _SUBROUTINE.format("``VFRIC_COEF`` (Abaqus/Explicit, general contact)"),
                 needs_box=False, source_code=True),
    ExportFormat("abaqus-vfric", write_abaqus_subroutine,
                 "Fortran VFRIC (Abaqus/Explicit contact pairs), friction force",
                 "Fortran user subroutine ``VFRIC`` (Abaqus/Explicit, contact pairs) that "
                 "evaluates the law itself and returns the friction force",
                 needs_box=False, source_code=True),
    ExportFormat("opensees", write_opensees,
                 "OpenSees frictionModel VelDependent/Coulomb (exact laws only)",
                 "OpenSees ``frictionModel VelDependent`` (μ_slow, μ_fast, transition rate) "
                 "when the law is exactly exponential decay in the velocity, ``Coulomb`` "
                 "when μ is constant; Tcl, for the friction bearing elements",
                 needs_box=False,
                 options=(FormatOption("opensees_tag", *_ID, 1,
                                       "OpenSees friction model tag"),)),
)}

class _Options(Mapping[str, FormatOption]):
    """Every format option by name, read from :data:`FORMATS` on each use (a view of the
    table, not a copy of it)."""

    def _all(self) -> dict[str, FormatOption]:
        return {o.name: o for f in FORMATS.values() for o in f.options}

    def __getitem__(self, name: str) -> FormatOption:
        return self._all()[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._all())

    def __len__(self) -> int:
        return len(self._all())


#: Every format option by name (the keys ``export(options=...)`` takes), from :data:`FORMATS`.
OPTIONS: Mapping[str, FormatOption] = _Options()


def formats_taking(option: str) -> list[str]:
    """The formats that take ``option`` (a name of :data:`OPTIONS`), in table order."""
    return [f.name for f in FORMATS.values() if any(o.name == option for o in f.options)]
