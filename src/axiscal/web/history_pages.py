"""History pages (machines, tests, compare, trend, upload): built on :mod:`axiscal.store`."""

from __future__ import annotations


def add_routes(app) -> None:
    """The history routes."""
