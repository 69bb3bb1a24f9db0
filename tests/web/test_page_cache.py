"""A test's page kept whole by a worker (axiscal.web.page_cache, issue 40): each viewer gets
their own CSRF token and the protective headers, a kept view costs one statement, and every
path that writes the history shows on the next view (never a stale page)."""

from __future__ import annotations

import re
import shutil

import pytest
from fastapi.testclient import TestClient

from axiscal.store import corrections, open_store
from axiscal.web import memo, page_cache
from axiscal.web.app import create_app
from tests.store.test_queries import _file
from tests.web.test_memo import _selects


@pytest.fixture(scope="module")
def template(tmp_path_factory):
    """A history of three tests of VMC X and one of another machine (their evaluations
    kept in a cache folder the module shares)."""
    d = tmp_path_factory.mktemp("page-cache")
    with pytest.MonkeyPatch.context() as m:
        m.setenv("AXISCAL_CACHE", str(d / "cache"))
        store = open_store(f"sqlite:///{d / 'h.sqlite'}")
        for k in range(3):
            store.add(_file(k, day=k + 1), f"x{k}.csv")
        store.add(_file(9, machine="Mill B", day=9), "b.csv")
        store.close()
    return d


@pytest.fixture
def site(template, tmp_path, monkeypatch):
    """(client, url) of a workbench over a copy of the template history."""
    monkeypatch.setenv("AXISCAL_CACHE", str(template / "cache"))
    monkeypatch.setenv("AXISCAL_CONFIG", str(tmp_path / "none.toml"))
    shutil.copy(template / "h.sqlite", tmp_path / "h.sqlite")
    memo.forget()
    page_cache.forget()
    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    return TestClient(create_app(url), base_url="http://127.0.0.1"), url


def _token(page: str) -> str:
    return re.search(r'csrf-token" content="([^"]+)"', page).group(1)


def test_a_kept_page_is_each_viewers_own_and_costs_one_statement(site):
    """Two people (two anonymous cookies) see the same kept page, each with their own CSRF
    token in every form and the headers of every page (no-store: Back after log-out asks
    again); a kept view reads only the history's generation; the page is byte for byte the
    page made afresh."""
    c, url = site
    first = c.get("/tests/2")
    other = TestClient(c.app, base_url="http://127.0.0.1")
    seen = _selects(c.app)
    again, theirs = c.get("/tests/2"), other.get("/tests/2")
    assert len(seen) == 2                            # one statement each: the generation
    mine, its = _token(again.text), _token(theirs.text)
    assert mine != its and page_cache.CSRF_MARK not in again.text
    assert again.text.count(f'value="{mine}"') == first.text.count(f'value="{mine}"') >= 2
    assert its in theirs.text and mine not in theirs.text
    assert again.text == first.text
    for r in (again, theirs):
        assert r.headers["cache-control"] == "no-store"
        assert r.headers["x-frame-options"] == "DENY" and "default-src" in \
            r.headers["content-security-policy"]
        assert r.headers["content-type"] == "text/html; charset=utf-8"
    page_cache.forget()
    assert c.get("/tests/2").text == first.text      # made again: the same page


def test_an_upload_elsewhere_keeps_the_page_but_lists_the_new_test(site):
    """A new test of the axis leaves the kept page as it is, and its list of tests to compare
    with shows the new one at once."""
    c, url = site
    assert "b=2" in c.get("/tests/2").text
    assert "/compare?a=5&amp;b=2" not in c.get("/tests/2").text
    open_store(url).add(_file(20, day=20), "new.csv")
    assert "/compare?a=5&amp;b=2" in c.get("/tests/2").text


def _withdraw(store):
    corrections.withdraw(store, 2, by="ana", reason="loose mount")


def _edit(store):
    corrections.edit_test(store, 2, by="ana", reason="typed", note="spindle warm")


def _rename(store):
    corrections.rename_machine(store, 1, "VMC Nord", by="ana", reason="moved")


def _rename_axis(store):
    corrections.rename_axis(store, 1, "X", "X1", by="ana", reason="two X axes")


def _merge(store):
    corrections.merge_machines(store, 1, "Mill B", by="ana", reason="one machine")


def _laboratory(store):
    from axiscal.store.laboratory import set_laboratory

    set_laboratory(store, {"company": {"name": "Kalibrierlabor Nord", "code": "KN"}},
                   by="ana", reason="entered")


def _drift_check(store):
    from axiscal.store.laboratory import add_drift_check

    add_drift_check(store, 2, b"reading\n0.1\n0.4\n-0.2\n", "dc-morning.csv", by="ana")


def _table(store):
    store.add_table(2, "fanuc", "table-written.txt", "N1 X0\n")


def _certificate(store):
    store.issue_certificate(
        test_id=2, laboratory="PM", series="PM|2026", number_for=lambda n: f"PM-2026-{n:05d}",
        render=lambda n: f"%PDF certificate {n}".encode(), customer="Example AG",
        issued="2026-11-24", media_type="application/pdf", inputs={"config": {}})


def _imported(store, tmp_path):
    from axiscal.store.archive import export_history, import_history

    src = open_store(f"sqlite:///{tmp_path / 'other.sqlite'}")
    src.add(_file(30, day=25), "imported.csv")
    export_history(src, tmp_path / "a.zip")
    import_history(store, tmp_path / "a.zip")


WRITES = {"withdraw": (_withdraw, "loose mount"), "edit": (_edit, "spindle warm"),
          "rename machine": (_rename, "VMC Nord"), "rename axis": (_rename_axis, "axis X1"),
          "merge machines": (_merge, "Mill B"), "laboratory": (_laboratory, "Kalibrierlabor Nord"),
          "drift check": (_drift_check, "dc-morning.csv"),
          "compensation table": (_table, "table-written.txt"),
          "certificate": (_certificate, "PM-2026-00001"),
          "import": (_imported, "/compare?a=5&amp;b=2")}


@pytest.mark.parametrize("path", WRITES)
def test_every_write_shows_on_the_next_view(site, tmp_path, path):
    """Each path that writes the history (by another store, as the command line or another
    worker process would) changes the kept test page at the next view."""
    c, url = site
    write, shown = WRITES[path]
    before = c.get("/tests/2").text
    assert shown not in before and c.get("/tests/2").text == before      # kept
    store = open_store(url)
    write(store, tmp_path) if path == "import" else write(store)
    after = c.get("/tests/2")
    assert after.status_code == 200 and shown in after.text, path


def test_a_refused_form_is_never_kept(site):
    """A sign-off refused at its form (an empty drift-check file: the reason beside the field)
    changes nothing kept: the next plain view is the page as it was, with no error."""
    c, _ = site
    before = c.get("/tests/2").text
    tok = _token(before)
    r = c.post("/tests/2/signoff", data={"csrf": tok, "action": "verdict", "operator": "ana"},
               files={"drift_check": ("dc.csv", b"", "text/csv")})
    assert "is empty" in r.text
    after = c.get("/tests/2").text
    assert "is empty" not in after and after == before


def test_a_page_made_again_reads_its_test_and_little_else(site):
    """A test's first view in a worker, once another test's page was made: the generation and
    the test (three statements); the laboratory, the machine's last certificate and which tests
    have certificates, drift checks or audit entries are kept under the generation, and a test
    without them is not asked for them."""
    c, _ = site
    c.get("/tests/1")
    seen = _selects(c.app)
    assert c.get("/tests/2").status_code == 200
    assert len(seen) == 4, seen
    seen.clear()
    _withdraw(open_store(c.app.state.db_url))                # an audit entry of test 2 now
    assert "loose mount" in c.get("/tests/2").text
    assert any("FROM audit" in s for s in seen)
