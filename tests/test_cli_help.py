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


def test_no_internal_document_names_in_any_help():
    """User-facing text cites documents by their real title, never an internal file name
    ("seed 003"); every command is reached by walking the app's groups."""
    import typer
    from typer._click import core
    from typer.testing import CliRunner

    from axiscal.cli import app

    def walk(cmd, path, ctx):
        if hasattr(cmd, "list_commands"):
            sub = core.Context(cmd, info_name=path[-1] if path else "axiscal", parent=ctx)
            yield path
            for name in cmd.list_commands(sub):
                yield from walk(cmd.get_command(sub, name), path + [name], sub)
        else:
            yield path

    paths = list(walk(typer.main.get_command(app), [], None))
    assert len(paths) > 15
    for path in paths:
        r = CliRunner().invoke(app, [*path, "--help"], env={"COLUMNS": "200"})
        assert r.exit_code == 0, path
        assert "seed 00" not in r.output.lower(), (path, r.output)


def test_an_option_name_means_one_thing():
    """--alpha is the misalignment α of Renishaw's eq. 1 (rotary budget) and nowhere an expansion
    coefficient (scale compensate: --expansion-coefficient); --reference is a reference line
    (straightness, biaxial) and nowhere a home position (compensate: --home)."""
    from typer.testing import CliRunner

    from axiscal.cli import app

    def options(*path):
        r = CliRunner().invoke(app, [*path, "--help"], env={"COLUMNS": "250"})
        return r.output

    assert "--expansion-coefficient" in options("scale", "compensate")
    assert "--alpha" not in options("scale", "compensate")
    assert "--home" in options("compensate") and "--reference" not in options("compensate")
    assert "--reference" in options("straightness") and "--alpha" in options("rotary", "budget")


def test_every_command_help_has_a_runnable_example():
    """Each command's help ends its description with one ``Example: axiscal <the command> …``
    line a user can copy (issue 11)."""
    from axiscal.cli import COMMANDS, _load_command

    def leaves(cmd, path):
        sub = getattr(cmd, "commands", None)
        if sub:
            for n, c in sub.items():
                yield from leaves(c, path + [n])
        else:
            yield " ".join(path), cmd

    missing = []
    for name in sorted(COMMANDS):
        for path, cmd in leaves(_load_command(name), [name]):
            if f"Example: axiscal {path}" not in " ".join((cmd.help or "").split()):
                missing.append(path)
    assert not missing, f"no 'Example: axiscal …' in the help of {missing}"


def test_no_message_cites_a_document_by_its_seed_file():
    """Every string the program can show (not docstrings or comments) names documents by title:
    a warning "the seed asks for < 0.04 mm" or an error "seed 004 defines machines 1 to 7" sent the
    user to a file they do not have. A random-number seed ("--seed", "[simulation] seed") is fine."""
    import ast
    import re
    from pathlib import Path

    import axiscal

    pattern = re.compile(r"seed 00\d|\bthe seed\b(?! by| of the)|\bseed's\b|\bseeds/")
    found = []
    for path in sorted(Path(axiscal.__file__).parent.rglob("*.py")):
        tree = ast.parse(path.read_text())
        docs = {id(n.body[0].value) for n in ast.walk(tree)
                if isinstance(n, (ast.Module, ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef))
                and n.body and isinstance(n.body[0], ast.Expr)
                and isinstance(n.body[0].value, ast.Constant)}
        for node in ast.walk(tree):
            if (isinstance(node, ast.Constant) and isinstance(node.value, str)
                    and id(node) not in docs and pattern.search(node.value)):
                found.append(f"{path.name}:{node.lineno}: {node.value[:80]!r}")
    # and the files a user opens: examples, the embedded configurations, the docs and README
    root = Path(axiscal.__file__).parents[2]
    for path in [*sorted((root / "examples").iterdir()), *sorted((root / "docs").glob("*.md")),
                 *sorted(Path(axiscal.__file__).parent.joinpath("data").glob("*.toml")),
                 root / "README.md"]:
        if path.suffix in (".toml", ".csv", ".md", ".json", ".txt"):
            for n, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
                if pattern.search(line):
                    found.append(f"{path.name}:{n}: {line[:80]!r}")
    assert not found, "\n".join(found)
