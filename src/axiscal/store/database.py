"""Opening the history database: recognised before anything is written, created whole, upgraded
under a lock, read-only when it has to be.

What is opened
    An axiscal history is recognised by its own schema: the ``alembic_version`` table holding
    one of axiscal's revisions, with the ``machine``, ``axis`` and ``test`` tables. Anything
    else is refused in one line *before* a byte is written (no table added, the journal mode
    left alone): a zero-byte file, a file that is not SQLite, another application's SQLite
    database, a database of another Alembic project. A history written by a newer axiscal
    (a revision this one does not know) is refused too, and said so.

A new SQLite history
    A path where no file exists is created whole: the schema is made in a temporary file
    beside it (``.NAME.PID-RANDOM.creating``), which is then linked to the path in one step (a hard
    link fails when the path exists, so two processes creating one history at once both end up
    using the one linked first). Axiscal therefore never leaves a zero-byte or half-made file at
    a history's path, and a zero-byte file found there was made by someone else (``touch``, a
    failed copy): it is refused, never converted. A PostgreSQL database with no table at all
    (as a database administrator creates it) is made a history; one holding other tables is
    refused.

Upgrades
    The schema is read first, without writing; only when it is older than this axiscal's the
    upgrade runs, under an exclusive lock taken before the first statement: ``BEGIN IMMEDIATE``
    on SQLite (writers wait up to the 30 s busy timeout, never fail on a lock upgrade), a
    transaction-scoped advisory lock (``pg_advisory_xact_lock``) on PostgreSQL, so two processes
    opening a fresh or old database at once do not both run the DDL. The revision is read again
    under the lock.

Read-only histories
    A SQLite history whose file or folder cannot be written (no write permission, or no write
    bit in its mode: a file of mode 0444, a folder of mode 0555, even for root) is opened
    read-only (SQLite URI ``mode=ro``; when its folder cannot hold the ``-shm`` file and no
    write-ahead log is pending, ``immutable=1``): it can be listed and shown; a write, or a
    needed upgrade, is refused in one line. The journal is switched to WAL only on a writable
    history that axiscal recognised.
"""

from __future__ import annotations

import os
from pathlib import Path

from axiscal.errors import AxiscalError, NotFoundError, StoreError

__all__ = ["StoreError", "NotFoundError", "Guard", "sqlite_path", "make_engine", "upgrade", "shown"]

#: The key of PostgreSQL's advisory lock around a schema upgrade ("axiscal" in ASCII, 6 bytes).
ADVISORY_KEY = 0x61786973_63616C
#: SQLite's busy timeout, ms: how long a writer waits for another's write lock.
BUSY_TIMEOUT_MS = 30_000
_OWN_TABLES = {"machine", "axis", "test"}


class Guard:
    """Database errors as one line that names the database and what went wrong."""

    def __init__(self, url: str, what: str):
        self.url, self.what = url, what

    def __enter__(self):
        return self

    def __exit__(self, typ, exc, tb):
        if exc is None or isinstance(exc, AxiscalError):
            return False
        from sqlalchemy.exc import DBAPIError, SQLAlchemyError

        if isinstance(exc, (SQLAlchemyError, DBAPIError)) or _is_driver_error(exc):
            raise StoreError(f"history database {shown(self.url)}: "
                             f"{_reason(exc, self.url)}") from None
        return False


def shown(url: str) -> str:
    """The URL without a password."""
    if "@" in url and "://" in url:
        scheme, rest = url.split("://", 1)
        cred, host = rest.rsplit("@", 1)
        return f"{scheme}://{cred.split(':')[0]}@{host}"
    return url


def sqlite_path(url: str) -> Path | None:
    """The file of a ``sqlite:///PATH`` URL (None for an in-memory database)."""
    from sqlalchemy.engine import make_url

    db = make_url(url).database
    if not db or db == ":memory:" or db.startswith("file:"):
        return None
    return Path(db).expanduser()


def make_engine(url: str):
    """``(engine, read_only)`` for ``url``: a SQLite file is recognised (and a new one created
    whole) first; see the module docstring."""
    from sqlalchemy import create_engine, event

    if url.split(":", 1)[0] not in ("sqlite", "sqlite+pysqlite"):   # another driver (pysqlcipher
        return create_engine(url, pool_pre_ping=True), False    # ...) is checked before a file
    path = sqlite_path(url)
    read_only = False
    if path is not None:
        if not path.exists() and not path.is_symlink():
            _create_sqlite(url, path)
        _check_sqlite_file(url, path)
        read_only = not _writable(path)
    if read_only:
        engine = create_engine("sqlite://", creator=lambda: _read_only_connection(url, path))
    else:
        engine = create_engine(url)
    event.listen(engine, "connect", _sqlite_connect)
    event.listen(engine, "begin", _sqlite_begin)
    return engine, read_only


def upgrade(engine, url: str, read_only: bool, allow_empty: bool) -> None:
    """Bring the schema to this axiscal's head revision, under an exclusive lock; nothing is
    written when it is there already."""
    from alembic import command

    cfg, head, known = _alembic()
    with engine.connect() as conn:
        rev = _revision(conn, url, known, head, allow_empty)
        journal = (conn.exec_driver_sql("PRAGMA journal_mode").scalar()
                   if engine.dialect.name == "sqlite" else "")
    if rev == head:
        return
    if read_only:
        raise StoreError(f"history database {shown(url)} is read-only and its schema (revision "
                         f"{rev or 'none'}) needs upgrading to {head}; open it once where it "
                         "can be written")
    if engine.dialect.name == "sqlite" and str(journal).lower() not in ("wal", "memory"):
        raw = engine.raw_connection()                  # outside a transaction, as SQLite wants
        try:
            raw.cursor().execute("PRAGMA journal_mode=WAL")
        finally:
            raw.close()
    with engine.execution_options(axiscal_write=True).begin() as conn:
        if engine.dialect.name == "postgresql":
            from sqlalchemy import func, select

            conn.execute(select(func.pg_advisory_xact_lock(ADVISORY_KEY)))
        if _revision(conn, url, known, head, allow_empty) != head:   # again, under the lock
            cfg.attributes["connection"] = conn
            command.upgrade(cfg, "head")


def read_only_refusal(url: str, path: Path | None) -> StoreError:
    """The one line for a write to a read-only history."""
    why = _why_read_only(path) if path is not None else "opened read-only"
    return StoreError(f"history database {shown(url)} is read-only ({why}): it can be listed "
                      "and shown, not written")


# -- internals ---------------------------------------------------------------------------------
def _alembic():
    from alembic.config import Config
    from alembic.script import ScriptDirectory

    cfg = Config()
    cfg.set_main_option("script_location", str(Path(__file__).parent / "migrations"))
    script = ScriptDirectory.from_config(cfg)
    return cfg, script.get_current_head(), {r.revision for r in script.walk_revisions()}


def _revision(conn, url: str, known: set, head: str, allow_empty: bool) -> str | None:
    """The history's revision; None for an empty database that may become one; else refused."""
    from sqlalchemy import inspect, text

    names = set(inspect(conn).get_table_names())
    if "alembic_version" in names:
        revs = list(conn.execute(text("SELECT version_num FROM alembic_version")).scalars())
        if len(revs) == 1 and revs[0] in known and _OWN_TABLES <= names:
            return revs[0]
        if len(revs) == 1 and _OWN_TABLES <= names:
            raise StoreError(f"history database {shown(url)}: its schema revision {revs[0]!r} "
                             f"is newer than this axiscal's ({head}); upgrade axiscal")
        raise StoreError(f"history database {shown(url)}: not an axiscal history database "
                         f"(another application's Alembic revision {revs[:1]}); left untouched")
    if not names and allow_empty:
        return None
    listed = ", ".join(sorted(names)[:5]) + (" ..." if len(names) > 5 else "")
    raise StoreError(f"history database {shown(url)}: not an axiscal history database "
                     + (f"(it holds other tables: {listed}); left untouched" if names else
                        "(an empty SQLite database axiscal did not make); left untouched"))


def _check_sqlite_file(url: str, path: Path) -> None:
    """Refuse, before SQLite touches it, a path that is not a SQLite file."""
    try:
        if not path.is_file():
            raise StoreError(f"history database {shown(url)}: not a regular file")
        with path.open("rb") as f:
            head = f.read(16)
    except PermissionError:
        raise StoreError(f"history database {shown(url)}: permission denied") from None
    except OSError as exc:
        raise StoreError(f"history database {shown(url)}: {exc.strerror or exc}") from None
    if not head:
        raise StoreError(f"history database {shown(url)}: an empty file (0 bytes) is not an "
                         "axiscal history database; remove it, or name a path where no file "
                         "exists and axiscal creates one")
    if head != b"SQLite format 3\x00":
        raise StoreError(f"history database {shown(url)}: the file is not an axiscal history "
                         "database (not even SQLite); left untouched")


def _create_sqlite(url: str, path: Path) -> None:
    """Make the history in a temporary file beside ``path`` and link it there in one step."""
    from sqlalchemy import create_engine, event

    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise StoreError(f"history database {shown(url)}: cannot make its folder "
                         f"({exc.strerror or exc})") from None
    import uuid

    tmp = path.parent / f".{path.name}.{os.getpid()}-{uuid.uuid4().hex[:8]}.creating"
    engine = create_engine(f"sqlite:///{tmp}")
    event.listen(engine, "connect", _sqlite_connect)
    event.listen(engine, "begin", _sqlite_begin)
    try:
        with Guard(url, "create"):
            upgrade(engine, url, False, True)
        engine.dispose()                          # the last close checkpoints the WAL away
        try:
            os.link(tmp, path)
        except FileExistsError:
            pass                                  # another process made it first: use theirs
        except OSError:                           # a file system without hard links
            if not path.exists():
                os.replace(tmp, path)
    except OSError as exc:
        raise StoreError(f"history database {shown(url)}: cannot create it "
                         f"({exc.strerror or exc})") from None
    finally:
        engine.dispose()
        for suffix in ("", "-wal", "-shm", "-journal"):
            Path(f"{tmp}{suffix}").unlink(missing_ok=True)


def _writable(path: Path) -> bool:
    return _why_read_only(path) == ""


def _why_read_only(path: Path) -> str:
    folder = path.parent
    for what, p in (("its file", path), ("its folder", folder)):
        try:
            mode = p.stat().st_mode
        except OSError:
            continue
        if not mode & 0o222 or not os.access(p, os.W_OK):
            return f"{what} {p} is mode {mode & 0o777:04o}" if not mode & 0o222 else \
                f"{what} {p} is not writable by this user"
    return ""


def _read_only_connection(url: str, path: Path):
    """A read-only connection; ``immutable=1`` when the folder cannot take SQLite's ``-shm``
    file and no write-ahead log waits to be read."""
    import sqlite3
    from urllib.parse import quote

    uri = f"file:{quote(str(path.resolve()))}?mode=ro"
    conn = sqlite3.connect(uri, uri=True, check_same_thread=False)
    try:
        conn.execute("SELECT count(*) FROM sqlite_master").fetchone()
        return conn
    except sqlite3.OperationalError:
        conn.close()
        wal = Path(f"{path}-wal")
        if wal.exists() and wal.stat().st_size > 0:
            raise
    return sqlite3.connect(uri + "&immutable=1", uri=True, check_same_thread=False)


def _sqlite_connect(dbapi_conn, _record) -> None:
    dbapi_conn.isolation_level = None          # transactions begin in _sqlite_begin
    cur = dbapi_conn.cursor()
    cur.execute(f"PRAGMA busy_timeout={BUSY_TIMEOUT_MS}")
    cur.execute("PRAGMA foreign_keys=ON")
    cur.close()


def _sqlite_begin(conn) -> None:
    """Writers take the write lock at once (no deadlock between two upgrading readers); readers
    begin a deferred transaction, so in WAL mode they never wait for each other or a writer."""
    write = conn.get_execution_options().get("axiscal_write", False)
    conn.exec_driver_sql("BEGIN IMMEDIATE" if write else "BEGIN")


def _reason(exc, url: str | None = None) -> str:
    orig = getattr(exc, "orig", None) or exc
    text = str(orig).strip().splitlines()[0] if str(orig).strip() else type(orig).__name__
    low = text.lower()
    if "file is not a database" in low or "not a database" in low:
        return "the file is not an axiscal history database (SQLite says: file is not a database)"
    if "disk is full" in low or "database or disk is full" in low or "no space" in low:
        return "the disk is full; nothing of this write was kept"
    if "unable to open database" in low:
        return "cannot open the database file (does its folder exist and is it writable?)"
    if "readonly database" in low or "read-only" in low:
        return "the database is read-only; it can be listed and shown, not written"
    if "disk i/o error" in low:   # SQLite's word for a full disk or a file-size limit too
        cause = _io_cause(url)
        if cause:
            return f"{cause}; nothing of this write was kept (SQLite says: {text})"
    return text


def _io_cause(url: str | None) -> str:
    """Why a SQLite write failed with "disk I/O error" when the cause can be told: the process's
    file-size limit (``ulimit -f``) reached by the database or its log, or a full disk."""
    try:
        path = sqlite_path(url) if url and url.startswith("sqlite") else None
    except Exception:   # noqa: BLE001 - no path, no diagnosis
        path = None
    if path is None:
        return ""
    try:
        import resource

        limit = resource.getrlimit(resource.RLIMIT_FSIZE)[0]
        if limit != resource.RLIM_INFINITY:
            biggest = max((Path(f"{path}{s}").stat().st_size for s in ("", "-wal", "-journal")
                           if Path(f"{path}{s}").exists()), default=0)
            if biggest + 65536 >= limit:
                return (f"the file-size limit of this process is reached (ulimit -f: "
                        f"{limit} bytes)")
    except (ImportError, OSError, ValueError):
        pass
    try:
        st = os.statvfs(path.parent)
        if st.f_bavail * st.f_frsize < 1 << 20:
            return "the disk is full"
    except OSError:
        pass
    return ""


def _is_driver_error(exc) -> bool:
    mod = type(exc).__module__
    return mod.startswith(("sqlite3", "psycopg", "alembic"))
