"""``axiscal evaluate FILE --standard KEY|all``: a positioning test by the standard a contract names.

JSON output (``--json``), stable: ``unit``, ``target_unit``, ``standards`` (one object per standard:
``standard`` (key), ``title``, ``evaluated`` (bool), ``parameters`` (name -> ``value``, ``unit``,
``description``; empty if not evaluated), ``not_evaluated`` (name -> why axiscal does not evaluate
that parameter of a standard evaluated in part), ``warnings`` (list of text), ``reason`` (why the
standard was not evaluated at all, else null)). With ``--tolerance``: ``acceptance``,
``decision_rule`` and ``accepted`` as in ``axiscal iso230-2`` (``U`` null where no budget gives it: every standard but ISO 230-2:2014;
``U_display`` the same rounded up to two significant digits), ``warnings`` (a tolerance not larger
than its U) and, for ISO 230-2:2014, ``uncertainty_budget`` as in ``axiscal iso230-2``. A
Renishaw ``.rta`` (deviations in µrad in the file, shown in arcsec): ``in_file_unit``
(``deviation_unit`` ``urad``, ``source``, ``standards``: key -> name -> value in µrad).

Exit codes: 0 evaluated (and every tolerance proven met), 1 a tolerance not proven met, 2 a user
error (including a single ``--standard`` whose definitions were not publicly available to axiscal).
"""

from __future__ import annotations

from pathlib import Path
from typing import List, Optional

import typer

from axiscal.cli._epics import (REFERENCE_OFFSET, REFERENCE_PV, REFERENCE_SCALE, REST_WINDOW,
                                SETPOINT_PV, TARGETS, epics_options, show_notes)
from axiscal.cli._common import note, plot_path, print_json, progress_bar, report_path
from axiscal.cli._encoding import ENCODING

__all__ = ["register"]

_KEYS = "iso230-2:2014|iso230-2:2006|iso230-2:1997|iso230-2:1988|gb-t17421.2|jis-b6192|vdi3441|" \
        "asme-b5.54|bs3800|nmtba|all"


def evaluate(
    file: Path = typer.Argument(..., help="Positioning data: tidy CSV, axiscal JSON, Renishaw .rtl/.rta, EPICS ecmc file or EPICS camonitor log."),
    standard: str = typer.Option(..., "--standard", "-s", help=f"{_KEYS}. Standards whose definitions were not publicly available are listed with the reason and not evaluated."),
    target_unit: Optional[str] = typer.Option(None, "--target-unit", help="Unit of the targets in a file that does not declare it: mm or deg."),
    deviation_unit: Optional[str] = typer.Option(None, "--deviation-unit", help="Unit of the deviations in a CSV that does not declare it: um, mm or arcsec."),
    json_out: bool = typer.Option(False, "--json", help="Print the result as JSON (stable keys, see the docs)."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Write the per-target plot with the chosen standard's band (±2s ISO 230-2:2014/2006, ±3s JIS and ISO 230-2:1988, none where not public) and parameters; 'all' draws ISO 230-2:2014's, or the first standard's that evaluates the test."),
    report: Optional[Path] = typer.Option(None, "--report", help="Write the HTML report: every parameter of the chosen standard(s) with its source, what is not evaluated and why, the acceptance, the per-target figure."),
    tolerance: List[str] = typer.Option([], "--tolerance", help="NAME=VALUE in the deviation unit, in the chosen standard's names, e.g. -s jis-b6192 --tolerance R=6 (exit code 1 if not proven met)."),
    rule: Optional[str] = typer.Option(None, "--rule", help="Decision rule: iso14253-1 (with U of ISO 230-9; default and only for iso230-2:2014) or simple (default for the other standards, whose U no published budget gives)."),
    uncertainty: List[str] = typer.Option([], "--uncertainty", help="With -s iso230-2:2014: an input of its uncertainty budget as NAME=VALUE, e.g. --uncertainty e_ve=0.3, in the unit the output shows or with its unit ('expansion_coefficient=11.5 um/(m K)'), as 'axiscal iso230-2'; every input not given is shown as assumed."),
    setpoint_pv: Optional[str] = SETPOINT_PV,
    reference_pv: Optional[str] = REFERENCE_PV,
    targets: Optional[str] = TARGETS,
    reference_scale: Optional[float] = REFERENCE_SCALE,
    reference_offset: Optional[float] = REFERENCE_OFFSET,
    rest_window: Optional[float] = REST_WINDOW,
    encoding: Optional[str] = ENCODING,
) -> None:
    """Evaluate a positioning test by a named standard, or by all of them side by side.

    Example: axiscal evaluate x.csv --standard all
    """
    from axiscal import api
    from axiscal.cli.iso230_2 import parse_tolerances, parse_uncertainty
    from axiscal.errors import InputError
    from axiscal.standards import positioning_standards as ps

    key = standard.strip().lower()
    tolerances = parse_tolerances(tolerance)
    table = parse_uncertainty(uncertainty)
    if key == "all" and tolerances:
        raise InputError("--tolerance needs one --standard (parameter names differ between "
                         "standards)")
    if key != "all" and key not in ps.STANDARDS:
        raise InputError(f"--standard {standard}: use one of {_KEYS.replace('|', ', ')}")
    for p, check in ((plot, plot_path), (report, report_path)):
        if p is not None:
            check(p)
    with progress_bar(f"reading {file.name}") as bar:
        ds = api.read(file, kind="iso230-2", target_unit=target_unit,
                      deviation_unit=deviation_unit, progress=bar, epics=epics_options(
                          setpoint_pv, reference_pv, targets, reference_scale,
                          reference_offset, rest_window), encoding=encoding)
    ev = api.evaluate(ds, key, tolerances=tolerances, rule=rule, uncertainty=table,
                      form="standards")
    show_notes(ds)   # after the evaluation: a refusal is then the one line (issue 39)
    if plot is not None:
        from axiscal.report.plots import save_figure

        try:
            fig = ev.plot()
        except InputError:
            raise InputError("--plot: no standard evaluates this test, so there is no figure; "
                             "the reasons are in the table without --plot") from None
        save_figure(fig, plot)
    if report is not None:
        what = "every positioning standard" if key == "all" else ev.results[0][0].title
        ev.report(report, title=f"Positioning test {file.name} by {what}")
    if json_out:
        print_json(ev.to_dict())
    else:
        budget = ev.budget if "uncertainty_budget" in ev.to_dict() else None
        _render(ev.results, ds, str(file), ev.verdicts, budget)
    for p, what in ((plot, "plot"), (report, "report")):
        if p is not None:
            note(f"wrote {what} {p}")
    if ev.conformance_proven is False:
        raise typer.Exit(1)


def _render(results, ds, title, verdicts, budget=None) -> None:
    import math

    from axiscal.standards import positioning_standards as ps

    from rich.markup import escape
    from rich.table import Table

    from axiscal.cli._common import console

    con = console()
    sym = {"um": "µm"}.get(ds.deviation_unit, ds.deviation_unit)
    heading = f"Positioning test {title} by standard"
    t = Table(title=escape(heading), title_justify="left")
    for c, j in (("standard", "left"), ("parameter", "left"), (f"value [{sym}]", "right"),
                 ("meaning (clause)", "left")):
        t.add_column(escape(c), justify=j)
    skipped = []
    for std, res in results:
        if isinstance(res, str):
            skipped.append((std, res))
            continue
        for title_, label, v, desc, done in ps.table_rows(std, res):
            value = "—" if v is None or math.isnan(v) else f"{v:.2f}"
            t.add_row(escape(title_), label, value, escape(desc), style=None if done else "dim")
        t.add_section()
    con.print(t)
    unpublished = [std.title for std, _ in skipped if not std.available]
    if unpublished:
        con.print("not evaluated, no public text of their definitions was available to axiscal "
                  f"(docs/standards.md): {escape(', '.join(unpublished))}")
    for std, reason in skipped:
        if std.available:
            con.print(f"not evaluated ({escape(std.title)}): {escape(reason)}")
    if verdicts:
        from axiscal.standards.iso14253_1 import unprovable
        from axiscal.standards.iso230_9 import format_uncertainty

        con.print(f"acceptance ({verdicts[0].rule.value} decision rule):")
        for v in verdicts:
            state = "n/a" if v.outcome is None else v.outcome.value
            u = ("uncertainty not estimated" if math.isnan(v.U) else
                 f"U = {format_uncertainty(v.U)}")
            value = "n/a" if v.value is None else f"{v.value:.2f}"
            con.print(f"  {escape(v.parameter)}: {value} ({u}), tolerance {v.upper:g}: {state}")
        for w in unprovable(verdicts, sym):
            con.print(f"[bold red]warning:[/bold red] {escape(w)}")
    if budget is not None:
        from axiscal.cli.iso230_2 import render_uncertainty

        render_uncertainty(con, budget)
    for std, res in results:
        if not isinstance(res, str):
            for w in res.warnings:
                con.print(f"[yellow]warning ({escape(std.title)}):[/yellow] {escape(w)}")


def register(app: typer.Typer) -> None:
    """Add the ``evaluate`` command to the application."""
    app.command("evaluate")(evaluate)
