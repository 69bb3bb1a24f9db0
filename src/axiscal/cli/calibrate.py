"""``axiscal calibrate CONFIG``: the whole job on LinuxCNC in one run (issue 41).

A linear or a rotary axis (a turntable: the full turn and its overruns). Plan → LinuxCNC program → LinuxCNC runs it while the simulated laser records → capture → ISO 230-2
→ compensation table loaded into LinuxCNC → the program again → both tests stored in the history
→ a report showing both (:func:`axiscal.compensation.by_program.calibrate`) → with
``--certificate``, the "as found / as left" certificate of the two stored tests
(:func:`axiscal.report.issue.write_as_found_as_left`, what ``axiscal certificate as-found-as-left``
calls), numbered as the as-left test's with the as-found test named beside it in the register.

``--json`` prints ``before`` and ``after`` (the ISO 230-2 parameters of each test), ``reduction``
(of E), ``unit``, ``runs`` (per LinuxCNC run: ``samples``, ``seconds`` of servo time, ``stops``,
``measurements``, ``gaps``, ``compensated``, ``travel``: the lowest and highest position in
LinuxCNC's record, mm or deg), ``history`` (the stored tests' ``id`` and
``duplicate``, ``before`` then ``after``), ``table`` (``points``, ``spacing``) and
``certificate`` (null without ``--certificate``; else ``path``, ``draft``, ``number`` (null for a
DRAFT) and ``missing``: what a DRAFT lacks).
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from axiscal.cli._certificate import APPROVED_BY, DRAFT, JOB, PAPER, PREPARED_BY, RULE
from axiscal.cli._common import note, print_json, progress_bar, report_path


def calibrate_cmd(
    config: Path = typer.Argument(..., help="Machine and test configuration (TOML, as compensate --verify takes)."),
    targets: Optional[int] = typer.Option(None, "--targets", min=2, max=10_000, help="Targets of the test (default: the configuration's)."),
    runs: Optional[int] = typer.Option(None, "--runs", min=1, max=100, help="Runs per direction (default: the configuration's)."),
    spacing: Optional[float] = typer.Option(None, "--spacing", help="Spacing of the compensation table, mm or deg (default: the configuration's)."),
    dwell: float = typer.Option(0.3, "--dwell", help="Dwell of the program at each target, s (the simulated drive settles in 0.1 s)."),
    feed: float = typer.Option(30000.0, "--feed", help="Feed of the program's moves, mm/min (deg/min on a rotary axis)."),
    seed: int = typer.Option(1, "--seed", min=0, help="Seed of the simulated machine's noise."),
    db: Optional[str] = typer.Option(None, "--db", help="History database URL (default: AXISCAL_DB, else SQLite in the user's data folder)."),
    report: Optional[Path] = typer.Option(None, "--report", help="Write a report showing both tests (.html or .pdf)."),
    certificate: Optional[Path] = typer.Option(None, "--certificate", help="Also issue the 'as found / as left' certificate of the two tests (.html or .pdf), as 'axiscal certificate as-found-as-left' does."),
    job: Optional[Path] = JOB,
    tolerance: list[str] = typer.Option([], "--tolerance", help="Acceptance tolerance as NAME=VALUE, decided for both tests on the certificate."),
    rule: Optional[str] = RULE, paper: Optional[str] = PAPER, draft: bool = DRAFT,
    prepared_by: str = PREPARED_BY, approved_by: str = APPROVED_BY,
    json_out: bool = typer.Option(False, "--json", help="Print the result as JSON."),
) -> None:
    """Calibrate an axis on LinuxCNC in one run: test, compensate, test again, store both.

    Example: axiscal calibrate examples/compensation_linear.toml --report calibration.html
    --certificate X-as-left.pdf --job job.toml
    """
    from axiscal import api
    from axiscal.compensation.by_program import calibrate
    from axiscal.io._files import load_toml
    from axiscal.io.csv import format_positioning_csv

    if report is not None:
        report_path(report)
    cert_cfg = tolerances = None
    if certificate is not None:          # every input of the certificate checked before LinuxCNC
        from axiscal.cli.iso230_2 import parse_tolerances
        from axiscal.report.issue import load_config

        report_path(certificate)
        cert_cfg, tolerances = load_config(job), parse_tolerances(tolerance)
    cfg = load_toml(config)
    test = dict(cfg.get("test", {}))
    test.update({k: v for k, v in (("n_targets", targets), ("runs", runs)) if v is not None})
    cfg["test"] = test
    over = {} if spacing is None else {"spacing": spacing}
    with progress_bar("LinuxCNC runs the test program") as bar:
        r, hook = calibrate(cfg, seed=seed, dwell=dwell, feed=feed, progress=bar, **over)
    meta = cfg.get("meta", {})
    machine = str(meta.get("machine", "LinuxCNC simulated machine"))
    axis = str(cfg.get("axis", {}).get("name", "X"))
    stored = []
    with api.History(db) as h:
        for label, ds in (("before", r.before_data), ("after", r.after_data)):
            name = f"calibrate_{config.stem}_{axis}_{label}.csv"
            a = h.add(format_positioning_csv(ds).encode(), filename=name, machine=machine,
                      axis=axis, note=f"axiscal calibrate: {'as found' if label == 'before' else 'as left, compensation loaded'} (LinuxCNC)")
            stored.append({"id": a.id, "duplicate": a.duplicate})
        outcome = None
        if certificate is not None:
            outcome = _certificate(h.store, stored, certificate, cert_cfg, tolerances, rule,
                                   paper, job, prepared_by, approved_by)
    d = dict(before=r.before.parameters(), after=r.after.parameters(), reduction=r.reduction,
             unit=r.unit, runs=hook.runs, history=stored,
             table=dict(points=r.table.n_points, spacing=r.table.spacing),
             certificate=None if outcome is None else dict(
                 path=str(outcome.path), draft=outcome.draft, missing=list(outcome.missing),
                 number=None if outcome.draft else outcome.record.number))
    if report is not None:
        from axiscal.report.compensation_plots import compensation_figure
        from axiscal.report.html import write_result_report

        write_result_report(report, f"Calibration on LinuxCNC — {config.name}", d,
                            figure=compensation_figure(r), simulation=True,
                            method="The plan's LinuxCNC part program run on a headless LinuxCNC "
                                   "while the simulated laser recorded, the stops captured and "
                                   "evaluated by ISO 230-2:2014, the LinuxCNC table loaded as "
                                   "COMP_FILE and the program run again.")
        note(f"wrote report {report}")
    for s, label in zip(stored, ("as found", "as left")):
        note(f"history: {label} test {'already stored as' if s['duplicate'] else 'stored as'} {s['id']}")
    if json_out:
        print_json(d)
    else:
        _tell(r, hook)
    if outcome is not None:
        from axiscal.cli._certificate import tell_outcome

        tell_outcome(outcome, draft)


def _certificate(store, stored, path, cfg, tolerances, rule, paper, job, prepared_by,
                 approved_by):
    """The as found / as left certificate of the two tests just stored (the library call of
    ``axiscal certificate as-found-as-left``)."""
    from axiscal.io.user_config import config_problem
    from axiscal.report.issue import write_as_found_as_left

    return write_as_found_as_left(path, store, stored[0]["id"], stored[1]["id"], cfg, tolerances,
                                  rule, paper, job, config_note=config_problem(),
                                  prepared_by=prepared_by, approved_by=approved_by)


def _tell(r, hook) -> None:
    u = {"um": "µm", "arcsec": "″"}.get(r.unit, r.unit)
    typer.echo(f"E {r.before.E:.3f} {u} as found, {r.after.E:.3f} {u} as left: fell by "
               f"{100 * r.reduction:.1f} % (LinuxCNC table of {r.table.n_points} points every "
               f"{r.table.spacing:g} {'deg' if r.unit == 'arcsec' else 'mm'})")
    for k, run in enumerate(hook.runs):
        typer.echo(f"run {k + 1}{' (compensated)' if run['compensated'] else ''}: "
                   f"{run['seconds']:.1f} s of servo time, {run['stops']} stops, "
                   f"{run['measurements']} readings, {run['gaps']} samples missing")


def register(app: typer.Typer) -> None:
    """Add the ``calibrate`` command."""
    app.command("calibrate")(calibrate_cmd)
