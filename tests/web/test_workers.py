"""Several worker processes (``axiscal serve --workers 2``) sharing logins, and heavy work
bounded (axiscal.web.workers)."""

from __future__ import annotations

import asyncio
import threading
import time

import httpx
import pytest

from axiscal.web import workers
from axiscal.web.security import UserFile
from axiscal.web.sessions import FREE_FAILURES
from tests.web.conftest import start_server, stop_server

PASSWORD = "correct horse battery"


@pytest.fixture(scope="module")
def two_workers(tmp_path_factory):
    d = tmp_path_factory.mktemp("workers")
    UserFile.load(d / "users.toml").add("eng", "engineer", PASSWORD)
    proc, base = start_server(d, "--workers", "2", "--users", str(d / "users.toml"))
    yield base
    stop_server(proc)


def _spread(base: str, cookies, n: int = 40) -> dict:
    """{worker: [status, ...]} of ``n`` GET / on new connections (the kernel shares them out)."""
    seen: dict = {}
    for _ in range(n):
        with httpx.Client(base_url=base, cookies=cookies) as c:
            r = c.get("/")
            seen.setdefault(r.headers["x-axiscal-worker"], []).append(r.status_code)
    return seen


def _log_in(base: str, password: str = PASSWORD, name: str = "eng") -> httpx.Response:
    with httpx.Client(base_url=base) as c:
        return c.post("/login", data={"username": name, "password": password, "next": "/"})


def test_a_login_on_one_worker_holds_on_every_worker_and_log_out_ends_it(two_workers):
    r = _log_in(two_workers)
    assert r.status_code == 303 and "axiscal_session" in str(r.headers.get("set-cookie"))
    seen = _spread(two_workers, r.cookies)
    assert len(seen) == 2, seen                        # both workers answered
    assert all(set(codes) == {200} for codes in seen.values()), seen
    with httpx.Client(base_url=two_workers, cookies=r.cookies) as c:
        page = c.get("/")
        token = page.text.split('csrf-token" content="', 1)[1].split('"', 1)[0]
        assert c.post("/logout", data={"csrf": token}).status_code == 303
    after = _spread(two_workers, r.cookies)
    assert len(after) == 2 and all(set(codes) == {303} for codes in after.values()), after


def test_wrong_passwords_are_counted_across_workers(two_workers):
    answered = set()
    for _ in range(FREE_FAILURES):
        r = _log_in(two_workers, "wrong", name="guessed")
        assert r.status_code == 401
        answered.add(r.headers["x-axiscal-worker"])
    refused = [_log_in(two_workers, "wrong", name="guessed") for _ in range(6)]
    assert {r.status_code for r in refused} == {429}
    assert len(answered | {r.headers["x-axiscal-worker"] for r in refused}) == 2


def test_shared_sessions_two_processes_one_store(tmp_path):
    clock = [1000.0]
    a = workers.SharedSessions(tmp_path, idle=60, absolute=3600, clock=lambda: clock[0])
    b = workers.SharedSessions(tmp_path, idle=60, absolute=3600, clock=lambda: clock[0])
    assert a.key == b.key and a.csrf_for("x" * 32) == b.csrf_for("x" * 32)
    cookie = a.issue("eng", "engineer")
    assert b.read(cookie)["name"] == "eng" and b.read(cookie) == a.read(cookie)
    clock[0] += 61                                              # idle past the limit
    assert a.read(cookie) is None and b.read(cookie) is None
    cookie = b.issue("eng", "viewer")
    assert b.revoke(cookie) and a.read(cookie) is None and len(a) == 0


def test_heavy_work_runs_one_at_a_time_per_worker():
    running, most = [0], [0]
    lock = threading.Lock()

    def job(i):
        with lock:
            running[0] += 1
            most[0] = max(most[0], running[0])
        time.sleep(0.05)
        with lock:
            running[0] -= 1
        return i

    async def six():
        return await asyncio.gather(*(workers.heavy(job, i) for i in range(6)))

    assert asyncio.run(six()) == list(range(6))
    assert most[0] == workers.HEAVY_AT_ONCE == 1


def test_a_report_is_made_once_then_read_from_the_cache(tmp_path, monkeypatch):
    from fastapi.testclient import TestClient

    import axiscal.web.history_pages as pages
    from axiscal.store import cache, open_store
    from axiscal.web.app import create_app
    from tests.store.test_cache import _file

    monkeypatch.setenv("AXISCAL_CACHE", str(tmp_path / "cache"))
    url = f"sqlite:///{tmp_path / 'h.sqlite'}"
    test_id = open_store(url).add(_file(7), "r.csv").id
    made = []
    real = pages._report_html
    monkeypatch.setattr(pages, "_report_html", lambda t, ev: (made.append(1), real(t, ev))[1])
    client = TestClient(create_app(url), base_url="http://127.0.0.1")
    first = client.get(f"/tests/{test_id}/report.html")
    cache.forget_memory()
    second = client.get(f"/tests/{test_id}/report.html")
    assert first.status_code == second.status_code == 200
    assert first.content == second.content and b"ISO 230-2" in first.content
    assert len(made) == 1
    assert len(list(cache.cache_folder().rglob("*.report.html"))) == 1
