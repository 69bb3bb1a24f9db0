"""The certificate register: controlled numbers, the issued documents, amendments.

A certificate number is unique per laboratory and comes from a counter in the register, never
from the data alone (ISO/IEC 17025:2017 §7.8.2.1 b: "unique identification"). The number is
formed by the caller's pattern from the next counter of a *series* (the laboratory, and the year
when the pattern holds one); the database's unique constraints on (laboratory, series, counter)
and (laboratory, number) make two processes that take the same counter at once collide, and the
loser renders again with the next counter. The document is rendered *before* the write
transaction (a PDF takes a second; SQLite's write lock is not held meanwhile) and kept byte for
byte with its SHA-256.

An amendment (§7.8.8.2, §7.8.8.3) is a new certificate with a new number that names the one it
replaces and the reason; the old one is kept and marked ``superseded`` in the same transaction.
Both stay retrievable.

The :class:`~axiscal.store.history.Store` methods ``issue_certificate``, ``certificates`` and
``certificate`` call these functions.
"""

from __future__ import annotations

import datetime as dt
import hashlib
import json
from dataclasses import dataclass, field
from typing import Callable

from axiscal.errors import InputError

__all__ = ["CertificateRecord", "issue", "listing", "fetch", "ISSUED", "SUPERSEDED"]

ISSUED, SUPERSEDED = "issued", "superseded"
#: How often a number taken by another process at the same moment is tried again.
ATTEMPTS = 20


@dataclass(frozen=True)
class CertificateRecord:
    """One certificate of the register (``document`` empty in a listing)."""

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

    def __str__(self) -> str:
        s = f"{self.number}  {self.status}  issued {self.issued}  test {self.test_id}  {self.customer}"
        if self.replaces:
            s += f"  (replaces {self.replaces}: {self.reason})"
        if self.replaced_by:
            s += f"  (replaced by {self.replaced_by})"
        return s


def issue(store, *, test_id: int, laboratory: str, series: str,
          number_for: Callable[[int], str], render: Callable[[str], bytes], customer: str,
          issued: str, media_type: str, inputs: dict, replaces: str = "",
          reason: str = "") -> CertificateRecord:
    """Take the next number of ``series``, render the document with it and keep both.

    Parameters
    ----------
    store : Store
    test_id : int
        The stored test the certificate is for.
    laboratory : str
        The laboratory's name: numbers are unique per laboratory.
    series : str
        The counter's scope within the laboratory.
    number_for : callable
        counter -> number (the laboratory's pattern); a callable that ignores the counter gives
        a fixed number, refused if the laboratory issued it before.
    render : callable
        number -> the document's bytes.
    replaces, reason : str
        The number of the laboratory's certificate this one amends, and why (both or neither).
    """
    from sqlalchemy import func, select

    from axiscal.store.models import Certificate

    if bool(replaces) != bool(reason.strip()):
        raise InputError("an amendment names the certificate it replaces and the reason, both")
    for _ in range(ATTEMPTS):
        with store._guard("read"), store._session() as s:
            last = s.scalar(select(func.max(Certificate.counter)).where(
                Certificate.laboratory == laboratory, Certificate.series == series))
        counter = (last or 0) + 1
        number = number_for(counter)
        if _exists(store, laboratory, number):
            raise InputError(f"certificate number {number} was issued before by {laboratory}; "
                             "a number is never given twice (amend with 'axiscal certificate "
                             "reissue')")
        doc = render(number)
        now = dt.datetime.now(dt.timezone.utc).replace(tzinfo=None)
        row = Certificate(test_id=test_id, laboratory=laboratory, series=series,
                          counter=counter, number=number, customer=customer[:400],
                          issued=issued, status=ISSUED, reason=reason, media_type=media_type,
                          document=doc, sha256=hashlib.sha256(doc).hexdigest(),
                          inputs_json=json.dumps(inputs), created=now)
        if _commit(store, row, laboratory, replaces):
            return fetch(store, number, laboratory)
    raise InputError(f"no free certificate number for {laboratory} after {ATTEMPTS} attempts "
                     "(other processes issue at the same time); try again")


def listing(store, laboratory: str | None = None,
            test_id: int | None = None) -> list[CertificateRecord]:
    """Every certificate of the register (of one laboratory, of one test), newest first,
    without documents (which are not read)."""
    from sqlalchemy import select

    from axiscal.store.models import Certificate

    c = Certificate.__table__.c            # plain rows, the documents not read
    q = (select(*(col for col in c if col.key not in ("document", "inputs_json")))
         .order_by(c.created.desc(), c.id.desc()))
    if laboratory:
        q = q.where(c.laboratory == laboratory)
    if test_id is not None:
        q = q.where(c.test_id == test_id)
    with store._guard("read"), store._session() as s:
        rows = s.connection().execute(q).all()
        links = _links(s) if rows else {}
        return [_record(r, links, with_document=False) for r in rows]


def fetch(store, number: str, laboratory: str | None = None) -> CertificateRecord:
    """One certificate with its document; the document's SHA-256 is checked against the one kept."""
    from sqlalchemy import select

    from axiscal.store.database import NotFoundError, StoreError
    from axiscal.store.models import Certificate

    q = select(Certificate).where(Certificate.number == number)
    if laboratory:
        q = q.where(Certificate.laboratory == laboratory)
    with store._guard("read"), store._session() as s:
        rows = s.scalars(q).all()
        if not rows:
            raise NotFoundError(f"no certificate {number} in the register")
        if len(rows) > 1:
            labs = ", ".join(sorted(c.laboratory for c in rows))
            raise InputError(f"certificate {number} was issued by {len(rows)} laboratories "
                             f"({labs}); name the laboratory")
        rec = _record(rows[0], _links(s), with_document=True)
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


def _commit(store, row, laboratory: str, replaces: str) -> bool:
    """Insert ``row`` (and supersede ``replaces``) in one transaction; False if the counter or
    number was taken meanwhile."""
    from sqlalchemy import select
    from sqlalchemy.exc import IntegrityError

    from axiscal.store.database import NotFoundError
    from axiscal.store.models import Certificate

    with store._guard("store"), store._session(write=True) as s:
        try:
            if replaces:
                old = s.scalars(select(Certificate).where(
                    Certificate.laboratory == laboratory, Certificate.number == replaces)).first()
                if old is None:
                    raise NotFoundError(f"no certificate {replaces} of {laboratory} to replace")
                if old.status != ISSUED:
                    raise InputError(f"certificate {replaces} is already superseded; amend the "
                                     "certificate that replaced it")
                old.status = SUPERSEDED
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


def _record(c, links, with_document: bool) -> CertificateRecord:
    replaced_by = next((n for i, (n, r) in links.items() if r == c.id), "")
    replaces = links[c.replaces_id][0] if c.replaces_id in links else ""
    return CertificateRecord(
        c.number, c.laboratory, c.test_id, c.customer, c.issued, c.status, c.media_type,
        c.sha256, c.created, replaces, replaced_by, c.reason,
        c.document if with_document else b"",
        json.loads(c.inputs_json) if with_document else {})
