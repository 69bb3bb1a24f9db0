"""A real ``axiscal serve`` (uvicorn on 127.0.0.1) against raw sockets: a client that sends its
headers slowly, or stops inside a body, loses its connection; the connection limit answers 503 and
frees itself; a declared 200 MB upload is refused before its body is sent (issue 31)."""

from __future__ import annotations

import re
import socket
import sys
import time
import urllib.request

import pytest

from tests.web.conftest import start_server, stop_server

HEADER_TIMEOUT, BODY_TIMEOUT, MAX_CONNECTIONS = 1.0, 1.5, 4


@pytest.fixture(scope="module")
def limited(tmp_path_factory):
    proc, base = start_server(tmp_path_factory.mktemp("limits"),
                              "--header-timeout", str(HEADER_TIMEOUT),
                              "--body-timeout", str(BODY_TIMEOUT),
                              "--max-connections", str(MAX_CONNECTIONS),
                              "--allowed-host", "Bench.Shop.Local")
    yield base
    stop_server(proc)


def _port(base: str) -> int:
    return int(base.rsplit(":", 1)[1])


def _open(base: str, first: bytes) -> socket.socket:
    s = socket.create_connection(("127.0.0.1", _port(base)), timeout=10)
    s.sendall(first)
    return s


def _closed_within(s: socket.socket, seconds: float) -> bytes | None:
    """What the server sent before closing the connection, or None if it stayed open."""
    s.settimeout(seconds)
    got = b""
    try:
        while chunk := s.recv(65536):
            got += chunk
    except TimeoutError:
        return None
    except ConnectionResetError:
        pass
    return got


def _status(url: str) -> int:
    try:
        return urllib.request.urlopen(url, timeout=10).status
    except urllib.error.HTTPError as exc:
        return exc.code


def test_slow_headers_do_not_hold_a_connection(limited):
    """Slowloris: half-sent headers; each connection is closed after the header timeout, and
    meanwhile the connection limit refuses others with 503 instead of letting them queue."""
    slow = [_open(limited, b"GET /plan HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ")
            for _ in range(MAX_CONNECTIONS)]
    time.sleep(0.2)
    assert _status(limited + "/plan") == 503
    start = time.monotonic()
    for s in slow:
        assert _closed_within(s, HEADER_TIMEOUT + 5) == b""
        s.close()
    assert time.monotonic() - start < HEADER_TIMEOUT + 5
    assert _status(limited + "/plan") == 200                    # served again


def test_a_body_that_stops_loses_its_connection_and_nothing_is_stored(limited):
    s = _open(limited, b"POST /upload HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 100000\r\n"
                       b"Content-Type: multipart/form-data; boundary=xyz\r\n\r\n--xyz\r\n")
    assert _closed_within(s, BODY_TIMEOUT + 5) is not None
    s.close()
    assert "The history is empty" in urllib.request.urlopen(limited + "/", timeout=10).read() \
        .decode()


def test_a_declared_200_mb_upload_is_refused_before_its_body(limited):
    s = _open(limited, b"POST /upload HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 209715200\r\n"
                       b"Content-Type: multipart/form-data; boundary=xyz\r\n\r\n")
    answer = _closed_within(s, 5)
    s.close()
    assert answer is not None and answer.startswith(b"HTTP/1.1 413")
    assert b"200 MiB" in answer and b"at most 21 MiB" in answer


def _get(base: str, host: bytes) -> bytes:
    s = _open(base, b"GET /plan HTTP/1.1\r\nHost: " + host + b"\r\nConnection: close\r\n\r\n")
    answer = _closed_within(s, 5)
    s.close()
    return answer


def test_the_host_check_holds_on_the_real_server(limited):
    answer = _get(limited, b"evil.example")
    assert answer.startswith(b"HTTP/1.1 400") and b'csrf-token" content=""' in answer
    answer = _get(limited, b"bench.shop.local:" + str(_port(limited)).encode())   # --allowed-host
    assert answer.startswith(b"HTTP/1.1 200") and re.search(rb'csrf-token" content="\w+', answer)


def test_every_interface_answers_to_the_computers_names():
    from axiscal.web.guards import allowed_hosts

    names = allowed_hosts("0.0.0.0", ["[FE80::1]"])
    assert socket.gethostname().lower() in names and "fe80::1" in names
    assert {"127.0.0.1", "::1", "localhost"} <= names and "evil.example" not in names
    assert allowed_hosts("192.168.1.20") == {"127.0.0.1", "::1", "localhost", "192.168.1.20"}


def test_serve_defaults_are_the_library_limits():
    """The command line's defaults (shown in its help) are the limits the library documents."""
    import inspect

    from axiscal.cli.serve import serve
    from axiscal.web.server import LIMITS
    from axiscal.web.sessions import ABSOLUTE_SECONDS, IDLE_SECONDS

    d = {k: v.default.default for k, v in inspect.signature(serve).parameters.items()}
    assert d["header_timeout"] == LIMITS["header_timeout"]
    assert d["body_timeout"] == LIMITS["body_timeout"]
    assert d["max_connections"] == LIMITS["max_connections"]
    assert d["session_idle"] * 60 == IDLE_SECONDS and d["session_max"] * 3600 == ABSOLUTE_SECONDS


def test_a_connection_is_closed_after_its_requests_so_clients_spread_over_workers(limited):
    """The n-th request on one keep-alive connection is answered with ``Connection: close``
    (RFC 9112 §9.6) and the server closes it; the client's next request opens a new connection,
    which the kernel hands to whichever worker accepts first."""
    import http.client

    from axiscal.web.server import LIMITS

    n = LIMITS["requests_per_connection"]
    conn = http.client.HTTPConnection("127.0.0.1", _port(limited), timeout=10)
    said = []
    for _ in range(n):
        conn.request("GET", "/plan", headers={"Host": "127.0.0.1"})
        r = conn.getresponse()
        r.read()
        said.append((r.status, r.getheader("connection")))
    assert said[:-1] == [(200, None)] * (n - 1) and said[-1] == (200, "close")
    assert conn.sock is None                     # http.client closed it, as the server asked
    conn.request("GET", "/plan", headers={"Host": "127.0.0.1"})    # a new connection
    assert conn.getresponse().status == 200


def test_a_worker_process_leaves_what_it_loaded_out_of_garbage_collections(tmp_path,
                                                                           monkeypatch):
    """app_from_env freezes the objects of the built application (gc.freeze), so a collection of
    the oldest generation no longer walks them (a 120-280 ms stop of the loop under load)."""
    import gc
    import json

    from axiscal.web import server, workers

    monkeypatch.setenv(workers.ENV, json.dumps({
        "app": {"db_url": f"sqlite:///{tmp_path / 'h.sqlite'}"},
        "header_timeout": 10, "body_timeout": 30}))
    gc.unfreeze()
    interval = sys.getswitchinterval()
    try:
        app = server.app_from_env()
        assert app.state.db_url.endswith("h.sqlite")
        assert gc.get_freeze_count() > 10_000          # the modules, classes, templates loaded
    finally:
        gc.unfreeze()
        sys.setswitchinterval(interval)
