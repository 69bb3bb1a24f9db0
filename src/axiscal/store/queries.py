"""The reads a page makes on every view, each a few SQL statements built once.

A stored test, a page of a machine's tests with their parameters, one machine, the machines'
names, and the history's *generation*. They are SQLAlchemy Core statements over the tables of
:mod:`axiscal.store.models`, built once per process with bound parameters (:func:`_statements`)
where they can be, and read as plain rows: the ORM's unit of work, identity map and
per-statement compilation cost a page of the workbench ten times the database's own time
(3.1 ms of CPU for one test's three ORM queries, 0.17 ms for the same rows read here).
:class:`~axiscal.store.history.Store` makes its records of them (``get``, ``tests``,
``machine``); this module imports nothing of it.

Notes
-----
:func:`generation` is what a worker process may keep a page's reads, or a page, under
(:mod:`axiscal.web.memo`, :mod:`axiscal.web.page_cache`): the number of rows and the largest id
of every table a page shows (:data:`GENERATION_TABLES`: tests, the audit trail, machines, axes,
certificates, compensation tables, drift checks; for the one laboratory row its count and the
time of its last edit; a sign-off saved for approval, its count and the time of the last save). Every write of the history adds a row to one of them
(:mod:`axiscal.store.corrections`: a change of a test, a machine or the laboratory is a new
audit row written in the same transaction; a test is withdrawn, never removed; a machine merged
away goes with an audit row; an upload adds a test, a table a table row, an issue or an
amendment a certificate row, a drift check its row, an import the rows it brings), so every
committed change a page shows changes a count. The count is needed beside the largest id: on
PostgreSQL ids come from a sequence, and a transaction that took id 5 may commit after one that
took id 6, leaving the largest id unchanged. The tests of ``tests/web/test_page_cache.py``
check it for each path that writes.
"""

from __future__ import annotations

from functools import lru_cache
from typing import NamedTuple

__all__ = ["MachineName", "machine", "machine_names", "generation", "test", "test_rows",
           "parameters", "tests_with", "GENERATION_TABLES", "NEW_TESTS"]

#: The tables :func:`generation` counts, in its order (two figures each: rows, largest id; the
#: laboratory's: rows, time of its last edit).
GENERATION_TABLES = ("test", "audit", "machine", "axis", "certificate", "compensation_table",
                     "drift_check", "laboratory", "signoff_for_approval")
#: How many of :func:`generation`'s figures a new test changes and nothing else: the ``test``
#: table's (an upload to a known axis adds a test and its parameters, no other row). A page
#: that shows no other test than its own may be kept under ``generation(store)[NEW_TESTS:]``.
NEW_TESTS = 2


class MachineName(NamedTuple):
    """A machine's id and name."""

    id: int
    name: str


def test(store, test_id: int) -> tuple | None:
    """(row, parameters, tables) of test ``test_id`` in three statements, else None: the row's
    fields by name (``kind``, ``tested_at`` ... ``size``, the stored bytes' length, ``axis``,
    ``machine``, ``machine_id``; not the bytes), the parameters {name: (value, unit)} in the
    order they were stored, the tables as (controller, filename, text)."""
    q = _statements()
    with store._guard("read"), store.engine.connect() as c:
        r = c.execute(q["test"], {"id": test_id}).first()
        if r is None:
            return None
        params = {n: (v, u) for n, v, u in c.execute(q["parameters"], {"id": test_id})}
        tables = tuple(tuple(x) for x in c.execute(q["tables"], {"id": test_id}))
    return r, params, tables


def test_rows(store, machine=None, axis=None, kind=None, since=None, limit=None, offset=0):
    """The rows (id, machine, axis, kind, tested_at, date_known, filename, note, withdrawn,
    machine id) of the tests that pass the filters, newest first."""
    from sqlalchemy import select

    from axiscal.store.models import Axis, Machine, Test

    t, a, m = Test.__table__.c, Axis.__table__.c, Machine.__table__.c
    q = (select(t.id, m.name, a.name, t.kind, t.tested_at, t.date_known, t.filename, t.note,
                t.withdrawn, m.id)
         .select_from(Test.__table__.join(Axis.__table__, t.axis_id == a.id)
                      .join(Machine.__table__, a.machine_id == m.id))
         .order_by(t.tested_at.desc(), t.id.desc()))
    for column, value in ((m.name, machine), (a.name, axis and axis.upper()), (t.kind, kind)):
        if value:
            q = q.where(column == value)
    if since:
        q = q.where(t.tested_at >= since)
    if limit:
        q = q.limit(min(limit, 2**63 - 1))
    if offset:
        q = q.offset(offset)
    with store._guard("read"), store.engine.connect() as c:
        return [tuple(r) for r in c.execute(q)]


def parameters(store, ids: list, names: tuple | None) -> dict[int, dict]:
    """{test id: {name: (value, unit)}} of tests ``ids``, in the order they were stored: all
    their parameters, or those named in ``names`` and each test's first (none for an empty
    ``names``)."""
    out: dict[int, dict] = {i: {} for i in ids}
    if names is not None and not names:
        return out
    q = _statements()["parameters_of" if names is None else "parameters_named"]
    with store._guard("read"), store.engine.connect() as c:
        for k in range(0, len(ids), 900):                     # SQLite's bound-parameter limit
            bound = {"ids": ids[k:k + 900]}
            if names is not None:
                bound["names"] = list(names)
            for tid, name, value, unit in c.execute(q, bound):
                out[tid][name] = (value, unit)
    return out


def machine(store, machine_id: int) -> list:
    """Rows (name, maker, model, serial, location, axis, tests, last test date) of one machine,
    one per axis (none if there is no such machine), in one statement."""
    with store._guard("read"), store.engine.connect() as c:
        return c.execute(_statements()["machine"], {"id": machine_id}).all()


def machine_names(store) -> list[MachineName]:
    """Every machine's id and name, by name."""
    with store._guard("read"), store.engine.connect() as c:
        return [MachineName(i, n) for i, n in c.execute(_statements()["machine_names"])]


def generation(store) -> tuple:
    """(rows, largest id) of each of :data:`GENERATION_TABLES`, in one statement: changes with
    every committed write of the history (see the module notes)."""
    with store._guard("read"), store.engine.connect() as c:
        return tuple(c.execute(_statements()["generation"]).one())


def tests_with(store, table: str) -> frozenset:
    """The ids of the tests that have a row in ``table`` (``certificate``, ``drift_check``,
    ``audit`` or ``signoff_for_approval``): most tests have none, and a page need not ask for
    them one by one."""
    with store._guard("read"), store.engine.connect() as c:
        return frozenset(c.execute(_statements()[f"tests_with_{table}"]).scalars())


@lru_cache(maxsize=None)
def _statements() -> dict:
    """The statements with bound parameters, built once."""
    from sqlalchemy import bindparam, func, or_, select

    from axiscal.store.models import (Audit, Axis, Certificate, DriftCheck, Laboratory, Machine,
                                      Parameter, SignoffForApproval, Table, Test)

    t, a, m = Test.__table__.c, Axis.__table__.c, Machine.__table__.c
    p, tb = Parameter.__table__.c, Table.__table__.c
    one = bindparam("id")
    test = (select(t.kind, t.tested_at, t.date_known, t.filename, t.note, t.withdrawn,
                   t.sha256, t.result_json, t.dataset_json, t.environment_json, t.instrument,
                   t.operator, t.stored_at, t.axiscal_version,
                   func.length(t.raw).label("size"), a.name.label("axis"),
                   m.name.label("machine"), m.id.label("machine_id"))
            .select_from(Test.__table__.join(Axis.__table__, t.axis_id == a.id)
                         .join(Machine.__table__, a.machine_id == m.id))
            .where(t.id == one))
    machine_q = (select(m.name, m.maker, m.model, m.serial, m.location, a.name,
                        func.count(t.id), func.max(t.tested_at))
                 .select_from(Machine.__table__.outerjoin(Axis.__table__, a.machine_id == m.id)
                              .outerjoin(Test.__table__, t.axis_id == a.id))
                 .where(m.id == one).group_by(m.id, a.id).order_by(a.name))
    counted = (Test, Audit, Machine, Axis, Certificate, Table, DriftCheck, Laboratory,
               SignoffForApproval)
    last = {Laboratory: "updated", SignoffForApproval: "saved"}   # tables without an id
    counts = [part for table in counted for part in (
        select(func.count()).select_from(table.__table__).scalar_subquery(),
        select(func.max(table.__table__.c[last.get(table, "id")])).scalar_subquery())]
    # the parameters of a page of tests (all, or those named and each test's first): built
    # once with expanding parameters, so a page's view does not build and compile them again
    ids, names = bindparam("ids", expanding=True), bindparam("names", expanding=True)
    of = select(p.test_id, p.name, p.value, p.unit).where(p.test_id.in_(ids)).order_by(p.id)
    first = select(func.min(p.id)).where(p.test_id.in_(ids)).group_by(p.test_id)
    named = of.where(or_(p.name.in_(names), p.id.in_(first)))
    return {"test": test, "parameters_of": of, "parameters_named": named,
            "parameters": select(p.name, p.value, p.unit).where(p.test_id == one)
            .order_by(p.id),
            "tables": select(tb.controller, tb.filename, tb.text).where(tb.test_id == one)
            .order_by(tb.id),
            "machine": machine_q,
            "machine_names": select(m.id, m.name).order_by(m.name),
            **{f"tests_with_{x.__tablename__}": select(x.__table__.c.test_id).distinct()
               .where(x.__table__.c.test_id.is_not(None))
               for x in (Certificate, DriftCheck, Audit, SignoffForApproval)},
            "generation": select(*counts)}
