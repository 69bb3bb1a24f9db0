"""``axiscal iso230-2 FILE``: evaluate a positioning test by ISO 230-2:2014.

JSON output (``--json``), stable: top-level keys ``A``, ``A_up``, ``A_down``, ``E``, ``E_up``,
``E_down``, ``M``, ``R``, ``R_up``, ``R_down``, ``B``, ``B_mean`` (numbers in ``unit``, or null where
a unidirectional test makes them not apply), ``unit``, ``target_unit``, ``axis_kind``,
``n_runs``, ``missing``, ``closure_up``, ``closure_down``, ``machine``, ``axis`` (as the file
names them, "" if not), ``notes`` (the dataset's notes: for an EPICS camonitor log the PVs, the
stops found and the defaults used), ``targets`` (one object per target:
``target``, ``n_up``, ``n_down``, ``mean_up``, ``mean_down``, ``mean_bi``, ``reversal``, ``s_up``,
``s_down``, ``R_up_i``, ``R_down_i``, ``R_i``) and ``warnings`` (list of text). With
``--tolerance``: ``acceptance`` (one object per checked parameter: ``parameter``, ``value``,
``tolerance``, ``U`` (as printed, the U decided with), ``U_display``, ``outcome`` — ``conformance proven``, ``non-conformance
proven`` or ``uncertainty zone`` —, ``passed`` true/false/null for the zone), ``decision_rule`` and
``accepted`` (true when conformance is proven for every parameter, false when non-conformance is
proven for one, null otherwise); a tolerance not larger than its U (never provable, ISO
14253-1:2017 §5.2) adds a line to ``warnings``. Always: ``uncertainty`` (U at k = 2 per
parameter, ISO 230-2:2014 Annex A, in ``unit``, the raw number), ``uncertainty_display`` (U as
shown: two significant digits rounded up, JCGM 100:2008 §7.2.6) and ``uncertainty_budget``
(``unit``, ``k``, ``method``, ``U``, ``U_display``, ``contributors``, ``inputs``: name ->
``value``, ``unit``, ``assumed``, ``set_with``, ``rule``, ``label``; ``assumed`` (names),
``missing_inputs`` (left out of U, e.g. ``e_ve``), ``notes``, ``U_stated`` (the printed U the
``acceptance`` U is), ``U_narrow`` (Annex A's U of R and B without the sampling of the runs),
``cmc`` and ``floored`` (parameters whose U is the laboratory's CMC)). ``outliers``: readings
Grubbs' test finds apart from the other runs at their target (``target``, ``direction``,
``run``, ``value``, ``mean``, ``s``, ``G``, ``G_critical``, ``n``, ``sets`` — the parameters
the target decides —, ``rule``, ``text``), kept in the evaluation. A Renishaw ``.rta``, whose
deviations the file holds in µrad and axiscal shows in arcsec: ``in_file_unit``
(``deviation_unit`` ``urad``, ``source``, ``parameters``: ``A`` … ``B_mean`` in µrad). The
results as data, the same on every path (:mod:`axiscal.standards.quantities`): ``schema_version``, ``quantities``
and ``uncertainty_inputs``.

Exit codes: 0 evaluated (and conformance proven for every tolerance), 1 a tolerance not proven
met (non-conformance or uncertainty zone; with ``--rule simple``: exceeded), 2 a user error, 3 the
``--report`` certificate lacks a mandatory item and was written as a DRAFT (not with ``--draft``).
"""

from __future__ import annotations

from pathlib import Path
from typing import List, Optional

import typer

from axiscal.cli._certificate import APPROVED_BY, DRAFT, JOB, PAPER, PREPARED_BY, RULE
from axiscal.cli._epics import (REFERENCE_OFFSET, REFERENCE_PV, REFERENCE_SCALE, REST_WINDOW,
                                SETPOINT_PV, TARGETS, epics_options, show_notes)
from axiscal.cli._common import note, plot_path, print_json, progress_bar, report_path
from axiscal.cli._encoding import ENCODING

__all__ = ["register", "render_result"]


def iso230_2(
    file: Path = typer.Argument(..., help="Positioning data: tidy CSV, axiscal JSON, Renishaw .rtl/.rta, EPICS ecmc file or EPICS camonitor log."),
    target_unit: Optional[str] = typer.Option(None, "--target-unit", help="Unit of the targets in a CSV or ecmc file that does not declare it: mm or deg (a different declaration in the file is an error)."),
    deviation_unit: Optional[str] = typer.Option(None, "--deviation-unit", help="Unit of the deviations in a CSV that does not declare it: um, mm or arcsec (a different declaration in the file is an error)."),
    full_turn: str = typer.Option("separate", "--full-turn", help="Rotary 0-360 deg test: keep 0 and 360 deg as two targets ('separate') or pool them ('merge')."),
    json_out: bool = typer.Option(False, "--json", help="Print the result as JSON (stable keys, see the docs)."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Write the ISO 230-2 plot (PNG, SVG or PDF by extension)."),
    history: bool = typer.Option(False, "--history", help="Also store the test in the calibration history (see 'axiscal history')."),
    machine: Optional[str] = typer.Option(None, "--machine", help="With --history: the machine's name, if the file does not give it."),
    db: Optional[str] = typer.Option(None, "--db", help="With --history or --report: the history database whose certificate register numbers the certificate (default: AXISCAL_DB, else the user's SQLite file)."),
    report: Optional[Path] = typer.Option(None, "--report", help="Write the calibration certificate: self-contained HTML (.html) or PDF (.pdf, WeasyPrint); issued and numbered in the register when every mandatory item is given, else a DRAFT naming what is missing."),
    tolerance: List[str] = typer.Option([], "--tolerance", help="Acceptance tolerance as NAME=VALUE in the deviation unit, e.g. --tolerance A=12 --tolerance R=4 (exit code 1 if conformance is not proven)."),
    job: Optional[Path] = JOB,
    rule: Optional[str] = RULE,
    paper: Optional[str] = PAPER,
    draft: bool = DRAFT,
    prepared_by: str = PREPARED_BY,
    approved_by: str = APPROVED_BY,
    drift_check: Optional[Path] = typer.Option(None, "--drift-check", help="Drift-check file (CSV: a 'reading' column, or one column of numbers, in the deviation unit): E_VE of the uncertainty budget is the range of its readings, measured (ISO 230-2:2014 Annex A.5)."),
    uncertainty: List[str] = typer.Option([], "--uncertainty", help="An input of the uncertainty budget as NAME=VALUE, over the job file's \\[uncertainty], e.g. --uncertainty beam_offset=0.05 --uncertainty e_ve=0.3; a number is in the unit the 'Uncertainty inputs' table shows (expansion_coefficient=11.5 for 11.5 µm/(m·K)), or give its unit: 'material_temperature=293.15 K' (names, units and plausible ranges: the documentation's 'Uncertainty inputs' page; every input not given is shown as assumed, with the rule of its default)."),
    setpoint_pv: Optional[str] = SETPOINT_PV,
    reference_pv: Optional[str] = REFERENCE_PV,
    targets: Optional[str] = TARGETS,
    reference_scale: Optional[float] = REFERENCE_SCALE,
    reference_offset: Optional[float] = REFERENCE_OFFSET,
    rest_window: Optional[float] = REST_WINDOW,
    encoding: Optional[str] = ENCODING,
) -> None:
    """Evaluate a positioning test by ISO 230-2:2014: A, E, M, R, B, their U and verdicts.

    A, E, M, R, B per axis and per target, with their uncertainty (ISO 230-2:2014 Annex A) and,
    with tolerances, ISO 14253-1 decisions.

    Example: axiscal iso230-2 x_axis.csv --tolerance E=10 --report certificate.pdf
    """
    from axiscal import api

    tolerances = parse_tolerances(tolerance)

    if plot is not None:
        plot_path(plot)
    if report is not None:
        report_path(report)
    epics = epics_options(setpoint_pv, reference_pv, targets, reference_scale, reference_offset,
                          rest_window)
    if history and epics:
        from axiscal.errors import InputError

        raise InputError("--history keeps the file as it came and re-reads it alone, without "
                         f"--{next(iter(epics)).replace('_', '-')}: write the test to CSV "
                         "first (axiscal capture LOG --plan PLAN --out x.csv) and store that")
    if history and encoding is not None:
        from axiscal.cli._history_store import history_reads_alike

        history_reads_alike(file, encoding)
    with progress_bar(f"reading {file.name}") as bar:
        ds = api.read(file, kind="iso230-2", target_unit=target_unit,
                      deviation_unit=deviation_unit, progress=bar, epics=epics,
                      encoding=encoding)
    if full_turn != "separate" and ds.axis_kind.value != "rotary":
        from axiscal.errors import InputError

        raise InputError(f"--full-turn {full_turn} pools 0 and 360 deg of a rotary test; {file} "
                         f"is a {ds.axis_kind.value} axis")
    ev = api.evaluate(ds, tolerances=tolerances, rule=rule, job=job, full_turn=full_turn,
                      uncertainty=parse_uncertainty(uncertainty), drift_check=drift_check)
    show_notes(ds)   # after the evaluation: a refusal is then the one line (issue 39)
    if plot is not None:
        from axiscal.report.plots import save_figure

        save_figure(ev.plot(), plot)
    outcome = None
    if report is not None:
        from axiscal.io.user_config import config_problem
        from axiscal.report.issue import write_certificate
        from axiscal.store import open_store

        outcome = write_certificate(report, ds, ev.result, ev.config, Path(file).read_bytes(),
                                    tolerances, rule, paper, job, store=lambda: open_store(db),
                                    filename=file.name, config_note=config_problem(),
                                    prepared_by=prepared_by, approved_by=approved_by)
    if json_out:
        print_json(ev.to_dict())
    else:
        render_result(ev.result, ds, title=str(file), verdicts=ev.verdicts, budget=ev.budget)
    if plot is not None:
        note(f"wrote plot {plot}")
    if history:
        from axiscal.cli._history_store import store_run

        store_run(file, db, machine=machine, drift_check=drift_check)
    if outcome is not None:
        from axiscal.cli._certificate import tell_outcome

        tell_outcome(outcome, draft)
    if ev.conformance_proven is False:
        raise typer.Exit(1)


def parse_tolerances(items: List[str]) -> dict:
    """``["A=12", "R=4"]`` -> ``{"A": 12.0, "R": 4.0}``; a malformed item is an InputError."""
    from axiscal.errors import InputError

    out = {}
    for item in items:
        name, sep, value = item.partition("=")
        if name.strip() in out:
            raise InputError(f"--tolerance {name.strip()} is given twice; give each parameter once")
        try:
            out[name.strip()] = float(value)
        except ValueError:
            sep = ""
        if not sep:
            raise InputError(f"--tolerance {item!r}: write NAME=VALUE, e.g. A=12")
    return out


def parse_uncertainty(items: List[str]) -> dict:
    """``--uncertainty NAME=VALUE`` items as the inputs of the uncertainty budget: a number
    where the value is one, else text (``reference=encoder``; the budget checks the names)."""
    from axiscal.errors import InputError

    table: dict = {}
    for item in items:
        name, sep, value = (x.strip() for x in item.partition("="))
        if not sep or not name or not value:
            raise InputError(f"--uncertainty {item!r}: write NAME=VALUE, e.g. beam_offset=0.05")
        try:
            table[name] = float(value)
        except ValueError:
            table[name] = value
    return table


def _sym(unit: str) -> str:
    return {"um": "µm"}.get(unit, unit)


#: Most per-target rows printed in the terminal (a table of 40,000 targets took minutes to draw).
TABLE_ROWS = 100


def render_result(result, ds=None, title: str = "", console=None, verdicts=(), budget=None) -> None:
    """Print the per-target table and the axis parameters as rich tables."""
    import math

    from rich.markup import escape
    from rich.table import Table

    from axiscal.cli._common import console as make_console
    from axiscal.standards.positioning_standards import parameter_label

    con = console or make_console()
    u, tu = result.deviation_unit, result.target_unit
    sym = {"um": "µm"}.get(u, u)

    def f(v, digits=2):
        return "—" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{v:.{digits}f}"

    heading = "ISO 230-2:2014 positioning test"
    if ds is not None and (ds.metadata.machine or ds.metadata.axis):
        heading += f" — {ds.metadata.machine} {ds.metadata.axis}".rstrip()
    elif title:
        heading += f" — {title}"
    t = Table(title=escape(heading), title_justify="left")
    t.add_column(escape(f"target [{tu}]"), justify="right")
    cols = [("n↑", "n_up"), (f"x̄↑ [{sym}]", "mean_up"), (f"s↑ [{sym}]", "s_up"),
            ("n↓", "n_down"), (f"x̄↓ [{sym}]", "mean_down"), (f"s↓ [{sym}]", "s_down"),
            (f"x̄ [{sym}]", "mean_bi"), (f"B_i [{sym}]", "reversal"), (f"R_i [{sym}]", "R_i")]
    bidir = result.bidirectional
    keep = [c for c in cols if bidir or not math.isnan(float(getattr(result, c[1])[0]))
            and getattr(result, c[1])[0] is not None]
    keep = [c for c in keep if not (c[1].startswith("n_") and int(getattr(result, c[1]).max()) == 0)]
    for name, _ in keep:
        t.add_column(escape(name), justify="right")
    m = len(result.targets)
    shown = range(m) if m <= TABLE_ROWS else [*range(TABLE_ROWS // 2), *range(m - TABLE_ROWS // 2, m)]
    for i in shown:
        if m > TABLE_ROWS and i == m - TABLE_ROWS // 2:
            t.add_row("⋮", *[""] * len(keep), end_section=False)
            t.add_row(f"{m - TABLE_ROWS} more", *[""] * len(keep))
        cells = [f"{result.targets[i]:g}"]
        for _, attr in keep:
            v = getattr(result, attr)[i]
            cells.append(str(int(v)) if attr.startswith("n_") else f(float(v)))
        t.add_row(*cells)
    if m > TABLE_ROWS:
        t.caption = (f"{m} targets: the first and last {TABLE_ROWS // 2} are shown; every target "
                     "is in --json and --report")
    con.print(t)

    p = Table(title=escape(f"Axis parameters [{sym}]"), title_justify="left")
    p.add_column("parameter")
    p.add_column("value", justify="right")
    if budget is not None:
        p.add_column("U (k=2)", justify="right")
    p.add_column("meaning")
    meanings = {
        "A": "bidirectional accuracy of positioning", "A_up": "unidirectional accuracy ↑",
        "A_down": "unidirectional accuracy ↓", "E": "bidirectional systematic positioning error",
        "E_up": "unidirectional systematic error ↑", "E_down": "unidirectional systematic error ↓",
        "M": "range of mean bidirectional positioning error", "R": "bidirectional repeatability",
        "R_up": "unidirectional repeatability ↑", "R_down": "unidirectional repeatability ↓",
        "B": "reversal value (max |B_i|)", "B_mean": "mean reversal value (signed, B_i = x̄↑ − x̄↓)",
    }
    for name, v in result.parameters().items():
        extra = [] if budget is None else ["—" if v is None else budget.U_text(name)]
        p.add_row(parameter_label(name), f(v), *extra, meanings[name])
    for arrow, v in (("↑", result.closure_up), ("↓", result.closure_down)):
        if v is not None:   # a full turn keeps 0° and 360° as two targets
            p.add_row(f"closure{arrow}", f(v), *(["—"] if budget is not None else []),
                      "360° minus 0° mean deviation (full turn)")
    con.print(p)
    if verdicts:
        _render_acceptance(con, verdicts, f, sym)
    for w in result.warnings:
        con.print(f"[yellow]warning:[/yellow] {w}")
    if budget is not None:
        render_uncertainty(con, budget)


def _render_acceptance(con, verdicts, f, sym: str) -> None:
    """The ISO 14253-1 decisions as a table, U as displayed, then each tolerance that can never
    be proven (one warning line each)."""
    from rich.markup import escape
    from rich.table import Table

    from axiscal.standards.iso14253_1 import unprovable
    from axiscal.standards.iso230_9 import format_uncertainty

    a = Table(title=escape(f"Acceptance ({verdicts[0].rule.value} decision rule)"),
              title_justify="left")
    for c in ("parameter", "measured", "U", "tolerance", "verdict"):
        a.add_column(c, justify="left" if c in ("parameter", "verdict") else "right")
    for v in verdicts:
        state = {"PASS": "[green]PASS[/green]", "FAIL": "[bold red]FAIL[/bold red]",
                 "ZONE": "[yellow]ZONE[/yellow]"}[v.outcome.short] if v.outcome else "n/a"
        text = f"{state} {v.outcome.value}" if v.outcome else state
        a.add_row(v.parameter, f(v.value), format_uncertainty(v.U), f"{v.upper:g}", text)
    con.print(a)
    for w in unprovable(verdicts, sym):
        con.print(f"[bold red]warning:[/bold red] {escape(w)}")


def render_uncertainty(con, budget) -> None:
    """The budget's inputs as a table (value, where it came from, the rule of an assumed one)
    and what the budget says in words besides (inputs left out of U, the runs behind R and B)."""
    from rich.markup import escape
    from rich.table import Table

    t = Table(title=escape("Uncertainty inputs (ISO 230-2:2014 Annex A): an assumed input is a "
                           "default; declare yours with --uncertainty NAME=VALUE or [uncertainty] "
                           "NAME in the job file"), title_justify="left")
    # the NAME under its input, not in a column of its own: that column (31 characters for
    # expansion_coefficient_halfwidth) left the rule 15 characters on a 100-column terminal
    t.add_column("input / NAME", max_width=34, overflow="fold")   # the longest NAME whole
    t.add_column("value", justify="right", no_wrap=True)
    t.add_column("from", no_wrap=True)
    t.add_column("rule or source", ratio=1)
    for i in budget.inputs:
        src = ("[bold red]missing[/bold red]" if i.name in budget.missing_inputs else
               "[yellow]assumed[/yellow]" if i.assumed else
               "data file" if i.rule.startswith("taken from the data file") else "declared")
        t.add_row(f"{escape(i.label)}\n[dim]{i.name}[/dim]", escape(i.value_text), src,
                  escape(i.rule))
    con.print(t)
    for n in budget.notes:
        if not n.startswith("assumed: "):   # those are the table's rows
            con.print(f"[yellow]uncertainty:[/yellow] {escape(n)}")


def register(app: typer.Typer) -> None:
    """Add the ``iso230-2`` command to the application."""
    app.command("iso230-2")(iso230_2)
