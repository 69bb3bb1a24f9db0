"""The calibration history: a database of machines, axes, tests, results and tables.

:func:`open_store` opens (and creates or upgrades, by the Alembic migrations) the database at a
SQLAlchemy URL: SQLite by default (``history.sqlite`` in the user's data folder, platformdirs),
PostgreSQL through psycopg 3 for a shop or a fleet (``postgresql+psycopg://user@host/db``); the
``AXISCAL_DB`` environment variable names it too. The same code serves both. What is opened is
recognised before anything is written (a file that is not an axiscal history is refused, not
converted), a new SQLite history is created whole, upgrades run under an exclusive lock and a
read-only history is listed and shown: :mod:`axiscal.store.database`.

Every change is one transaction: a file is evaluated before the transaction (one that fails
leaves nothing), and :meth:`Store.add_all` stores many files (an archive import) in one, so a
killed process leaves the database exactly as it was (SQLite's WAL journal, PostgreSQL's MVCC).
Many processes may add at once: SQLite writers take the write lock at once (``BEGIN
IMMEDIATE``) and wait for it (a 30 s busy timeout, waited again :data:`LOCKED_RETRIES` times;
readers never wait in WAL mode); a new machine or axis is made by ``INSERT ... ON CONFLICT DO
NOTHING`` then read, so two processes making it at once both use the one row; a write that
still collides (the same file stored by another process at that moment, a PostgreSQL deadlock)
is run again and then finds the other's rows. Certificates issued for a test are kept in the
register (:mod:`axiscal.store.register`) with numbers unique per laboratory.
"""

from __future__ import annotations

import datetime as dt
import hashlib
import json
import os
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

from axiscal.errors import InputError
from axiscal.store.database import Guard, NotFoundError, StoreError
from axiscal.store.kinds import Evaluated, evaluate_file

__all__ = ["StoreError", "Store", "open_store", "default_url", "AddResult", "TestSummary",
           "MachineSummary", "StoredTest", "NotFoundError", "Prepared", "prepare", "ATTEMPTS"]

#: How often a write that collided with another process's is run again.
ATTEMPTS = 8
#: How often a SQLite write waits the busy timeout again for a lock others keep holding.
LOCKED_RETRIES = 3


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
    id: int = 0


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
    withdrawn: str = ""       # why it was withdrawn (axiscal.store.corrections); "" counts
    machine_id: int = 0


@dataclass(frozen=True)
class StoredTest:
    """A stored test, all of it. Its bytes (``raw``) are read from the database when first
    asked for: a page that shows what was kept of the test (its evaluation, by SHA-256) never
    reads them."""

    summary: TestSummary
    sha256: str
    result: dict
    dataset_json: str
    environment: dict
    instrument: str
    operator: str
    stored_at: dt.datetime
    axiscal_version: str
    tables: tuple             # (controller, filename, text)
    size: int = 0             # bytes of the stored file
    _read_raw: object = field(default=None, repr=False, compare=False)

    @cached_property
    def raw(self) -> bytes:
        """The file's bytes, as they came."""
        return self._read_raw()

    def evaluate_again(self) -> Evaluated:
        """The evaluation of the stored bytes by this version of axiscal: evaluated once and
        kept (:mod:`axiscal.store.cache`), since it is a function of the bytes and the version."""
        from axiscal.store.cache import evaluated

        return evaluated(lambda: self.raw, self.sha256, self.summary.filename,
                         self.summary.kind, self.size)

    def named(self, ev: Evaluated) -> Evaluated:
        """``ev`` (this test's evaluation) with the machine and axis names the history keeps,
        in its dataset's metadata too: what every plot and report of the test names."""
        return _as_stored(ev, self.summary)

    def record(self) -> Evaluated:
        """The test's one record: :meth:`evaluate_again` with the uncertainty budget made from
        the inputs stored with it (a test stored before inputs were kept: none, each assumed
        and said), so its U is the U it was stored with."""
        from axiscal.store.kinds import with_uncertainty

        return _as_stored(with_uncertainty(self.evaluate_again(),
                                           self.result.get("uncertainty_inputs")), self.summary)


def _as_stored(ev, summary):
    """``ev`` with the machine and axis names the history keeps for the test (as corrected:
    renamed, merged), also in its dataset's metadata, so every plot and report made from the
    record names them, not the names in the file."""
    from dataclasses import replace

    md = getattr(ev.dataset, "metadata", None)
    names = {"machine": summary.machine, "axis": summary.axis}
    if md is not None and all(hasattr(md, k) for k in names) and \
            (md.machine, md.axis) != (summary.machine, summary.axis):
        ev = replace(ev, dataset=replace(ev.dataset, metadata=replace(md, **names)))
    return replace(ev, **names) if (ev.machine, ev.axis) != (summary.machine, summary.axis) \
        else ev


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
        from sqlalchemy.exc import ArgumentError, NoSuchModuleError

        from axiscal.store.database import make_engine, sqlite_path

        self.url = url
        try:
            self.engine, self.read_only = make_engine(url)
        except (ArgumentError, NoSuchModuleError, ValueError) as exc:
            raise StoreError(f"history database URL {url!r}: {exc}") from None
        except ImportError as exc:   # a scheme whose database driver is not installed
            raise StoreError(f"history database URL {url.split(':', 1)[0]}://...: its driver "
                             f"({exc.name or exc}) is not installed; axiscal stores to SQLite or "
                             "PostgreSQL (postgresql+psycopg://)") from None
        with self._guard("open"):
            self._upgrade(allow_empty=not url.startswith("sqlite") or sqlite_path(url) is None)

    # -- adding ------------------------------------------------------------------------
    def add(self, raw: bytes, filename: str, *, machine: str | None = None,
            axis: str | None = None, kind: str | None = None, instrument: str = "",
            operator: str = "", note: str = "", date: str | None = None,
            tables: tuple = (), uncertainty: dict | None = None,
            drift_check: tuple[bytes, str] | None = None,
            machine_default: str | None = None) -> AddResult:
        """Evaluate and store one file; a file stored before is reported, not stored again.

        ``tables`` are (controller, filename, text) written from this test; ``uncertainty``
        the inputs of its budget (default: the user configuration's, :func:`prepare`);
        ``drift_check`` the (bytes, name) of its drift check, kept with it (:func:`prepare`).
        ``machine`` replaces the name the file gives; ``machine_default`` is taken only when
        the file names no machine (the workbench's "Machine (if the file does not name it)").
        """
        existing = self._find_hash(hashlib.sha256(raw).hexdigest())
        if existing is not None:
            return existing
        return self.add_all([prepare(raw, filename, machine=machine, axis=axis, kind=kind,
                                     instrument=instrument, operator=operator, note=note,
                                     date=date, tables=tables, uncertainty=uncertainty,
                                     drift_check=drift_check,
                                     machine_default=machine_default)])[0]

    def add_all(self, items, then=None) -> list[AddResult]:
        """Store every :class:`Prepared` file in ONE transaction: all or nothing.

        ``then(session, results)``, if given, runs in the same transaction after the tests are
        inserted (an archive's withdrawals, audit trail and certificates): its error undoes all.

        An error, a full disk or a killed process leaves the database as it was before; a file
        stored before (or twice in ``items``) is reported as a duplicate. When another process
        stores the same file or makes the same new machine at the same moment, the transaction
        is run again (the rows it collided with are then found), up to :data:`ATTEMPTS` times;
        a SQLite write lock still held by others after the busy timeout (30 s: many writers on
        a loaded machine) is waited for again, :data:`LOCKED_RETRIES` times.
        """
        now = dt.datetime.now(dt.timezone.utc).replace(tzinfo=None)
        locked = 0
        with self._guard("store"):
            for _ in range(ATTEMPTS):
                with self._session(write=True) as s:
                    try:
                        out = self._insert_all(s, list(items), now)
                        if then is not None:
                            then(s, out)
                        s.commit()
                        return out
                    except Exception as exc:
                        s.rollback()
                        if _busy(exc) and locked < LOCKED_RETRIES:
                            locked += 1
                            continue
                        if not _collision(exc):
                            raise
        raise StoreError(f"history database: {len(items)} test(s) could not be stored; other "
                         f"processes wrote the same rows {ATTEMPTS} times over; try again")

    def stored(self, digests) -> dict:
        """{SHA-256: AddResult (a duplicate)} of each of ``digests`` already in the history."""
        with self._guard("read"), self._session() as s:
            return _stored(s, list(digests))

    def add_table(self, test_id: int, controller: str, filename: str, text: str) -> None:
        """Keep a compensation table written from stored test ``test_id``."""
        from axiscal.store.models import Table, Test

        now = dt.datetime.now(dt.timezone.utc).replace(tzinfo=None)
        with self._guard("store"), self._session(write=True) as s:
            t = s.get(Test, _test_id(test_id))
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
                                    Machine.serial, Machine.location, Machine.id)
                             .join(Axis, Axis.machine_id == Machine.id, isouter=True)
                             .join(Test, Test.axis_id == Axis.id, isouter=True)
                             .group_by(Machine.id, Axis.id).order_by(Machine.name, Axis.name)
                             ).all()
        out: dict[str, dict] = {}
        for name, axis, n, last, maker, model, serial, location, mid in rows:
            m = out.setdefault(name, {"axes": [], "tests": 0, "last": None, "maker": maker,
                                      "model": model, "serial": serial, "location": location,
                                      "id": mid})
            if axis:
                m["axes"].append(axis)
            m["tests"] += n
            if last and (m["last"] is None or last > m["last"]):
                m["last"] = last
        return [MachineSummary(k, tuple(v["axes"]), v["tests"], v["last"], v["maker"],
                               v["model"], v["serial"], v["location"], v["id"])
                for k, v in out.items()]

    def tests(self, machine: str | None = None, axis: str | None = None,
              kind: str | None = None, since: dt.datetime | None = None,
              limit: int | None = None, offset: int = 0,
              parameters: tuple | None = None) -> list[TestSummary]:
        """Tests, newest first, filtered (``limit`` and ``offset`` page through them).

        ``parameters`` (names) narrows what each summary's ``parameters`` holds to those names
        and the test's first parameter (what a listing shows of it), an empty tuple to none;
        default: all of them."""
        from axiscal.store import queries

        if offset >= 2**63:                   # no test that far (SQLite could not even bind it)
            return []
        rows = queries.test_rows(self, machine, axis, kind, since, limit, offset)
        params = queries.parameters(self, [r[0] for r in rows], parameters)
        return [TestSummary(i, m, a, k, t, bool(dk), f, params[i], n or "", w or "", mid)
                for i, m, a, k, t, dk, f, n, w, mid in rows]

    def get(self, test_id: int) -> StoredTest:
        """One stored test, all of it (its bytes read when first asked for)."""
        from axiscal.store import queries

        tid = _test_id(test_id)
        found = queries.test(self, tid)
        if found is None:
            raise NotFoundError(f"no test {test_id} in the history")
        r, params, tables = found
        summary = TestSummary(tid, r.machine, r.axis, r.kind, r.tested_at, bool(r.date_known),
                              r.filename, params, r.note or "", r.withdrawn or "", r.machine_id)
        return StoredTest(summary, r.sha256, json.loads(r.result_json), r.dataset_json,
                          json.loads(r.environment_json), r.instrument, r.operator,
                          r.stored_at, r.axiscal_version, tables, int(r.size or 0),
                          lambda: self._raw(tid))

    def machine(self, machine_id: int) -> MachineSummary:
        """One machine with its axes, test count and last test date (one statement)."""
        from axiscal.store import queries

        mid = int(machine_id)
        rows = queries.machine(self, mid) if 0 < mid < 2**63 else []
        if not rows:
            raise NotFoundError(f"no machine {machine_id} in the history")
        name, maker, model, serial, location = rows[0][:5]
        lasts = [r[7] for r in rows if r[7] is not None]
        return MachineSummary(name, tuple(r[5] for r in rows if r[5]), sum(r[6] for r in rows),
                              max(lasts) if lasts else None, maker, model, serial, location,
                              mid)

    def _raw(self, test_id: int) -> bytes:
        from sqlalchemy import select

        from axiscal.store.models import Test

        with self._guard("read"), self._session() as s:
            raw = s.scalar(select(Test.raw).where(Test.id == test_id))
        if raw is None:
            raise NotFoundError(f"no test {test_id} in the history")
        return bytes(raw)

    def parameter_series(self, machine: str, axis: str, parameter: str,
                         kind: str | None = None) -> list[tuple[dt.datetime, float, str, int, bool]]:
        """(date, value, unit, test id, whether the file gave the date) of one parameter of one
        axis, oldest first."""
        from sqlalchemy import select

        from axiscal.store.models import Axis, Machine, Parameter, Test

        q = (select(Test.tested_at, Parameter.value, Parameter.unit, Test.id, Test.date_known)
             .join(Parameter, Parameter.test_id == Test.id).join(Axis).join(Machine)
             .where(Machine.name == machine, Axis.name == axis.upper(),
                    Parameter.name == parameter, Test.withdrawn == "")   # withdrawn: out
             .order_by(Test.tested_at, Test.id))
        if kind:
            q = q.where(Test.kind == kind)
        with self._guard("read"), self._session() as s:
            return [tuple(r) for r in s.execute(q).all()]

    def parameter_names(self, machine: str, axis: str) -> list[tuple[str, str]]:
        """(name, unit) of every parameter the counted (not withdrawn) tests of one axis have,
        sorted by name: what a trend of the axis can follow."""
        from sqlalchemy import select

        from axiscal.store.models import Axis, Machine, Parameter, Test

        q = (select(Parameter.name, Parameter.unit).distinct()
             .join(Test, Parameter.test_id == Test.id).join(Axis).join(Machine)
             .where(Machine.name == machine, Axis.name == axis.upper(), Test.withdrawn == "")
             .order_by(Parameter.name))
        with self._guard("read"), self._session() as s:
            return [tuple(r) for r in s.execute(q).all()]

    # -- the certificate register (axiscal.store.register) --------------------------------
    def issue_certificate(self, **kw):
        """Number, render and keep a certificate of a stored test (see
        :func:`axiscal.store.register.issue`); returns its ``CertificateRecord``."""
        from axiscal.store.register import issue

        return issue(self, **kw)

    def certificates(self, laboratory: str | None = None, test_id: int | None = None) -> list:
        """The register (of one laboratory, of one test), newest first (``CertificateRecord``
        without documents)."""
        from axiscal.store.register import listing

        return listing(self, laboratory, test_id)

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

        if write and self.read_only:
            from axiscal.store.database import read_only_refusal, sqlite_path

            raise read_only_refusal(self.url, sqlite_path(self.url))
        engine = self.engine.execution_options(axiscal_write=True) if write else self.engine
        return Session(engine, expire_on_commit=False)

    def _guard(self, what: str):
        return Guard(self.url, what)

    def _upgrade(self, allow_empty: bool) -> None:
        from axiscal.store.database import upgrade

        upgrade(self.engine, self.url, self.read_only, allow_empty)

    def _find_hash(self, digest: str) -> AddResult | None:
        return self.stored([digest]).get(digest)

    def _insert_all(self, s, items: list, now) -> list[AddResult]:
        """Insert the tests not stored yet, with their parameters and tables (plain INSERTs on
        the session's connection: the ORM's unit of work took 5 ms of CPU per test)."""
        from sqlalchemy import insert

        from axiscal import __version__
        from axiscal.store.models import Parameter, Table, Test

        stored = _stored(s, [p.sha256 for p in items])
        axes = {}          # machines and axes made in one (sorted) order: no deadlock between two
        for m, a, k in sorted({(p.machine, p.axis, p.axis_kind) for p in items}):
            axes.setdefault((m, a), _get_or_create_axis(s, m, a, k, now))
        conn, made, params, tables = s.connection(), {}, [], []
        for p in items:
            if p.sha256 in stored or p.sha256 in made:
                continue
            tid = conn.execute(insert(Test.__table__).values(
                axis_id=axes[p.machine, p.axis], kind=p.kind, tested_at=p.tested_at,
                date_known=p.date_known, stored_at=now, instrument=p.instrument,
                operator=p.operator, note=p.note, filename=p.filename, sha256=p.sha256,
                raw=p.raw, dataset_json=p.dataset_json, result_json=p.result_json,
                environment_json=p.environment_json, axiscal_version=__version__,
                withdrawn="")).inserted_primary_key[0]
            made[p.sha256] = tid
            params += [{"test_id": tid, "name": n, "value": v, "unit": u}
                       for n, v, u in p.parameters]
            tables += [{"test_id": tid, "controller": c, "filename": f, "text": x,
                        "created": now} for c, f, x in p.tables]
        for table, rows in ((Parameter.__table__, params), (Table.__table__, tables)):
            if rows:                                  # in order: ids follow the file's order
                conn.execute(insert(table), rows)
        out, seen = [], set()
        for p in items:
            if p.sha256 in stored:
                out.append(stored[p.sha256])
            else:
                out.append(AddResult(made[p.sha256], p.sha256 in seen, p.kind, p.machine,
                                     p.axis))
                seen.add(p.sha256)
        return out


def prepare(raw: bytes, filename: str, *, machine: str | None = None, axis: str | None = None,
            kind: str | None = None, instrument: str = "", operator: str = "", note: str = "",
            date: str | None = None, tables: tuple = (),
            uncertainty: dict | None = None,
            drift_check: tuple[bytes, str] | None = None,
            machine_default: str | None = None,
            kept_drift_check: dict | None = None) -> "Prepared":
    """Evaluate one file into the row it will be stored as (no database is touched).

    ``machine`` replaces the machine the file names; ``machine_default`` is used only where
    the file names none.

    ``uncertainty``: the inputs of the test's uncertainty budget
    (:func:`axiscal.store.kinds.with_uncertainty`), stored with it so that every later view,
    report and certificate gives the U it was stored with; default the user configuration's
    table for the kind (:func:`axiscal.store.kinds.inputs_from_config`). ``drift_check``: the
    (bytes, name) of the positioning test's drift check (ISO 230-2:2014 Annex A.5), kept in
    the test's record (:func:`axiscal.store.kinds.drift_check_record`: its readings and E_VE)
    and its E_VE the budget's, measured. ``kept_drift_check``: instead, the drift check a
    stored record kept without its file (its readings,
    :func:`axiscal.store.kinds.drift_check_from_readings`), as an archive brings it."""
    from axiscal._json import jsonable
    from axiscal.store.kinds import (drift_check_from_readings, drift_check_record,
                                     inputs_from_config, with_drift_check, with_uncertainty)

    ev = evaluate_file(raw, filename, kind)
    if Path(filename).name[:300] == filename:     # as a view evaluates it: kept for the views
        from axiscal.store.cache import remember

        remember(raw, hashlib.sha256(raw).hexdigest(), ev)
    when, known = _date(date or ev.date)
    if uncertainty is None:
        from axiscal.io.user_config import load_user_config

        inputs = inputs_from_config(ev.kind, load_user_config(), ev.dataset)
    else:
        inputs = dict(uncertainty)
    if drift_check is not None:
        ev, inputs = with_drift_check(ev, inputs, drift_check_record(*drift_check),
                                      declared=uncertainty)
    elif kept_drift_check is not None:
        ev, inputs = with_drift_check(ev, inputs, drift_check_from_readings(kept_drift_check),
                                      declared=uncertainty)
    from axiscal.store.limits import checked_text
    from axiscal.store.models import Axis, Machine, Test

    return Prepared(
        hashlib.sha256(raw).hexdigest(), raw,
        checked_text(Path(filename).name[:300], "file name", Test, "filename"),
        checked_text(_name(machine or ev.machine or machine_default, "machine", filename),
                     "machine name",
                     Machine, "name"),
        checked_text(_name(axis or ev.axis, "axis", filename).upper(), "axis name", Axis,
                     "name"), ev.axis_kind, ev.kind, when, known,
        checked_text(instrument or ev.instrument, "instrument", Test),
        checked_text(operator or ev.operator, "operator", Test),
        checked_text(note, "note", limit=10_000, single_line=False), ev.dataset_json,
        json.dumps(jsonable(with_uncertainty(ev, inputs).stored_result())),
        json.dumps(jsonable(ev.environment)),
        tuple((n, float(v), u) for n, (v, u) in ev.parameters.items()),
        tuple(tuple(x) for x in tables))


@dataclass(frozen=True)
class Prepared:
    """A file evaluated and ready to store: every field of its row, computed before any write."""

    sha256: str
    raw: bytes
    filename: str
    machine: str
    axis: str
    axis_kind: str
    kind: str
    tested_at: dt.datetime
    date_known: bool
    instrument: str
    operator: str
    note: str
    dataset_json: str
    result_json: str
    environment_json: str
    parameters: tuple          # (name, value, unit)
    tables: tuple              # (controller, filename, text)


def _stored(s, digests: list) -> dict:
    """AddResult (duplicate) of each of ``digests`` already in the history."""
    from sqlalchemy import select

    from axiscal.store.models import Axis, Machine, Test

    t, a, m = Test.__table__.c, Axis.__table__.c, Machine.__table__.c     # plain rows
    found, unique = {}, sorted(set(digests))
    for k in range(0, len(unique), 900):                      # SQLite's bound-parameter limit
        q = (select(t.sha256, t.id, t.kind, m.name, a.name)
             .select_from(Test.__table__.join(Axis.__table__, t.axis_id == a.id)
                          .join(Machine.__table__, a.machine_id == m.id))
             .where(t.sha256.in_(unique[k:k + 900])))
        for sha, tid, kind, m_name, a_name in s.connection().execute(q):
            found[sha] = AddResult(tid, True, kind, m_name, a_name)
    return found


def _get_or_create_axis(s, machine: str, axis: str, kind: str, now) -> int:
    """The axis row's id, made with its machine if new; a row another process inserts at the same
    moment is taken, not fought over (INSERT ... ON CONFLICT DO NOTHING, then SELECT: under
    PostgreSQL's READ COMMITTED the insert waits for the other transaction and the select then
    sees its row)."""
    from sqlalchemy import select

    from axiscal.store.models import Axis, Machine

    found = s.scalar(select(Axis.id).join(Machine, Axis.machine_id == Machine.id)
                     .where(Machine.name == machine, Axis.name == axis))
    if found is not None:                       # the usual case: one statement
        return found
    insert = _dialect_insert(s)
    s.execute(insert(Machine).values(name=machine, maker="", model="", serial="", location="",
                                     created=now).on_conflict_do_nothing(index_elements=["name"]))
    m_id = s.scalar(select(Machine.id).where(Machine.name == machine))
    s.execute(insert(Axis).values(machine_id=m_id, name=axis, kind=kind)
              .on_conflict_do_nothing(index_elements=["machine_id", "name"]))
    return s.scalar(select(Axis.id).where(Axis.machine_id == m_id, Axis.name == axis))


def _dialect_insert(s):
    if s.get_bind().dialect.name == "postgresql":
        from sqlalchemy.dialects.postgresql import insert
    else:
        from sqlalchemy.dialects.sqlite import insert
    return insert


def _collision(exc) -> bool:
    """A write that lost a race to another process: a unique row taken, a deadlock or a
    serialization failure (PostgreSQL SQLSTATE 40P01, 40001); run again, it succeeds."""
    from sqlalchemy.exc import DBAPIError, IntegrityError

    if isinstance(exc, IntegrityError):
        return True
    code = getattr(getattr(exc, "orig", None), "sqlstate", None)
    return isinstance(exc, DBAPIError) and code in ("40P01", "40001")


def _busy(exc) -> bool:
    """SQLite's "database is locked" (SQLITE_BUSY, 5) after its busy timeout ran out."""
    return getattr(getattr(exc, "orig", None), "sqlite_errorcode", None) == 5


def _test_id(test_id) -> int:
    """A test id the database can bind: one outside 1 .. 2**63 - 1 (a 64-bit integer, what
    SQLite and PostgreSQL's BIGINT hold) names no test, so :class:`NotFoundError`."""
    n = int(test_id)
    if not 0 < n < 2**63:
        raise NotFoundError(f"no test {test_id} in the history")
    return n


def _name(value: str, what: str, filename: str) -> str:
    v = (value or "").strip()
    if not v:
        raise InputError(f"{filename}: the file does not name the {what}; give --{what}")
    if len(v) > 200:
        raise InputError(f"{what} name of {len(v)} characters; at most 200")
    from axiscal.store.limits import checked_text

    return checked_text(v, f"{what} name")


#: The earliest test date taken (axiscal's rule: no numerically controlled machine tool was
#: calibrated by these methods before it; ISO 230-2's first edition is of 1972): an earlier date
#: is a typing or clock error, refused with its reason.
EARLIEST_TEST_DATE = dt.date(1950, 1, 1)


def _date(text: str) -> tuple[dt.datetime, bool]:
    """(date of the test, whether it was given). A date before :data:`EARLIEST_TEST_DATE` or
    after today (UTC, one day of grace for the time zones) is refused, naming the rule."""
    if not text:
        return dt.datetime.now(dt.timezone.utc).replace(tzinfo=None, microsecond=0), False
    when = _parse_date(str(text).strip())
    today = dt.datetime.now(dt.timezone.utc).date()
    if when.date() < EARLIEST_TEST_DATE:
        raise InputError(f"date {when:%Y-%m-%d} is before {EARLIEST_TEST_DATE:%Y}: give the "
                         "day the test was measured (YYYY-MM-DD)")
    if when.date() > today + dt.timedelta(days=1):
        raise InputError(f"date {when:%Y-%m-%d} is in the future (today is {today:%Y-%m-%d}): "
                         "give the day the test was measured (YYYY-MM-DD)")
    return when, True


def _parse_date(t: str) -> dt.datetime:
    for fmt in ("%Y-%m-%d", "%Y-%m-%dT%H:%M:%S", "%Y-%m-%d %H:%M:%S", "%Y-%m-%dT%H:%M",
                "%Y-%m-%d %H:%M", "%d.%m.%Y", "%Y/%m/%d"):
        try:
            return dt.datetime.strptime(t, fmt)
        except ValueError:
            continue
    try:
        d = dt.datetime.fromisoformat(t)
        return d.astimezone(dt.timezone.utc).replace(tzinfo=None) if d.tzinfo else d
    except ValueError:
        import re

        if re.fullmatch(r"\d{4}-\d{2}-\d{2}", t[:10]):     # written right, no such day
            raise InputError(f"date: {t[:10]} is not a date (no such day in the calendar)") \
                from None
        raise InputError(f"date {t!r}: write it as YYYY-MM-DD (or an ISO 8601 date and time)")
