"""Rules behind the last findings of the third hostile corpus (issue 12), part two.

Each test states a general rule and checks it on generated or hand-built inputs (the
corpus itself stays outside the project):

* a command line that cannot run shows the usage of the (sub-)command concerned on
  stdout and one ``error:`` line on stderr, exit 2; a missing command names the
  commands there are, as the parser knows them;
* a campaign is read whole before any fit: every dataset that cannot be read is named
  on its own ``error:`` line, then one line sums up, exit 2 and nothing fitted;
* a grouping column (``by=``, ``--by``) groups rows: a measured quantity (a law
  variable, ``mu``, ``mu_std``, ``n``), a column that is not there, or one that leaves
  fewer than two rows a group on average is refused;
* a rig quantity outside its plausible range is refused naming ``rig.toml``, the key,
  the value with its unit and the range; a filter cutoff must lie below the Nyquist
  frequency of every record;
* a Magic Formula fit keeps the peak friction within physical bounds while it fits, and
  says so when the data stop before the peak instead of refusing the fit.
"""

from __future__ import annotations

import pytest
from hostile import check_outcome, run_cli

HOSTILE = pytest.mark.hostile


# ------------------------------------------------------------------ usage


def _commands() -> list[str]:
    from frictionlaws.cli import build_parser, command_names

    return command_names(build_parser())


@HOSTILE
@pytest.mark.parametrize("argv,words", [
    ([], "no command given; choose one of: "),
    (["--bogus"], "unrecognized arguments: --bogus"),
    (["fit"], "the following arguments are required"),
    (["tyre"], "frictionlaws tyre: no command given; choose one of: cornering"),
    (["-q"], "no command given"),
])
def test_a_command_line_that_cannot_run_shows_usage_and_one_error(argv: list[str],
                                                                  words: str) -> None:
    res = run_cli(argv)
    check_outcome(res, codes=[2])
    assert words in res.err
    assert res.out.startswith("usage: frictionlaws"), res.out
    if not argv or argv == ["-q"]:
        listed = res.err.split("choose one of: ", 1)[1].strip().split(", ")
        assert listed == _commands() and "fit" in listed and "export" in listed


@HOSTILE
def test_with_json_a_usage_error_leaves_stdout_empty() -> None:
    res = run_cli(["fit", "--json"])
    check_outcome(res, codes=[2])
    assert res.out == ""
