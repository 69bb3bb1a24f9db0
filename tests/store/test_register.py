"""The certificate register (issue 28) on SQLite and PostgreSQL: numbers from the laboratory's
pattern and the register's counter, never from the data; two certificates of the same file get
two numbers; a reissue takes a new number that replaces the old, which is kept, superseded;
the issued bytes come back with their SHA-256; two writers at once never share a number."""

from __future__ import annotations

import hashlib
import threading

import numpy as np
import pytest

from axiscal.datasets import Metadata, PositioningDataset
from axiscal.errors import AxiscalError
from axiscal.io.csv import format_positioning_csv
from axiscal.store import open_store


def _raw(seed=1) -> bytes:
    rng = np.random.default_rng(seed)
    t = np.linspace(0, 800, 5)
    up = rng.normal(0, 2, (5, 5))
    return format_positioning_csv(PositioningDataset(
        "linear", t, up, up - 3, "mm", "um", Metadata(machine="VMC-800", axis="X",
                                                     date="2026-03-01"))).encode()


def _issue(store, test_id, lab="Precision Metrology GmbH", replaces="", reason="", **kw):
    return store.issue_certificate(
        test_id=test_id, laboratory=lab, series=f"{lab}|2026",
        number_for=kw.pop("number_for", lambda c: f"PM-2026-{c:05d}"),
        render=kw.pop("render", lambda n: f"%PDF certificate {n}".encode()),
        customer="Example Machining AG", issued="2026-11-24", media_type="application/pdf",
        inputs={"config": {}}, replaces=replaces, reason=reason)


def test_two_certificates_of_the_same_file_have_two_numbers(db_url):
    s = open_store(db_url)
    tid = s.add(_raw(), "x.csv").id
    a, b = _issue(s, tid), _issue(s, tid)
    assert (a.number, b.number) == ("PM-2026-00001", "PM-2026-00002")
    assert a.test_id == b.test_id == tid
    other = _issue(s, tid, lab="Other Lab", number_for=lambda c: f"OL-{c}")
    assert other.number == "OL-1"                      # counters are per laboratory
    got = s.certificate("PM-2026-00001")
    assert got.document == b"%PDF certificate PM-2026-00001"
    assert got.sha256 == hashlib.sha256(got.document).hexdigest()


def test_reissue_replaces_and_keeps_the_old(db_url):
    s = open_store(db_url)
    tid = s.add(_raw(), "x.csv").id
    old = _issue(s, tid)
    new = _issue(s, tid, replaces=old.number, reason="serial number corrected")
    assert new.number == "PM-2026-00002" and new.replaces == old.number
    assert new.reason == "serial number corrected" and new.status == "issued"
    kept = s.certificate(old.number)
    assert kept.status == "superseded" and kept.replaced_by == new.number
    assert kept.document == b"%PDF certificate PM-2026-00001"       # both retrievable
    assert [r.number for r in s.certificates()] == [new.number, old.number]
    with pytest.raises(AxiscalError, match="already superseded"):
        _issue(s, tid, replaces=old.number, reason="again")
    with pytest.raises(AxiscalError, match="replaces and the reason"):
        _issue(s, tid, replaces=new.number)
    assert len(s.certificates()) == 2                                # nothing half-done


def test_a_fixed_number_is_never_given_twice(db_url):
    s = open_store(db_url)
    tid = s.add(_raw(), "x.csv").id
    _issue(s, tid, number_for=lambda c: "PM-FIXED-1")
    with pytest.raises(AxiscalError, match="PM-FIXED-1 was issued before"):
        _issue(s, tid, number_for=lambda c: "PM-FIXED-1")


def test_altered_document_is_detected(db_url):
    from sqlalchemy import update

    from axiscal.store.models import Certificate

    s = open_store(db_url)
    n = _issue(s, s.add(_raw(), "x.csv").id).number
    with s.engine.begin() as c:
        c.execute(update(Certificate).values(document=b"%PDF forged"))
    with pytest.raises(AxiscalError, match="does not match its SHA-256"):
        s.certificate(n)


def test_two_writers_at_once_never_share_a_number(db_url):
    """Each writer renders slowly between reading the counter and writing: both read the same
    counter, one insert loses on the unique constraint and takes the next number."""
    s1, s2 = open_store(db_url), open_store(db_url)
    tid = s1.add(_raw(), "x.csv").id
    barrier = threading.Barrier(2)
    numbers, errors = [], []

    def render(n):
        try:
            barrier.wait(timeout=5)
        except threading.BrokenBarrierError:
            pass
        return n.encode()

    def work(store):
        try:
            for _ in range(3):
                numbers.append(_issue(store, tid, render=render).number)
        except Exception as exc:  # noqa: BLE001 - reported below
            errors.append(exc)

    threads = [threading.Thread(target=work, args=(st,)) for st in (s1, s2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    assert sorted(numbers) == [f"PM-2026-{i:05d}" for i in range(1, 7)]
