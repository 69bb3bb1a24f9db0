"""Who may do what on the workbench, and the protections every request passes (issue 15).

These use the application in-process (FastAPI's TestClient); the browser tests use a real
server and Chromium."""

from __future__ import annotations

import re

import pytest
from fastapi.testclient import TestClient

from axiscal.errors import AxiscalError
from axiscal.web.app import create_app
from axiscal.web.security import MAX_UPLOAD_BYTES, check_upload, is_loopback
from tests.web.conftest import log_in as _login


def _csrf(client, path="/plan") -> str:
    return re.search(r'name="csrf-token" content="([^"]*)"', client.get(path).text).group(1)


def test_serving_beyond_localhost_needs_accounts(tmp_path):
    with pytest.raises(AxiscalError, match="needs accounts"):
        create_app(f"sqlite:///{tmp_path / 'h.sqlite'}", tmp_path / "none.toml",
                   require_login=True)
    assert is_loopback("127.0.0.1") and is_loopback("::1") and is_loopback("localhost")
    assert not is_loopback("0.0.0.0") and not is_loopback("192.168.1.2")


def test_login_roles_and_csrf(tmp_path, users):
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}", users, require_login=True),
                   base_url="http://127.0.0.1")
    r = c.get("/", follow_redirects=False)
    assert r.status_code == 303 and r.headers["location"].startswith("/login")
    assert _login(c, "eng", "wrong password").status_code == 401
    assert _login(c, "nobody", "whatever!").status_code == 401
    r = _login(c, "view", "staple battery horse")
    assert r.status_code == 303
    assert c.get("/").status_code == 200
    r = c.get("/upload")
    assert r.status_code == 403 and "viewer" in r.text                    # read-only role
    tok = _csrf(c, "/")
    r = c.post("/upload", data={"csrf": tok}, files={"file": ("x.csv", b"a", "text/csv")})
    assert r.status_code == 403
    c.cookies.clear()
    _login(c, "eng", "correct horse battery")
    assert c.get("/upload").status_code == 200
    r = c.post("/plan", data={"kind": "linear", "travel": "800"})             # no token
    assert r.status_code == 403 and "CSRF" in r.text
    r = c.post("/plan", data={"csrf": "forged", "kind": "linear", "travel": "800"})
    assert r.status_code == 403


def test_passwords_are_stored_as_argon2id(users):
    text = users.read_text()
    assert "$argon2id$" in text and "correct horse" not in text
    assert oct(users.stat().st_mode & 0o777) == "0o600"


@pytest.mark.parametrize("name, ctype, size, words", [
    ("x.exe", "application/x-msdownload", 10, "ending in"),
    ("../../etc/passwd", "text/plain", 10, "ending in"),
    ("x.csv", "text/html", 10, "sent as 'text/html'"),
    ("x.csv", "text/csv", MAX_UPLOAD_BYTES + 1, "at most"),
    ("x.csv", "text/csv", 0, "empty"),
])
def test_uploads_are_checked(name, ctype, size, words):
    with pytest.raises(AxiscalError, match=words):
        check_upload(name, ctype, size)


def test_upload_size_limit_on_the_server(tmp_path):
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}", upload_limit=1000),
                   base_url="http://127.0.0.1")
    tok = _csrf(c)
    r = c.post("/upload", data={"csrf": tok},
               files={"file": ("x.csv", b"#" * 5000, "text/csv")})
    assert r.status_code == 413 and "at most" in r.text      # RFC 9110 §15.5.14 Content Too Large
    assert "Data file" in r.text                               # the form is shown again
    assert c.get("/").text.count("<tr>") == 0


def test_every_page_sends_protective_headers_and_no_trace(tmp_path):
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}"),
                   base_url="http://127.0.0.1")
    for path in ("/", "/plan", "/nowhere", "/tests/5", "/trend?machine=M&axis=X"):
        r = c.get(path)
        assert r.headers["x-content-type-options"] == "nosniff"
        assert "default-src 'self'" in r.headers["content-security-policy"]
        assert "Traceback" not in r.text
    assert c.get("/nowhere").status_code == 404
    assert "no test 5" in c.get("/tests/5").text
    r = c.get("/tests/abc")
    assert r.status_code in (404, 422) and "Traceback" not in r.text


def test_download_names_are_never_paths(tmp_path):
    from axiscal.web.app import download

    r = download(b"x", "../../etc/passwd", "text/plain")
    assert r.headers["content-disposition"] == 'attachment; filename=".._.._etc_passwd"'
