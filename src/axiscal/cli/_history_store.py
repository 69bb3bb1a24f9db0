"""The history database as every command that reaches it sees it.

The ``--db`` and ``--json`` options of ``axiscal history ...`` (shared by its corrections,
:mod:`axiscal.cli.history_corrections`, and by ``axiscal certificate``), opening the store, and
the ``--history`` step of an evaluating command (:func:`store_run`). It sits below
:mod:`axiscal.cli.history`, :mod:`axiscal.cli.history_corrections` and
:mod:`axiscal.cli.iso230_2` so that they share it without importing one another.
"""

from __future__ import annotations

from pathlib import Path

import typer

from axiscal.cli._common import note

__all__ = ["DB", "JSON", "open_db", "store_run"]

DB = typer.Option(None, "--db", help="Database URL (default: AXISCAL_DB, else SQLite in the "
                  "user's data folder), e.g. postgresql+psycopg://user@host/axiscal. A file "
                  "that is not an axiscal history is refused, not converted; a read-only one "
                  "is listed and shown.")
JSON = typer.Option(False, "--json", help="Print the result as JSON (stable keys).")


def open_db(db, create: bool = False):
    """The history store at ``db`` (a URL, or None for the default).

    Only a command that stores (``create=True``: ``history import``) makes a new SQLite history;
    one that reads or corrects refuses a file that does not exist, and creates no folder
    (issue 39: ``history list --db sqlite:///typo/h.sqlite`` made the folder ``typo`` and an
    empty database).
    """
    from axiscal.store import open_store

    if not create:
        _existing(db)
    return open_store(db)


def _existing(db) -> None:
    from axiscal.store.database import StoreError
    from axiscal.store.history import default_url

    url = db or default_url()
    if url.split(":", 1)[0] not in ("sqlite", "sqlite+pysqlite"):
        return
    try:
        from axiscal.store.database import sqlite_path

        path = sqlite_path(url)
    except Exception:   # noqa: BLE001 - a bad URL: the store's own message
        return
    if path is not None and not path.exists() and not path.is_symlink():
        raise StoreError(f"no history database at {str(path)[:200]}: nothing is stored there "
                         "yet (a command that only reads creates none; 'axiscal history add "
                         "FILE' starts one)")


def store_run(file: Path, db, machine=None, axis=None, drift_check=None) -> None:
    """The ``--history`` step of an evaluating command: store the file just evaluated
    (:meth:`axiscal.api.History.add`), with its drift check when one was given."""
    from axiscal import api

    extra = {} if drift_check is None else {"drift_check": drift_check}
    with api.History(db) as h:
        r = h.add(file, machine=machine, axis=axis, **extra)
    note(f"history: {'already stored as' if r.duplicate else 'stored as'} test {r.id} "
         f"({r.machine} {r.axis}){' with its drift check' if extra and not r.duplicate else ''}")


def history_reads_alike(file: Path, encoding: str) -> None:
    """``--history`` with ``--encoding``: the history keeps the file's bytes and re-reads them
    alone (UTF-8, UTF-16 with a BOM, else Windows-1252): refused where that reading would give
    other text than the code page given (a cp1250 "ł" would come back as "³")."""
    from axiscal.errors import InputError
    from axiscal.io._files import read_bytes
    from axiscal.io.renishaw import decode

    data = read_bytes(file)
    if decode(data, encoding, str(file))[0] != decode(data, None, str(file))[0]:
        raise InputError(f"--history keeps {file} as it came and re-reads it without "
                         f"--encoding {encoding}, which would read its text differently: store "
                         "it as UTF-8 (or Windows-1252) first, or drop --history")
