"""The calibration history: a database of machines, axes, tests, results and tables.

:func:`open_store` opens (and creates or upgrades, by the Alembic migrations) the database at a
SQLAlchemy URL: SQLite by default (``history.sqlite`` in the user's data folder, platformdirs),
PostgreSQL through psycopg 3 for a shop or a fleet (``postgresql+psycopg://user@host/db``); the
``AXISCAL_DB`` environment variable names it too. The same code serves both.

Every change is one transaction: a file that fails to read or evaluate leaves nothing, a killed
process leaves the database as it was before the interrupted test (SQLite's WAL journal,
PostgreSQL's MVCC), and an import can be run again (files already stored are recognised by
their SHA-256 and skipped). Two processes may add at once: SQLite writers wait for the write lock
(``BEGIN IMMEDIATE`` with a 30 s busy timeout; readers never wait in WAL mode), PostgreSQL's unique index on the hash lets one
of two identical files in. Certificates issued for a test are kept in the register
(:mod:`axiscal.store.register`) with numbers unique per laboratory.
"""

from __future__ import annotations

import datetime as dt
import hashlib
import json
import os
from dataclasses import dataclass
from pathlib import Path

from axiscal.errors import AxiscalError, InputError
from axiscal.store.kinds import Evaluated, evaluate_file

__all__ = ["StoreError", "Store", "open_store", "default_url", "AddResult", "TestSummary",
           "MachineSummary", "StoredTest", "NotFoundError"]


class StoreError(AxiscalError, RuntimeError):
    """The history database cannot be used as asked (not a database, full, unreachable)."""


class NotFoundError(AxiscalError, LookupError):
    """No such test, machine or axis in the history."""


@dataclass(frozen=True)
class AddResult:
    """What :meth:`Store.add` did."""

    id: int
    duplicate: bool
    kind: str
    machine: str
    axis: str


@dataclass(frozen=True)
class MachineSummary:
    """A machine with its axes and the number and date of its tests."""

    name: str
    axes: tuple
    tests: int
    last: dt.datetime | None
    maker: str = ""
    model: str = ""
    serial: str = ""
    location: str = ""


@dataclass(frozen=True)
class TestSummary:
    """One row of a listing."""

    id: int
    machine: str
    axis: str
    kind: str
    tested_at: dt.datetime
    date_known: bool
    filename: str
    parameters: dict          # name -> (value, unit)
    note: str = ""


@dataclass(frozen=True)
class StoredTest:
    """A stored test, all of it."""

    summary: TestSummary
    raw: bytes
    sha256: str
    result: dict
    dataset_json: str
    environment: dict
    instrument: str
    operator: str
    stored_at: dt.datetime
    axiscal_version: str
    tables: tuple             # (controller, filename, text)

    def evaluate_again(self) -> Evaluated:
        """Evaluate the stored bytes again with this version of axiscal."""
        return evaluate_file(self.raw, self.summary.filename, self.summary.kind)


def default_url() -> str:
    """``AXISCAL_DB``, else SQLite in the user's data folder."""
    env = os.environ.get("AXISCAL_DB")
    if env:
        return env
    from platformdirs import user_data_dir

    return f"sqlite:///{Path(user_data_dir('axiscal')) / 'history.sqlite'}"


def open_store(url: str | None = None) -> "Store":
    """Open the history at ``url`` (default :func:`default_url`), creating or upgrading it."""
    return Store(url or default_url())


class Store:
    """The history database (see the module docstring)."""

    def __init__(self, url: str):
        from sqlalchemy import create_engine, event
        from sqlalchemy.exc import ArgumentError, NoSuchModuleError

        self.url = url
        try:
            if url.startswith("sqlite"):
                _sqlite_folder(url)
                self.engine = create_engine(url)
                event.listen(self.engine, "connect", _sqlite_connect)
                event.listen(self.engine, "begin", _sqlite_begin)
            else:
                self.engine = create_engine(url, pool_pre_ping=True)
        except (ArgumentError, NoSuchModuleError, ValueError) as exc:
            raise StoreError(f"history database URL {url!r}: {exc}") from None
        with self._guard("open"):
            self._upgrade()

    # -- adding ------------------------------------------------------------------------
    def add(self, raw: bytes, filename: str, *, machine: str | None = None,
            axis: str | None = None, kind: str | None = None, instrument: str = "",
            operator: str = "", note: str = "", date: str | None = None,
            tables: tuple = ()) -> AddResult:
        """Evaluate and store one file; a file stored before is reported, not stored again.

        ``tables`` are (controller, filename, text) written from this test.
        """

        from axiscal import __version__
        from axiscal._json import jsonable
        from axiscal.store.models import Parameter, Table, Test

        digest = hashlib.sha256(raw).hexdigest()
        existing = self._find_hash(digest)
        if existing is not None:
            return existing
        ev = evaluate_file(raw, filename, kind)          # before any write: nothing half-stored
        m_name = _name(machine or ev.machine, "machine", filename)
        a_name = _name(axis or ev.axis, "axis", filename).upper()
        when, known = _date(date or ev.date)
        now = dt.datetime.now(dt.timezone.utc).replace(tzinfo=None)
        with self._guard("store"), self._session(write=True) as s:
            try:
                ax = self._axis(s, m_name, a_name, ev.axis_kind, now)
                t = Test(axis=ax, kind=ev.kind, tested_at=when, date_known=known, stored_at=now,
                         instrument=instrument or ev.instrument, operator=operator or ev.operator,
                         note=note, filename=Path(filename).name[:300], sha256=digest, raw=raw,
                         dataset_json=ev.dataset_json, result_json=json.dumps(ev.result),
                         environment_json=json.dumps(jsonable(ev.environment)),
                         axiscal_version=__version__)
                t.parameters = [Parameter(name=n, value=float(v), unit=u)
                                for n, (v, u) in ev.parameters.items()]
                t.tables = [Table(controller=c, filename=f, text=x, created=now)
                            for c, f, x in tables]
                s.add(t)
                s.commit()
                return AddResult(t.id, False, ev.kind, m_name, a_name)
            except _integrity_error():
                s.rollback()
        dup = self._find_hash(digest)           # another process stored the same file just now
        if dup is None:
            raise StoreError(f"{filename}: could not be stored (a conflicting write)")
        return dup

    def add_table(self, test_id: int, controller: str, filename: str, text: str) -> None:
        """Keep a compensation table written from stored test ``test_id``."""
        from axiscal.store.models import Table, Test

        now = dt.datetime.now(dt.timezone.utc).replace(tzinfo=None)
        with self._guard("store"), self._session(write=True) as s:
            t = s.get(Test, test_id)
            if t is None:
                raise NotFoundError(f"no test {test_id} in the history")
            s.add(Table(test=t, controller=controller, filename=filename, text=text,
                        created=now))
            s.commit()

    # -- reading -------------------------------------------------------------------------
    def machines(self) -> list[MachineSummary]:
        """Every machine with its axes, test count and last test date."""
        from sqlalchemy import func, select

        from axiscal.store.models import Axis, Machine, Test

        with self._guard("read"), self._session() as s:
            rows = s.execute(select(Machine.name, Axis.name, func.count(Test.id),
                                    func.max(Test.tested_at), Machine.maker, Machine.model,
                                    Machine.serial, Machine.location)
                             .join(Axis, Axis.machine_id == Machine.id, isouter=True)
                             .join(Test, Test.axis_id == Axis.id, isouter=True)
                             .group_by(Machine.id, Axis.id).order_by(Machine.name, Axis.name)
                             ).all()
        out: dict[str, dict] = {}
        for name, axis, n, last, maker, model, serial, location in rows:
            m = out.setdefault(name, {"axes": [], "tests": 0, "last": None, "maker": maker,
                                      "model": model, "serial": serial, "location": location})
            if axis:
                m["axes"].append(axis)
            m["tests"] += n
            if last and (m["last"] is None or last > m["last"]):
                m["last"] = last
        return [MachineSummary(k, tuple(v["axes"]), v["tests"], v["last"], v["maker"],
                               v["model"], v["serial"], v["location"]) for k, v in out.items()]

    def tests(self, machine: str | None = None, axis: str | None = None,
              kind: str | None = None, since: dt.datetime | None = None,
              limit: int | None = None, offset: int = 0) -> list[TestSummary]:
        """Tests, newest first, filtered (``limit`` and ``offset`` page through them)."""
        from sqlalchemy import select

        from axiscal.store.models import Axis, Machine, Parameter, Test

        q = (select(Test.id, Machine.name, Axis.name, Test.kind, Test.tested_at,
                    Test.date_known, Test.filename, Test.note)
             .join(Axis, Test.axis_id == Axis.id).join(Machine, Axis.machine_id == Machine.id)
             .order_by(Test.tested_at.desc(), Test.id.desc()))
        if machine:
            q = q.where(Machine.name == machine)
        if axis:
            q = q.where(Axis.name == axis.upper())
        if kind:
            q = q.where(Test.kind == kind)
        if since:
            q = q.where(Test.tested_at >= since)
        if limit:
            q = q.limit(limit)
        if offset:
            q = q.offset(offset)
        with self._guard("read"), self._session() as s:      # plain rows: fast for thousands
            rows = s.execute(q).all()
            params: dict[int, dict] = {r[0]: {} for r in rows}
            ids = list(params)
            for k in range(0, len(ids), 900):                 # SQLite's bound-parameter limit
                chunk = ids[k:k + 900]
                for tid, name, value, unit in s.execute(
                        select(Parameter.test_id, Parameter.name, Parameter.value,
                               Parameter.unit).where(Parameter.test_id.in_(chunk))
                        .order_by(Parameter.id)):
                    params[tid][name] = (value, unit)
        return [TestSummary(i, m, a, k, t, bool(dk), f, params[i], n or "")
                for i, m, a, k, t, dk, f, n in rows]

    def get(self, test_id: int) -> StoredTest:
        """One stored test, all of it."""
        from axiscal.store.models import Test

        with self._guard("read"), self._session() as s:
            t = s.get(Test, int(test_id))
            if t is None:
                raise NotFoundError(f"no test {test_id} in the history")
            return StoredTest(_summary(t), t.raw, t.sha256, json.loads(t.result_json),
                              t.dataset_json, json.loads(t.environment_json), t.instrument,
                              t.operator, t.stored_at, t.axiscal_version,
                              tuple((x.controller, x.filename, x.text) for x in t.tables))

    def parameter_series(self, machine: str, axis: str, parameter: str,
                         kind: str | None = None) -> list[tuple[dt.datetime, float, str, int]]:
        """(date, value, unit, test id) of one parameter of one axis, oldest first."""
        from sqlalchemy import select

        from axiscal.store.models import Axis, Machine, Parameter, Test

        q = (select(Test.tested_at, Parameter.value, Parameter.unit, Test.id)
             .join(Parameter, Parameter.test_id == Test.id).join(Axis).join(Machine)
             .where(Machine.name == machine, Axis.name == axis.upper(),
                    Parameter.name == parameter).order_by(Test.tested_at, Test.id))
        if kind:
            q = q.where(Test.kind == kind)
        with self._guard("read"), self._session() as s:
            return [tuple(r) for r in s.execute(q).all()]

    # -- the certificate register (axiscal.store.register) --------------------------------
    def issue_certificate(self, **kw):
        """Number, render and keep a certificate of a stored test (see
        :func:`axiscal.store.register.issue`); returns its ``CertificateRecord``."""
        from axiscal.store.register import issue

        return issue(self, **kw)

    def certificates(self, laboratory: str | None = None) -> list:
        """The register, newest first (``CertificateRecord`` without documents)."""
        from axiscal.store.register import listing

        return listing(self, laboratory)

    def certificate(self, number: str, laboratory: str | None = None):
        """One certificate with its issued document (SHA-256 checked)."""
        from axiscal.store.register import fetch

        return fetch(self, number, laboratory)

    def close(self) -> None:
        """Release the connections."""
        self.engine.dispose()

    # -- internals -----------------------------------------------------------------------
    def _session(self, write: bool = False):
        from sqlalchemy.orm import Session

        engine = self.engine.execution_options(axiscal_write=True) if write else self.engine
        return Session(engine, expire_on_commit=False)

    def _guard(self, what: str):
        return _Guard(self.url, what)

    def _upgrade(self) -> None:
        from alembic import command
        from alembic.config import Config

        cfg = Config()
        cfg.set_main_option("script_location", str(Path(__file__).parent / "migrations"))
        with self.engine.begin() as conn:
            cfg.attributes["connection"] = conn
            command.upgrade(cfg, "head")

    def _find_hash(self, digest: str) -> AddResult | None:
        from sqlalchemy import select

        from axiscal.store.models import Test

        with self._guard("read"), self._session() as s:
            t = s.scalars(select(Test).where(Test.sha256 == digest)).first()
            if t is None:
                return None
            return AddResult(t.id, True, t.kind, t.axis.machine.name, t.axis.name)

    def _axis(self, s, machine: str, axis: str, kind: str, now):
        from sqlalchemy import select

        from axiscal.store.models import Axis, Machine

        m = s.scalars(select(Machine).where(Machine.name == machine)).first()
        if m is None:
            m = Machine(name=machine, maker="", model="", serial="", location="", created=now)
            s.add(m)
        a = s.scalars(select(Axis).where(Axis.machine == m, Axis.name == axis)).first() \
            if m.id else None
        if a is None:
            a = Axis(machine=m, name=axis, kind=kind)
            s.add(a)
        return a


class _Guard:
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
            raise StoreError(f"history database {_shown(self.url)}: {_reason(exc)}") from None
        return False


def _reason(exc) -> str:
    orig = getattr(exc, "orig", None) or exc
    text = str(orig).strip().splitlines()[0] if str(orig).strip() else type(orig).__name__
    low = text.lower()
    if "file is not a database" in low or "not a database" in low:
        return "the file is not an axiscal history database (SQLite says: file is not a database)"
    if "disk is full" in low or "database or disk is full" in low or "no space" in low:
        return "the disk is full; nothing of this write was kept"
    if "unable to open database" in low:
        return "cannot open the database file (does its folder exist and is it writable?)"
    return text


def _is_driver_error(exc) -> bool:
    mod = type(exc).__module__
    return mod.startswith(("sqlite3", "psycopg", "alembic"))


def _shown(url: str) -> str:
    """The URL without a password."""
    if "@" in url and "://" in url:
        scheme, rest = url.split("://", 1)
        cred, host = rest.rsplit("@", 1)
        return f"{scheme}://{cred.split(':')[0]}@{host}"
    return url


def _integrity_error():
    from sqlalchemy.exc import IntegrityError

    return IntegrityError


def _sqlite_folder(url: str) -> None:
    path = url.split("///", 1)[1] if "///" in url else ""
    if path and path != ":memory:":
        Path(path).expanduser().parent.mkdir(parents=True, exist_ok=True)


def _sqlite_connect(dbapi_conn, _record) -> None:
    dbapi_conn.isolation_level = None          # transactions begin in _sqlite_begin
    cur = dbapi_conn.cursor()
    cur.execute("PRAGMA busy_timeout=30000")
    cur.execute("PRAGMA foreign_keys=ON")
    cur.execute("PRAGMA journal_mode=WAL")
    cur.close()


def _sqlite_begin(conn) -> None:
    """Writers take the write lock at once (no deadlock between two upgrading readers); readers
    begin a deferred transaction, so in WAL mode they never wait for each other or a writer."""
    write = conn.get_execution_options().get("axiscal_write", False)
    conn.exec_driver_sql("BEGIN IMMEDIATE" if write else "BEGIN")


def _name(value: str, what: str, filename: str) -> str:
    v = (value or "").strip()
    if not v:
        raise InputError(f"{filename}: the file does not name the {what}; give --{what}")
    if len(v) > 200:
        raise InputError(f"{what} name of {len(v)} characters; at most 200")
    return v


def _date(text: str) -> tuple[dt.datetime, bool]:
    if not text:
        return dt.datetime.now(dt.timezone.utc).replace(tzinfo=None, microsecond=0), False
    t = str(text).strip()
    for fmt in ("%Y-%m-%d", "%Y-%m-%dT%H:%M:%S", "%Y-%m-%d %H:%M:%S", "%Y-%m-%dT%H:%M",
                "%Y-%m-%d %H:%M", "%d.%m.%Y", "%Y/%m/%d"):
        try:
            return dt.datetime.strptime(t, fmt), True
        except ValueError:
            continue
    try:
        d = dt.datetime.fromisoformat(t)
        return (d.astimezone(dt.timezone.utc).replace(tzinfo=None) if d.tzinfo else d), True
    except ValueError:
        raise InputError(f"date {t!r}: write it as YYYY-MM-DD (or an ISO 8601 date and time)")


def _summary(t) -> TestSummary:
    return TestSummary(t.id, t.axis.machine.name, t.axis.name, t.kind, t.tested_at,
                       t.date_known, t.filename,
                       {p.name: (p.value, p.unit) for p in t.parameters}, t.note)
