"""The certificate register: controlled numbers, the issued documents, amendments.

A certificate number is unique per laboratory and comes from a counter in the register, never
from the data alone (ISO/IEC 17025:2017 §7.8.2.1 d: "unique identification"). The register is
keyed by the laboratory's *code* (``[company] code``), never by its display name: a name written
another way (a full stop added) is the same laboratory and continues its counter; the name is
kept beside each certificate as it was printed. The number is formed by the caller's pattern
from the next counter of a *series* (the laboratory, and the year when the pattern holds one);
the database's unique constraints on (laboratory, series, counter) and (laboratory, number) make
two processes that take the same counter at once collide, and the loser renders again with the
next counter. The document is rendered *before* the write transaction (a PDF takes a second;
SQLite's write lock is not held meanwhile) and kept byte for byte with its SHA-256.

What the register refuses (each in one line, nothing written):

* a date of issue in the future, or before the date of the laboratory's last certificate (the
  numbers and the dates of one laboratory run the same way);
* a second certificate of a test that has an issued one, unless it amends that one;
* a certificate of a withdrawn test (:func:`axiscal.store.corrections.withdraw`); a test
  withdrawn after its certificate was issued leaves the certificate as it was issued, and the
  register says beside it that its test was withdrawn, and why.

An amendment (§7.8.8.2, §7.8.8.3) is a new certificate with a new number that names the one it
replaces, the reason and what changed; the old one is kept and marked ``superseded`` in the same
transaction. Both stay retrievable.

The :class:`~axiscal.store.history.Store` methods ``issue_certificate``, ``certificates`` and
``certificate`` call these functions.
"""

from __future__ import annotations

import datetime as dt
import hashlib
import json
import random
import time
from dataclasses import dataclass, field
from typing import Callable

from axiscal.errors import InputError

__all__ = ["CertificateRecord", "issue", "listing", "fetch", "check_issue_date", "ISSUED",
           "SUPERSEDED"]

ISSUED, SUPERSEDED = "issued", "superseded"
#: How often a number taken by another process at the same moment is tried again (each round
#: one of the processes wins, so n issuers at once need at most n rounds).
ATTEMPTS = 64


@dataclass(frozen=True)
class CertificateRecord:
    """One certificate of the register (``document`` empty in a listing).

    ``laboratory`` is the laboratory's code (the register's key), ``laboratory_name`` its name
    as printed; ``test_withdrawn`` the reason its test was withdrawn after issue ("" while the
    test counts); ``changes`` what an amendment changed (``{"what", "old", "new"}`` each).
    """

    number: str
    laboratory: str
    test_id: int
    customer: str
    issued: str
    status: str
    media_type: str
    sha256: str
    created: dt.datetime
    replaces: str = ""
    replaced_by: str = ""
    reason: str = ""
    document: bytes = b""
    inputs: dict = field(default_factory=dict)
    laboratory_name: str = ""
    prepared_by: str = ""
    approved_by: str = ""
    approved_role: str = ""
    changes: tuple = ()
    test_withdrawn: str = ""
    as_found_test_id: int | None = None

    def __str__(self) -> str:
        s = f"{self.number}  {self.status}  issued {self.issued}  test {self.test_id}  {self.customer}"
        if self.as_found_test_id is not None:
            s += f"  (as found: test {self.as_found_test_id})"
        if self.approved_by:
            s += (f"  prepared by {self.prepared_by or 'not stated'}, authorised by "
                  f"{self.approved_by}" + (f" ({self.approved_role})" if self.approved_role
                                           else ""))
        if self.replaces:
            s += f"  (replaces {self.replaces}: {self.reason})"
        if self.replaced_by:
            s += f"  (replaced by {self.replaced_by})"
        if self.test_withdrawn:
            s += f"  TEST WITHDRAWN after issue: {self.test_withdrawn}"
        return s


def issue(store, *, test_id: int, laboratory: str, series: str,
          number_for: Callable[[int], str], render: Callable[[str], bytes], customer: str,
          issued: str, media_type: str, inputs: dict, replaces: str = "",
          reason: str = "", laboratory_name: str = "", prepared_by: str = "",
          approved_by: str = "", approved_role: str = "", changes=(),
          as_found_test_id: int | None = None, today: dt.date | None = None
          ) -> CertificateRecord:
    """Take the next number of ``series``, render the document with it and keep both.

    Parameters
    ----------
    store : Store
    test_id : int
        The stored test the certificate is for (the "as left" test of an as found / as left
        certificate).
    laboratory : str
        The laboratory's code: numbers are unique per laboratory code.
    series : str
        The counter's scope within the laboratory.
    number_for : callable
        counter -> number (the laboratory's pattern); a callable that ignores the counter gives
        a fixed number, refused if the laboratory issued it before.
    render : callable
        number -> the document's bytes.
    issued : str
        Date of issue, ``YYYY-MM-DD``: not after ``today`` and not before the laboratory's last
        certificate.
    replaces, reason : str
        The number of the laboratory's certificate this one amends, and why (both or neither).
    laboratory_name, prepared_by, approved_by, approved_role : str
        Kept beside the number: the laboratory's name as printed, who prepared the certificate,
        the authorised signatory who approved its issue and the signatory's role.
    changes : sequence of dict
        An amendment's changes (``what``, ``old``, ``new``).
    as_found_test_id : int, optional
        The test before adjustment of an as found / as left certificate.
    today : datetime.date, optional
        The date a date of issue may not pass (default: the clock's).

    Raises
    ------
    InputError
        One of the refusals of the module's docstring; nothing is written.
    """
    from sqlalchemy import func, select

    from axiscal.store.models import Certificate

    from axiscal.store.limits import checked_tables, checked_text

    checked_tables((inputs or {}).get("config") or {}, "certificate:")
    for text, what in ((customer, "customer name"), (laboratory_name, "laboratory name"),
                       (prepared_by, "prepared by"), (approved_by, "approved by"),
                       (approved_role, "approver's role")):
        checked_text(text, what)
    checked_text(reason, "reason for the amendment", single_line=False)
    if bool(replaces) != bool(reason.strip()):
        raise InputError("an amendment names the certificate it replaces and the reason, both")
    issued_on = check_issue_date(issued, today)
    rules = dict(laboratory=laboratory, test_id=test_id, replaces=replaces, issued=issued_on,
                 as_found=as_found_test_id)
    with store._guard("read"), store._session() as s:
        _check(s, **rules)
    for attempt in range(ATTEMPTS):
        with store._guard("read"), store._session() as s:
            last = s.scalar(select(func.max(Certificate.counter)).where(
                Certificate.laboratory == laboratory, Certificate.series == series))
        counter = (last or 0) + 1
        number = number_for(counter)
        if _exists(store, laboratory, number):
            if number_for(counter + 1) != number:     # taken meanwhile: the next counter
                continue
            raise InputError(f"certificate number {number} was issued before by {laboratory}; "
                             "a number is never given twice (amend with 'axiscal certificate "
                             "reissue')")
        doc = render(number)
        now = dt.datetime.now(dt.timezone.utc).replace(tzinfo=None)
        row = Certificate(test_id=test_id, laboratory=laboratory, series=series,
                          counter=counter, number=number, customer=customer[:400],
                          issued=issued, status=ISSUED, reason=reason, media_type=media_type,
                          document=doc, sha256=hashlib.sha256(doc).hexdigest(),
                          inputs_json=json.dumps(inputs), created=now,
                          laboratory_name=(laboratory_name or laboratory)[:200],
                          prepared_by=prepared_by[:200], approved_by=approved_by[:200],
                          approved_role=approved_role[:200],
                          changes_json=json.dumps(list(changes), default=str),
                          as_found_test_id=as_found_test_id)
        if _commit(store, row, rules):
            return fetch(store, number, laboratory)
        time.sleep(random.uniform(0, 0.005 * (attempt + 1)))     # spread the next round
    raise InputError(f"no free certificate number for {laboratory} after {ATTEMPTS} attempts "
                     "(other processes issue at the same time); try again")


def check_issue_date(issued: str, today: dt.date | None = None) -> dt.date:
    """The date of issue as a date; one in the future is refused (before anything is kept)."""
    try:
        when = dt.date.fromisoformat(str(issued).strip()[:10])
    except ValueError:
        raise InputError(f"date of issue {issued!r}: write it as YYYY-MM-DD") from None
    today = today or dt.date.today()
    if when > today:
        raise InputError(f"date of issue {when} is in the future (today is {today}): a "
                         "certificate is dated the day it is issued")
    return when


def _check(s, *, laboratory: str, test_id: int, replaces: str, issued: dt.date,
           as_found: int | None) -> None:
    """The register's refusals, read in session ``s`` (again inside the write transaction)."""
    from sqlalchemy import func, select

    from axiscal.store.database import NotFoundError
    from axiscal.store.models import Certificate, Test

    for tid, what in ((test_id, "test"), (as_found, "as found test")):
        if tid is None:
            continue
        t = s.get(Test, tid)
        if t is None:
            raise NotFoundError(f"no test {tid} in the history")
        if t.withdrawn:
            raise InputError(f"{what} {tid} is withdrawn ({t.withdrawn}): a withdrawn test is "
                             "never certified (reinstate it first if the withdrawal was wrong)")
    last = s.execute(select(Certificate.issued, Certificate.number).where(
        Certificate.laboratory == laboratory).order_by(
        func.substr(Certificate.issued, 1, 10).desc(), Certificate.id.desc()).limit(1)).first()
    if last is not None and str(last[0])[:10] > issued.isoformat():
        raise InputError(f"date of issue {issued} is before {last[0][:10]}, the date of "
                         f"{laboratory}'s last certificate {last[1]}: a certificate is never "
                         "backdated behind the register")
    current = s.execute(select(Certificate.number, Certificate.issued).where(
        Certificate.laboratory == laboratory, Certificate.test_id == test_id,
        Certificate.status == ISSUED)).first()
    if current is not None and not replaces:
        raise InputError(f"test {test_id} has certificate {current[0]} of {laboratory} (issued "
                         f"{current[1]}); a second certificate of the same test is an amendment: "
                         f"axiscal certificate reissue {current[0]} --reason ...")
    if replaces:
        old = s.execute(select(Certificate.test_id, Certificate.status).where(
            Certificate.laboratory == laboratory, Certificate.number == replaces)).first()
        if old is None:
            raise NotFoundError(f"no certificate {replaces} of {laboratory} to replace")
        if old[1] != ISSUED:
            raise InputError(f"certificate {replaces} is already superseded; amend the "
                             "certificate that replaced it")
        if old[0] != test_id:
            raise InputError(f"certificate {replaces} is of test {old[0]}, not of test "
                             f"{test_id}: an amendment reports the same test")


def listing(store, laboratory: str | None = None,
            test_id: int | None = None) -> list[CertificateRecord]:
    """Every certificate of the register (of one laboratory, by its code or name; of one test),
    newest first, without documents (which are not read)."""
    from sqlalchemy import select

    from axiscal.store.models import Certificate, Test

    c = Certificate.__table__.c            # plain rows, the documents not read
    q = (select(*(col for col in c if col.key not in ("document", "inputs_json")),
                Test.withdrawn.label("test_withdrawn"))
         .join(Test, Test.id == c.test_id)
         .order_by(c.created.desc(), c.id.desc()))
    if laboratory:
        q = q.where((c.laboratory == laboratory) | (c.laboratory_name == laboratory))
    if test_id is not None:
        q = q.where(c.test_id == test_id)
    with store._guard("read"), store._session() as s:
        rows = s.connection().execute(q).all()
        links = _links(s) if rows else {}
        return [_record(r, links, with_document=False) for r in rows]


def fetch(store, number: str, laboratory: str | None = None) -> CertificateRecord:
    """One certificate with its document; the document's SHA-256 is checked against the one
    kept. ``laboratory`` is the laboratory's code (or its name as printed)."""
    from sqlalchemy import select

    from axiscal.store.database import NotFoundError, StoreError
    from axiscal.store.models import Certificate, Test

    q = select(Certificate, Test.withdrawn).join(Test, Test.id == Certificate.test_id).where(
        Certificate.number == number)
    if laboratory:
        q = q.where((Certificate.laboratory == laboratory)
                    | (Certificate.laboratory_name == laboratory))
    with store._guard("read"), store._session() as s:
        rows = s.execute(q).all()
        if not rows:
            raise NotFoundError(f"no certificate {number} in the register")
        if len(rows) > 1:
            labs = ", ".join(sorted(c.laboratory for c, _ in rows))
            raise InputError(f"certificate {number} was issued by {len(rows)} laboratories "
                             f"({labs}); name the laboratory's code (--laboratory)")
        rec = _record(rows[0][0], _links(s), with_document=True, withdrawn=rows[0][1])
    if hashlib.sha256(rec.document).hexdigest() != rec.sha256:
        raise StoreError(f"certificate {number}: the stored document does not match its SHA-256 "
                         f"{rec.sha256} (altered in the database)")
    return rec


def _exists(store, laboratory: str, number: str) -> bool:
    from sqlalchemy import select

    from axiscal.store.models import Certificate

    with store._guard("read"), store._session() as s:
        return s.scalar(select(Certificate.id).where(Certificate.laboratory == laboratory,
                                                     Certificate.number == number)) is not None


def _commit(store, row, rules: dict) -> bool:
    """Insert ``row`` (and supersede the one it replaces) in one transaction, the register's
    refusals checked again inside it; False if the counter or number was taken meanwhile."""
    from sqlalchemy import select
    from sqlalchemy.exc import IntegrityError

    from axiscal.store.models import Certificate, Test

    with store._guard("store"), store._session(write=True) as s:
        try:
            # PostgreSQL: the test's row locked, so two issuers of one test wait for each other
            # (SQLite's write transaction is exclusive already)
            s.execute(select(Test.id).where(Test.id == row.test_id).with_for_update())
            _check(s, **rules)
            if rules["replaces"]:
                old = s.scalars(select(Certificate).where(
                    Certificate.laboratory == rules["laboratory"],
                    Certificate.number == rules["replaces"])).one()
                old.status = SUPERSEDED
                s.flush()
                row.replaces_id = old.id
            s.add(row)
            s.commit()
            return True
        except IntegrityError:
            s.rollback()
            return False


def _links(s) -> dict[int, tuple[str, int | None]]:
    """id -> (number, replaces_id) of every certificate (small: one row per certificate)."""
    from sqlalchemy import select

    from axiscal.store.models import Certificate

    return {i: (n, r) for i, n, r in s.execute(
        select(Certificate.id, Certificate.number, Certificate.replaces_id))}


def _record(c, links, with_document: bool, withdrawn: str | None = None) -> CertificateRecord:
    replaced_by = next((n for i, (n, r) in links.items() if r == c.id), "")
    replaces = links[c.replaces_id][0] if c.replaces_id in links else ""
    return CertificateRecord(
        c.number, c.laboratory, c.test_id, c.customer, c.issued, c.status, c.media_type,
        c.sha256, c.created, replaces, replaced_by, c.reason,
        c.document if with_document else b"",
        json.loads(c.inputs_json) if with_document else {},
        c.laboratory_name or c.laboratory, c.prepared_by or "", c.approved_by or "",
        c.approved_role or "", tuple(json.loads(c.changes_json or "[]")),
        (withdrawn if withdrawn is not None else getattr(c, "test_withdrawn", "")) or "",
        c.as_found_test_id)
