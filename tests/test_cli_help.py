"""Every command and command group of the CLI has help text (CONVENTIONS habit 10)."""

import typer
from typer.testing import CliRunner

from axiscal import __version__
from axiscal.cli import app

runner = CliRunner()


def _walk(cmd, path=()):
    yield path, cmd
    if hasattr(cmd, "list_commands"):
        for name in cmd.list_commands(None):
            yield from _walk(cmd.get_command(None, name), path + (name,))


def test_every_command_has_help_text():
    root = typer.main.get_command(app)
    seen = 0
    for path, cmd in _walk(root):
        assert (cmd.help or "").strip(), f"command {' '.join(path) or 'axiscal'} has no help text"
        result = runner.invoke(app, [*path, "--help"])
        assert result.exit_code == 0, (path, result.output)
        seen += 1
    assert seen >= 6


def test_version():
    result = runner.invoke(app, ["--version"])
    assert result.exit_code == 0
    assert result.output.strip() == f"axiscal {__version__}"
