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
#: A date as the history prints it: the day a test was stored, so the README's day is not today's.
DATE = re.compile(r"\d{4}-\d{2}-\d{2}")


def _tour():
    """(command line, first shown output line or None) of every ``$ axiscal`` in the README, and
    ``("export NAME=VALUE", None)`` for an environment variable the tour sets."""
    lines = (ROOT / "README.md").read_text().splitlines()
    out = []
    for i, line in enumerate(lines):
        e = re.match(r"^\s{4}\$ (export \w+=\S+)$", line)
        if e:
            out.append((e.group(1), None))
            continue
        m = re.match(r"^\s{4}\$ axiscal (.*)$", line)
        if not m:
            continue
        shown = lines[i + 1].strip() if i + 1 < len(lines) else ""
        shown = None if (not shown or shown.startswith("$") or shown == "...") else shown
        out.append((m.group(1).split("  #")[0].strip(), shown))
    return out


def _normal(text: str) -> str:
    return " ".join(DATE.sub("YYYY-MM-DD", text.replace("…", "")).split())


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
    readme = (ROOT / "README.md").read_text()
    shown_job = readme.split("$ cat demo-output/job.toml\n", 1)[1].split("\n\n", 1)[0]
    assert [ln.strip() for ln in shown_job.splitlines()] == \
        (tmp_path / "demo-output" / "job.toml").read_text().splitlines()
    failures = []
    for command, shown in tour:
        if command.startswith("export "):
            name, _, value = command[len("export "):].partition("=")
            monkeypatch.setenv(name, value)
            continue
        args = shlex.split(command)
        if args[0] in NEVER_ENDS:
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
    # the lines that once could not run (their inputs were not written by make demo) are run
    for k in ("--job demo-output/job.toml", "history list", "raw.csv", "run.rtx"):
        assert any(k in c for c, _ in tour), k
