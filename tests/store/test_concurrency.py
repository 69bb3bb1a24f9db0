"""Concurrent writers (issue 30): ten processes opening one fresh history at once and adding six
files each, and ten files of one new machine arriving at once, on SQLite and PostgreSQL: every
file stored, no "database is locked", no "conflicting write".

Before the fix 7 of 130 concurrent adds on a fresh SQLite history failed ("database is locked":
the schema upgrade ran in a deferred transaction), 5 of 30 on a fresh PostgreSQL database
(concurrent DDL: pg_type_typname_nsp_index) and 5 of 60 when ten files of one new machine came
at once ("conflicting write")."""

from __future__ import annotations

import multiprocessing as mp

import numpy as np

from axiscal.store import open_store

from tests.store.test_history import _dataset, _raw

WRITERS = 10


def _writer(url: str, seed: int, n: int, barrier, machine: str | None) -> None:
    """Wait for every writer, then open the history and add ``n`` files."""
    rng = np.random.default_rng(seed)
    files = [_raw(_dataset(rng, machine=machine or f"M{seed}", date=f"2024-{k + 1:02d}-01"))
             for k in range(n)]
    barrier.wait()
    s = open_store(url)
    for k, raw in enumerate(files):
        r = s.add(raw, f"{seed}-{k}.csv")
        assert not r.duplicate
    s.close()


def _run_writers(url: str, n: int, machine: str | None = None) -> list:
    ctx = mp.get_context("fork")          # quick; the parent holds no connection
    barrier = ctx.Barrier(WRITERS)
    procs = [ctx.Process(target=_writer, args=(url, seed, n, barrier, machine))
             for seed in range(WRITERS)]
    for p in procs:
        p.start()
    for p in procs:
        p.join(300)
    return [p.exitcode for p in procs]


def test_ten_writers_on_a_fresh_database(db_url):
    """10 processes × 6 files, all opening the same fresh (non-existent SQLite file, empty
    PostgreSQL database) history at the same moment: all 60 stored, one schema."""
    assert _run_writers(db_url, 6) == [0] * WRITERS
    s = open_store(db_url)
    assert len(s.tests()) == WRITERS * 6
    assert sorted(m.name for m in s.machines()) == sorted(f"M{k}" for k in range(WRITERS))


def test_ten_files_of_one_new_machine_at_once(db_url):
    """10 processes each add one file of the same machine, new to the history, at the same
    moment: one machine, one axis, ten tests."""
    open_store(db_url).close()
    assert _run_writers(db_url, 1, machine="NEW-5AX") == [0] * WRITERS
    s = open_store(db_url)
    [m] = s.machines()
    assert (m.name, m.axes, m.tests) == ("NEW-5AX", ("X",), WRITERS)


def test_a_write_lock_held_past_the_busy_timeout_is_waited_for_again(tmp_path, monkeypatch):
    """Another writer holds SQLite's write lock longer than the busy timeout (shortened here to
    0.2 s): the add waits again (LOCKED_RETRIES times) and is stored when the lock goes; held
    for good, the add fails in one line and nothing is half-stored."""
    import sqlite3
    import threading

    import pytest

    import axiscal.store.database as database
    from axiscal.store import StoreError
    from axiscal.store.history import LOCKED_RETRIES, prepare

    monkeypatch.setattr(database, "BUSY_TIMEOUT_MS", 200)
    f = tmp_path / "h.sqlite"
    s = open_store(f"sqlite:///{f}")
    rng = np.random.default_rng(8)
    a, b = (prepare(_raw(_dataset(rng)), name) for name in ("a.csv", "b.csv"))
    holder = sqlite3.connect(f, isolation_level=None, check_same_thread=False)
    holder.execute("BEGIN IMMEDIATE")
    release = threading.Timer(0.5, lambda: holder.execute("COMMIT"))
    release.start()
    [r] = s.add_all([a])                                       # 0.2 s, 0.2 s, then free
    release.join()
    assert not r.duplicate and len(s.tests()) == 1
    holder.execute("BEGIN IMMEDIATE")
    with pytest.raises(StoreError, match="database is locked"):
        s.add_all([b])
    holder.execute("ROLLBACK")
    assert [t.filename for t in s.tests()] == ["a.csv"] and LOCKED_RETRIES >= 2
