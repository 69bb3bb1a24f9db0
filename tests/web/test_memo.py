"""A machine's history page kept by a worker while the history is unchanged (axiscal.web.memo),
read again after any write by anyone; the statements a page costs (issue 31)."""

from __future__ import annotations

import re
import subprocess
import sys

from fastapi.testclient import TestClient
from sqlalchemy import event

from axiscal.web import memo
from axiscal.web.app import create_app
from tests.store.test_queries import _file


def _client(tmp_path, monkeypatch):
    monkeypatch.setenv("AXISCAL_CACHE", str(tmp_path / "cache"))
    monkeypatch.setenv("AXISCAL_CONFIG", str(tmp_path / "none.toml"))
    memo.forget()
    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    app = create_app(url)
    c = TestClient(app, base_url="http://127.0.0.1")
    tok = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    for k in range(3):
        r = c.post("/upload", data={"csrf": tok},
                   files={"file": (f"x{k}.csv", _file(k, day=k + 1), "text/csv")})
        assert r.status_code == 200
    return c, app, url


def _selects(app) -> list:
    seen: list = []
    event.listen(app.state.store.engine, "before_cursor_execute",
                 lambda c, cur, sql, *a: seen.append(sql)
                 if sql.lstrip().upper().startswith("SELECT") else None)
    return seen


def _in_another_process(url: str, code: str) -> None:
    """Run ``code`` (with ``store`` open on ``url``) in a separate Python process, as another
    worker or the command line would write."""
    subprocess.run([sys.executable, "-c", "from axiscal.store import open_store, corrections\n"
                    f"from tests.store.test_queries import _file\nstore = open_store({url!r})\n"
                    + code], check=True, cwd=str(__import__("pathlib").Path(__file__)
                                                  .resolve().parents[2]))


def test_an_unchanged_history_page_costs_one_statement(tmp_path, monkeypatch):
    c, app, _ = _client(tmp_path, monkeypatch)
    first = c.get("/machine/1")
    seen = _selects(app)
    again = c.get("/machine/1")
    assert again.status_code == 200 and len(seen) == 1          # the generation, nothing else
    assert again.text == first.text
    seen.clear()
    memo.forget()                              # read again: one statement per read the page
    assert c.get("/machine/1").text == first.text      # makes, the trend's from its rows
    assert len(seen) == 8
    seen.clear()
    c.get("/machine/1?axis=X")                 # another page, read once: the trend's newest
    assert len(seen) == 10                     # test of the axis is read for it (2 more)


def test_a_write_from_another_process_shows_on_the_next_view(tmp_path, monkeypatch):
    """A new test, a withdrawal and a renamed machine, each written by another process, are on
    the page at the next view; so is an upload through the page."""
    c, app, url = _client(tmp_path, monkeypatch)
    page = c.get("/machine/1").text
    assert page.count('<a href="/tests/') == 3 and "3 tests in all" in page
    _in_another_process(url, "store.add(_file(7, day=20), 'new.csv')")
    page = c.get("/machine/1").text
    assert '<a href="/tests/4">4</a>' in page and "4 tests in all" in page
    _in_another_process(url, "corrections.withdraw(store, 2, by='ana', reason='loose mount')")
    assert "loose mount" in c.get("/machine/1").text
    _in_another_process(url, "corrections.rename_machine(store, 1, 'VMC Nord', by='ana', "
                        "reason='moved')")
    assert "<h1>VMC Nord</h1>" in c.get("/machine/1").text
    tok = re.search(r'csrf-token" content="([^"]+)"', page).group(1)
    c.post("/upload", data={"csrf": tok, "machine": "VMC Nord"},
           files={"file": ("y.csv", _file(8, machine="", day=21), "text/csv")})
    # (the form's machine names a file's machine only where the file names none: issue 40)
    assert '<a href="/tests/5">5</a>' in c.get("/machine/1").text


def test_a_test_page_reads_a_few_statements_and_never_the_bytes(tmp_path, monkeypatch):
    """A view of a stored test: the test (3 statements), its certificates, its audit trail and
    the other tests of its axis, and (issue 40) what the sign-off form starts from: the
    laboratory, the machine's last certificate, the test's drift checks (one indexed row
    each), read once for the page's U and the form alike; the sign-off saved for approval and
    the last certificate of the axis and kind (its tolerances), one row each; its stored bytes
    are not read (the evaluation is kept)."""
    c, app, _ = _client(tmp_path, monkeypatch)
    c.get("/tests/2")
    seen = _selects(app)
    r = c.get("/tests/2")
    assert r.status_code == 200 and 'id="parameters"' in r.text
    assert len(seen) <= 11
    assert not any(re.search(r"test\.raw\s*(,|FROM)", s) for s in seen)


def test_a_new_tests_page_is_made_with_the_upload(tmp_path, monkeypatch):
    """The test's page parts are made in the upload's thread before its answer (303), so the
    first view finds them kept and makes nothing; a duplicate makes nothing."""
    import axiscal.web.stored_test_page as pages

    c, app, _ = _client(tmp_path, monkeypatch)
    made = []
    real = pages._test_parts
    monkeypatch.setattr(pages, "_test_parts", lambda t, ev, *a: made.append(ev.kind) or
                        real(t, ev, *a))
    tok = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    r = c.post("/upload", data={"csrf": tok}, follow_redirects=False,
               files={"file": ("n.csv", _file(30, day=28), "text/csv")})
    assert r.status_code == 303 and made == ["iso230-2"]       # made once, with the upload
    page = c.get(r.headers["location"])
    assert page.status_code == 200 and 'id="parameters"' in page.text and len(made) == 1
    again = c.post("/upload", data={"csrf": tok}, follow_redirects=False,
                   files={"file": ("n2.csv", _file(30, day=28), "text/csv")})
    assert "stored=again" in again.headers["location"] and len(made) == 1   # nothing new
