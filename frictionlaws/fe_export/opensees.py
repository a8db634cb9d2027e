"""OpenSees friction models for its friction bearing elements (``flatSliderBearing``,
``singleFPBearing``): ``frictionModel VelDependent tag muSlow muFast transRate``, that is
``mu = muFast - (muFast - muSlow) exp(-transRate |v|)``, exact for a law of the form
``mu_k + (mu_s - mu_k) exp(-d_c v)``, and ``frictionModel Coulomb tag mu`` for a
constant mu.  Written as Tcl."""

from __future__ import annotations

from ..base.errors import Argument, InputError
from .exact import exp_decay_form
from .job import Job, Written, commented

__all__ = ["write_opensees", "tcl_comment"]


def tcl_comment(line: str) -> str:
    """A comment line that Tcl reads as one line: braces become parentheses, and an odd
    run of backslashes at its end (which would continue the comment onto the command
    below it) is made even."""
    line = line.replace("{", "(").replace("}", ")")
    run = len(line) - len(line.rstrip("\\"))
    return line + "\\" if run % 2 else line


def write_opensees(job: Job) -> Written:
    """``frictionModel VelDependent`` (``Coulomb`` for a constant mu): the law itself."""
    form, why = exp_decay_form(job.law, job.values)
    if form is None:
        raise InputError([f"opensees: {why}, so no OpenSees friction model is the law. "
                          "Fit 'exponential-decay' with delta held at 1 first (",
                          Argument("fix", "delta=1"), ")"])
    job.check_levels({"muSlow": form.mu_s, "muFast": form.mu_k})
    if min(form.mu_s, form.mu_k) <= 0:
        raise InputError(f"opensees: law '{job.law.id}' gives muSlow = {form.mu_s:.6g}, "
                         f"muFast = {form.mu_k:.6g}; OpenSees takes positive friction "
                         "coefficients only; nothing was written")
    tag = job.options["opensees_tag"]
    scale, _ = job.units.affine("v")
    rate = form.d_c * scale  # 1/(m/s) -> 1/(the model's velocity unit)
    if form.d_c == 0:
        command = f"frictionModel Coulomb {tag} {form.mu_k!r}"
        what = f"mu = {form.mu_k!r} at every velocity: frictionModel Coulomb"
    else:
        command = f"frictionModel VelDependent {tag} {form.mu_s!r} {form.mu_k!r} {rate!r}"
        what = (f"muSlow = {form.mu_s!r}, muFast = {form.mu_k!r}, transRate = {rate!r} "
                f"[1/({job.units.label('v')})]")
    body = [*job.box_lines(),
            "exact: OpenSees' mu = muFast - (muFast - muSlow) exp(-transRate |v|) is the "
            "law itself (checked numerically)", what,
            f"friction model tag {tag} (API option opensees_tag): give it to a "
            "flatSliderBearing or singleFPBearing element; v is the element's sliding "
            "velocity in the model's units"]
    head = job.header("OpenSees frictionModel", body,
                      "the same formula holds at every velocity (no table, no box)")
    lines = [tcl_comment(line) for line in commented(head, "# ")]
    return Written("\n".join([*lines, command]) + "\n", exact=True, summary=body[-2:],
                   details={"muSlow": form.mu_s, "muFast": form.mu_k, "transRate": rate})
