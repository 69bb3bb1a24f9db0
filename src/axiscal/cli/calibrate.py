"""``axiscal calibrate CONFIG``: the whole job on LinuxCNC in one run (issue 41).

Plan → LinuxCNC program → LinuxCNC runs it while the simulated laser records → capture → ISO 230-2
→ compensation table loaded into LinuxCNC → the program again → both tests stored in the history
→ a report showing both (:func:`axiscal.compensation.by_program.calibrate`). The "as found / as
left" certificate is not issued here yet (``axiscal certificate`` makes it from the history).

``--json`` prints ``before`` and ``after`` (the ISO 230-2 parameters of each test), ``reduction``
(of E), ``unit``, ``runs`` (per LinuxCNC run: ``samples``, ``seconds`` of servo time, ``stops``,
``measurements``, ``gaps``, ``compensated``), ``history`` (the stored tests' ``id`` and
``duplicate``, ``before`` then ``after``) and ``table`` (``points``, ``spacing``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from axiscal.cli._common import note, print_json, progress_bar, report_path


def calibrate_cmd(
    config: Path = typer.Argument(..., help="Machine and test configuration (TOML, as compensate --verify takes)."),
    targets: Optional[int] = typer.Option(None, "--targets", min=2, max=10_000, help="Targets of the test (default: the configuration's)."),
    runs: Optional[int] = typer.Option(None, "--runs", min=1, max=100, help="Runs per direction (default: the configuration's)."),
    spacing: Optional[float] = typer.Option(None, "--spacing", help="Spacing of the compensation table, mm (default: the configuration's)."),
    dwell: float = typer.Option(0.3, "--dwell", help="Dwell of the program at each target, s (the simulated drive settles in 0.1 s)."),
    feed: float = typer.Option(30000.0, "--feed", help="Feed of the program's moves, mm/min."),
    seed: int = typer.Option(1, "--seed", min=0, help="Seed of the simulated machine's noise."),
    db: Optional[str] = typer.Option(None, "--db", help="History database URL (default: AXISCAL_DB, else SQLite in the user's data folder)."),
    report: Optional[Path] = typer.Option(None, "--report", help="Write a report showing both tests (.html or .pdf)."),
    json_out: bool = typer.Option(False, "--json", help="Print the result as JSON."),
) -> None:
    """Calibrate an axis on LinuxCNC in one run: test, compensate, test again, store both.

    Example: axiscal calibrate examples/compensation_linear.toml --report calibration.html
    """
    from axiscal import api
    from axiscal.compensation.by_program import calibrate
    from axiscal.io._files import load_toml
    from axiscal.io.csv import format_positioning_csv

    if report is not None:
        report_path(report)
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
    d = dict(before=r.before.parameters(), after=r.after.parameters(), reduction=r.reduction,
             unit=r.unit, runs=hook.runs, history=stored,
             table=dict(points=r.table.n_points, spacing=r.table.spacing))
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
        return
    u = {"um": "µm"}.get(r.unit, r.unit)
    typer.echo(f"E {r.before.E:.3f} {u} as found, {r.after.E:.3f} {u} as left: fell by "
               f"{100 * r.reduction:.1f} % (LinuxCNC table of {r.table.n_points} points every "
               f"{r.table.spacing:g} mm)")
    for k, run in enumerate(hook.runs):
        typer.echo(f"run {k + 1}{' (compensated)' if run['compensated'] else ''}: "
                   f"{run['seconds']:.1f} s of servo time, {run['stops']} stops, "
                   f"{run['measurements']} readings, {run['gaps']} samples missing")


def register(app: typer.Typer) -> None:
    """Add the ``calibrate`` command."""
    app.command("calibrate")(calibrate_cmd)
