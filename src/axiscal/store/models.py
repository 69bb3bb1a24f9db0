"""The tables of the calibration history (SQLAlchemy 2 typed ORM).

One machine has axes; one axis has tests; a test keeps the file exactly as it came (bytes and
their SHA-256, which makes a second copy of the same file a duplicate), the dataset in axiscal's
exact JSON where the kind has one, the full evaluation as JSON, its summary parameters as rows
(what ``list`` and ``trend`` query), the compensation tables written from it and the
certificates issued for it (the register: :class:`Certificate`). Numbers are
stored as 8-byte floats (SQLite REAL, PostgreSQL double precision): exact, no rounding through
text. The schema is created and changed only by the Alembic migrations in
``axiscal/store/migrations``.
"""

from __future__ import annotations

import datetime as dt

from sqlalchemy import (Double, ForeignKey, Index, LargeBinary, String, Text, UniqueConstraint)
from sqlalchemy.orm import DeclarativeBase, Mapped, mapped_column, relationship

__all__ = ["Base", "Machine", "Axis", "Test", "Parameter", "Table", "Certificate", "Audit",
           "Laboratory", "DriftCheck", "SignoffForApproval"]


class Base(DeclarativeBase):
    """Declarative base of the history tables."""


class Machine(Base):
    """A machine, named as its owner names it (unique), with its identification."""

    __tablename__ = "machine"
    id: Mapped[int] = mapped_column(primary_key=True)
    name: Mapped[str] = mapped_column(String(200), unique=True)
    maker: Mapped[str] = mapped_column(String(200), default="")
    model: Mapped[str] = mapped_column(String(200), default="")
    serial: Mapped[str] = mapped_column(String(200), default="")
    location: Mapped[str] = mapped_column(String(200), default="")
    created: Mapped[dt.datetime] = mapped_column()
    axes: Mapped[list["Axis"]] = relationship(back_populates="machine",
                                              cascade="all, delete-orphan")


class Axis(Base):
    """An axis of a machine (``X``, ``C`` ...); ``kind`` is linear or rotary."""

    __tablename__ = "axis"
    __table_args__ = (UniqueConstraint("machine_id", "name"),)
    id: Mapped[int] = mapped_column(primary_key=True)
    machine_id: Mapped[int] = mapped_column(ForeignKey("machine.id", ondelete="CASCADE"))
    name: Mapped[str] = mapped_column(String(50))
    kind: Mapped[str] = mapped_column(String(20), default="")
    machine: Mapped[Machine] = relationship(back_populates="axes")
    tests: Mapped[list["Test"]] = relationship(back_populates="axis",
                                               cascade="all, delete-orphan")


class Test(Base):
    """One measurement of one axis, as it came, with its evaluation."""

    __tablename__ = "test"
    __table_args__ = (Index("ix_test_axis_date", "axis_id", "tested_at"),)
    id: Mapped[int] = mapped_column(primary_key=True)
    axis_id: Mapped[int] = mapped_column(ForeignKey("axis.id", ondelete="CASCADE"))
    kind: Mapped[str] = mapped_column(String(40))
    tested_at: Mapped[dt.datetime] = mapped_column()
    date_known: Mapped[bool] = mapped_column(default=True)
    stored_at: Mapped[dt.datetime] = mapped_column()
    instrument: Mapped[str] = mapped_column(String(200), default="")
    operator: Mapped[str] = mapped_column(String(200), default="")
    note: Mapped[str] = mapped_column(Text, default="")
    filename: Mapped[str] = mapped_column(String(300))
    sha256: Mapped[str] = mapped_column(String(64), unique=True)
    raw: Mapped[bytes] = mapped_column(LargeBinary)
    dataset_json: Mapped[str] = mapped_column(Text, default="")
    result_json: Mapped[str] = mapped_column(Text)
    environment_json: Mapped[str] = mapped_column(Text, default="{}")
    axiscal_version: Mapped[str] = mapped_column(String(40))
    #: Why the test was withdrawn ("" while it counts): a withdrawn test stays, marked, but
    #: leaves trends and compares (axiscal.store.corrections).
    withdrawn: Mapped[str] = mapped_column(Text, default="")
    axis: Mapped[Axis] = relationship(back_populates="tests")
    parameters: Mapped[list["Parameter"]] = relationship(back_populates="test",
                                                         cascade="all, delete-orphan",
                                                         order_by="Parameter.id")
    tables: Mapped[list["Table"]] = relationship(back_populates="test",
                                                 cascade="all, delete-orphan",
                                                 order_by="Table.id")
    certificates: Mapped[list["Certificate"]] = relationship(back_populates="test",
                                                             cascade="all, delete-orphan")


class Parameter(Base):
    """One summary parameter of a test's evaluation (``E``, ``R``, ``squareness``...)."""

    __tablename__ = "parameter"
    __table_args__ = (UniqueConstraint("test_id", "name"), Index("ix_parameter_name", "name"))
    id: Mapped[int] = mapped_column(primary_key=True)
    test_id: Mapped[int] = mapped_column(ForeignKey("test.id", ondelete="CASCADE"))
    name: Mapped[str] = mapped_column(String(60))
    value: Mapped[float] = mapped_column(Double)
    unit: Mapped[str] = mapped_column(String(20))
    test: Mapped[Test] = relationship(back_populates="parameters")


class Table(Base):
    """A compensation table written from a test (the controller's file, as written)."""

    __tablename__ = "compensation_table"
    id: Mapped[int] = mapped_column(primary_key=True)
    test_id: Mapped[int] = mapped_column(ForeignKey("test.id", ondelete="CASCADE"))
    controller: Mapped[str] = mapped_column(String(40))
    filename: Mapped[str] = mapped_column(String(300))
    text: Mapped[str] = mapped_column(Text)
    created: Mapped[dt.datetime] = mapped_column()
    test: Mapped[Test] = relationship(back_populates="tables")


class Certificate(Base):
    """A certificate issued for a test: its number, the issued document as it left, its status.

    ``counter`` is unique in its ``series`` (the laboratory, and the year when the number
    pattern holds one) and ``number`` unique per laboratory: two processes that take the same
    counter at once cannot both commit, and the loser takes the next one (ISO/IEC 17025:2017
    §7.8.2.1 b: a unique identification). ``inputs_json`` keeps what the page was built from
    (customer, machine, conditions, instruments, tolerances, rule) so an amendment can be
    rebuilt; ``replaces_id`` and ``reason`` make an amendment (§7.8.8), ``status`` is
    ``issued`` or ``superseded``.

    ``laboratory`` is the laboratory's *code* (``[company] code``), the register's key: a name
    may change (a full stop added) without starting a second counter; ``laboratory_name`` is the
    name printed at issue. ``prepared_by`` and ``approved_by`` (with ``approved_role``) name who
    prepared the certificate and the authorised signatory who approved its issue (§7.8.2.1 o);
    ``changes_json`` lists what an amendment changed (§7.8.8.3); ``as_found_test_id`` is the
    test before adjustment of an "as found / as left" certificate (§7.8.4.1 d).
    """

    __tablename__ = "certificate"
    __table_args__ = (UniqueConstraint("laboratory", "number"),
                      UniqueConstraint("laboratory", "series", "counter"))
    id: Mapped[int] = mapped_column(primary_key=True)
    test_id: Mapped[int] = mapped_column(ForeignKey("test.id", ondelete="CASCADE"))
    laboratory: Mapped[str] = mapped_column(String(200))
    series: Mapped[str] = mapped_column(String(250))
    counter: Mapped[int] = mapped_column()
    number: Mapped[str] = mapped_column(String(100))
    customer: Mapped[str] = mapped_column(String(400), default="")
    issued: Mapped[str] = mapped_column(String(40))
    status: Mapped[str] = mapped_column(String(20), default="issued")
    replaces_id: Mapped[int | None] = mapped_column(ForeignKey("certificate.id"), nullable=True)
    reason: Mapped[str] = mapped_column(Text, default="")
    media_type: Mapped[str] = mapped_column(String(40))
    document: Mapped[bytes] = mapped_column(LargeBinary)
    sha256: Mapped[str] = mapped_column(String(64))
    inputs_json: Mapped[str] = mapped_column(Text, default="{}")
    created: Mapped[dt.datetime] = mapped_column()
    laboratory_name: Mapped[str] = mapped_column(String(200), default="")
    prepared_by: Mapped[str] = mapped_column(String(200), default="")
    approved_by: Mapped[str] = mapped_column(String(200), default="")
    approved_role: Mapped[str] = mapped_column(String(200), default="")
    changes_json: Mapped[str] = mapped_column(Text, default="[]")
    as_found_test_id: Mapped[int | None] = mapped_column(nullable=True)
    test: Mapped[Test] = relationship(back_populates="certificates")


class Audit(Base):
    """One change to the history: who, when, what, why, and the values before and after (JSON).

    Rows are only ever added (ISO/IEC 17025:2017 §7.5.2, §8.4.2); ``machine_id``, ``axis_id``
    and ``test_id`` name what was changed, without a foreign key, so an entry outlives a machine
    merged into another. Written by :mod:`axiscal.store.corrections`.
    """

    __tablename__ = "audit"
    __table_args__ = (Index("ix_audit_machine", "machine_id"), Index("ix_audit_test", "test_id"))
    id: Mapped[int] = mapped_column(primary_key=True)
    at: Mapped[dt.datetime] = mapped_column()
    by: Mapped[str] = mapped_column(String(200))
    action: Mapped[str] = mapped_column(String(40))
    what: Mapped[str] = mapped_column(Text)
    reason: Mapped[str] = mapped_column(Text)
    machine_id: Mapped[int | None] = mapped_column(nullable=True)
    axis_id: Mapped[int | None] = mapped_column(nullable=True)
    test_id: Mapped[int | None] = mapped_column(nullable=True)
    old_json: Mapped[str] = mapped_column(Text)
    new_json: Mapped[str] = mapped_column(Text)


class Laboratory(Base):
    """The laboratory as the history keeps it (one row): the configuration tables that identify
    it and what it certifies with, as JSON (``company``, ``signatory``, ``instrument``,
    ``uncertainty``), edited by :mod:`axiscal.store.laboratory` with an audit entry each time."""

    __tablename__ = "laboratory"
    id: Mapped[int] = mapped_column(primary_key=True)
    tables_json: Mapped[str] = mapped_column(Text)
    updated: Mapped[dt.datetime] = mapped_column()
    updated_by: Mapped[str] = mapped_column(String(200))


class DriftCheck(Base):
    """A drift-check file kept beside a test, byte for byte, with the E_VE it gives (the range
    of its readings, ISO 230-2:2014 Annex A.5) in the test's deviation unit."""

    __tablename__ = "drift_check"
    __table_args__ = (Index("ix_drift_check_test", "test_id"),)
    id: Mapped[int] = mapped_column(primary_key=True)
    test_id: Mapped[int] = mapped_column(ForeignKey("test.id", ondelete="CASCADE"))
    filename: Mapped[str] = mapped_column(String(300))
    raw: Mapped[bytes] = mapped_column(LargeBinary)
    sha256: Mapped[str] = mapped_column(String(64))
    e_ve: Mapped[float] = mapped_column(Double)
    readings: Mapped[int] = mapped_column()
    created: Mapped[dt.datetime] = mapped_column()
    by: Mapped[str] = mapped_column(String(200))


class SignoffForApproval(Base):
    """The sign-off form of a test as its preparer (a signed-in account) saved it for approval
    by an authorised signatory: the fields as JSON, who saved it and when (one row a test)."""

    __tablename__ = "signoff_for_approval"
    test_id: Mapped[int] = mapped_column(ForeignKey("test.id", ondelete="CASCADE"),
                                         primary_key=True)
    values_json: Mapped[str] = mapped_column(Text)
    by: Mapped[str] = mapped_column(String(200))
    saved: Mapped[dt.datetime] = mapped_column()
