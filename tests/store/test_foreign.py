"""Databases that are not an axiscal history, and histories that cannot be written (issue 30).

A file that is not an axiscal history is refused in one line, before anything is written: no
table added, its bytes and journal mode as they were (before the fix an empty file or another
application's SQLite database became a history: 6 tables added, its journal switched to WAL).
A read-only history (file mode 0444, a folder of mode 0555) can be listed and shown; a write or
a needed upgrade is refused in one line. Ids outside 64 bits name no test."""

from __future__ import annotations

import json
import sqlite3
from pathlib import Path

import numpy as np
import pytest
from sqlalchemy import create_engine, inspect, text
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.store import NotFoundError, StoreError, open_store

from tests.store.test_history import _dataset, _raw

runner = CliRunner()


def _one_line(args, *words):
    r = runner.invoke(app, args)
    assert r.exit_code == 2, r.output
    assert len(r.stderr.strip().splitlines()) == 1 and "Traceback" not in r.stderr, r.stderr
    for w in words:
        assert w in r.stderr, r.stderr
    return r.stderr


def _untouched(path: Path, before: bytes) -> None:
    assert path.read_bytes() == before
    assert not Path(f"{path}-wal").exists() and not Path(f"{path}-shm").exists()


def test_an_empty_file_is_refused_not_converted(tmp_path):
    """A zero-byte file (``touch history.sqlite``) was not made by axiscal, which creates a
    history whole and links it into place: refused, still zero bytes."""
    f = tmp_path / "h.sqlite"
    f.touch()
    _one_line(["history", "list", "--db", f"sqlite:///{f}"], "empty file (0 bytes)",
              "not an axiscal history")
    _untouched(f, b"")


def test_another_applications_sqlite_database_is_refused(tmp_path):
    """Another application's SQLite database (rollback journal): refused naming its tables; no
    table added, journal mode still 'delete', every byte as before."""
    f = tmp_path / "notes.sqlite"
    with sqlite3.connect(f) as c:
        c.execute("create table notes (id integer primary key, body text)")
        c.execute("insert into notes (body) values ('keep me')")
    before = f.read_bytes()
    for cmd in (["history", "list"], ["history", "machines"]):
        _one_line([*cmd, "--db", f"sqlite:///{f}"], "not an axiscal history", "notes")
    _untouched(f, before)
    with sqlite3.connect(f) as c:
        assert c.execute("pragma journal_mode").fetchone()[0] == "delete"
        assert [r[0] for r in c.execute("select name from sqlite_master")] == ["notes"]
    raw = tmp_path / "x.csv"
    raw.write_bytes(_raw(_dataset(np.random.default_rng(1))))
    _one_line(["history", "add", str(raw), "--db", f"sqlite:///{f}"], "not an axiscal history")
    _untouched(f, before)


def test_an_empty_sqlite_database_and_another_alembic_project_are_refused(tmp_path):
    empty = tmp_path / "empty.sqlite"
    with sqlite3.connect(empty) as c:
        c.execute("pragma user_version = 7")            # a valid SQLite file with no table
    other = tmp_path / "other.sqlite"
    with sqlite3.connect(other) as c:
        c.execute("create table alembic_version (version_num varchar(32) primary key)")
        c.execute("insert into alembic_version values ('a1b2c3d4')")
        c.execute("create table invoice (id integer)")
    for f, word in ((empty, "did not make"), (other, "Alembic revision")):
        before = f.read_bytes()
        with pytest.raises(StoreError, match=word):
            open_store(f"sqlite:///{f}")
        _untouched(f, before)


def test_a_history_of_a_newer_axiscal_is_refused_and_said_so(tmp_path):
    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    open_store(url).close()
    with sqlite3.connect(tmp_path / "h.sqlite") as c:
        c.execute("update alembic_version set version_num = '9999'")
    with pytest.raises(StoreError, match="newer than this axiscal's"):
        open_store(url)


def test_a_new_path_is_created_whole(tmp_path):
    """A path where no file exists becomes a history, in a folder made for it, and no
    temporary file is left beside it."""
    f = tmp_path / "new" / "folder" / "h.sqlite"
    s = open_store(f"sqlite:///{f}")
    s.add(_raw(_dataset(np.random.default_rng(2))), "x.csv")
    s.close()
    assert sorted(p.name for p in f.parent.iterdir()) == ["h.sqlite"]
    with sqlite3.connect(f) as c:
        assert c.execute("pragma journal_mode").fetchone()[0] == "wal"


def test_a_postgresql_database_of_another_application_is_refused(pg_server):
    from tests.store.conftest import _fresh_pg_database

    url = _fresh_pg_database(pg_server)
    engine = create_engine(url)
    with engine.begin() as c:
        c.execute(text("create table orders (id integer)"))
    with pytest.raises(StoreError, match="other tables: orders"):
        open_store(url)
    with engine.connect() as c:
        assert inspect(c).get_table_names() == ["orders"]
    engine.dispose()


@pytest.fixture
def stored(tmp_path):
    """A history folder holding one test; (folder, URL, the test's id)."""
    folder = tmp_path / "shared"
    url = f"sqlite:///{folder / 'h.sqlite'}"
    s = open_store(url)
    tid = s.add(_raw(_dataset(np.random.default_rng(4))), "x.csv").id
    s.close()
    yield folder, url, tid
    folder.chmod(0o755)
    (folder / "h.sqlite").chmod(0o644)


@pytest.mark.parametrize("what", ["file", "folder"])
def test_a_read_only_history_is_listed_and_shown_not_written(stored, tmp_path, what):
    """File mode 0444, or its folder 0555 (read-only by mode even for root): list, machines
    and show work; add is refused in one line; the file's bytes are unchanged."""
    folder, url, tid = stored
    f = folder / "h.sqlite"
    before = f.read_bytes()
    (f if what == "file" else folder).chmod(0o444 if what == "file" else 0o555)
    r = runner.invoke(app, ["history", "list", "--db", url, "--json"])
    assert r.exit_code == 0, r.output
    assert [t["id"] for t in json.loads(r.stdout)] == [tid]
    r = runner.invoke(app, ["history", "show", str(tid), "--db", url, "--json"])
    assert r.exit_code == 0, r.output
    assert json.loads(r.stdout)["file"] == "x.csv"
    raw = tmp_path / "y.csv"
    raw.write_bytes(_raw(_dataset(np.random.default_rng(5))))
    err = _one_line(["history", "add", str(raw), "--db", url], "read-only",
                    "listed and shown, not written")
    assert ("0444" if what == "file" else "0555") in err
    assert f.read_bytes() == before


def test_a_read_only_history_needing_an_upgrade_says_so(tmp_path):
    """A history at an older revision, read-only: one line saying it needs upgrading where it
    can be written; nothing written."""
    from alembic import command
    from alembic.config import Config

    import axiscal.store.history as h

    f = tmp_path / "old.sqlite"
    engine = create_engine(f"sqlite:///{f}")
    cfg = Config()
    cfg.set_main_option("script_location", str(Path(h.__file__).parent / "migrations"))
    with engine.begin() as conn:
        cfg.attributes["connection"] = conn
        command.upgrade(cfg, "0001")
    engine.dispose()
    before = f.read_bytes()
    f.chmod(0o444)
    try:
        _one_line(["history", "list", "--db", f"sqlite:///{f}"], "read-only",
                  "needs upgrading", "revision 0001")
    finally:
        f.chmod(0o644)
    assert f.read_bytes() == before


@pytest.mark.parametrize("test_id", [0, -1, 2**63, 10**20])
def test_ids_outside_64_bits_name_no_test(tmp_path, test_id):
    s = open_store(f"sqlite:///{tmp_path / 'h.sqlite'}")
    with pytest.raises(NotFoundError, match="no test"):
        s.get(test_id)
    with pytest.raises(NotFoundError, match="no test"):
        s.add_table(test_id, "csv", "x.csv", "")


def test_a_page_beyond_64_bits_is_empty(tmp_path):
    s = open_store(f"sqlite:///{tmp_path / 'h.sqlite'}")
    s.add(_raw(_dataset(np.random.default_rng(6))), "x.csv")
    assert s.tests(offset=10**20) == [] and s.tests(offset=2**63, limit=10) == []
    assert len(s.tests(limit=10**20)) == 1
