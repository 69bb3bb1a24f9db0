"""``axiscal history ...`` and ``--history`` (issue 13), on SQLite."""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from axiscal.cli import app

from tests.store.test_history import _dataset, _raw

runner = CliRunner()


@pytest.fixture
def files(tmp_path):
    """Three yearly tests of one axis at the same targets, drifting."""
    from dataclasses import replace

    base = _dataset(np.random.default_rng(11))
    out = []
    for k, date in enumerate(("2023-01-10", "2024-01-10", "2025-01-10")):
        ds = replace(base, up=base.up + 2.0 * k * np.linspace(0, 1, 5)[:, None],
                     metadata=replace(base.metadata, date=date))
        p = tmp_path / f"x{k}.csv"
        p.write_bytes(_raw(ds))
        out.append(p)
    return out


def _run(*args):
    r = runner.invoke(app, list(args))
    assert r.exit_code == 0, r.output
    return r


def test_add_list_show_compare_trend(tmp_path, files):
    db = f"sqlite:///{tmp_path / 'h.sqlite'}"
    ids = [json.loads(_run("history", "add", str(f), "--db", db, "--json").stdout)["id"]
           for f in files]
    again = json.loads(_run("history", "add", str(files[0]), "--db", db, "--json").stdout)
    assert again == {"id": ids[0], "duplicate": True, "kind": "iso230-2", "machine": "VMC-800",
                     "axis": "X"}
    rows = json.loads(_run("history", "list", "--db", db, "--json").stdout)
    assert [r["id"] for r in rows] == ids[::-1]
    shown = json.loads(_run("history", "show", str(ids[1]), "--db", db, "--json").stdout)
    direct = json.loads(_run("iso230-2", str(files[1]), "--json").stdout)
    for k in ("A", "E", "M", "R", "B", "B_mean"):
        assert shown["parameters"][k]["value"] == direct[k]
    c = json.loads(_run("history", "compare", str(ids[0]), str(ids[2]), "--db", db,
                        "--json", "--plot", str(tmp_path / "c.png")).stdout)
    assert c["first"] == ids[0] and len(c["difference"]) == 5
    tr = json.loads(_run("history", "trend", "--machine", "VMC-800", "--axis", "X",
                         "--parameter", "E", "--tolerance", "40", "--db", db, "--json",
                         "--plot", str(tmp_path / "t.png")).stdout)
    assert len(tr["points"]) == 3 and tr["model"].startswith("least-squares")
    # another standard's parameter has its own trend (JIS R: 3s, drifting with the up runs)
    jis = json.loads(_run("history", "trend", "--machine", "VMC-800", "--axis", "X",
                          "--parameter", "jis-b6192:R", "--db", db, "--json").stdout)
    direct_jis = json.loads(_run("evaluate", str(files[2]), "--standard", "jis-b6192",
                                 "--json").stdout)
    assert jis["points"][-1]["value"] == direct_jis["standards"][0]["parameters"]["R"]["value"]
    assert jis["points"][0]["value"] < jis["points"][-1]["value"]
    assert (tmp_path / "c.png").stat().st_size > 5000 and (tmp_path / "t.png").exists()
    r = _run("history", "show", str(ids[0]), "--db", db, "--report", str(tmp_path / "r.html"))
    assert "ISO 230-2:2014" in r.stdout and (tmp_path / "r.html").exists()
    m = json.loads(_run("history", "machines", "--db", db, "--json").stdout)
    assert m == [{"name": "VMC-800", "axes": ["X"], "tests": 3, "last": "2025-01-10T00:00:00"}]


def test_export_import(tmp_path, files):
    a, b = f"sqlite:///{tmp_path / 'a.sqlite'}", f"sqlite:///{tmp_path / 'b.sqlite'}"
    for f in files:
        _run("history", "add", str(f), "--db", a)
    _run("history", "export", str(tmp_path / "h.zip"), "--db", a)
    r = json.loads(_run("history", "import", str(tmp_path / "h.zip"), "--db", b, "--json").stdout)
    assert r == {"archive": str(tmp_path / "h.zip"), "added": 3, "duplicates": 0, "audit": 0,
                 "laboratory": 0, "drift_checks": 0, "certificates": 0, "documents": 0}


def test_iso230_2_history_stores_the_run(tmp_path, files):
    db = f"sqlite:///{tmp_path / 'h.sqlite'}"
    r = runner.invoke(app, ["iso230-2", str(files[0]), "--history", "--db", db])
    assert r.exit_code == 0 and "history: stored as test 1" in r.stderr
    assert len(json.loads(_run("history", "list", "--db", db, "--json").stdout)) == 1


@pytest.mark.parametrize("args, words", [   # a command that reads creates no history (issue 39)
    (["history", "show", "7"], "no history database"),
    (["history", "add", "nowhere.csv"], "nowhere.csv"),
    (["history", "compare", "1", "1"], "no history database"),
    (["history", "trend", "--machine", "M", "--axis", "X"], "no history database"),
    (["history", "import", "nowhere.zip"], "nowhere.zip"),
    (["history", "add", "--date", "yesterday", "F"], "F"),
])
def test_user_errors_are_one_line(tmp_path, args, words):
    r = runner.invoke(app, [*args, "--db", f"sqlite:///{tmp_path / 'h.sqlite'}"])
    assert r.exit_code == 2 and words in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1
    if words == "no history database":
        assert not (tmp_path / "h.sqlite").exists()


def test_a_bad_date_and_a_file_without_machine(tmp_path, files):
    db = f"sqlite:///{tmp_path / 'h.sqlite'}"
    r = runner.invoke(app, ["history", "add", str(files[0]), "--date", "yesterday", "--db", db])
    assert r.exit_code == 2 and "YYYY-MM-DD" in r.stderr
    p = tmp_path / "anon.csv"
    p.write_bytes(_raw(_dataset(np.random.default_rng(1), machine="")))
    r = runner.invoke(app, ["history", "add", str(p), "--db", db])
    assert r.exit_code == 2 and "give --machine" in r.stderr
