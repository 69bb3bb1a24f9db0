"""Corrections that lose nothing (issue 31; ISO/IEC 17025:2017 §7.5.2, §8.4.2): rename, merge,
edit, withdraw and reinstate, each an entry of the audit trail, on SQLite and PostgreSQL."""

from __future__ import annotations

import numpy as np
import pytest

from axiscal.errors import InputError
from axiscal.store import NotFoundError, open_store, trend
from axiscal.store import corrections as c
from axiscal.store.analysis import compare_tests
from tests.store.test_history import _dataset, _raw

WHO = {"by": "A. Engineer", "reason": "typed wrong at the machine"}


def _history(db_url, machine="VMC-800", n=4, axis="X"):
    s = open_store(db_url)
    rng = np.random.default_rng(31)
    ids = [s.add(_raw(_dataset(rng, machine=machine, axis=axis, date=f"202{k}-05-01",
                               offset=1.5 * k)), f"{machine}{axis}{k}.csv").id
           for k in range(n)]
    return s, ids


def _test_rows(s) -> int:
    from sqlalchemy import func, select

    from axiscal.store.models import Test

    with s._session() as ses:
        return ses.scalar(select(func.count(Test.id)))


def test_rename_machine_keeps_id_and_old_name_in_the_trail(db_url):
    s, ids = _history(db_url)
    mid = s.machines()[0].id
    e = c.rename_machine(s, "VMC-800", "DMU 50 S/N 1234", **WHO)
    assert [m.name for m in s.machines()] == ["DMU 50 S/N 1234"]
    assert s.machines()[0].id == mid
    assert s.get(ids[0]).summary.machine == "DMU 50 S/N 1234"
    assert (e.old, e.new, e.by, e.reason) == ({"name": "VMC-800"}, {"name": "DMU 50 S/N 1234"},
                                              "A. Engineer", "typed wrong at the machine")
    assert c.machine_id(s, "VMC-800") == mid == c.machine_id(s, "DMU 50 S/N 1234")
    assert [a.action for a in c.audit(s, machine=mid)] == ["rename-machine"]
    c.rename_axis(s, mid, "x", "x1", **WHO)
    assert s.machines()[0].axes == ("X1",)
    with pytest.raises(InputError, match="merge"):
        _rename_to_taken(s)


def _rename_to_taken(s, taken="DMU 50 S/N 1234"):
    s2 = s.add(_raw(_dataset(np.random.default_rng(2), machine="other")), "o.csv")
    assert s2.machine == "other"
    c.rename_machine(s, "other", taken, **WHO)


def test_merge_machines_moves_every_test_and_deletes_none(db_url):
    s, a = _history(db_url, "VMC-800", 2)
    _, b = _history(db_url, "VMC 800", 2, axis="Y")
    s.add(_raw(_dataset(np.random.default_rng(5), machine="VMC 800", axis="X",
                        date="2026-01-01")), "x.csv")
    before = _test_rows(s)
    dst = c.machine_id(s, "VMC-800")
    e = c.merge_machines(s, "VMC 800", "VMC-800", **WHO)
    assert _test_rows(s) == before == 5
    (m,) = s.machines()
    assert (m.name, m.axes, m.tests, m.id) == ("VMC-800", ("X", "Y"), 5, dst)
    assert e.new["tests_moved"] == {"X": 1, "Y": 2} and e.old["name"] == "VMC 800"
    assert c.machine_id(s, "VMC 800") == dst        # the old name leads to the merged machine
    assert len(trend(s, "VMC-800", "X", "E").values) == 3


def test_merge_axes(db_url):
    s, _ = _history(db_url, n=2)
    s.add(_raw(_dataset(np.random.default_rng(6), axis="X2", date="2026-01-01")), "x2.csv")
    e = c.merge_axes(s, "VMC-800", "x2", "x", **WHO)
    assert s.machines()[0].axes == ("X",) and e.new["tests_moved"] == 1
    assert len(trend(s, "VMC-800", "X", "E").values) == 3


def test_edit_keeps_old_values_in_the_trail(db_url):
    s, ids = _history(db_url, n=1)
    e = c.edit_test(s, ids[0], date="2024-02-03", operator="K. Ng", note="after the crash",
                    instrument="XL-80 #123", **WHO)
    t = s.get(ids[0])
    assert (t.summary.tested_at.isoformat(), t.operator, t.summary.note, t.instrument) == \
        ("2024-02-03T00:00:00", "K. Ng", "after the crash", "XL-80 #123")
    assert e.old == {"date": "2020-05-01T00:00:00", "operator": "", "note": "",
                     "instrument": ""}
    assert [x.id for x in c.audit(s, test_id=ids[0])] == [e.id]
    with pytest.raises(InputError, match="only date, operator, instrument, note"):
        c.edit_test(s, ids[0], axis="Y", **WHO)


def test_withdrawn_test_leaves_trend_and_compare_but_stays(db_url):
    s, ids = _history(db_url)
    assert len(trend(s, "VMC-800", "X", "E").values) == 4
    c.withdraw(s, ids[1], by="A. Engineer", reason="laser beam clipped on run 3")
    tr = trend(s, "VMC-800", "X", "E")
    assert len(tr.values) == 3 and ids[1] not in tr.test_ids
    t = s.get(ids[1])                                 # retrievable, marked
    assert t.summary.withdrawn == "laser beam clipped on run 3"
    assert {x.id: x.withdrawn for x in s.tests()}[ids[1]] == "laser beam clipped on run 3"
    with pytest.raises(InputError, match="withdrawn"):
        compare_tests(s.get(ids[0]), t)
    assert _test_rows(s) == 4
    c.reinstate(s, ids[1], by="B. Lead", reason="clipping was on run 3 only, re-evaluated")
    assert len(trend(s, "VMC-800", "X", "E").values) == 4
    trail = c.audit(s, test_id=ids[1])
    assert [(x.action, x.by) for x in trail] == [("reinstate", "B. Lead"),
                                                 ("withdraw", "A. Engineer")]
    assert trail[0].old == {"withdrawn": True, "reason": "laser beam clipped on run 3"}


def test_refusals_change_nothing(db_url):
    s, ids = _history(db_url, n=1)
    for kw, match in (({"by": "", "reason": "x"}, "who"), ({"by": "me", "reason": " "}, "why")):
        with pytest.raises(InputError, match=match):
            c.withdraw(s, ids[0], **kw)
    with pytest.raises(NotFoundError):
        c.withdraw(s, 10**6, **WHO)
    with pytest.raises(NotFoundError):
        c.rename_machine(s, "nope", "x", **WHO)
    with pytest.raises(InputError, match="itself"):
        c.merge_machines(s, "VMC-800", "VMC-800", **WHO)
    with pytest.raises(InputError, match="date"):
        c.edit_test(s, ids[0], date="yesterday", **WHO)
    with pytest.raises(InputError, match="merge"):
        _rename_to_taken(s, "VMC-800")
    assert s.get(ids[0]).summary.withdrawn == "" and c.audit(s) == []
    assert sorted(m.name for m in s.machines()) == ["VMC-800", "other"]
