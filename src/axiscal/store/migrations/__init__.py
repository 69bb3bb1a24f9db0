"""Alembic migrations of the history schema (run by :func:`axiscal.store.open_store`)."""
