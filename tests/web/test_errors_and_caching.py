"""Issue 40: the Origin check compares scheme, host and port (RFC 6454 §4), pages of a session
are never cached (``Cache-Control: no-store``: Back after log-out asks the server again),
``/favicon.ico`` is served, and a request without a live session is told where to log in."""

from __future__ import annotations

import re
from pathlib import Path

from fastapi.testclient import TestClient

from axiscal.web.app import create_app
from tests.web.conftest import log_in


def _client(tmp_path, base="http://127.0.0.1", **kw) -> TestClient:
    return TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}", **kw), base_url=base)


def _csrf(c) -> str:
    return re.search(r'name="csrf-token" content="([^"]*)"', c.get("/plan").text).group(1)


def test_origin_of_another_scheme_is_another_site(tmp_path):
    """RFC 6454 §4: an origin is (scheme, host, port). A POST to the http server whose Origin
    says https on the same host and port is refused; the same server behind https (a proxy
    that says so) takes https and refuses http."""
    c = _client(tmp_path)
    form = {"csrf": _csrf(c), "kind": "linear", "travel": "800"}
    assert c.post("/plan", data=form, headers={"origin": "http://127.0.0.1"}).status_code == 200
    for origin in ("https://127.0.0.1", "https://127.0.0.1:80", "https://127.0.0.1:443"):
        r = c.post("/plan", data=form, headers={"origin": origin})
        assert r.status_code == 403 and "another site" in r.text, origin
    r = c.post("/plan", data=form, headers={"referer": "https://127.0.0.1/plan"})
    assert r.status_code == 403
    s = _client(tmp_path, base="https://127.0.0.1")
    form["csrf"] = _csrf(s)
    assert s.post("/plan", data=form, headers={"origin": "https://127.0.0.1"}).status_code == 200
    assert s.post("/plan", data=form, headers={"origin": "http://127.0.0.1:443"}).status_code \
        == 403


def test_pages_of_a_session_are_not_stored_assets_are(tmp_path, users):
    c = _client(tmp_path, users_file=users, require_login=True)
    assert log_in(c, "eng", "correct horse battery").status_code == 303
    for path in ("/", "/plan", "/audit", "/upload", "/no-such-page"):
        r = c.get(path)
        assert r.headers.get("cache-control") == "no-store", path
    assert "no-store" not in c.get("/static/axiscal.css").headers.get("cache-control", "")


def test_favicon_is_served_without_a_session(tmp_path, users):
    c = _client(tmp_path, users_file=users, require_login=True)
    r = c.get("/favicon.ico", follow_redirects=False)
    assert r.status_code == 200 and r.headers["content-type"] == "image/x-icon"
    assert r.content[:4] == b"\x00\x00\x01\x00"          # an ICO file's header


def test_refusals_of_an_htmx_post_carry_their_words_for_the_form(tmp_path, users):
    """htmx swaps nothing on a 4xx/5xx answer; the page's script shows the answer's
    ``role="alert"`` words at the form (static/axiscal.js). Each refusal of the sign-off POST
    has them: 401 (session ended, nothing done), 403 (token), 413 (too large, before reading)."""
    c = _client(tmp_path, users_file=users, require_login=True, upload_limit=1000)
    hx = {"HX-Request": "true"}
    r = c.post("/tests/1/signoff", data={"action": "verdict"}, headers=hx)
    assert r.status_code == 401 and re.search(r'role="alert">[^<]*session has ended', r.text)
    assert 'href="/login?' in r.text
    assert log_in(c, "eng", "correct horse battery").status_code == 303
    r = c.post("/tests/1/signoff", data={"csrf": "stale", "action": "verdict"}, headers=hx)
    assert r.status_code == 403 and re.search(r'role="alert">[^<]*CSRF', r.text)
    r = c.post("/tests/1/signoff", headers=hx, data={"csrf": "x"},
               files={"drift_check": ("d.csv", b"0.1\n" * 2_000_000, "text/csv")})
    assert r.status_code == 413 and re.search(r'role="alert">[^<]*MiB', r.text)
    js = (Path(create_app.__code__.co_filename).parent / "static" / "axiscal.js").read_text()
    assert "htmx:responseError" in js and "htmx:sendError" in js and "expired=1" in js
