"""The certificate register (issues 28, 38) on SQLite and PostgreSQL: numbers from the
laboratory's pattern and the register's counter, never from the data, keyed by the laboratory's
code (a renamed laboratory continues its counter); a second certificate of a test only as an
amendment; a reissue takes a new number that replaces the old, which is kept, superseded; no
date of issue in the future or behind the register; no certificate of a withdrawn test, and a
test withdrawn later marked beside its certificate; the issued bytes come back with their
SHA-256; 20 issuers at once never share a number and leave no gap."""

from __future__ import annotations

import hashlib
import threading
from pathlib import Path

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


def _issue(store, test_id, lab="PM", replaces="", reason="", **kw):
    return store.issue_certificate(
        test_id=test_id, laboratory=lab, series=f"{lab}|2026",
        number_for=kw.pop("number_for", lambda c: f"PM-2026-{c:05d}"),
        render=kw.pop("render", lambda n: f"%PDF certificate {n}".encode()),
        customer="Example Machining AG", issued=kw.pop("issued", "2026-11-24"),
        media_type="application/pdf", inputs={"config": {}}, replaces=replaces, reason=reason,
        laboratory_name=kw.pop("name", "Precision Metrology GmbH"), **kw)


def test_a_second_certificate_of_a_test_is_only_an_amendment(db_url):
    """Issue 38: the same command run twice issued two certificates of one test, neither naming
    the other; the second is refused and names the first and the way to amend it."""
    s = open_store(db_url)
    tid = s.add(_raw(), "x.csv").id
    a = _issue(s, tid)
    with pytest.raises(AxiscalError, match="test 1 has certificate PM-2026-00001 of PM .*"
                       "certificate reissue PM-2026-00001"):
        _issue(s, tid)
    assert len(s.certificates()) == 1
    b = _issue(s, s.add(_raw(2), "y.csv").id)
    assert (a.number, b.number) == ("PM-2026-00001", "PM-2026-00002")
    other = _issue(s, tid, lab="OL", number_for=lambda c: f"OL-{c}")
    assert other.number == "OL-1"                      # counters are per laboratory
    got = s.certificate("PM-2026-00001")
    assert got.document == b"%PDF certificate PM-2026-00001"
    assert got.sha256 == hashlib.sha256(got.document).hexdigest()


def test_a_renamed_laboratory_keeps_one_counter(db_url):
    """Issue 38: a full stop added to the company's name issued NKL-2026-00001 a second time and
    'certificate show' then failed ('issued by 2 laboratories'). The register is keyed by the
    code; the name is kept as printed."""
    from axiscal.report.issue import number_format

    s = open_store(db_url)
    numbers = []
    for seed, name in ((1, "Nordkap Kalibrier Labor"), (2, "Nordkap Kalibrier Labor.")):
        code, series, number_for = number_format({"company": {"name": name}}, "2026-11-24")
        assert (code, series) == ("NKL", "NKL|2026")
        numbers.append(s.issue_certificate(
            test_id=s.add(_raw(seed), f"{seed}.csv").id, laboratory=code, series=series,
            number_for=number_for, render=lambda n: n.encode(), customer="C",
            issued="2026-11-24", media_type="text/html", inputs={}, laboratory_name=name))
    assert [r.number for r in numbers] == ["NKL-2026-00001", "NKL-2026-00002"]
    shown = s.certificate("NKL-2026-00001")
    assert (shown.laboratory, shown.laboratory_name) == ("NKL", "Nordkap Kalibrier Labor")
    assert s.certificate("NKL-2026-00002", "Nordkap Kalibrier Labor.").test_id == 2
    assert len(s.certificates("NKL")) == 2


def test_date_of_issue_is_neither_future_nor_behind_the_register(db_url):
    """Issue 38: a date of issue in 2031 was accepted and numbered today, and a backdated one
    after later certificates."""
    import datetime as dt

    s = open_store(db_url)
    ids = [s.add(_raw(seed), f"{seed}.csv").id for seed in (1, 2, 3)]
    with pytest.raises(AxiscalError, match="date of issue 2031-01-01 is in the future"):
        _issue(s, ids[0], issued="2031-01-01")
    with pytest.raises(AxiscalError, match="date of issue 2026-11-25 is in the future"):
        _issue(s, ids[0], issued="2026-11-25", today=dt.date(2026, 11, 24))
    _issue(s, ids[0], issued="2026-11-24")
    with pytest.raises(AxiscalError, match="2026-11-20 is before 2026-11-24, the date of PM's "
                       "last certificate PM-2026-00001"):
        _issue(s, ids[1], issued="2026-11-20")
    assert _issue(s, ids[1], issued="2026-11-24").number == "PM-2026-00002"   # same day: yes
    assert _issue(s, ids[2], issued="2026-11-20", lab="OL").issued == "2026-11-20"  # per lab
    assert len(s.certificates()) == 3


def test_a_withdrawn_test_is_never_certified_and_a_later_withdrawal_is_shown(db_url):
    """Issue 38: a withdrawn test could be certified ('CONFORMS', withdrawal not mentioned),
    and withdrawing a test left its certificate 'issued' with nothing said."""
    from axiscal.store.corrections import withdraw

    s = open_store(db_url)
    gone, kept = s.add(_raw(1), "a.csv").id, s.add(_raw(2), "b.csv").id
    withdraw(s, gone, by="QA", reason="wrong reflector")
    with pytest.raises(AxiscalError, match="test 1 is withdrawn \\(wrong reflector\\): a "
                       "withdrawn test is never certified"):
        _issue(s, gone)
    assert s.certificates() == []
    n = _issue(s, kept).number
    assert s.certificate(n).test_withdrawn == ""
    withdraw(s, kept, by="QA", reason="laser not warmed up")
    shown = s.certificate(n)
    assert shown.status == "issued" and shown.test_withdrawn == "laser not warmed up"
    assert "TEST WITHDRAWN after issue: laser not warmed up" in str(shown)
    assert s.certificates()[0].test_withdrawn == "laser not warmed up"


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
        _issue(s, s.add(_raw(2), "y.csv").id, number_for=lambda c: "PM-FIXED-1")


def test_altered_document_is_detected(db_url):
    from sqlalchemy import update

    from axiscal.store.models import Certificate

    s = open_store(db_url)
    n = _issue(s, s.add(_raw(), "x.csv").id).number
    with s.engine.begin() as c:
        c.execute(update(Certificate).values(document=b"%PDF forged"))
    with pytest.raises(AxiscalError, match="does not match its SHA-256"):
        s.certificate(n)


def test_twenty_issuers_at_once_never_share_a_number_and_leave_no_gap(db_url):
    """Issue 38: 20 issuers, each with its own connection and its own test, all render between
    reading the counter and writing (a barrier makes them read the same counter): every insert
    but one loses on the unique constraint and takes the next number; 20 numbers, 1 to 20."""
    first = open_store(db_url)
    ids = [first.add(_raw(seed), f"{seed}.csv").id for seed in range(20)]
    stores = [open_store(db_url) for _ in ids]
    barrier = threading.Barrier(20)
    numbers, errors = [], []

    def render(n):
        try:
            barrier.wait(timeout=2)
        except threading.BrokenBarrierError:
            pass
        return n.encode()

    def work(store, tid):
        try:
            numbers.append(_issue(store, tid, render=render).number)
        except Exception as exc:  # noqa: BLE001 - reported below
            errors.append(exc)

    threads = [threading.Thread(target=work, args=a) for a in zip(stores, ids)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    assert sorted(numbers) == [f"PM-2026-{i:05d}" for i in range(1, 21)]
    assert sorted(r.test_id for r in first.certificates()) == ids


def test_two_issuers_of_one_test_give_one_certificate(db_url):
    """The same test issued from two connections at once: one certificate, one refusal."""
    s1, s2 = open_store(db_url), open_store(db_url)
    tid = s1.add(_raw(), "x.csv").id
    barrier = threading.Barrier(2)
    out = []

    def render(n):
        try:
            barrier.wait(timeout=2)
        except threading.BrokenBarrierError:
            pass
        return n.encode()

    def work(store):
        try:
            out.append(_issue(store, tid, render=render).number)
        except AxiscalError as exc:
            out.append(str(exc))

    threads = [threading.Thread(target=work, args=(st,)) for st in (s1, s2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert sorted(out)[0] == "PM-2026-00001"
    assert "a second certificate of the same test is an amendment" in sorted(out)[1]
    assert len(s1.certificates()) == 1


def test_an_old_register_keyed_by_name_is_keyed_by_code(tmp_path):
    """Migration 0005 on a register of revision 0004 holding the fault: NKL-2026-00001 issued
    twice, under two spellings of the name. The first becomes NKL's, the second keeps its
    name as key (nothing lost); the next number continues NKL's counter."""
    from alembic import command
    from alembic.config import Config
    from sqlalchemy import create_engine, text

    import axiscal.store.history as h

    url = f"sqlite:///{tmp_path / 'old.sqlite'}"
    engine = create_engine(url)
    cfg = Config()
    cfg.set_main_option("script_location", str(Path(h.__file__).parent / "migrations"))
    raw = _raw()
    with engine.begin() as conn:
        cfg.attributes["connection"] = conn
        command.upgrade(cfg, "0004")
        conn.execute(text("insert into machine (id, name, maker, model, serial, location, "
                          "created) values (1, 'M', '', '', '', '', '2026-01-01')"))
        conn.execute(text("insert into axis (id, machine_id, name, kind) values (1, 1, 'X', "
                          "'linear')"))
        conn.execute(text(
            "insert into test (id, axis_id, kind, tested_at, date_known, stored_at, instrument, "
            "operator, note, filename, sha256, raw, dataset_json, result_json, environment_json, "
            "axiscal_version, withdrawn) values (1, 1, 'iso230-2', '2026-01-02', true, "
            "'2026-01-02', '', '', '', 'x.csv', :sha, :raw, '', '{}', '{}', '0.0.1', '')"),
            {"raw": raw, "sha": hashlib.sha256(raw).hexdigest()})
        for i, name in ((1, "Nordkap Labor"), (2, "Nordkap Labor.")):
            conn.execute(text(
                "insert into certificate (id, test_id, laboratory, series, counter, number, "
                "customer, issued, status, reason, media_type, document, sha256, inputs_json, "
                "created) values (:i, 1, :name, 'NKL|2026', 1, 'NKL-2026-00001', 'C', "
                "'2026-11-01', 'issued', '', 'text/html', :doc, :sha, '{}', '2026-11-01')"),
                {"i": i, "name": name, "doc": b"d%d" % i,
                 "sha": hashlib.sha256(b"d%d" % i).hexdigest()})
    engine.dispose()
    s = open_store(url)
    rows = sorted((r.laboratory, r.laboratory_name) for r in s.certificates())
    assert rows == [("NKL", "Nordkap Labor"), ("Nordkap Labor.", "Nordkap Labor.")]
    assert s.certificate("NKL-2026-00001", "NKL").document == b"d1"
    nxt = s.issue_certificate(
        test_id=s.add(_raw(5), "y.csv").id, laboratory="NKL", series="NKL|2026",
        number_for=lambda c: f"NKL-2026-{c:05d}", render=lambda n: n.encode(), customer="C",
        issued="2026-11-24", media_type="text/html", inputs={})
    assert nxt.number == "NKL-2026-00002"
