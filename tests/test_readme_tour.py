"""The README's tour runs as written: every ``$ axiscal ...`` line is run, in order, in a folder
holding ``examples/``, ``src/axiscal/data/`` (as at the repository's root) and the outputs of ``axiscal demo --out demo-output`` (what ``make demo``
writes); each must end with exit 0 (or 1 where the README shows a failed tolerance), and the first
output line the README shows under a command must be the real first line."""

from __future__ import annotations

import re
import shlex
import shutil
from pathlib import Path

from typer.testing import CliRunner

from axiscal.cli import app

ROOT = Path(__file__).resolve().parents[1]

#: Commands the test cannot run to an end: ``serve`` starts a web server that runs until stopped.
NEVER_ENDS = {"serve"}
#: README lines whose input is not (yet) written by ``make demo``: a job file the user writes, the
#: history store the demo fills elsewhere, a raw interferometer capture and an environment log.
#: Listed by name so that each is fixed in its own section; the test checks they are still there.
NOT_FROM_DEMO = ("--job job.toml", "history ", "raw.csv", "run.rtx")


def _tour():
    """(command line, first shown output line or None) of every ``$ axiscal`` in the README."""
    lines = (ROOT / "README.md").read_text().splitlines()
    out = []
    for i, line in enumerate(lines):
        m = re.match(r"^\s{4}\$ axiscal (.*)$", line)
        if not m:
            continue
        shown = lines[i + 1].strip() if i + 1 < len(lines) else ""
        shown = None if (not shown or shown.startswith("$") or shown == "...") else shown
        out.append((m.group(1).split("  #")[0].strip(), shown))
    return out


def _normal(text: str) -> str:
    return " ".join(text.replace("…", "").split())


def test_readme_tour_runs_as_written(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("AXISCAL_CONFIG", str(tmp_path / "config.toml"))
    monkeypatch.setenv("COLUMNS", "160")
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    shutil.copytree(ROOT / "src" / "axiscal" / "data", tmp_path / "src" / "axiscal" / "data")
    runner = CliRunner()
    r = runner.invoke(app, ["demo", "--out", "demo-output"])
    assert r.exit_code == 0, r.output
    tour = _tour()
    assert len(tour) > 20
    failures = []
    for command, shown in tour:
        args = shlex.split(command)
        if args[0] in NEVER_ENDS or any(k in command for k in NOT_FROM_DEMO):
            continue
        r = runner.invoke(app, args)
        if shown is not None and shown.startswith("axiscal: error:"):   # a shown mistake
            if r.exit_code != 2 or _normal(shown) not in _normal(r.stderr):
                failures.append(f"axiscal {command}: README shows {shown!r}; got {r.stderr!r}")
            continue
        failed_tolerance = "FAIL" in r.output or '"passed": false' in r.output
        if r.exit_code not in (0, 1) or (r.exit_code == 1 and not failed_tolerance):
            failures.append(f"axiscal {command}: exit {r.exit_code}: {r.output.strip()[-300:]}")
            continue
        if shown is not None and not shown.startswith(("┏", "┃", "│", "[")):
            first = _normal(shown.split("...")[0])
            if first and first not in _normal(r.output):
                failures.append(f"axiscal {command}: README shows {shown!r}; real output starts "
                                f"{r.output.strip().splitlines()[:1]}")
    assert not failures, "\n".join(failures)
    for k in NOT_FROM_DEMO:
        assert any(k in c for c, _ in tour), f"{k!r} no longer in the README: drop it from the list"
