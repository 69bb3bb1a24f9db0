"""``axiscal serve``: the web workbench (FastAPI + htmx, served by uvicorn).

Localhost (127.0.0.1, the default) needs no login. Any other ``--host`` needs accounts in a users
file (``--users``, default ``users.toml`` in the user's axiscal configuration folder); add one
with ``axiscal serve --add-user NAME --role engineer|viewer`` (the password is asked for, or read
from ``AXISCAL_PASSWORD``).

Only requests naming the bound address (and 127.0.0.1, localhost, [::1], and any
``--allowed-host``) in their Host header are answered (DNS rebinding); logins end after
``--session-idle`` minutes without a request and ``--session-max`` hours; slow or endless requests
are cut off (:mod:`axiscal.web.server`). Every limit in force is printed when the server starts.
"""

from __future__ import annotations

from pathlib import Path
from typing import List, Optional

import typer

__all__ = ["register"]


def serve(
    db: Optional[str] = typer.Option(None, "--db", help="History database URL (default: the "
                                     "user's SQLite file, or AXISCAL_DB)."),
    host: str = typer.Option("127.0.0.1", "--host", help="Address to listen on; other than "
                             "localhost it needs accounts (--users)."),
    port: int = typer.Option(8000, "--port", min=1, max=65535, help="TCP port."),
    users: Optional[Path] = typer.Option(None, "--users", help="Accounts file (TOML, Argon2id "
                                         "hashes); default users.toml in the axiscal "
                                         "configuration folder."),
    add_user: Optional[str] = typer.Option(None, "--add-user", help="Add (or replace) an "
                                           "account in the users file and exit."),
    role: str = typer.Option("engineer", "--role", help="Role of --add-user: viewer (reads) or "
                             "engineer (uploads, stores, writes tables)."),
    allowed_host: Optional[List[str]] = typer.Option(
        None, "--allowed-host", help="Another host name the server answers to (repeatable), e.g. "
        "its DNS name; requests naming any other host get 400."),
    session_idle: float = typer.Option(30.0, "--session-idle", min=1, max=24 * 60,
                                       help="Minutes without a request that end a login."),
    session_max: float = typer.Option(12.0, "--session-max", min=0.1, max=24 * 7,
                                      help="Hours after which a login ends in any case."),
    header_timeout: float = typer.Option(10.0, "--header-timeout", min=0.1, max=600,
                                         help="Seconds a client has to send a request's "
                                         "headers."),
    body_timeout: float = typer.Option(30.0, "--body-timeout", min=0.1, max=3600,
                                       help="Seconds of silence allowed within a request body."),
    max_connections: int = typer.Option(100, "--max-connections", min=1, max=10_000,
                                        help="Connections served at once; more get 503."),
    workers: Optional[int] = typer.Option(None, "--workers", min=1, max=64,
                                          help="Worker processes (default: the number of "
                                          "cores); logins are shared by them."),
) -> None:
    """Serve the web workbench: machines, history, upload, compare, trend, tables, plans.

    Example: axiscal serve --port 8000   (then open http://127.0.0.1:8000 in a browser)
    """
    from axiscal.errors import InputError

    _need_web_extra()
    from axiscal.web.security import UserFile, is_loopback

    users_path = users or _default_users()
    if add_user is not None:
        return _add_user(users_path, add_user, role)
    loopback = is_loopback(host)
    if not loopback and not UserFile.load(users_path).users:
        raise InputError(f"--host {host} is reachable from other computers: add an account "
                         f"first (axiscal serve --add-user NAME --users {users_path})")
    from axiscal.web.app import create_app
    from axiscal.web.guards import allowed_hosts
    from axiscal.web.server import run

    _port_free(host, port)   # before the database is upgraded and the banner printed
    hosts = allowed_hosts(host, allowed_host or ())
    settings = dict(db_url=db, users_file=str(users_path) if (not loopback or users) else None,
                    require_login=not loopback, hosts=sorted(hosts),
                    session_idle=session_idle * 60, session_max=session_max * 3600)
    app = create_app(**settings)     # checked (and the database upgraded) once, before workers
    n = workers or _cores()
    typer.echo(f"axiscal workbench on http://{_url_host(host)}:{port}/ (Ctrl+C stops it); answers "
               f"to {', '.join(sorted(hosts))}; logins end after {session_idle:g} min idle or "
               f"{session_max:g} h; {_limits(header_timeout, body_timeout, max_connections, app)}"
               f"; {n} worker process{'es' if n > 1 else ''}"
               f"{'' if workers else ' (default: the cores)'}", err=True)
    if n == 1:
        return run(app, host, port, header_timeout, body_timeout, max_connections)
    import tempfile

    with tempfile.TemporaryDirectory(prefix="axiscal-sessions-") as folder:   # mode 0700
        run(None, host, port, header_timeout, body_timeout, max_connections, workers=n,
            settings={**settings, "sessions_folder": folder})


#: The distributions of the ``web`` extra (pyproject.toml) and the module names each may
#: install (python-multipart before 0.0.13 has only ``multipart``).
WEB_EXTRA = {"fastapi": ("fastapi",), "uvicorn": ("uvicorn",),
             "python-multipart": ("python_multipart", "multipart"), "argon2-cffi": ("argon2",)}


def _need_web_extra() -> None:
    """Every module of the ``web`` extra importable, else one line naming the extra to install
    (a plain ``pip install axiscal`` has none of them)."""
    import importlib

    from axiscal.errors import MissingExtraError

    for dist, modules in WEB_EXTRA.items():
        for module in modules:
            try:
                importlib.import_module(module)
                break
            except ImportError:
                continue
        else:
            raise MissingExtraError(f"axiscal serve needs the web extra: pip install "
                                    f"'axiscal[web]' ({dist} is not installed)")


def _port_free(host: str, port: int) -> None:
    """Bind ``host``:``port`` as uvicorn will (SO_REUSEADDR, so a closed connection's TIME_WAIT
    does not count): a port another program listens on is one line, not uvicorn's log of
    [Errno 98] after the banner."""
    import socket

    from axiscal.errors import InputError

    try:
        infos = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM, flags=socket.AI_PASSIVE)
    except OSError as exc:
        raise InputError(f"--host {host}: no address to listen on ({exc.strerror})") from None
    family, kind, proto, _name, address = infos[0]
    with socket.socket(family, kind, proto) as sock:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            sock.bind(address)
        except OSError as exc:
            why = "another program listens on it" if exc.errno in _IN_USE else exc.strerror
            raise InputError(f"--port {port}: cannot listen on {_url_host(host)}:{port} ({why}); "
                             "stop it or give another --port") from None


#: errno of an address in use (Linux 98, BSD and macOS 48, Windows WSAEADDRINUSE 10048).
_IN_USE = (98, 48, 10048)


def _limits(header_timeout: float, body_timeout: float, max_connections: int, app) -> str:
    """Every limit of :data:`axiscal.web.server.LIMITS` in force, and the upload size, in words
    (the first three as given on the command line)."""
    from axiscal.web.server import LIMITS

    return (f"headers within {header_timeout:g} s and {LIMITS['max_header_bytes'] / 1024:g} KiB, "
            f"body silences under {body_timeout:g} s, uploads up to "
            f"{app.state.upload_limit / 2**20:g} MiB, {max_connections} connections at once, "
            f"{LIMITS['requests_per_connection']} requests per connection (then it is closed), "
            f"idle connections closed after {LIMITS['keep_alive']:g} s")


def _cores() -> int:
    """Processor cores this process may use (2 if unknown)."""
    import os

    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return os.cpu_count() or 2


def _add_user(users_path: Path, name: str, role: str) -> None:
    """``--add-user``: the password from AXISCAL_PASSWORD or asked on the terminal."""
    import os
    import sys

    from axiscal.errors import InputError
    from axiscal.web.security import ROLES, UserFile

    if role not in ROLES:   # before the password is asked for, not after
        raise InputError(f"--role {role[:40]!r}: use {' or '.join(ROLES)}")
    password = os.environ.get("AXISCAL_PASSWORD")
    if not password and not sys.stdin.isatty():
        raise InputError("--add-user: no terminal to ask the password on; set "
                         "AXISCAL_PASSWORD")
    password = password or typer.prompt(f"password for {name}", hide_input=True,
                                        confirmation_prompt=True)
    UserFile.load(users_path).add(name, role, password)
    typer.echo(f"{name} ({role}) written to {users_path}")


def _url_host(host: str) -> str:
    return f"[{host}]" if ":" in host else host


def _default_users() -> Path:
    from platformdirs import user_config_dir

    return Path(user_config_dir("axiscal")) / "users.toml"


def register(app: typer.Typer) -> None:
    """Add ``serve`` to the application."""
    app.command("serve")(serve)
