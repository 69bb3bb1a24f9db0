"""The workbench hardened (issue 31, "Security" and the error pages of "Rough edges"): Host
allow-list and Origin check, server-side sessions, password back-off, bounded bodies and fields,
and an error page of the workbench's own for every failure. In-process (FastAPI's TestClient);
the server's timeouts are in test_server_limits.py."""

from __future__ import annotations

import asyncio
import re
from html import unescape

import pytest
from fastapi.testclient import TestClient

from axiscal.web.app import create_app
from axiscal.web.security import UserFile
from axiscal.web.sessions import FREE_FAILURES, LoginThrottle, Sessions
from tests.web.conftest import log_in as _login

LOCAL = "http://127.0.0.1"


def _client(tmp_path, **kw) -> TestClient:
    return TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}", **kw), base_url=LOCAL)


def _csrf(client, path="/plan", **kw) -> str:
    return re.search(r'name="csrf-token" content="([^"]*)"', client.get(path, **kw).text).group(1)


def _stored(client) -> int:
    """Tests in the history behind the client's application."""
    return len(client.app.state.store.tests(limit=1000))


def _positioning_file() -> bytes:
    from tests.web.conftest import positioning_file

    return positioning_file()


def test_dns_rebinding_gets_neither_the_token_nor_a_stored_upload(tmp_path):
    """A page rebound to 127.0.0.1 under evil.example: its Host header names evil.example."""
    c = _client(tmp_path)
    evil = {"host": "evil.example"}
    r = c.get("/plan", headers=evil)
    assert r.status_code == 400 and "does not answer to that host name" in r.text
    assert _csrf(c, "/plan", headers=evil) == ""                   # no token to read
    assert c.get("/", headers=evil).status_code == 400             # nor the history
    token = _csrf(c)                                               # even with a good token
    r = c.post("/upload", data={"csrf": token}, headers=evil,
               files={"file": ("x.csv", _positioning_file(), "text/csv")})
    assert r.status_code == 400 and _stored(c) == 0
    for good in ("127.0.0.1:8000", "localhost", "LOCALHOST:1", "[::1]:8000"):
        assert c.get("/plan", headers={"host": good}).status_code == 200, good
    for bad in ("evil.example", "127.0.0.1.evil.example", "user@127.0.0.1", "[::1", ""):
        assert c.get("/plan", headers={"host": bad}).status_code == 400, bad
    named = _client(tmp_path, hosts=["127.0.0.1", "bench.shop.local"])
    assert named.get("/plan", headers={"host": "bench.shop.local:8000"}).status_code == 200


def test_every_post_must_come_from_this_site(tmp_path):
    """OWASP CSRF Prevention Cheat Sheet, "Verifying origin with standard headers"."""
    c = _client(tmp_path)
    form = {"csrf": _csrf(c), "kind": "linear", "travel": "800"}
    assert c.post("/plan", data=form, headers={"origin": LOCAL}).status_code == 200
    assert c.post("/plan", data=form,
                  headers={"referer": LOCAL + "/plan"}).status_code == 200
    for headers in ({"origin": "http://evil.example"}, {"origin": "null"},
                    {"origin": "http://127.0.0.1:9999"}, {"origin": "ftp://127.0.0.1"},
                    {"referer": "http://evil.example/page"}):
        r = c.post("/plan", data=form, headers=headers)
        assert r.status_code == 403 and "another site" in r.text, headers
    r = c.post("/upload", data=form, headers={"origin": "http://evil.example"},
               files={"file": ("x.csv", _positioning_file(), "text/csv")})
    assert r.status_code == 403 and _stored(c) == 0


def test_logout_ends_the_session_for_every_copy_of_the_cookie(tmp_path, users):
    c = _client(tmp_path, users_file=users, require_login=True)
    assert _login(c, "eng", "correct horse battery").status_code == 303
    copied = dict(c.cookies)
    assert c.get("/", follow_redirects=False).status_code == 200
    assert c.post("/logout", follow_redirects=False).status_code == 303
    thief = TestClient(c.app, base_url=LOCAL, cookies=copied)     # another client, same server
    r = thief.get("/", follow_redirects=False)
    assert r.status_code == 303 and r.headers["location"].startswith("/login")
    assert len(c.app.state.sessions) == 0


def test_sessions_end_when_idle_and_after_their_lifetime():
    now = [0.0]
    s = Sessions(idle=60, absolute=300, clock=lambda: now[0])
    a = s.issue("eng", "engineer")
    assert s.read(a)["role"] == "engineer" and s.read(a)["csrf"]
    for t in (50, 100, 150, 200, 250, 299):           # active: never 60 s idle
        now[0] = t
        assert s.read(a) is not None, t
    now[0] = 301                                       # past the absolute lifetime
    assert s.read(a) is None
    b = s.issue("eng", "engineer")
    now[0] = 301 + 61                                  # idle too long
    assert s.read(b) is None
    assert s.read("forged") is None and s.read(None) is None and s.read("x" * 10_000) is None
    c = s.issue("eng", "engineer")
    assert c not in repr(s._live)                      # only a hash of the cookie is kept
    assert s.revoke(c) and s.read(c) is None and not s.revoke(c)


def test_wrong_passwords_lock_the_account_and_the_page_says_for_how_long(tmp_path, users):
    c = _client(tmp_path, users_file=users, require_login=True)
    for _ in range(FREE_FAILURES):
        assert _login(c, "eng", "wrong password").status_code == 401
    r = _login(c, "eng", "correct horse battery")      # even the right one, while locked
    assert r.status_code == 429 and "too many wrong passwords" in r.text
    seconds = int(re.search(r"try again in (\d+) s", r.text).group(1))
    assert 0 < seconds <= 30 and r.headers["retry-after"] == str(seconds)


def test_back_off_grows_per_account_and_per_address():
    now = [0.0]
    t = LoginThrottle(base=30, free=3, clock=lambda: now[0])
    for _ in range(3):
        assert t.wait("eng", "10.0.0.1") == 0
        t.failed("eng", "10.0.0.1")
    assert t.wait("eng", "10.0.0.9") == 30            # the account, from anywhere
    assert t.wait("ann", "10.0.0.1") == 30            # the address, for any account
    assert t.wait("ann", "10.0.0.9") == 0             # others are not held up
    now[0] = 31
    assert t.wait("eng", "10.0.0.1") == 0
    t.failed("eng", "10.0.0.1")                       # the fourth: twice as long
    assert t.wait("eng", "10.0.0.9") == 60
    t.succeeded("eng", "10.0.0.1")
    assert t.wait("eng", "10.0.0.1") == 0


def test_the_password_is_checked_in_a_worker_thread(tmp_path, users, monkeypatch):
    """Argon2id verification takes tens of ms of CPU: never on the event loop."""
    seen = []
    original = UserFile.check

    def check(self, name, password):
        try:
            asyncio.get_running_loop()
            seen.append("event loop")
        except RuntimeError:
            seen.append("worker thread")
        return original(self, name, password)

    monkeypatch.setattr(UserFile, "check", check)
    c = _client(tmp_path, users_file=users, require_login=True)
    assert _login(c, "eng", "wrong password").status_code == 401
    assert _login(c, "eng", "correct horse battery").status_code == 303
    assert seen == ["worker thread", "worker thread"]


def test_a_15_mb_note_is_refused_naming_the_field(tmp_path):
    c = _client(tmp_path)
    r = c.post("/upload", data={"csrf": _csrf(c), "note": "n" * 15_000_000},
               files={"file": ("x.csv", _positioning_file(), "text/csv")})
    assert r.status_code == 413
    assert "the field 'note' has 15,000,000 characters" in unescape(r.text)
    assert "at most 10,000" in r.text
    assert _stored(c) == 0
    r = c.post("/upload", data={"csrf": _csrf(c), "note": "n" * 10_000},
               files={"file": ("x.csv", _positioning_file(), "text/csv")},
               follow_redirects=False)
    assert r.status_code == 303 and _stored(c) == 1                   # at the bound: taken


def _asgi(app, headers: list, chunks: list) -> tuple[int, bytes, int]:
    """POST /upload straight through ASGI; returns (status, body, body chunks the app read)."""
    read = [0]

    async def receive():
        if read[0] < len(chunks):
            read[0] += 1
            return {"type": "http.request", "body": chunks[read[0] - 1],
                    "more_body": read[0] < len(chunks)}
        return {"type": "http.disconnect"}

    out = {"body": b""}

    async def send(message):
        if message["type"] == "http.response.start":
            out["status"] = message["status"]
        elif message["type"] == "http.response.body":
            out["body"] += message.get("body", b"")

    scope = {"type": "http", "asgi": {"version": "3.0"}, "http_version": "1.1",
             "method": "POST", "scheme": "http", "path": "/upload", "raw_path": b"/upload",
             "query_string": b"", "root_path": "", "client": ("127.0.0.1", 5000),
             "server": ("127.0.0.1", 8000),
             "headers": [(b"host", b"127.0.0.1:8000"),
                         (b"content-type", b"multipart/form-data; boundary=xyz"), *headers]}
    asyncio.run(app(scope, receive, send))
    return out["status"], out["body"], read[0]


def test_an_oversized_body_is_refused_before_it_is_read(tmp_path):
    """A declared 200 MB: refused (413) having read none of it; a body without a length is
    stopped at the limit, never spooled past it (RFC 9110 §15.5.14)."""
    app = create_app(f"sqlite:///{tmp_path / 'h.sqlite'}", upload_limit=1000)
    limit = app.state.upload_limit + 2**20
    head = (b'--xyz\r\nContent-Disposition: form-data; name="file"; filename="x.csv"\r\n'
            b"Content-Type: text/csv\r\n\r\n")
    chunks = [head] + [b"1," * 32768] * 200
    status, body, read = _asgi(app, [(b"content-length", b"209715200")], chunks)
    assert status == 413 and read == 0 and b"200 MiB" in body and b"Back to" in body
    status, body, read = _asgi(app, [(b"transfer-encoding", b"chunked")], chunks)
    assert status == 413 and (read - 1) * 65536 <= limit + 65536 and read < 200
    status, _, read = _asgi(app, [(b"content-length", b"x" * 30)], chunks)
    assert status == 413 and read == 0


@pytest.mark.parametrize("path, status, words", [
    ("/tests/abc", 404, "no such page"),
    ("/tests/9223372036854775808", 404, "no such page"),
    ("/tests/9223372036854775807", 404, "no test 9223372036854775807"),
    ("/tests/99999999999999999999999/raw", 404, "no such page"),
    ("/tests/0/result.json", 404, "no such page"),
    ("/tests/-1/report.html", 404, "no such page"),
    ("/machines/M?page=99999999999999999999", 400, "page"),
    ("/machines/M?page=abc", 400, "page"),
    ("/compare?a=1", 400, "choose two tests"),
    ("/compare", 400, "choose two tests"),
    ("/compare?a=1&b=99999999999999999999", 400, "choose two tests"),
    ("/trend?machine=M", 400, "'axis'"),
    ("/nowhere", 404, "no such page"),
    ("/static/nothing.js", 404, "no such page"),
])
def test_every_error_is_a_page_with_a_way_back(tmp_path, path, status, words):
    c = _client(tmp_path)
    r = c.get(path, headers={"referer": LOCAL + "/plan"})
    assert r.status_code == status
    assert r.headers["content-type"].startswith("text/html")
    assert words in unescape(r.text) and f"HTTP {status}" in r.text
    assert 'href="/">Back to the machines' in r.text and 'href="/plan">Back to the page' in r.text
    assert "Traceback" not in r.text and '"detail"' not in r.text


def test_an_internal_error_is_a_page_and_the_trace_stays_in_the_log(tmp_path, monkeypatch):
    app = create_app(f"sqlite:///{tmp_path / 'h.sqlite'}")

    def broken():
        raise RuntimeError("secret internals")

    monkeypatch.setattr(app.state.store, "machines", broken)
    r = TestClient(app, base_url=LOCAL, raise_server_exceptions=False).get("/")
    assert r.status_code == 500 and "internal error" in r.text and "HTTP 500" in r.text
    assert "secret internals" not in r.text and "Back to the machines" in r.text
    r = TestClient(app, base_url=LOCAL).post("/plan", data={"csrf": "x"})
    assert r.status_code == 403 and "HTTP 403" in r.text
    assert TestClient(app, base_url=LOCAL).put("/plan").status_code == 405
