"""``axiscal iso230-2 FILE``: evaluate a positioning test by ISO 230-2:2014.

JSON output (``--json``), stable: top-level keys ``A``, ``A_up``, ``A_down``, ``E``, ``E_up``,
``E_down``, ``M``, ``R``, ``R_up``, ``R_down``, ``B``, ``B_mean`` (numbers in ``unit``, or null where
a unidirectional test makes them not apply), ``unit``, ``target_unit``, ``axis_kind``,
``n_runs``, ``missing``, ``closure_up``, ``closure_down``, ``targets`` (one object per target:
``target``, ``n_up``, ``n_down``, ``mean_up``, ``mean_down``, ``mean_bi``, ``reversal``, ``s_up``,
``s_down``, ``R_up_i``, ``R_down_i``, ``R_i``) and ``warnings`` (list of text). With
``--tolerance``: ``acceptance`` (one object per checked parameter: ``parameter``, ``value``,
``tolerance``, ``passed``) and ``accepted`` (true, false, or null if nothing applied).

Exit codes: 0 evaluated (and every tolerance met), 1 a tolerance was exceeded, 2 a user error.
"""

from __future__ import annotations

from pathlib import Path
from typing import List, Optional

import typer

from axiscal.cli._common import note, plot_path, print_json, report_path

__all__ = ["register", "result_json", "render_result"]


def iso230_2(
    file: Path = typer.Argument(..., help="Positioning data: tidy CSV, axiscal JSON or EPICS ecmc file."),
    target_unit: Optional[str] = typer.Option(None, "--target-unit", help="Unit of the targets in a CSV or ecmc file that does not declare it: mm or deg (a different declaration in the file is an error)."),
    deviation_unit: Optional[str] = typer.Option(None, "--deviation-unit", help="Unit of the deviations in a CSV that does not declare it: um, mm or arcsec (a different declaration in the file is an error)."),
    full_turn: str = typer.Option("separate", "--full-turn", help="Rotary 0-360 deg test: keep 0 and 360 deg as two targets ('separate') or pool them ('merge')."),
    json_out: bool = typer.Option(False, "--json", help="Print the result as JSON (stable keys, see the docs)."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Write the ISO 230-2 plot (PNG, SVG or PDF by extension)."),
    report: Optional[Path] = typer.Option(None, "--report", help="Write a self-contained HTML report (.html)."),
    tolerance: List[str] = typer.Option([], "--tolerance", help="Acceptance tolerance as NAME=VALUE in the deviation unit, e.g. --tolerance A=12 --tolerance R=4 (exit code 1 if one is exceeded)."),
) -> None:
    """Evaluate a positioning test by ISO 230-2:2014 (A, E, M, R, B per axis and per target)."""
    from axiscal.io import read_positioning
    from axiscal.standards.iso230_2 import check_tolerances, evaluate

    tolerances = parse_tolerances(tolerance)

    if plot is not None:
        plot_path(plot)
    if report is not None:
        report_path(report)
    ds = read_positioning(file, target_unit=target_unit, deviation_unit=deviation_unit)
    if full_turn != "separate" and ds.axis_kind.value != "rotary":
        from axiscal.errors import InputError

        raise InputError(f"--full-turn {full_turn} pools 0 and 360 deg of a rotary test; {file} "
                         f"is a {ds.axis_kind.value} axis")
    result = evaluate(ds, full_turn=full_turn)  # type: ignore[arg-type]
    verdicts = check_tolerances(result, tolerances) if tolerances else ()
    if plot is not None:
        from axiscal.report.plots import save_iso230_2_plot

        save_iso230_2_plot(result, ds, plot)
    if report is not None:
        from axiscal.report.html import write_positioning_report

        write_positioning_report(report, ds, result, verdicts=verdicts)
    if json_out:
        print_json(result_json(result, verdicts))
    else:
        render_result(result, ds, title=str(file), verdicts=verdicts)
    for p, what in ((plot, "plot"), (report, "report")):
        if p is not None:
            note(f"wrote {what} {p}")
    if any(v.passed is False for v in verdicts):
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


def verdicts_json(verdicts) -> dict:
    """The acceptance part of the JSON output."""
    states = [v.passed for v in verdicts if v.passed is not None]
    return {"acceptance": [v.__dict__ for v in verdicts],
            "accepted": None if not states else all(states)}


def result_json(result, verdicts=()) -> dict:
    """The stable JSON object of an ISO 230-2 result (see the module docstring)."""
    d = dict(result.parameters())
    d.update(
        unit=result.deviation_unit,
        target_unit=result.target_unit,
        axis_kind=result.axis_kind.value,
        n_runs=result.n_runs,
        missing=result.missing,
        closure_up=result.closure_up,
        closure_down=result.closure_down,
        targets=result.target_table(),
        warnings=list(result.warnings),
    )
    if verdicts:
        d.update(verdicts_json(verdicts))
    return d


def render_result(result, ds=None, title: str = "", console=None, verdicts=()) -> None:
    """Print the per-target table and the axis parameters as rich tables."""
    import math

    from rich.markup import escape
    from rich.table import Table

    from axiscal.cli._common import console as make_console

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
    for i, target in enumerate(result.targets):
        cells = [f"{target:g}"]
        for _, attr in keep:
            v = getattr(result, attr)[i]
            cells.append(str(int(v)) if attr.startswith("n_") else f(float(v)))
        t.add_row(*cells)
    con.print(t)

    p = Table(title=escape(f"Axis parameters [{sym}]"), title_justify="left")
    p.add_column("parameter")
    p.add_column("value", justify="right")
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
        p.add_row(name.replace("_up", "↑").replace("_down", "↓").replace("_mean", " mean"),
                  f(v), meanings[name])
    for arrow, v in (("↑", result.closure_up), ("↓", result.closure_down)):
        if v is not None:   # a full turn keeps 0° and 360° as two targets
            p.add_row(f"closure{arrow}", f(v), "360° minus 0° mean deviation (full turn)")
    con.print(p)
    if verdicts:
        a = Table(title="Acceptance", title_justify="left")
        for c in ("parameter", "measured", "tolerance", "verdict"):
            a.add_column(c, justify="left" if c in ("parameter", "verdict") else "right")
        for v in verdicts:
            state = {True: "[green]PASS[/green]", False: "[bold red]FAIL[/bold red]", None: "n/a"}[v.passed]
            a.add_row(v.parameter, f(v.value), f"{v.tolerance:g}", state)
        con.print(a)
    for w in result.warnings:
        con.print(f"[yellow]warning:[/yellow] {w}")


def register(app: typer.Typer) -> None:
    """Add the ``iso230-2`` command to the application."""
    app.command("iso230-2")(iso230_2)
