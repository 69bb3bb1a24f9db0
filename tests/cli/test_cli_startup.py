"""What ``axiscal iso230-2 FILE --json`` loads on its way (issue 30: start-up at most 1.5x
``python -c "import numpy"``).

The time itself is measured in ``benchmarks/bench_iso230_2.py`` as a ratio to that reference,
never asserted here (CONVENTIONS habit 12). What is pinned is deterministic: the modules a run
imports. A heavy library or another command's module appearing on this path is a regression of
start-up that no timing on a shared machine would show reliably.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

#: Runs the command line as ``python -m axiscal`` does, then writes every imported module's name.
_RUN = """
import atexit, runpy, sys
out = sys.argv[1]
atexit.register(lambda: open(out, "w").write("\\n".join(sorted(sys.modules))))
sys.argv = ["axiscal", *sys.argv[2:]]
runpy.run_module("axiscal", run_name="__main__", alter_sys=True)
"""

#: Libraries the JSON of a positioning test never needs: plots, reports, tables, the history
#: database, the workbench, GTC, pint (read only for an uncertainty input written with its unit).
HEAVY = ("matplotlib", "scipy", "GTC", "pint", "jinja2", "sqlalchemy", "alembic", "rich",
         "fastapi", "starlette", "weasyprint", "pandas", "pygments", "markdown_it")

#: axiscal's own modules that serve other formats, other commands or other outputs (of the
#: history only its one evaluation of a test, axiscal.store.kinds, whose record the command
#: prints: the package's names load on first use).
NOT_FOR_A_CSV = ("axiscal._schema", "axiscal.io.epics", "axiscal.io.ecmc", "axiscal.io.renishaw",
                 "axiscal.io.json", "axiscal.report.plots", "axiscal.report.html",
                 "axiscal.store.history", "axiscal.store.database", "axiscal.store.models",
                 "axiscal.store.cache", "axiscal.web", "axiscal.procedures", "axiscal.machines",
                 "axiscal.instruments", "axiscal.compensation",
                 "axiscal.standards.positioning_standards")


def _csv(folder) -> str:
    """A small bidirectional positioning test: five targets, three runs each way, µm."""
    lines = ["# target_unit=mm deviation_unit=um", "target,direction,run,deviation"]
    for i, t in enumerate((0, 100, 200, 300, 400)):
        for d, off in (("+", 0.0), ("-", -2.0)):
            lines += [f"{t},{d},{r},{0.5 * i + off + 0.1 * r}" for r in (1, 2, 3)]
    p = folder / "x.csv"
    p.write_text("\n".join(lines) + "\n")
    return str(p)


def _modules(tmp_path, *args) -> tuple[set[str], subprocess.CompletedProcess]:
    env = {k: v for k, v in os.environ.items() if not k.startswith("AXISCAL_")}
    env["XDG_CONFIG_HOME"] = str(tmp_path / "no-config")   # no user configuration
    out = tmp_path / "modules.txt"
    r = subprocess.run([sys.executable, "-c", _RUN, str(out), *args], capture_output=True,
                       text=True, env=env, timeout=120)
    return set(out.read_text().split()), r


def _loaded(modules: set[str], names) -> list[str]:
    return sorted(m for m in modules if any(m == n or m.startswith(n + ".") for n in names))


def test_iso230_2_json_loads_no_heavy_library(tmp_path):
    """The JSON of a CSV test is computed and printed without any heavy library, without the
    readers of the other formats and without the TOML schema (no configuration file read)."""
    modules, r = _modules(tmp_path, "iso230-2", _csv(tmp_path), "--json")
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["n_runs"] == 3            # the run did evaluate the file
    assert {"numpy", "typer", "axiscal.standards.iso230_2", "axiscal.io.csv"} <= modules
    assert _loaded(modules, HEAVY) == []
    assert _loaded(modules, NOT_FOR_A_CSV) == []


def test_a_command_loads_only_its_own_command_module(tmp_path):
    """Commands are registered lazily (``axiscal.cli.COMMANDS``): running one imports its module
    and the shared ``cli._*`` helpers, no other command's."""
    modules, r = _modules(tmp_path, "iso230-2", _csv(tmp_path), "--json")
    assert r.returncode == 0, r.stderr
    commands = [m for m in modules if m.startswith("axiscal.cli.")
                and not m.rpartition(".")[2].startswith("_")]
    assert commands == ["axiscal.cli.iso230_2"]


@pytest.mark.parametrize("args", [["--version"], ["--help"], ["iso230-2", "--help"],
                                  ["evaluate", "--help"]])
def test_version_and_help_load_no_numpy(tmp_path, args):
    """``--version`` and the help compute nothing: NumPy is not loaded."""
    modules, r = _modules(tmp_path, *args)
    assert r.returncode == 0, r.stderr
    assert "numpy" not in modules


def test_iso230_2_is_one_of_the_positioning_standards():
    """The evaluation of ``iso230-2`` knows its standard's key without importing the table of
    every positioning standard; the key must still be that table's."""
    from axiscal.report.evaluations import ISO230_2
    from axiscal.standards.positioning_standards import STANDARDS

    assert ISO230_2 in STANDARDS and STANDARDS[ISO230_2].title == "ISO 230-2:2014"


def test_the_root_help_loads_no_command_module(tmp_path):
    """``axiscal --help`` lists the commands from ``axiscal.cli.SUMMARIES``: no command module
    is imported to draw it."""
    modules, r = _modules(tmp_path, "--help")
    assert r.returncode == 0, r.stderr
    assert "iso230-2" in r.stdout and "volumetric" in r.stdout
    assert [m for m in modules if m.startswith("axiscal.cli.")
            and not m.rpartition(".")[2].startswith("_")] == []


def test_the_listed_help_is_each_commands_own(monkeypatch):
    """Each entry of ``SUMMARIES`` is the first paragraph of its command's help (what the
    list shows), and the root help drawn from the table is the one drawn from the commands."""
    import inspect

    from typer.testing import CliRunner

    from axiscal import cli

    assert set(cli.SUMMARIES) == set(cli.COMMANDS)
    for name in cli.COMMANDS:
        cmd = cli._load_command(name)
        own = inspect.cleandoc(cmd.short_help or cmd.help or "").split("\n\n")[0]
        assert cli.SUMMARIES[name] == own, f"axiscal.cli.SUMMARIES[{name!r}] is not its help"
    listed = CliRunner().invoke(cli.app, ["--help"], env={"COLUMNS": "200"})
    monkeypatch.setattr(cli, "SUMMARIES", {})          # every command loaded to be listed
    loaded = CliRunner().invoke(cli.app, ["--help"], env={"COLUMNS": "200"})
    assert listed.exit_code == loaded.exit_code == 0
    assert listed.output == loaded.output


@pytest.fixture
def collector():
    """The cycle collector as the test found it, afterwards (main() freezes what exists)."""
    import gc

    was = gc.isenabled()
    yield gc
    gc.unfreeze()
    gc.enable() if was else gc.disable()


def test_the_collector_pauses_for_start_up_only(tmp_path, monkeypatch, collector):
    """``main`` pauses the cycle collector while the command line and the command are loaded;
    the command's own work runs with it on, and it is on after the call."""
    from axiscal import cli
    from axiscal.cli import iso230_2

    seen = []
    real = iso230_2.print_json
    monkeypatch.setattr(iso230_2, "print_json", lambda obj: (seen.append(collector.isenabled()),
                                                             real(obj)))
    monkeypatch.setattr(sys, "argv", ["axiscal", "iso230-2", _csv(tmp_path), "--json"])
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "no-config"))
    collector.enable()
    with pytest.raises(SystemExit) as exit_:
        cli.main()
    assert exit_.value.code == 0
    assert seen == [True] and collector.isenabled()


def test_a_paused_collector_stays_paused(monkeypatch, collector):
    """A program that paused the collector itself finds it paused after ``main``."""
    from axiscal import cli

    monkeypatch.setattr(sys, "argv", ["axiscal", "--version"])
    collector.disable()
    with pytest.raises(SystemExit):
        cli.main()
    assert not collector.isenabled()
