"""``axiscal history rename-machine|rename-axis|merge|edit|withdraw|reinstate|audit`` (issue 31;
ISO/IEC 17025:2017 §7.5.2: a change names who, when, what and why, the old values kept)."""

from __future__ import annotations

import json

from typer.testing import CliRunner

from axiscal.cli import app

from tests.cli.test_cli_history import files  # noqa: F401  (the fixture)

runner = CliRunner()
WHO = ["--by", "A. Ng", "--reason", "serial added"]


def _run(*args):
    r = runner.invoke(app, list(args))
    assert r.exit_code == 0, r.output
    return r


def _fails(*args) -> str:
    r = runner.invoke(app, list(args))
    assert r.exit_code != 0 and "Traceback" not in r.output
    return r.stderr.strip()


def test_corrections_from_the_command_line(tmp_path, files):  # noqa: F811
    db = f"sqlite:///{tmp_path / 'h.sqlite'}"
    ids = [json.loads(_run("history", "add", str(f), "--db", db, "--json").stdout)["id"]
           for f in files]
    r = _run("history", "rename-machine", "VMC-800", "DMU 50 S/N 1234", *WHO, "--db", db)
    assert r.stdout.startswith("machine 'VMC-800' renamed 'DMU 50 S/N 1234' (audit entry 1, "
                               "by A. Ng: serial added)")
    e = json.loads(_run("history", "withdraw", str(ids[1]), "--by", "A. Ng", "--reason",
                        "beam clipped", "--db", db, "--json").stdout)
    assert (e["action"], e["test_id"], e["new"]) == ("withdraw", ids[1], {"withdrawn": True})
    listed = _run("history", "list", "--db", db).stdout.splitlines()
    assert [x for x in listed if x.strip().startswith(str(ids[1]))][0].endswith(
        "WITHDRAWN: beam clipped")
    tr = json.loads(_run("history", "trend", "--machine", "DMU 50 S/N 1234", "--axis", "X",
                         "--db", db, "--json").stdout)
    assert [p["test"] for p in tr["points"]] == [ids[0], ids[2]]
    _run("history", "edit", str(ids[0]), "--operator", "K. Ng", "--note", "new note", *WHO,
         "--db", db)
    _run("history", "reinstate", str(ids[1]), *WHO, "--db", db)
    trail = json.loads(_run("history", "audit", "--machine", "DMU 50 S/N 1234", "--db", db,
                            "--json").stdout)
    assert [t["action"] for t in trail] == ["reinstate", "edit", "withdraw", "rename-machine"]
    assert trail[1]["old"] == {"operator": "", "note": ""}
    assert trail[3]["old"] == {"name": "VMC-800"}
    text = _run("history", "audit", "--test", str(ids[0]), "--db", db).stdout
    assert "A. Ng: test 1: operator, note edited; why: serial added" in text


def test_corrections_refused_in_one_line(tmp_path, files):  # noqa: F811
    db = f"sqlite:///{tmp_path / 'h.sqlite'}"
    _run("history", "add", str(files[0]), "--db", db)
    assert _fails("history", "withdraw", "1", "--by", " ", "--reason", "x", "--db", db) == \
        "axiscal: error: say who makes the change (--by NAME): the audit trail records it"
    assert "--reason" in _fails("history", "withdraw", "1", "--by", "me", "--db", db)
    assert _fails("history", "merge", "VMC-800", "nope", *WHO, "--db", db) == \
        "axiscal: error: no machine 'nope' in the history"
    assert _fails("history", "edit", "1", *WHO, "--db", db) == \
        "axiscal: error: nothing to change: give one of date, operator, instrument, note"
    assert _fails("history", "merge", "X", "Y", "--machine", "VMC-800", *WHO, "--db", db) == \
        "axiscal: error: machine 'VMC-800' has no axis 'Y'"
    assert json.loads(_run("history", "audit", "--db", db, "--json").stdout) == []


def test_a_note_typed_on_a_duplicate_is_said_not_stored(tmp_path, files):  # noqa: F811
    db = f"sqlite:///{tmp_path / 'h.sqlite'}"
    _run("history", "add", str(files[0]), "--db", db)
    r = _run("history", "add", str(files[0]), "--db", db, "--note", "after the crash",
             "--json")
    assert json.loads(r.stdout)["duplicate"] is True
    assert r.stderr.strip() == (
        "not stored: --note 'after the crash' (test 1 keeps what it was stored with); to "
        "change it: axiscal history edit 1 --note 'after the crash' --by NAME --reason TEXT")
    assert json.loads(_run("history", "list", "--db", db, "--json").stdout)[0]["withdrawn"] \
        is None
    assert "not stored" not in _run("history", "add", str(files[0]), "--db", db).stderr
