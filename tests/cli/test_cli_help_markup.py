"""Help texts are rendered by Rich, whose markup takes a lowercase ``[word]`` for a style tag and
drops it: "the job file's [uncertainty]" printed as "the job file's , e.g.". A literal table name
in a help text is written ``\\[word]`` (CONVENTIONS habit 10: help that says something useful)."""

import re

import typer
from typer._click import core
from typer.testing import CliRunner

from axiscal.cli import app

#: What Rich reads as a markup tag (rich.markup's RE_TAGS: a "[" then a-z, #, / or @).
_RICH_TAG = re.compile(r"(?<!\\)\[[a-z#/@][^\[\]]*\]")


def _commands(cmd, path, ctx):
    yield path, cmd
    if hasattr(cmd, "list_commands"):
        sub = core.Context(cmd, info_name=path[-1] if path else "axiscal", parent=ctx)
        for name in cmd.list_commands(sub):
            yield from _commands(cmd.get_command(sub, name), path + [name], sub)


def test_no_help_text_holds_a_word_rich_would_swallow():
    seen = 0
    for path, cmd in _commands(typer.main.get_command(app), [], None):
        texts = [cmd.help or "", *(getattr(p, "help", None) or "" for p in cmd.params)]
        for text in texts:
            assert not _RICH_TAG.search(text), (" ".join(path), text)
        seen += 1
    assert seen > 40


def test_iso230_2_help_names_the_job_files_uncertainty_table():
    r = CliRunner().invoke(app, ["iso230-2", "--help"], env={"COLUMNS": "300"})
    assert r.exit_code == 0
    assert "over the job file's [uncertainty], e.g." in r.output


def test_every_listed_summary_is_one_line():
    """A command's first help paragraph is what its group lists; a line break in it broke the
    list mid-sentence ("... the old one stays in" / "the register, ...")."""
    for path, cmd in _commands(typer.main.get_command(app), [], None):
        first = (cmd.help or "").strip().split("\n\n")[0]
        assert "\n" not in first, (" ".join(path), first)
