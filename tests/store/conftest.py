"""History tests run on SQLite and on a real, throw-away PostgreSQL server (tools/pgtest.py)."""

from __future__ import annotations

import sys
import uuid
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))


@pytest.fixture(scope="session")
def pg_server():
    """One PostgreSQL server per test process, stopped at the end."""
    import pgtest

    url, stop = pgtest.start()
    yield url
    stop()


def _fresh_pg_database(server_url: str) -> str:
    import psycopg

    name = f"t_{uuid.uuid4().hex[:12]}"
    host = server_url.split("host=", 1)[1]
    with psycopg.connect(host=host, user="axiscal", dbname="postgres", autocommit=True) as c:
        c.execute(f"CREATE DATABASE {name}")
    return server_url.replace("/postgres?", f"/{name}?")


@pytest.fixture(params=["sqlite", "postgresql"])
def db_url(request, tmp_path):
    """A fresh, empty history database of each kind."""
    if request.param == "sqlite":
        return f"sqlite:///{tmp_path / 'history.sqlite'}"
    return _fresh_pg_database(request.getfixturevalue("pg_server"))
