"""The history under faults (issue 13): a killed import, a full disk, a file that is not a
database, an old schema, two writers at once."""

from __future__ import annotations

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


def _archive(tmp_path, n: int) -> Path:
    src = open_store(f"sqlite:///{tmp_path / 'src.sqlite'}")
    rng = np.random.default_rng(0)
    for k in range(n):
        src.add(_raw(_dataset(rng, n_targets=21, date=f"20{10 + k // 12:02d}-{k % 12 + 1:02d}-01")),
                f"t{k}.csv")
    export_history(src, tmp_path / "a.zip")
    return tmp_path / "a.zip"


def _count(db: Path) -> int:
    with sqlite3.connect(db) as c:
        return c.execute("select count(*) from test").fetchone()[0]


def test_sigkill_during_import_leaves_a_consistent_database_and_the_import_reruns(tmp_path):
    """A process killed with SIGKILL in the middle of a large import: the database passes
    SQLite's integrity check, holds only whole tests, and running the import again completes it
    without doubling anything."""
    n = 120
    archive = _archive(tmp_path, n)
    db = tmp_path / "h.sqlite"
    url = f"sqlite:///{db}"
    open_store(url).close()
    proc = subprocess.Popen([PY, "-m", "axiscal", "history", "import", str(archive), "--db", url,
                             "--json"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and proc.poll() is None:
        if _count(db) >= 10:
            break
        time.sleep(0.02)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    with sqlite3.connect(db) as c:
        assert c.execute("pragma integrity_check").fetchone()[0] == "ok"
        stored = c.execute("select count(*) from test").fetchone()[0]
        orphans = c.execute("select count(*) from parameter where test_id not in "
                            "(select id from test)").fetchone()[0]
        whole = c.execute("select count(*) from test where id not in "
                          "(select test_id from parameter)").fetchone()[0]
    assert 10 <= stored < n and orphans == 0 and whole == 0
    r = runner.invoke(app, ["history", "import", str(archive), "--db", url, "--json"])
    assert r.exit_code == 0, r.output
    assert _count(db) == n


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
            " '', 'old.csv', 'abc', :raw, '', '{}', '{}', '0.0.1')"), {"raw": raw})
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
