"""Corrections in the workbench (issue 31): a machine of any name (a "/" in it) reachable by id,
rename, merge, edit, withdraw and reinstate through forms with the CSRF token, every change in
the audit trail on the page; a withdrawn test marked and out of the trend."""

from __future__ import annotations

import html
import re

import numpy as np
from fastapi.testclient import TestClient

from axiscal.web.app import create_app
from tests.store.test_history import _dataset, _raw

SLASH = "DMU 50 S/N 1234"


def _client(tmp_path):
    from axiscal.store import open_store

    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    s = open_store(url)
    rng = np.random.default_rng(4)
    for k in range(3):
        s.add(_raw(_dataset(rng, machine=SLASH, date=f"202{k}-05-01", offset=k)), f"{k}.csv")
    s.add(_raw(_dataset(rng, machine="DMU 50", axis="Y")), "y.csv")
    c = TestClient(create_app(url), base_url="http://127.0.0.1")
    tok = re.search(r'csrf-token" content="([^"]+)"', c.get("/").text).group(1)
    return c, tok


def _post(c, path, **data):
    return c.post(path, data=data, follow_redirects=True)


def test_a_machine_with_a_slash_is_reachable_from_every_link(tmp_path):
    c, _ = _client(tmp_path)
    home = c.get("/").text
    link = re.search(r'<a href="(/machine/\d+)">DMU 50 S/N 1234</a>', home).group(1)
    page = c.get(link)
    assert page.status_code == 200 and "<h1>DMU 50 S/N 1234</h1>" in page.text
    for href in set(re.findall(r'href="(/(?:machine|tests|trend)[^"]*)"', page.text)):
        assert c.get(href.replace("&amp;", "&")).status_code == 200, href
    test = c.get("/tests/1").text
    axis_link = re.search(r'<a href="([^"]+)">the axis\'s history</a>', test).group(1)
    assert c.get(axis_link.replace("&amp;", "&")).status_code == 200
    old = c.get("/machines/DMU 50 S%2FN 1234?axis=X")          # an old link, by name
    assert old.status_code == 200 and str(old.url).endswith(f"{link}?axis=X")


def test_rename_merge_withdraw_with_the_audit_trail_on_the_page(tmp_path):
    c, tok = _client(tmp_path)
    mid = int(re.search(r'/machine/(\d+)">DMU 50 S/N 1234', c.get("/").text).group(1))
    other = int(re.search(r'/machine/(\d+)">DMU 50<', c.get("/").text).group(1))
    r = _post(c, f"/machine/{mid}/rename", csrf=tok, name="DMU 50 / 1234", by="A. Ng",
              reason="serial written as on the plate")
    assert r.status_code == 200 and "<h1>DMU 50 / 1234</h1>" in r.text
    trail = r.text.split('id="audit"')[1].split("</table>")[0]
    assert "A. Ng" in trail and "serial written as on the plate" in trail
    assert "name: DMU 50 S/N 1234" in trail and "name: DMU 50 / 1234" in trail
    r = _post(c, "/tests/2/withdraw", csrf=tok, by="A. Ng", reason="beam clipped")
    assert 'id="withdrawn"' in r.text and "beam clipped" in r.text
    machine = c.get(f"/machine/{mid}").text
    assert machine.count('class="withdrawn"') == 1 and "WITHDRAWN</strong>: beam clipped" in machine
    trend = c.get("/trend", params={"machine": "DMU 50 / 1234", "axis": "X"})
    assert trend.status_code == 200 and "E over 2 tests" in trend.text
    assert c.get("/compare?a=1&b=2").status_code == 400
    r = _post(c, "/tests/1/edit", csrf=tok, date="2019-01-02", operator="K. Ng",
              instrument="", note="", by="A. Ng", reason="date from the log book")
    assert "operator: K. Ng" in r.text and "date: 2019-01-02T00:00:00" in r.text
    r = _post(c, f"/machine/{other}/merge", csrf=tok, into=str(mid), by="A. Ng",
              reason="one machine")
    assert r.status_code == 200 and str(r.url).endswith(f"/machine/{mid}")
    assert "merged into" in r.text and "Y" in r.text.split("Axes:")[1].split("</p>")[0]
    assert c.get("/machines/DMU 50").url.path == f"/machine/{mid}"   # the merged name leads on
    audit = html.unescape(c.get("/audit").text)
    whats = re.findall(r"<td[^>]*>(?:<a href=\"[^\"]+\">)?(machine '[^<]*|test \d[^<]*)<", audit)
    assert whats == [f"machine 'DMU 50' (id {other}) merged into 'DMU 50 / 1234'",
                     "test 1: date, operator edited", "test 2 withdrawn",
                     "machine 'DMU 50 S/N 1234' renamed 'DMU 50 / 1234'"], whats
    assert c.get("/tests/2").status_code == 200      # nothing deleted


def test_refusals_are_pages_and_change_nothing(tmp_path):
    c, tok = _client(tmp_path)
    r = _post(c, "/tests/1/withdraw", csrf=tok, by="A. Ng", reason="")
    assert r.status_code == 400 and "say why" in r.text
    r = _post(c, "/tests/1/withdraw", csrf="nope", by="A. Ng", reason="x")
    assert r.status_code == 403
    r = _post(c, "/tests/1/edit", csrf=tok, date="2020-05-01", by="A. Ng", reason="x")
    assert r.status_code == 400 and "nothing to change" in r.text
    assert _post(c, "/machine/1/merge", csrf=tok, into="abc", by="A", reason="x"
                 ).status_code == 400
    assert c.get("/machine/99").status_code == 404
    assert c.get("/machines/nothing here").status_code == 404
    assert "No change recorded" in c.get("/audit").text


def test_a_viewer_cannot_correct_and_an_engineer_is_the_one_recorded(tmp_path, users):
    from tests.web.conftest import log_in

    _client(tmp_path)                                           # the history, filled
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}", users, require_login=True),
                   base_url="http://127.0.0.1")
    log_in(c, "view", "staple battery horse")
    page = c.get("/tests/1").text
    assert 'id="withdraw-test"' not in page and 'id="audit"' in page   # the trail: readable
    tok = re.search(r'csrf-token" content="([^"]+)"', page).group(1)
    r = _post(c, "/tests/1/withdraw", csrf=tok, reason="x")
    assert r.status_code == 403 and "viewer" in r.text
    c.cookies.clear()
    log_in(c, "eng", "correct horse battery")
    page = c.get("/tests/1").text
    assert 'name="by"' not in page                         # the account is who, not a field
    tok = re.search(r'csrf-token" content="([^"]+)"', page).group(1)
    r = _post(c, "/tests/1/withdraw", csrf=tok, by="someone else", reason="beam clipped")
    trail = r.text.split('id="audit"')[1].split("</table>")[0]
    assert "class=\"who\">eng</td>" in trail and "someone else" not in trail


def test_what_is_typed_on_a_duplicate_upload_is_offered_as_a_correction(tmp_path):
    from axiscal.store import open_store

    c, tok = _client(tmp_path)
    raw = open_store(f"sqlite:///{tmp_path / 'h.sqlite'}").get(1).raw
    r = c.post("/upload", data={"csrf": tok, "note": "after the crash", "instrument": "XL-80"},
               files={"file": ("again.csv", raw, "text/csv")})
    assert r.status_code == 200 and r.url.path == "/tests/1"
    said = html.unescape(r.text.split('id="stored-again">')[1].split("</div>")[0])
    assert 'What you typed with it was not stored: instrument "XL-80"; note "after the crash".' \
        in said
    form = r.text.split('id="edit-test"')[1].split("</form>")[0]
    assert 'value="after the crash"' in form and 'value="XL-80"' in form
    assert '<details class="card" id="corrections" open>' in r.text
    r = _post(c, "/tests/1/edit", csrf=tok, date="", instrument="XL-80",
              note="after the crash", operator="", by="A. Ng", reason="typed on the upload")
    t = open_store(f"sqlite:///{tmp_path / 'h.sqlite'}").get(1)
    assert (t.summary.note, t.instrument, t.summary.tested_at.year) == \
        ("after the crash", "XL-80", 2020)


def test_hostile_names_and_reasons_are_text_in_the_trail(tmp_path):
    c, tok = _client(tmp_path)
    evil = '<script>alert("x")</script> & "/"'
    r = _post(c, "/machine/1/rename", csrf=tok, name=evil, by="<b>me</b>", reason="<i>why</i>")
    assert r.status_code == 200 and "<script>alert" not in r.text
    for page in (r.text, c.get("/audit").text):
        assert "&lt;script&gt;alert(&#34;x&#34;)&lt;/script&gt; &amp; &#34;/&#34;" in page
        assert "&lt;b&gt;me&lt;/b&gt;" in page and "&lt;i&gt;why&lt;/i&gt;" in page
    home = c.get("/").text                                   # the name and its axis, by id
    assert 'href="/machine/1">&lt;script&gt;' in home and 'href="/machine/1?axis=X"' in home
