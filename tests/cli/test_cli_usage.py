"""Mistakes on the command line itself are one line ``axiscal: error: ...`` with exit code 2.

Click's usage panel (several lines in a box) used to reach the user for an unknown command, a
missing option or ``--length abc``; number options also took ``nan`` and ``inf`` and failed later,
some with a traceback (``compensate --reference nan``).
"""

import pytest
from typer.testing import CliRunner

from axiscal.cli import app

runner = CliRunner()


def _one_error_line(r, *words):
    assert r.exit_code == 2, r.output
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("axiscal: error: "), r.stderr
    assert "Traceback" not in r.output and r.stdout == ""
    for w in words:
        assert w in lines[0], (w, lines[0])
    return lines[0]


@pytest.mark.parametrize("args, words", [
    (["bogus"], ["no such command 'bogus'", "axiscal --help"]),
    (["--bogus"], ["no such option: --bogus"]),
    (["plan", "bogus"], ["plan: no such command 'bogus'", "axiscal plan --help"]),
    (["plan", "linear"], ["plan linear: missing option '--length'", "axiscal plan linear --help"]),
    (["plan", "linear", "--length", "abc"], ["'--length'", "'abc' is not a valid float"]),
    (["plan", "linear", "--length", "800", "--targets", "x"], ["'--targets'", "not a valid int"]),
    (["iso230-2"], ["iso230-2: missing argument"]),
    (["iso230-2", "a.csv", "b.csv"], ["unexpected extra argument"]),
    (["rotary", "budget", "--alpha", "1"], ["missing option '--beta'"]),
])
def test_usage_errors_are_one_line(args, words):
    _one_error_line(runner.invoke(app, args), *words)


@pytest.mark.parametrize("args", [
    ["plan", "linear", "--length", "800", "--start", "nan"],
    ["plan", "rotary", "--start", "inf"],
    ["rotary", "budget", "--alpha", "1", "--beta", "1", "--base", "inf"],
    ["rotary", "budget", "--alpha", "1", "--beta", "1", "--accuracy", "inf"],
    ["squareness", "biaxial", "x.csv", "y.csv", "--prism-error", "nan"],
    ["compensate", "x.csv", "--home", "nan"],
    ["compensate", "x.csv", "--travel", "0", "--travel", "inf"],
    ["motion", "stability", "--duration-min", "inf"],
    ["scale", "compensate", "--material-temperature", "-inf"],
    ["air", "--temperature", "nan"],
])
def test_number_options_must_be_finite(args):
    """No length, angle, time or temperature is NaN or infinite; refused while parsing."""
    _one_error_line(runner.invoke(app, args), "is not a finite number")


@pytest.mark.parametrize("args", [
    ["plan", "linear", "--length", "800", "--targets", "1000000000"],
    ["plan", "rotary", "--targets", "1000000000"],
    ["plan", "rotary", "--runs", "100000000"],
    ["plan", "linear", "--length", "800", "--runs", "0"],
    ["motion", "repeatability", "x.toml", "--runs", "1000000"],
    ["plan", "linear", "--length", "1e12"],
    ["plan", "rotary", "--travel", "1e300"],
])
def test_counts_that_would_only_exhaust_memory(args):
    """A billion targets made numpy try to allocate tens of GiB (MemoryError traceback)."""
    _one_error_line(runner.invoke(app, args), "is not in the range")


def test_a_step_that_gives_too_many_targets():
    _one_error_line(runner.invoke(app, ["plan", "rotary", "--step", "1e-9"]),
                    "--step 1e-09 deg over 360 deg gives more than 10000 targets")


def test_group_without_a_command_still_shows_its_help():
    r = runner.invoke(app, ["plan"])
    assert r.exit_code == 2 and "linear" in r.output and "rotary" in r.output


def _all_command_paths():
    import typer

    root = typer.main.get_command(app)
    stack = [((), root)]
    while stack:
        path, cmd = stack.pop()
        yield path
        for name in getattr(cmd, "list_commands", lambda ctx: [])(None):
            stack.append((path + (name,), cmd.get_command(None, name)))


def test_help_is_accurate():
    """Single commands (iso230-2, simulate, demo, air, compensate) offered --install-completion
    for a scratch app; rich markup ate '[gantry]' out of 'scale gantry --help'."""
    seen = 0
    for path in _all_command_paths():
        r = runner.invoke(app, [*path, "--help"], env={"COLUMNS": "200"})
        assert r.exit_code == 0, path
        assert "--install-completion" not in r.stdout, path
        seen += 1
    assert seen >= 20
    r = runner.invoke(app, ["scale", "gantry", "--help"], env={"COLUMNS": "200"})
    assert "TOML with a gantry table" in r.stdout
    r = runner.invoke(app, ["iso230-2", "--help"], env={"COLUMNS": "200"})
    assert "HTML (.html) or PDF (.pdf" in r.stdout
