"""``axiscal history ...``: the calibration history of every machine, axis and test.

Commands: ``add FILE`` (evaluate and store; a file stored before is recognised), ``machines``,
``list`` (filters ``--machine --axis --kind --since``), ``show ID`` (the stored test evaluated
again from its stored bytes, with ``--plot``/``--report``), ``compare ID1 ID2``, ``trend
--machine M --axis A --parameter P [--tolerance T]``, ``export ARCHIVE.zip`` and ``import
ARCHIVE.zip``. Every command takes ``--db URL`` (default ``AXISCAL_DB``, else SQLite in the
user's data folder) and ``--json``.

JSON output (``--json``), stable keys:

* ``add``: ``id``, ``duplicate``, ``kind``, ``machine``, ``axis``.
* ``machines``: list of ``name``, ``axes``, ``tests``, ``last``.
* ``list``: list of ``id``, ``machine``, ``axis``, ``kind``, ``date``, ``date_known``,
  ``file``, ``parameters`` (name -> ``{"value", "unit"}``).
* ``show``: ``id``, ``machine``, ``axis``, ``kind``, ``date``, ``file``, ``sha256``,
  ``stored_with`` (axiscal version), ``parameters``, ``result`` (the evaluation), ``tables``.
* ``compare``: ``first``, ``second``, ``parameters`` (list of ``name``, ``first``, ``second``,
  ``change``, ``unit``), ``targets``, ``difference``, ``target_unit``, ``unit``.
* ``trend``: ``parameter``, ``unit``, ``points`` (``date``, ``value``, ``test``), ``model``,
  ``drift_per_year``, ``u_drift_per_year``, ``level``, ``tolerance``, ``crossing``,
  ``u_crossing_days``, ``recalibrate_by``.
* ``export``/``import``: ``archive``, ``tests`` / ``added``, ``duplicates`` and what came in
  beside the tests: ``audit`` (entries), ``laboratory`` (1 when taken), ``drift_checks``
  (files), ``certificates`` (register entries), ``documents`` (issued, distinct).
* ``list`` also ``withdrawn`` (the reason, or null). Corrections (``rename-machine``,
  ``rename-axis``, ``merge``, ``edit``, ``withdraw``, ``reinstate``, ``audit``):
  :mod:`axiscal.cli.history_corrections`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from axiscal.cli import history_corrections as _corrections
from axiscal.cli._common import note, plot_path, print_json, progress_bar, report_path
from axiscal.cli._history_store import DB as _DB
from axiscal.cli._history_store import JSON as _JSON
from axiscal.cli._history_store import open_db as _store
from axiscal.cli._history_store import store_run

__all__ = ["register", "store_run"]

app = typer.Typer(help="Calibration history: every machine, axis, test, result and table kept, "
                  "compared and trended (SQLite by default, PostgreSQL with --db).",
                  no_args_is_help=True)


@app.command("add")
def add(
    file: Path = typer.Argument(..., help="A data file axiscal evaluates (positioning, "
                                "straightness, ballbar, diagonal or five-error CSV, JSON; a "
                                "five-axis probing or R-test CSV stating its geometry; an ISO 230-3 thermal log; a volumetric configuration with its errors inline)."),
    machine: Optional[str] = typer.Option(None, "--machine", help="Machine name (default: the "
                                          "file's)."),
    axis: Optional[str] = typer.Option(None, "--axis", help="Axis name (default: the file's)."),
    kind: Optional[str] = typer.Option(None, "--kind", help="iso230-2, straightness, ballbar, "
                                       "diagonal, motion, fiveaxis, fiveaxis-ballbar, thermal "
                                       "or volumetric (default: from the content)."),
    instrument: str = typer.Option("", "--instrument", help="Instrument and its serial."),
    note_: str = typer.Option("", "--note", help="A note kept with the test."),
    date: Optional[str] = typer.Option(None, "--date", help="Test date YYYY-MM-DD (default: the "
                                       "file's, else today, marked as unknown)."),
    drift_check: Optional[Path] = typer.Option(None, "--drift-check", help="A positioning "
                                               "test's drift check (ISO 230-2:2014 Annex A.5), "
                                               "kept with it: its E_VE, measured, is the "
                                               "budget's."),
    db: Optional[str] = _DB,
    json_out: bool = _JSON,
) -> None:
    """Evaluate a test file and store it in the history.

    Example: axiscal history add demo-output/linear_data.csv --machine VMC-800 --axis X
    """
    from axiscal import api

    with api.History(db) as h:
        extra = {} if drift_check is None else {"drift_check": drift_check}
        r = h.add(file, machine=machine, axis=axis, kind=kind, instrument=instrument,
                  note=note_, date=date, **extra)
    if json_out:
        print_json({"id": r.id, "duplicate": r.duplicate, "kind": r.kind, "machine": r.machine,
                    "axis": r.axis})
    elif r.duplicate:
        typer.echo(f"already stored as test {r.id} ({r.machine} {r.axis}, {r.kind}): "
                   "same file content")
    else:
        typer.echo(f"stored as test {r.id}: {r.machine} {r.axis}, {r.kind}")
    from shlex import quote

    typed = [f"--{k} {quote(v)}" for k, v in (("date", date), ("instrument", instrument),
                                         ("note", note_)) if v]
    if r.duplicate and drift_check is not None:
        note(f"not stored: --drift-check {quote(str(drift_check))} (test {r.id} was stored "
             "before and keeps its record)")
    if r.duplicate and typed:      # not stored with the old test: said, with the correction
        note(f"not stored: {' '.join(typed)} (test {r.id} keeps what it was stored with); "
             f"to change it: axiscal history edit {r.id} {' '.join(typed)} --by NAME "
             "--reason TEXT")


@app.command("machines")
def machines(db: Optional[str] = _DB, json_out: bool = _JSON) -> None:
    """Every machine with its axes and tests.

    Example: axiscal history machines
    """
    rows = _store(db).machines()
    if json_out:
        print_json([{"name": m.name, "axes": list(m.axes), "tests": m.tests,
                     "last": m.last.isoformat() if m.last else None} for m in rows])
        return
    if not rows:
        typer.echo("the history is empty (axiscal history add FILE --machine NAME --axis X)")
    for m in rows:
        last = f"{m.last:%Y-%m-%d}" if m.last else "—"
        typer.echo(f"{m.name:<24} axes {' '.join(m.axes) or '—':<12} {m.tests:>5} tests, "
                   f"last {last}")


@app.command("list")
def list_(
    machine: Optional[str] = typer.Option(None, "--machine", help="Only this machine."),
    axis: Optional[str] = typer.Option(None, "--axis", help="Only this axis."),
    kind: Optional[str] = typer.Option(None, "--kind", help="Only this kind of test."),
    since: Optional[str] = typer.Option(None, "--since", help="Only tests on or after "
                                        "YYYY-MM-DD."),
    db: Optional[str] = _DB,
    json_out: bool = _JSON,
) -> None:
    """Stored tests, newest first.

    Example: axiscal history list --machine VMC-800 --axis X
    """
    from axiscal.report.labels import unit_text
    from axiscal.store.history import _parse_date

    when = _parse_date(since.strip()) if since else None     # a filter: any date
    rows = _store(db).tests(machine=machine, axis=axis, kind=kind, since=when)
    if json_out:
        print_json([_row(t) for t in rows])
        return
    if not rows:
        typer.echo("no stored test matches")
    wm = max([20, *(len(t.machine) for t in rows)])   # columns stay aligned for long names
    wa = max([4, *(len(t.axis) for t in rows)])
    for t in rows:
        key = next((k for k in ("E", "squareness", "straightness") if k in t.parameters), None)
        main = f"{key} {t.parameters[key][0]:.3f} {unit_text(t.parameters[key][1])}" if key else ""
        date = f"{t.tested_at:%Y-%m-%d}" + ("" if t.date_known else "?")
        typer.echo(f"{t.id:>6}  {date:<11} {t.machine:<{wm}} {t.axis:<{wa}} {t.kind:<13} "
                   f"{main:<22} {t.filename}"
                   + (f"  WITHDRAWN: {t.withdrawn}" if t.withdrawn else ""))


@app.command("show")
def show(
    test_id: int = typer.Argument(..., help="Test id (from 'history list')."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Write the test's plot again "
                                        "(.png, .svg, .pdf)."),
    report: Optional[Path] = typer.Option(None, "--report", help="Write its HTML report again "
                                          "(.html)."),
    db: Optional[str] = _DB,
    json_out: bool = _JSON,
) -> None:
    """A stored test, evaluated again from its stored bytes (same numbers as the first time).

    Example: axiscal history show 1 --report again.html
    """
    plot = plot_path(plot) if plot else None
    report = report_path(report) if report else None
    store = _store(db)
    t = store.get(test_id)
    ev = t.record()                     # the stored bytes' evaluation with its stored inputs' U
    if plot or report:
        _figures(store, test_id, plot, report, t)
    if json_out:
        s = t.summary
        stored = ev.stored_result()
        print_json({"id": s.id, "machine": s.machine, "axis": s.axis, "kind": s.kind,
                    "date": s.tested_at.isoformat(), "date_known": s.date_known,
                    "file": s.filename, "sha256": t.sha256, "stored_with": t.axiscal_version,
                    "schema_version": stored["schema_version"],
                    "quantities": stored["quantities"],
                    "uncertainty_inputs": stored["uncertainty_inputs"],
                    # deprecated (schema 1): the same numbers as quantities.NAME.value, .unit
                    "parameters": {k: {"value": v, "unit": u} for k, (v, u) in
                                   ev.parameters.items()},
                    "result": stored,
                    "tables": [{"controller": c, "file": f} for c, f, _ in t.tables]})
        return
    s = t.summary
    typer.echo(f"test {s.id}: {s.machine} {s.axis}, {s.kind}, {s.tested_at:%Y-%m-%d}"
               f"{'' if s.date_known else ' (date not in the file: the day it was stored)'}, "
               f"file {s.filename} (sha256 {t.sha256[:12]}…), stored with axiscal "
               f"{t.axiscal_version}")
    if ev.kind == "iso230-2":
        from axiscal.cli.iso230_2 import render_result

        render_result(ev.evaluation, ev.dataset, budget=ev.budget)
    else:
        typer.echo(str(ev.evaluation))
        for q in ev.quantities.values():
            if q.U is not None:
                typer.echo(str(q))
    for c, f, _ in t.tables:
        typer.echo(f"compensation table: {c} {f}")


@app.command("compare")
def compare(
    first: int = typer.Argument(..., help="Test id (before)."),
    second: int = typer.Argument(..., help="Test id (after)."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Per-target difference plot "
                                        "(.png, .svg, .pdf)."),
    db: Optional[str] = _DB,
    json_out: bool = _JSON,
    report: Optional[Path] = typer.Option(None, "--report", help="Write the comparison as a "
                                          "report (plot and every parameter): HTML or PDF."),
) -> None:
    """Two tests of one axis side by side: every parameter, its change, the difference per target.

    Example: axiscal history compare 1 2 --plot change.png
    """
    from axiscal.store.analysis import compare_tests

    plot = plot_path(plot) if plot else None
    report = report_path(report) if report else None
    store = _store(db)
    c = compare_tests(store.get(first), store.get(second))
    if plot:
        from axiscal.report.history_plots import comparison_figure
        from axiscal.report.plots import save_figure

        save_figure(comparison_figure(c), plot)
        note(f"wrote plot {plot}")
    if report:
        from axiscal.report.history_plots import comparison_figure
        from axiscal.report.html import write_result_report

        write_result_report(report, f"Tests {first} and {second} compared", c.as_dict(),
                            figure=comparison_figure(c),
                            method="Every parameter of the two tests (each evaluated by its "
                                   "standard from the stored readings) and its change, and the "
                                   "difference of the mean deviations per target.")
        note(f"wrote report {report}")
    if json_out:
        print_json(c.as_dict())
    else:
        typer.echo(str(c))


@app.command("trend")
def trend(
    machine: str = typer.Option(..., "--machine", help="Machine name."),
    axis: str = typer.Option(..., "--axis", help="Axis name."),
    parameter: str = typer.Option("E", "--parameter", help="Parameter (E, A, R, B, M, another standard's as KEY:NAME such as jis-b6192:R, "
                                  "squareness, straightness ...)."),
    tolerance: Optional[float] = typer.Option(None, "--tolerance", help="Tolerance to predict "
                                              "the crossing of, in the parameter's unit."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Trend plot (.png, .svg, .pdf)."),
    db: Optional[str] = _DB,
    json_out: bool = _JSON,
    report: Optional[Path] = typer.Option(None, "--report", help="Write the trend as a report "
                                          "(plot, drift, predicted crossing): HTML or PDF."),
) -> None:
    """A parameter over time with its fitted drift, and when it will reach a tolerance.

    Example: axiscal history trend --machine VMC-800 --axis X --parameter E --tolerance 15
    """
    from axiscal.store import trend as fit

    plot = plot_path(plot) if plot else None
    report = report_path(report) if report else None
    tr = fit(_store(db), machine, axis, parameter, tolerance)
    if plot:
        from axiscal.report.history_plots import trend_figure
        from axiscal.report.plots import save_figure

        save_figure(trend_figure(tr, f"{machine} {axis.upper()}"), plot)
        note(f"wrote plot {plot}")
    if report:
        from axiscal.report.history_plots import trend_figure
        from axiscal.report.html import write_result_report

        write_result_report(report, f"{parameter} of {machine} {axis.upper()} over time",
                            tr.as_dict(), figure=trend_figure(tr, f"{machine} {axis.upper()}"),
                            method="Least-squares straight line through the stored values "
                                   "(ISO/TS 28037:2010 clause 6); the date the line reaches the "
                                   "tolerance with its uncertainty by the GUM's law of "
                                   "propagation (JCGM 100:2008 §5.1.2), and a recalibration date "
                                   "at k = 2.")
        note(f"wrote report {report}")
    if json_out:
        print_json(tr.as_dict())
    else:
        typer.echo(f"{machine} {axis.upper()}: {tr}")


@app.command("export")
def export(
    archive: Path = typer.Argument(..., help="Archive to write (.zip)."),
    machine: Optional[str] = typer.Option(None, "--machine", help="Only this machine."),
    db: Optional[str] = _DB,
    json_out: bool = _JSON,
) -> None:
    """Write the history (or one machine's) as a portable archive: JSON lines + raw files.

    Written to a temporary file and renamed into place: a full disk leaves no partial archive.

    Example: axiscal history export vmc800.zip --machine VMC-800
    """
    from axiscal.cli._common import typed_path
    from axiscal.store.archive import export_history

    typed_path(archive, "archive", (".zip",))
    n = export_history(_store(db), archive, machine)
    if json_out:
        print_json({"archive": str(archive), "tests": n})
    else:
        typer.echo(f"wrote {n} tests to {archive}")


@app.command("import")
def import_(
    archive: Path = typer.Argument(..., help="Archive written by 'history export' (.zip)."),
    db: Optional[str] = _DB,
    json_out: bool = _JSON,
) -> None:
    """Store every test of an archive, all or nothing; tests already stored are skipped.

    The archive is checked whole before the first row (its ZIP directory's sizes, every record,
    every raw file and its SHA-256, every file evaluated again), then stored in one transaction:
    a damaged archive or an interrupted import leaves the history as it was.

    Example: axiscal history import vmc800.zip --db sqlite:///customer.sqlite
    """
    from axiscal.errors import MissingFileError
    from axiscal.store.archive import import_history

    if not archive.is_file():
        raise MissingFileError(archive)
    store = _store(db, create=True)
    if json_out:
        print_json({"archive": str(archive), **import_history(store, archive).to_dict()})
        return
    with progress_bar(f"importing {archive.name}") as bar:
        done = import_history(store, archive, bar)
    typer.echo(done.text(archive))


def _row(t) -> dict:
    return {"id": t.id, "machine": t.machine, "axis": t.axis, "kind": t.kind,
            "date": t.tested_at.isoformat(), "date_known": t.date_known, "file": t.filename,
            "parameters": {k: {"value": v, "unit": u} for k, (v, u) in t.parameters.items()},
            "withdrawn": t.withdrawn or None}


def _figures(store, test_id: int, plot, report, stored) -> None:
    """The plot and report of a stored test, made again from its record
    (``axiscal.History.evaluation``: its readings and the U of its stored inputs), as
    ``Evaluation.plot()`` and ``Evaluation.report()`` make them for every kind."""
    from axiscal.api import History

    ev = History(store=store).evaluation(test_id)
    if plot:
        from axiscal.report.plots import save_figure

        save_figure(ev.plot(), plot)
    if report:
        History(store=store).report(test_id, report)     # as the workbench's Report link
    for p, what in ((plot, "plot"), (report, "report")):
        if p:
            note(f"wrote {what} {p}")


def register(root: typer.Typer) -> None:
    """Add the ``history`` command group to the application."""
    root.add_typer(app, name="history")


_corrections.add_commands(app)       # rename-machine ... audit (axiscal.cli.history_corrections)
