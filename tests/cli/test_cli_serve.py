"""``axiscal serve`` prints every limit in force when it starts (its module docstring says so)."""

from __future__ import annotations

from typer.testing import CliRunner

from axiscal.cli import app

runner = CliRunner()


def _start_line(monkeypatch, tmp_path, *args: str) -> str:
    """What ``axiscal serve ARGS`` prints on stderr before it would serve (``run`` replaced)."""
    import axiscal.web.server as server

    served = []
    monkeypatch.setattr(server, "run", lambda *a, **k: served.append(a))
    r = runner.invoke(app, ["serve", "--db", f"sqlite:///{tmp_path / 'h.sqlite'}",
                            "--workers", "1", *args])
    assert r.exit_code == 0, r.output
    assert len(served) == 1                      # it went on to serve, once
    return r.stderr


def test_every_server_limit_is_printed_at_start(monkeypatch, tmp_path):
    """Each entry of ``web.server.LIMITS`` is named in the start-up line with its value, the
    three given on the command line as given; a limit added to LIMITS without words here fails
    (the keys must match)."""
    from axiscal.web.security import MAX_UPLOAD_BYTES
    from axiscal.web.server import LIMITS

    line = _start_line(monkeypatch, tmp_path, "--header-timeout", "7", "--body-timeout", "45",
                       "--max-connections", "12")
    words = {"header_timeout": "headers within 7 s",
             "max_header_bytes": f"and {LIMITS['max_header_bytes'] / 1024:g} KiB",
             "body_timeout": "body silences under 45 s",
             "max_connections": "12 connections at once",
             "requests_per_connection": f"{LIMITS['requests_per_connection']} requests per "
                                        "connection (then it is closed)",
             "keep_alive": f"idle connections closed after {LIMITS['keep_alive']:g} s"}
    assert set(words) == set(LIMITS)
    for key, text in words.items():
        assert text in line, (key, line)
    assert "16 KiB" in line and "20 requests per connection" in line   # the values of today
    assert f"uploads up to {MAX_UPLOAD_BYTES / 2**20:g} MiB," in line
    assert "uploads up to 20 MiB," in line
    assert line.count("\n") == 1 and line.rstrip().endswith("; 1 worker process")   # one line


def test_a_taken_port_is_one_line_and_exit_2(monkeypatch, tmp_path):
    """A port another program listens on: one line naming it, exit 2, before the banner and
    before serving (it was the banner, then uvicorn's "[Errno 98] address already in use" and
    exit 3)."""
    import socket

    import axiscal.web.server as server

    served = []
    monkeypatch.setattr(server, "run", lambda *a, **k: served.append(a))
    with socket.socket() as other:
        other.bind(("127.0.0.1", 0))
        other.listen()
        port = other.getsockname()[1]
        r = runner.invoke(app, ["serve", "--db", f"sqlite:///{tmp_path / 'h.sqlite'}",
                                "--workers", "1", "--port", str(port)])
    assert r.exit_code == 2 and not served
    assert r.stderr == (f"axiscal: error: --port {port}: cannot listen on 127.0.0.1:{port} "
                        "(another program listens on it); stop it or give another --port\n")
    assert not (tmp_path / "h.sqlite").exists()   # nothing made before the refusal


def test_serve_without_the_web_extra_says_which_to_install(monkeypatch):
    """A plain install (no ``[web]``): one line naming the extra, exit 2, no traceback
    (it was ``ModuleNotFoundError: fastapi``). A module set to None in ``sys.modules`` cannot
    be imported, as if not installed; tests/test_wheel.py checks the same from a wheel."""
    import sys

    for modules, dist in ((("fastapi",), "fastapi"), (("uvicorn",), "uvicorn"),
                          (("python_multipart", "multipart"), "python-multipart"),
                          (("argon2",), "argon2-cffi")):
        for module in modules:
            monkeypatch.setitem(sys.modules, module, None)
        r = runner.invoke(app, ["serve", "--port", "1"])
        assert r.exit_code == 2 and "Traceback" not in r.output
        assert r.stderr == ("axiscal: error: axiscal serve needs the web extra: pip install "
                            f"'axiscal[web]' ({dist} is not installed)\n")
        for module in modules:
            monkeypatch.delitem(sys.modules, module)
