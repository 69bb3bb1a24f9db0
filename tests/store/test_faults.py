"""The history under faults (issues 13 and 30): a killed import (all or nothing), a full disk, a
file that is not a database, an old schema, two writers at once."""

from __future__ import annotations

import hashlib
import os
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.store import open_store
from axiscal.store.archive import export_history

from tests.store.test_history import _dataset, _raw

runner = CliRunner()
PY = sys.executable


def _import(archive: Path, url: str) -> subprocess.Popen:
    return subprocess.Popen([PY, "-m", "axiscal", "history", "import", str(archive), "--db", url,
                             "--json"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def _whole_import(d: dict, before: dict, n: int) -> bool:
    """The dump holds what was there before and every test of the archive, each whole."""
    tests = d["test"]
    return (len(tests) == len(before["test"]) + n
            and set(before["test"]) <= set(tests)
            and len({r[0] for r in d["parameter"]}) == len(d["parameter"])
            and len(d["compensation_table"]) == len(before["compensation_table"]) + n)


def _kill_after(proc, delay: float, wal: Path | None, rng) -> None:
    """SIGKILL ``proc`` after ``delay`` s, or (``wal`` given) as soon as SQLite's write-ahead
    log grows, inside the write transaction, plus up to 30 ms."""
    t0 = time.monotonic()
    while proc.poll() is None and time.monotonic() - t0 < delay:
        if wal is not None and wal.exists() and wal.stat().st_size > 0:
            time.sleep(rng.uniform(0, 0.03))
            break
        time.sleep(0.002)
    proc.send_signal(signal.SIGKILL)
    proc.wait()


def test_killed_import_leaves_the_database_exactly_as_before(tmp_path, db_url):
    """An archive import SIGKILLed at random points (seeded delays over the import's whole
    run; on SQLite also as soon as its write-ahead log grows, that is inside the one write
    transaction): a dump of every table equals the dump before, or, when the kill came after
    the commit, holds the whole archive (the database is then put back for the next kill on
    SQLite); never a part. Finally the import runs to the end and completes."""
    from tests.store.test_archive_trust import dump, make_archive

    n = 24
    rng = np.random.default_rng(2026)
    src = open_store(f"sqlite:///{tmp_path / 'src.sqlite'}")
    for k in range(n):                               # big enough that SQLite spills pages
        src.add(_raw(_dataset(rng, n_targets=400, date=f"2021-{k % 12 + 1:02d}-01")),
                f"t{k}.csv", tables=(("csv", f"t{k}-table.csv", "position,correction\n"),))
    archive = tmp_path / "a.zip"
    export_history(src, archive)
    s = open_store(db_url)
    s.add(_raw(_dataset(rng, machine="Lathe-2")), "old.csv",
          tables=(("csv", "old-table.csv", "position,correction\n"),))
    s.close()
    before = dump(db_url)
    sqlite_file = Path(db_url.split("///", 1)[1]) if db_url.startswith("sqlite") else None
    saved = sqlite_file.read_bytes() if sqlite_file else None
    kinds = {"before": 0, "whole": 0}
    for trial in range(6 if sqlite_file else 4):
        wal = Path(f"{sqlite_file}-wal") if sqlite_file and trial % 2 else None
        _kill_after(_import(archive, db_url), rng.uniform(0.5, 9.0), wal, rng)
        d = dump(db_url)
        if d == before:
            kinds["before"] += 1
            continue
        assert _whole_import(d, before, n), f"trial {trial}: a part of the archive was kept"
        kinds["whole"] += 1
        if sqlite_file:                              # put the database back for the next kill
            for suffix in ("-wal", "-shm"):
                Path(f"{sqlite_file}{suffix}").unlink(missing_ok=True)
            sqlite_file.write_bytes(saved)
        else:
            before = d                               # later imports are all duplicates
    if sqlite_file:
        with sqlite3.connect(sqlite_file) as c:
            assert c.execute("pragma integrity_check").fetchone()[0] == "ok"
    assert kinds["before"] >= 1, kinds
    r = runner.invoke(app, ["history", "import", str(archive), "--db", db_url, "--json"])
    assert r.exit_code == 0, r.output
    assert len(open_store(db_url).tests()) == n + 1


def test_full_disk_stores_nothing_and_says_so(tmp_path):
    """A file-size limit (RLIMIT_FSIZE, as a full disk would) stops a large test from being
    written: one line, exit 2, the database intact with what it held before."""
    db = tmp_path / "h.sqlite"
    url = f"sqlite:///{db}"
    s = open_store(url)
    s.add(_raw(_dataset(np.random.default_rng(1))), "small.csv")
    s.close()
    big = tmp_path / "big.csv"
    big.write_bytes(_raw(_dataset(np.random.default_rng(2), n_targets=4000, runs=10)))
    limit = os.path.getsize(db) + os.path.getsize(tmp_path / "h.sqlite-wal") + 64 * 1024 \
        if (tmp_path / "h.sqlite-wal").exists() else os.path.getsize(db) + 64 * 1024

    def small_disk():
        import resource

        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    p = subprocess.run([PY, "-m", "axiscal", "history", "add", str(big), "--db", url],
                       capture_output=True, text=True, preexec_fn=small_disk, timeout=120)
    assert p.returncode == 2, p.stderr
    assert len(p.stderr.strip().splitlines()) == 1 and "history database" in p.stderr
    assert "Traceback" not in p.stderr
    s = open_store(url)
    assert [t.filename for t in s.tests()] == ["small.csv"]


def test_a_file_that_is_not_a_database(tmp_path):
    bad = tmp_path / "notes.sqlite"
    bad.write_bytes(b"these are my notes, not a database\n" * 200)
    r = runner.invoke(app, ["history", "list", "--db", f"sqlite:///{bad}"])
    assert r.exit_code == 2
    assert "not an axiscal history database" in r.stderr and len(r.stderr.splitlines()) == 1


def test_a_database_url_that_cannot_work(tmp_path):
    r = runner.invoke(app, ["history", "list", "--db", "nosuchdb://x"])
    assert r.exit_code == 2 and "history database" in r.stderr
    r = runner.invoke(app, ["history", "list", "--db",
                            f"postgresql+psycopg://nobody@/x?host={tmp_path}"])
    assert r.exit_code == 2 and "history database" in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1


def test_an_old_schema_is_upgraded_with_its_data(db_url):
    """A database made at the first revision (no compensation tables yet), holding a test, is
    upgraded by opening it; the test is still there and tables can now be kept."""
    from alembic import command
    from alembic.config import Config
    from sqlalchemy import create_engine, text

    import axiscal.store.history as h

    engine = create_engine(db_url)
    cfg = Config()
    cfg.set_main_option("script_location", str(Path(h.__file__).parent / "migrations"))
    with engine.begin() as conn:
        cfg.attributes["connection"] = conn
        command.upgrade(cfg, "0001")
        conn.execute(text("insert into machine (id, name, maker, model, serial, location, created)"
                          " values (1, 'Old', '', '', '', '', '2020-01-01')"))
        conn.execute(text("insert into axis (id, machine_id, name, kind) values (1, 1, 'X', "
                          "'linear')"))
        raw = _raw(_dataset(np.random.default_rng(3), machine="Old"))
        conn.execute(text(
            "insert into test (id, axis_id, kind, tested_at, date_known, stored_at, instrument, "
            "operator, note, filename, sha256, raw, dataset_json, result_json, environment_json, "
            "axiscal_version) values (1, 1, 'iso230-2', '2020-01-02', true, '2020-01-02', '', '',"
            " '', 'old.csv', :sha, :raw, '', '{}', '{}', '0.0.1')"),
            {"raw": raw, "sha": hashlib.sha256(raw).hexdigest()})
    engine.dispose()
    s = open_store(db_url)
    assert [t.filename for t in s.tests()] == ["old.csv"]
    s.add_table(1, "csv", "X.csv", "position,correction\n")
    assert s.get(1).tables[0][1] == "X.csv"
    assert s.get(1).evaluate_again().kind == "iso230-2"


def _adder(url: str, seed: int, n: int, same: bytes | None) -> None:
    s = open_store(url)
    rng = np.random.default_rng(seed)
    for k in range(n):
        s.add(_raw(_dataset(rng, machine=f"M{seed}")), f"{seed}-{k}.csv")
    if same is not None:
        s.add(same, f"same-{seed}.csv")


def test_two_processes_adding_at_once(db_url):
    """Two processes add 15 tests each at the same time, and both add one identical file: every
    different test is stored, the identical file once."""
    import multiprocessing as mp

    open_store(db_url).close()
    same = _raw(_dataset(np.random.default_rng(99), machine="Shared"))
    ctx = mp.get_context("spawn")
    procs = [ctx.Process(target=_adder, args=(db_url, seed, 15, same)) for seed in (1, 2)]
    for p in procs:
        p.start()
    for p in procs:
        p.join(120)
    assert [p.exitcode for p in procs] == [0, 0]
    s = open_store(db_url)
    assert len(s.tests()) == 31
    assert len(s.tests(machine="Shared")) == 1
