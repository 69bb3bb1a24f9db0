"""``axiscal serve``: the web workbench (FastAPI + htmx, served by uvicorn).

Localhost (127.0.0.1, the default) needs no login. Any other ``--host`` needs accounts in a users
file (``--users``, default ``users.toml`` in the user's axiscal configuration folder); add one
with ``axiscal serve --add-user NAME --role engineer|viewer`` (the password is asked for, or read
from ``AXISCAL_PASSWORD``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional

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
) -> None:
    """Serve the web workbench: machines, history, upload, compare, trend, tables, plans.

    Example: axiscal serve --port 8000   (then open http://127.0.0.1:8000 in a browser)
    """
    import os
    import sys

    from axiscal.errors import InputError
    from axiscal.web.security import UserFile, is_loopback

    users_path = users or _default_users()
    if add_user is not None:
        from axiscal.web.security import ROLES

        if role not in ROLES:   # before the password is asked for, not after
            raise InputError(f"--role {role[:40]!r}: use {' or '.join(ROLES)}")
        password = os.environ.get("AXISCAL_PASSWORD")
        if not password and not sys.stdin.isatty():
            raise InputError("--add-user: no terminal to ask the password on; set "
                             "AXISCAL_PASSWORD")
        password = password or typer.prompt(f"password for {add_user}", hide_input=True,
                                            confirmation_prompt=True)
        UserFile.load(users_path).add(add_user, role, password)
        typer.echo(f"{add_user} ({role}) written to {users_path}")
        return
    loopback = is_loopback(host)
    if not loopback and not UserFile.load(users_path).users:
        raise InputError(f"--host {host} is reachable from other computers: add an account "
                         f"first (axiscal serve --add-user NAME --users {users_path})")
    import uvicorn

    from axiscal.web.app import create_app

    app = create_app(db, users_path if (not loopback or users) else None,
                     require_login=not loopback)
    typer.echo(f"axiscal workbench on http://{host}:{port}/ (Ctrl+C stops it)", err=True)
    uvicorn.run(app, host=host, port=port, log_level="warning")


def _default_users() -> Path:
    from platformdirs import user_config_dir

    return Path(user_config_dir("axiscal")) / "users.toml"


def register(app: typer.Typer) -> None:
    """Add ``serve`` to the application."""
    app.command("serve")(serve)
