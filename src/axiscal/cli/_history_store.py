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


def open_db(db):
    """The history store at ``db`` (a URL, or None for the default)."""
    from axiscal.store import open_store

    return open_store(db)


def store_run(file: Path, db, machine=None, axis=None) -> None:
    """The ``--history`` step of an evaluating command: store the file just evaluated
    (:meth:`axiscal.api.History.add`)."""
    from axiscal import api

    with api.History(db) as h:
        r = h.add(file, machine=machine, axis=axis)
    note(f"history: {'already stored as' if r.duplicate else 'stored as'} test {r.id} "
         f"({r.machine} {r.axis})")
