"""The calibration history: machines, axes, tests, results and compensation tables, kept.

Library API (the ``axiscal history`` commands and the web workbench are thin layers over it)::

    from axiscal.store import open_store
    store = open_store()                      # AXISCAL_DB, or SQLite in the user's data folder
    r = store.add(raw_bytes, "x.csv", machine="VMC-800", axis="X")   # -> AddResult(id, duplicate…)
    store.machines(); store.tests(machine=..., axis=..., kind=..., since=...)
    t = store.get(r.id); t.evaluate_again()   # the same numbers from the stored bytes
    compare_tests(store.get(a), store.get(b)); fit_trend(...) via trend(store, ...)
    export_history(store, "vmc.zip"); import_history(store, "vmc.zip")
    store.certificates(); store.certificate("PM-2026-00001")   # the certificate register

Modules: :mod:`~axiscal.store.history` (the database), :mod:`~axiscal.store.database` (opening
it: recognised, created whole, upgraded under a lock, read-only), :mod:`~axiscal.store.kinds`
(what a file is and its evaluation), :mod:`~axiscal.store.analysis` (compare, trend),
:mod:`~axiscal.store.archive` (export, import), :mod:`~axiscal.store.register` (certificate
numbers, issued documents, amendments; issued by :mod:`axiscal.report.issue`),
:mod:`~axiscal.store.models` and the Alembic ``migrations``.
"""

from typing import TYPE_CHECKING

if TYPE_CHECKING:   # pragma: no cover - typing only
    from axiscal.store.history import (AddResult, MachineSummary, NotFoundError, Store,
                                       StoreError, StoredTest, TestSummary, default_url,
                                       open_store)

__all__ = ["AddResult", "MachineSummary", "NotFoundError", "Store", "StoreError", "StoredTest",
           "TestSummary", "default_url", "open_store", "trend"]


def __getattr__(name: str):
    """The history's names, imported on first use (PEP 562): the one evaluation of a test
    (:mod:`axiscal.store.kinds`) is used by commands that open no database, so importing it
    loads no database code."""
    if name in __all__ and name != "trend":
        from axiscal.store import history

        return getattr(history, name)
    raise AttributeError(f"module 'axiscal.store' has no attribute {name!r}")


def trend(store: "Store", machine: str, axis: str, parameter: str,
          tolerance: float | None = None, kind: str | None = None):
    """The :class:`~axiscal.store.analysis.Trend` of one parameter of one axis."""
    from axiscal.store.analysis import fit_trend

    from axiscal.store.history import NotFoundError

    rows = store.parameter_series(machine, axis, parameter, kind)
    if not rows:
        raise NotFoundError(f"no {parameter!r} stored for {machine} {axis.upper()}")
    return fit_trend(parameter, [r[0] for r in rows], [r[1] for r in rows], rows[0][2],
                     tolerance, [r[3] for r in rows], dated=[bool(r[4]) for r in rows])
