"""Serving the workbench from several processes: heavy work bounded, sessions shared.

* **Heavy work** (a report, a certificate: seconds and a hundred MB for a large test) runs in
  the thread pool, never on the event loop, and at most :data:`HEAVY_AT_ONCE` at a time in each
  worker process (:func:`heavy`); the others wait their turn. What it makes is kept
  (:func:`axiscal.store.cache.kept`), so the requests that waited for the same product read it
  instead of making it again: six concurrent requests for one report make it once, in the memory
  of one.
* **Sessions shared by the workers** (:class:`SharedSessions`): with ``axiscal serve --workers
  N`` a login served by one worker process must be known to the others, its log-out too, and the
  key that binds the no-login CSRF tokens must be the same. They are kept in a small SQLite
  database in a private folder (mode 0700) that ``axiscal serve`` makes for the run (WAL mode,
  one table, the cookie's SHA-256 as key as in :class:`~axiscal.web.sessions.Sessions`); a
  restart of the server logs everyone out, the safe direction, as with one process. The lifetimes
  are those of :mod:`axiscal.web.sessions` (OWASP Session Management Cheat Sheet), measured on
  the wall clock (``time.time``), common to the processes. The counts of wrong passwords
  (:class:`SharedThrottle`) are kept there too.
"""

from __future__ import annotations

import asyncio
import json
import os
import secrets
import sqlite3
import threading
import time
from pathlib import Path

from starlette.concurrency import run_in_threadpool

from axiscal.web.sessions import (ABSOLUTE_SECONDS, FREE_FAILURES, IDLE_SECONDS, LoginThrottle,
                                  Sessions, _digest)

__all__ = ["HEAVY_AT_ONCE", "heavy", "SharedSessions", "SharedThrottle", "WORKER_ID", "ENV"]

#: Reports and certificates made at once by one worker process (the rest wait).
HEAVY_AT_ONCE = 1
#: An opaque name of this worker process (the ``X-Axiscal-Worker`` header; no pid is shown).
WORKER_ID = secrets.token_hex(4)
#: Environment variable through which ``axiscal serve --workers N`` hands its settings to the
#: worker processes (JSON).
ENV = "AXISCAL_WORKBENCH"
_semaphores: dict = {}
_trim = None


async def heavy(fn, *args, **kwargs):
    """``fn(*args, **kwargs)`` in the thread pool, at most :data:`HEAVY_AT_ONCE` at once in this
    process (per event loop)."""
    loop = asyncio.get_running_loop()
    sem = _semaphores.get(loop)
    if sem is None:
        sem = _semaphores[loop] = asyncio.Semaphore(HEAVY_AT_ONCE)
    async with sem:
        try:
            return await run_in_threadpool(fn, *args, **kwargs)
        finally:
            _give_back_memory()


def _give_back_memory() -> None:
    """Return the heap a report freed to the system (glibc ``malloc_trim``; elsewhere nothing):
    without it a worker kept the peak of its largest report for good."""
    global _trim
    if _trim is None:
        try:
            import ctypes

            _trim = ctypes.CDLL("libc.so.6").malloc_trim
        except (OSError, AttributeError):
            _trim = False
    if _trim:
        _trim(0)


class SharedSessions(Sessions):
    """:class:`~axiscal.web.sessions.Sessions` kept in SQLite file ``folder/sessions.sqlite``,
    shared by every worker process; the CSRF key in ``folder/csrf.key``."""

    def __init__(self, folder, idle: float = IDLE_SECONDS, absolute: float = ABSOLUTE_SECONDS,
                 clock=time.time):
        super().__init__(idle, absolute, clock)
        self.folder = Path(folder)
        self.key = _shared_key(self.folder / "csrf.key")
        self._local = threading.local()
        with self._db() as db:
            db.execute("CREATE TABLE IF NOT EXISTS session (id TEXT PRIMARY KEY, name TEXT, "
                       "role TEXT, csrf TEXT, created REAL, seen REAL)")

    def _db(self) -> sqlite3.Connection:
        db = getattr(self._local, "db", None)
        if db is None:
            db = sqlite3.connect(self.folder / "sessions.sqlite", timeout=30,
                                 isolation_level=None, check_same_thread=False)
            db.execute("PRAGMA journal_mode=WAL")
            db.execute("PRAGMA synchronous=NORMAL")
            self._local.db = db
        return db

    def issue(self, name: str, role: str) -> str:
        token = secrets.token_urlsafe(32)
        now = self.clock()
        db = self._db()
        db.execute("DELETE FROM session WHERE seen < ? OR created < ?",
                   (now - self.idle, now - self.absolute))
        db.execute("INSERT INTO session VALUES (?, ?, ?, ?, ?, ?)",
                   (_digest(token), name, role, secrets.token_urlsafe(24), now, now))
        return token

    def read(self, cookie: str | None) -> dict | None:
        if not cookie or len(cookie) > 100:
            return None
        now, key, db = self.clock(), _digest(cookie), self._db()
        row = db.execute("SELECT name, role, csrf, created, seen FROM session WHERE id = ?",
                         (key,)).fetchone()
        if row is None:
            return None
        name, role, csrf, created, seen = row
        if now - seen > self.idle or now - created > self.absolute:
            db.execute("DELETE FROM session WHERE id = ?", (key,))
            return None
        if now - seen > 1.0:                       # activity, written at most once a second
            db.execute("UPDATE session SET seen = ? WHERE id = ?", (now, key))
        return {"name": name, "role": role, "csrf": csrf}

    def revoke(self, cookie: str | None) -> bool:
        cur = self._db().execute("DELETE FROM session WHERE id = ?", (_digest(cookie or ""),))
        return cur.rowcount > 0

    def __len__(self) -> int:
        return self._db().execute("SELECT count(*) FROM session").fetchone()[0]


class SharedThrottle(LoginThrottle):
    """:class:`~axiscal.web.sessions.LoginThrottle` whose failure counts are kept in the shared
    sessions database, so ``N`` workers do not give a password guesser ``N`` times the tries."""

    def __init__(self, sessions: SharedSessions, base: float = 30.0, free: int = FREE_FAILURES):
        super().__init__(base, free, clock=time.time)
        self._failures = _FailureTable(sessions._db)


class _FailureTable:
    """The few mapping calls :class:`LoginThrottle` makes on its failures, on a SQLite table
    (key -> (count, time of the last failure), oldest first)."""

    def __init__(self, db):
        self._db = db
        db().execute("CREATE TABLE IF NOT EXISTS failure (key TEXT PRIMARY KEY, count INTEGER, "
                     "last REAL)")

    def get(self, key, default=None):
        row = self._db().execute("SELECT count, last FROM failure WHERE key = ?",
                                 (_text(key),)).fetchone()
        return tuple(row) if row else default

    def pop(self, key, default=None):
        found = self.get(key, default)
        self._db().execute("DELETE FROM failure WHERE key = ?", (_text(key),))
        return found

    def __setitem__(self, key, value) -> None:
        self._db().execute("INSERT OR REPLACE INTO failure VALUES (?, ?, ?)",
                           (_text(key), int(value[0]), float(value[1])))

    def __len__(self) -> int:
        return self._db().execute("SELECT count(*) FROM failure").fetchone()[0]

    def popitem(self, last: bool = True):
        order = "DESC" if last else "ASC"
        row = self._db().execute(f"SELECT key FROM failure ORDER BY last {order} LIMIT 1"
                                 ).fetchone()
        self._db().execute("DELETE FROM failure WHERE key = ?", (row[0],))


def _text(key) -> str:
    return "|".join(key)


def _shared_key(path: Path) -> bytes:
    """The 32-byte key in ``path``, made by the first process that needs it (O_EXCL: one wins,
    the others read it)."""
    try:
        fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
    except FileExistsError:
        for _ in range(100):
            data = path.read_bytes()
            if len(data) == 32:
                return data
            time.sleep(0.01)
        raise RuntimeError(f"{path}: not a key") from None
    key = secrets.token_bytes(32)
    with os.fdopen(fd, "wb") as f:
        f.write(key)
    return key


def settings_from_env() -> dict:
    """The settings ``axiscal serve`` handed to this worker (:data:`ENV`)."""
    return json.loads(os.environ[ENV])
