"""The calibration history of the public API: :class:`History`.

``axiscal history add``, the ``--history`` step of ``axiscal iso230-2`` and the workbench's
upload store a test through :meth:`History.add`.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:   # pragma: no cover - typing only
    from axiscal.api._results import Evaluation, PathLike

__all__ = ["History"]


class History:
    """The calibration history (:class:`axiscal.store.Store`): SQLite or PostgreSQL by URL.

    Parameters
    ----------
    url : str, optional
        ``sqlite:///path.sqlite`` or ``postgresql+psycopg://...``; default ``AXISCAL_DB``, else
        the user's SQLite file (as ``axiscal history``).
    store : axiscal.store.Store, optional
        A history already open (the workbench's), instead of opening ``url``; :meth:`close`
        then leaves it open for its owner.
    """

    def __init__(self, url: str | None = None, *, store: Any = None) -> None:
        if store is not None and url is not None:
            from axiscal.errors import InputError

            raise InputError("History: give a url or an open store, not both")
        self._owned = store is None
        if store is None:
            from axiscal.store import open_store

            store = open_store(url)
        self.store = store

    def add(self, source: PathLike | bytes, *, filename: str | None = None,
            **metadata: Any) -> Any:
        """Evaluate and store a data file; a file stored before is reported, not stored again.

        Parameters
        ----------
        source : str, Path or bytes
            The data file, or its bytes as they came (an upload).
        filename : str, optional
            The file's name as stored (required with bytes; default the path's name).
        **metadata
            ``machine``, ``axis``, ``kind`` (default: from the content), ``instrument``,
            ``operator``, ``note``, ``date`` (``YYYY-MM-DD``; default the file's, else today,
            marked as unknown), ``uncertainty`` (the inputs of the test's uncertainty budget,
            stored with it; default the user configuration's, as :func:`axiscal.evaluate`),
            ``drift_check`` (a positioning test's drift check, ISO 230-2:2014 Annex A.5: a
            path, or (bytes, filename); kept in the test's record, its E_VE the budget's).

        Returns
        -------
        axiscal.store.history.AddResult
            ``id``, ``duplicate``, ``kind``, ``machine``, ``axis``.
        """
        from axiscal.io._files import read_bytes

        dc = metadata.get("drift_check")
        if dc is not None and not isinstance(dc, tuple):
            metadata["drift_check"] = (read_bytes(dc), Path(dc).name)
        if isinstance(source, (bytes, bytearray)):
            if not filename:
                from axiscal.errors import InputError

                raise InputError("History.add: give the filename of the bytes")
            return self.store.add(bytes(source), filename, **metadata)
        return self.store.add(read_bytes(source), filename or Path(source).name, **metadata)

    def tests(self, machine: str | None = None, axis: str | None = None) -> list:
        """The stored tests, newest first (TestSummary records)."""
        return self.store.tests(machine, axis)

    def machines(self) -> list:
        """The machines with their axes and test counts (MachineSummary records)."""
        return self.store.machines()

    def get(self, test_id: int) -> Any:
        """One stored test (StoredTest: its file, metadata and evaluation)."""
        return self.store.get(test_id)

    def evaluation(self, test_id: int) -> "Evaluation":
        """A stored test's record: its stored bytes evaluated again by this version of
        axiscal (kept once made, :mod:`axiscal.store.cache`) with the uncertainty budget of the
        inputs stored with it (:meth:`axiscal.store.history.StoredTest.record`): field for
        field what :func:`axiscal.evaluate` gave for the file with those inputs (quantities
        with U, budget, per-target table, ``to_dict()``, ``plot()``, ``report()``)."""
        from axiscal.api._results import Evaluation
        from axiscal.report.evaluations import record_fields

        return Evaluation(**record_fields(self.store.get(test_id).record()))

    def report(self, test_id: int, path: PathLike) -> Path:
        """Write a stored test's HTML report, of any kind (``axiscal history show ID --report``
        and the workbench's "Report" link): :meth:`evaluation`'s ``report()``, titled with
        the machine and axis names the history keeps (as corrected), which a positioning
        report takes from its dataset; returns the path."""
        from axiscal.report.evaluations import REPORT_TITLES

        t = self.store.get(test_id).summary
        ev = self.evaluation(test_id)
        title = None
        if ev.kind == "volumetric":          # the command's heading, the history's name
            title = f"{REPORT_TITLES[ev.kind]} — {t.machine}"
        elif ev.kind == "squareness":        # the command's heading names its two files
            title = (f"{t.machine} axis {t.axis} (test {t.id}, {t.filename}: "
                     f"{ev.dataset.one.source}, {ev.dataset.two.source})")
        elif ev.kind != "iso230-2":
            kind = ("Ballbar diagnosis" if ev.kind == "ballbar" and hasattr(ev.result, "circular")
                    else REPORT_TITLES[ev.kind])
            title = f"{kind} — {t.machine} axis {t.axis} (test {t.id}, {t.filename})"
        return Path(ev.report(path, title))

    def trend(self, machine: str, axis: str, parameter: str,
              tolerance: float | None = None) -> Any:
        """The trend of one parameter of one axis (axiscal.store.analysis.Trend)."""
        from axiscal.store import trend

        return trend(self.store, machine, axis, parameter, tolerance)

    def close(self) -> None:
        """Close the database (a store given open is left to its owner)."""
        if self._owned:
            self.store.close()

    def __enter__(self) -> "History":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
