"""``axiscal straightness FILE`` and ``axiscal squareness biaxial|diagonal|circular|simulate``.

Every squareness result states its sign convention and carries both (Chapman, Calibration of machine squareness Note 1).

JSON output (``--json``), stable keys:

* ``straightness``: ``file``, ``axis``, ``direction``, ``reference``, ``straightness_um``,
  ``slope_um_per_m``, ``intercept_um``, ``n``, ``methods`` (object per reference line,
  ``least_squares``, ``end_point``, ``minimum_zone``: ``straightness_um``, ``slope_um_per_m``),
  and the stored record's ``quantities`` (schema 1: ``straightness`` and
  ``straightness_min_zone`` in µm, ``slope`` in µm/m, each with ``U`` and ``k`` from the budget
  of :mod:`axiscal.standards.iso230_9_straightness`; inputs: the user configuration's
  ``[straightness_uncertainty]``), ``uncertainty_budget`` and ``uncertainty_inputs`` (the
  inputs given). The budget object: ``unit``, ``k``, ``method``, ``U``, ``U_display`` (as
  printed), ``U_stated``, ``U_narrow``, ``cmc``, ``floored``, ``contributors`` (``name``,
  ``quantity``, ``u``, ``distribution``, ``basis``, ``clause``, ``applies_to``), ``inputs``
  (by name: ``value``, ``unit``, ``assumed``, ``set_with``, ``rule``, ``label``; the
  measured ``reading_noise`` and ``slope_fit`` among them), ``assumed``, ``missing_inputs``,
  ``notes``.
* a *squareness object* (used below): ``axes``, ``um_per_m``, ``arcsec``, ``convention``,
  ``iso_datum``, ``iso_referred``, ``iso_um_per_m``, ``iso_arcsec``, ``angle_note``.
* ``squareness biaxial``: ``squareness`` (squareness object), ``config``, ``orientation``,
  ``reference``, ``prism_error_arcsec``, ``correction_um_per_m``, ``slope_first_um_per_m``,
  ``slope_second_um_per_m``, ``straightness_first_um``, ``straightness_second_um``.
* ``squareness diagonal``: ``squareness``, ``length_x_mm``, ``length_y_mm``, ``nominal_mm``,
  ``error_d1_um``, ``error_d2_um``, ``slope_d1_um_per_m``, ``slope_d2_um_per_m`` (null for two
  lengths), ``labels`` (the D1/D2 definitions).
* ``squareness circular``: ``squareness``, ``radius_mm``, ``scale_mismatch_um_per_m``,
  ``backlash_x_um``, ``backlash_y_um``, ``G_ccw_um``, ``G_cw_um`` (minimum zone), ``G_lsc_ccw_um``,
  ``G_lsc_cw_um`` (least-squares centre), ``H_um``, ``F_max_um``,
  ``F_min_um``, ``arc_deg``, ``fit_rms_um``, ``warnings``, ``folded`` (both directions: what the
  ISO 230-4 fit folds into squareness, scale mismatch and each backlash against the full ballbar
  diagnosis, as ``ballbar analyze`` gives it; empty with one direction: a list of ``quantity``,
  ``unit``, ``iso230_4`` (this fit's value), ``diagnosis`` (the full diagnosis's),
  ``difference``, ``folded`` (term -> what it adds), ``material`` (true when the difference
  exceeds the residual the diagnosis leaves, and so is printed) and ``statement``).
* ``squareness biaxial``, ``diagonal`` and ``circular`` also: ``U_um_per_m`` (expanded
  uncertainty, k = 2, ISO/TR 230-9 form, see ``axiscal.standards.iso230_9_geometry``) and
  ``uncertainty`` (list of ``name``, ``u_um_per_m``, ``clause``); inputs not measured take the
  documented defaults or the user configuration's ``[squareness_uncertainty]`` table.
* ``squareness biaxial --inline FILE.toml`` also writes both trajectories and every option to
  one file (:mod:`axiscal.io.biaxial`), which ``history add`` keeps as a ``squareness`` test; its
  record's JSON holds the keys above with the same numbers.
* ``squareness simulate``: ``machine``, ``scope``, ``truth_um_per_m``, ``convention``,
  ``results`` (``method``, ``group``, ``centre_mm``, ``size_mm``, ``um_per_m``, ``arcsec``,
  ``iso_um_per_m``), ``averages`` (``name``, ``centre_mm``, ``um_per_m``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from axiscal.cli._common import note, plot_path, print_json, report_path

__all__ = ["register", "render_comparison"]

REFERENCES = ("least_squares", "end_point", "minimum_zone")
_REF_HELP = "Reference line: least_squares, end_point or minimum_zone (ISO 230-1)."
_JSON_HELP = "Print the result as JSON (stable keys, see the module docs)."
_DATUM_HELP = "Datum axis of the ISO 230-1 sign (default the first axis)."

squareness_app = typer.Typer(
    help="Squareness between two linear axes by ISO 230-1, -4 and -6; every result gives the sign of "
    "Chapman, Calibration of machine squareness (positive when the angle exceeds 90°) and the ISO 230-1 datum/referred-axis sign.",
    no_args_is_help=True,
)


_REPORT = typer.Option(None, "--report", help="Write a self-contained report: HTML (.html) or PDF (.pdf, WeasyPrint).")


def _outputs(plot, report) -> None:
    """Check the plot and report files before any work."""
    if plot is not None:
        plot_path(plot)
    if report is not None:
        report_path(report)


def _wrote(plot, report) -> None:
    for what, path in (("plot", plot), ("report", report)):
        if path is not None:
            note(f"wrote {what} {path}")


def _reference(value: str) -> str:
    from axiscal.errors import InputError

    v = value.lower().replace("-", "_")
    if v not in REFERENCES:
        raise InputError(f"--reference {value!r}: choose least_squares, end_point or minimum_zone")
    return v


def _straightness_record(file: Path) -> dict:
    """The ``quantities`` (least-squares and minimum-zone straightness, slope: each with U
    and k), ``uncertainty_budget`` and ``uncertainty_inputs`` of the file's one record, as the
    history stores it (:func:`axiscal.store.kinds.with_uncertainty`; the budget of
    :mod:`axiscal.standards.iso230_9_straightness` with the user configuration's
    ``[straightness_uncertainty]``)."""
    from axiscal.io.user_config import load_user_config
    from axiscal.report.evaluations import RECORD_KEYS, evaluated_file, record_fields
    from axiscal.store.kinds import inputs_from_config, with_uncertainty

    rec = with_uncertainty(evaluated_file(file, "straightness"),
                           inputs_from_config("straightness", load_user_config()))
    j = record_fields(rec)["_json"]
    return {k: j[k] for k in RECORD_KEYS}


def straightness(
    file: Path = typer.Argument(..., help="Straightness CSV (position,deviation; see io.straightness)."),
    reference: str = typer.Option("least_squares", "--reference", help=_REF_HELP),
    json_out: bool = typer.Option(False, "--json", help=_JSON_HELP),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Write a plot of the readings and the line (PNG/SVG/PDF)."),
    report: Optional[Path] = _REPORT,
) -> None:
    """Straightness deviation and slope of one trajectory (ISO 230-1 reference lines).

    Example: axiscal straightness examples/squareness_L180_x.csv --reference minimum_zone
    """
    from axiscal.io.straightness import read_straightness
    from axiscal.standards.iso230_1 import straightness as evaluate

    method = _reference(reference)
    _outputs(plot, report)
    data = read_straightness(file)
    results = {m: evaluate(data.positions, data.deviations, m) for m in REFERENCES}  # type: ignore[arg-type]
    chosen = results[method]
    if plot is not None:
        from axiscal.report.squareness_plots import save_straightness_plot

        save_straightness_plot(data, chosen, plot)
    d = {"file": str(file), "axis": data.axis, "direction": data.direction,
         "reference": method, "straightness_um": chosen.deviation * 1e6,
         "slope_um_per_m": chosen.line.slope * 1e6,
         "intercept_um": chosen.line.intercept * 1e6, "n": chosen.n,
         "methods": {m: {"straightness_um": r.deviation * 1e6,
                         "slope_um_per_m": r.line.slope * 1e6}
                     for m, r in results.items()},
         **_straightness_record(file)}
    if report is not None:
        from axiscal.report.html import write_result_report
        from axiscal.report.squareness_plots import straightness_figure

        from axiscal.report.evaluations import RECORD_KEYS, uncertainty_tables

        shown = {k: v for k, v in d.items() if k not in RECORD_KEYS}   # U: in its tables
        write_result_report(report, f"Straightness — {file.name}", shown,
                            tables=uncertainty_tables(d),
                            figure=straightness_figure(data, chosen),
                            method=f"Straightness deviation about the {method.replace('_', ' ')} "
                                   "reference straight line, ISO 230-1:2012 §3.4.8 and §3.4.9; "
                                   "every reference line's figures are in the table.")
    if json_out:
        print_json(d)
    else:
        from axiscal.report.labels import value_text

        what = f"{data.axis or '?'} axis, deviation along {data.direction or '?'}"
        typer.echo(f"straightness of {file} ({what}, {chosen.n} readings)")
        for m, r in results.items():
            mark = "*" if m == method else " "
            typer.echo(f" {mark} {value_text(m):<14} straightness {r.deviation * 1e6:9.3f} µm   "
                       f"slope {r.line.slope * 1e6:+10.3f} µm/m")
        U = d["uncertainty_budget"]["U_display"]
        typer.echo(f"expanded uncertainty (k = {d['uncertainty_budget']['k']:g}, ISO/TR 230-9; "
                   "inputs in the user configuration's [straightness_uncertainty]): least "
                   f"squares U = {U['straightness']} µm, minimum zone U = "
                   f"{U['straightness_min_zone']} µm, slope U = {U['slope']} µm/m")
    _wrote(plot, report)


def biaxial(
    xfile: Path = typer.Argument(..., help="Trajectory of the first axis (deviations along the second), straightness CSV."),
    yfile: Path = typer.Argument(..., help="Trajectory of the second axis (deviations along the first), straightness CSV."),
    config: str = typer.Option("L", "--config", help="Set-up: L, T or + (Chapman, Calibration of machine squareness Methods 1-3)."),
    orientation: int = typer.Option(0, "--orientation", help="Equipment orientation, degrees clockwise: 0, 90, 180 or 270."),
    prism_error: float = typer.Option(0.0, "--prism-error", help="Angle error of the optical or mechanical square in orientation 0, arcsec (its angle minus 90°)."),
    reference: str = typer.Option("least_squares", "--reference", help=_REF_HELP),
    datum: str = typer.Option("", "--datum", help=_DATUM_HELP),
    square: str = typer.Option("optics", "--square", help="Reference square for the uncertainty budget: optics (straightness optics + optical square), square (mechanical square and probe) or reversal (square reversed)."),
    json_out: bool = typer.Option(False, "--json", help=_JSON_HELP),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Write both trajectories with their reference lines (PNG/SVG/PDF)."),
    report: Optional[Path] = _REPORT,
    inline: Optional[Path] = typer.Option(None, "--inline", help="Write both trajectories and every option to one file (.toml): the squareness test 'axiscal history add' keeps (kind squareness), evaluated again to the same numbers."),
) -> None:
    """Squareness from two straightness trajectories (ISO 230-1 §3.6.7, Chapman, Calibration of machine squareness Methods 1-3).

    Example: axiscal squareness biaxial examples/squareness_L180_x.csv examples/squareness_L180_y.csv --config L --orientation 180
    """
    from axiscal.io.straightness import read_straightness
    from axiscal.standards.squareness_biaxial import evaluate_biaxial

    _outputs(plot, report)
    if inline is not None:
        _inline_path(inline, xfile, yfile)
    one, two = read_straightness(xfile), read_straightness(yfile)
    b = evaluate_biaxial(one, two, config=config, orientation=orientation,
                         prism_error=prism_error, reference=_reference(reference), datum=datum,
                         square=square, inputs=_uncertainty_table())   # as the workbench's
    r, budget, d = b.result, b.budget, b.summary
    if inline is not None:
        _write_inline(inline, one, two, xfile, yfile, config=config, orientation=orientation,
                      prism_error=prism_error, reference=_reference(reference), datum=datum,
                      square=square)
    if plot is not None or report is not None:
        from axiscal.report.squareness_plots import biaxial_figure

        title = f"Bi-axial {config.upper()} {orientation}°"
        if plot is not None:
            from axiscal.report.plots import save_figure

            save_figure(biaxial_figure(one, two, r, title), plot)
        if report is not None:
            from axiscal.report.squareness_plots import write_biaxial_report

            write_biaxial_report(report, one, two, b, f"{xfile.name}, {yfile.name}", config,
                                 orientation)
    if json_out:
        print_json(d)
    else:
        typer.echo(f"bi-axial {config.upper()} {orientation}°: {r}")
        typer.echo(_budget_line(budget))
    _wrote(plot, report)
    if inline is not None:
        note(f"wrote {inline} (both trajectories and the options; axiscal history add keeps it)")


def _inline_path(out: Path, *inputs: Path) -> None:
    """``--inline``: a .toml in a writable folder, never one of the trajectories' files."""
    from axiscal.cli._common import typed_path
    from axiscal.errors import InputError

    typed_path(out, "--inline", (".toml",))
    if any(out.resolve() == Path(p).resolve() for p in inputs):
        raise InputError(f"--inline {out}: it is one of the trajectories' files; write it "
                         "elsewhere")


def _write_inline(out: Path, one, two, *files: Path, **options) -> None:
    """The squareness test file (:func:`axiscal.io.biaxial.format_biaxial_test`): the
    trajectories as read, every option, each file's SHA-256; checked as its reader checks it
    before it is written (a prism error over 1° is refused here, not at ``history add``)."""
    import hashlib

    from axiscal.io._files import read_bytes, write_text_atomic
    from axiscal.io.biaxial import biaxial_test, format_biaxial_test

    digests = tuple(hashlib.sha256(read_bytes(f)).hexdigest() for f in files)
    test = biaxial_test(one, two, sha256=digests, source="--inline", **options)
    write_text_atomic(out, format_biaxial_test(test))


def _budget(method: str, **measured):
    """The squareness budget with the user configuration's inputs under the measured ones
    (:func:`axiscal.standards.iso230_9_geometry.squareness_budget_with_inputs`)."""
    from axiscal.standards.iso230_9_geometry import squareness_budget_with_inputs

    return squareness_budget_with_inputs(method, _uncertainty_table(), **measured)


def _uncertainty_table() -> dict:
    """The user configuration's ``[squareness_uncertainty]`` table."""
    from axiscal.io.user_config import load_user_config

    return dict(load_user_config().get("squareness_uncertainty", {}))


def _budget_json(b) -> dict:
    return {"U_um_per_m": b.U("squareness"),
            "uncertainty": [{"name": c.name, "u_um_per_m": c.u, "clause": c.clause}
                            for c in b.contributors]}


def _budget_line(b) -> str:
    """U and what it holds, named as the report's budget table names each contribution."""
    from axiscal.standards.iso230_9 import format_uncertainty

    names = "; ".join(c.quantity for c in b.contributors)
    return f"U (k = 2) = {format_uncertainty(b.U('squareness'))} µm/m (ISO/TR 230-9) from: {names}"


def diagonal(
    x_length: Optional[float] = typer.Option(None, "--x-length", help="X side of the rectangle whose diagonals were measured (programmed X travel), mm; with --d1 --d2."),
    y_length: Optional[float] = typer.Option(None, "--y-length", help="Y side of the rectangle whose diagonals were measured (programmed Y travel), mm; with --d1 --d2."),
    d1: Optional[float] = typer.Option(None, "--d1", help="Length error of D1 (along -X +Y, from corner +X -Y), µm."),
    d2: Optional[float] = typer.Option(None, "--d2", help="Length error of D2 (along +X +Y, from corner -X -Y), µm."),
    file: Optional[Path] = typer.Option(None, "--file", help="Multi-point diagonal CSV (diagonal,position,error) instead of the lengths."),
    datum: str = typer.Option("", "--datum", help=_DATUM_HELP),
    json_out: bool = typer.Option(False, "--json", help=_JSON_HELP),
    plot: Optional[Path] = typer.Option(None, "--plot", help="With --file: write the length errors along both diagonals (PNG/SVG/PDF)."),
    report: Optional[Path] = _REPORT,
) -> None:
    """Squareness = D0 (D1 − D2) / (2XY) from two diagonals (ISO 230-6, Chapman, Calibration of machine squareness Method 5).

    Example: axiscal squareness diagonal --file examples/squareness_diagonal_600x800.csv
    """
    from axiscal.errors import InputError
    from axiscal.standards.iso230_6 import diagonal_squareness, diagonal_squareness_multipoint

    from axiscal._schema import check_option

    given = {"--x-length": x_length, "--y-length": y_length, "--d1": d1, "--d2": d2}
    for name in ("--x-length", "--y-length"):
        check_option(name, given[name], "mm", lo=1, hi=MAX_LENGTH_MM)   # a travel of at least 1 mm
    for name in ("--d1", "--d2"):   # a diagonal's length error: within a tenth of the travel
        check_option(name, given[name], "µm", lo=-MAX_ERROR_UM, hi=MAX_ERROR_UM)
    if plot is not None and file is None:
        raise InputError("--plot draws the errors along the diagonals of a --file; two lengths "
                         "have no curve to draw")
    _outputs(plot, report)
    d = None
    if file is not None:
        from axiscal.io.ballbar import read_diagonal

        both = [k for k, v in given.items() if v is not None]
        if both:
            raise InputError(f"--file holds the travels and the diagonals; drop {', '.join(both)}")

        d = read_diagonal(file)
        r = diagonal_squareness_multipoint(d.length_x, d.length_y, d.positions_d1, d.errors_d1,
                                           d.positions_d2, d.errors_d2, datum=datum)
    else:
        missing = [k for k, v in given.items() if v is None]
        if missing:
            raise InputError(f"missing {', '.join(missing)}: give the travels and both diagonal "
                             "errors, or --file")
        r = diagonal_squareness(x_length * 1e-3, y_length * 1e-3, d1 * 1e-6, d2 * 1e-6,  # type: ignore[operator]
                                datum=datum)
    from axiscal.standards.iso230_9_geometry import diagonal_budget

    budget = diagonal_budget(r, _uncertainty_table())
    um = (lambda v: None if v is None else v * 1e6)
    out = {**_budget_json(budget), "squareness": r.squareness.as_dict(), "length_x_mm": r.length_x * 1e3,
           "length_y_mm": r.length_y * 1e3, "nominal_mm": r.nominal * 1e3,
           "error_d1_um": r.error_d1 * 1e6, "error_d2_um": r.error_d2 * 1e6,
           "slope_d1_um_per_m": um(r.slope_d1), "slope_d2_um_per_m": um(r.slope_d2),
           "labels": {"D1": "along -X +Y, from corner (+X, -Y)",
                      "D2": "along +X +Y, from corner (-X, -Y)"}}
    if plot is not None:
        from axiscal.report.plots import save_figure
        from axiscal.report.squareness_plots import diagonal_figure

        save_figure(diagonal_figure(d, r), plot)
    if report is not None:
        from axiscal.report.html import write_result_report
        from axiscal.report.squareness_plots import diagonal_figure

        write_result_report(report, "Squareness from two diagonals"
                            + (f" — {file.name}" if file is not None else ""), out,
                            figure=diagonal_figure(d, r) if d is not None else None,
                            method="Squareness = D0 (D1 − D2) / (2XY) from the length errors of "
                                   "the two diagonals, ISO 230-6:2002 (Chapman, Calibration of "
                                   "machine squareness, Method 5); U by ISO/TR 230-9.")
    if json_out:
        print_json(out)
    else:
        typer.echo(str(r))
        typer.echo(_budget_line(budget))
    _wrote(plot, report)


#: Longest travel or ballbar radius taken (100 m) and largest diagonal length error (1 m).
MAX_LENGTH_MM, MAX_ERROR_UM = 100_000.0, 1e6


def circular(
    file: Path = typer.Argument(..., help="Ballbar CSV (angle,direction,deviation; see io.ballbar)."),
    radius: Optional[float] = typer.Option(None, "--radius", help="Nominal radius, mm (overrides the file)."),
    datum: str = typer.Option("", "--datum", help=_DATUM_HELP),
    json_out: bool = typer.Option(False, "--json", help=_JSON_HELP),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Write the ballbar polar plot (PNG/SVG/PDF)."),
    report: Optional[Path] = _REPORT,
) -> None:
    """Circular test by ISO 230-4: G, H, F, and squareness free of backlash and scale mismatch.

    With both directions the full ballbar diagnosis runs too, and every figure its simpler fit
    folds other errors into (servo mismatch into backlash, most often) is stated beside it.

    Example: axiscal squareness circular examples/squareness_ballbar_150mm.csv --plot polar.png
    """
    from axiscal.io.ballbar import read_ballbar
    from axiscal.store.kinds import evaluate_ballbar

    from axiscal._schema import check_option

    check_option("--radius", radius, "mm", lo=1, hi=MAX_LENGTH_MM)   # a ballbar of at least 1 mm
    _outputs(plot, report)
    data = read_ballbar(file, radius_mm=radius)
    full = evaluate_ballbar(data, datum=datum)
    r = getattr(full, "circular", full)            # one direction: the ISO 230-4 result itself
    folded = getattr(full, "folded", ())
    statements = [str(f) for f in folded if f.material]
    if plot is not None:
        from axiscal.report.squareness_plots import save_ballbar_plot

        save_ballbar_plot(data.runs, r, plot, title=f"Ballbar test {file.name}")
    budget = _budget("ballbar", ballbar_radius=data.radius)
    d = {**r.as_dict(), "folded": [f.as_dict() for f in folded], **_budget_json(budget)}
    if report is not None:
        from axiscal.report.html import write_result_report
        from axiscal.report.squareness_plots import ballbar_figure

        write_result_report(report, f"Circular test — {file.name}", d,
                            figure=ballbar_figure(data.runs, r, title=f"Ballbar test {file.name}"),
                            notes=statements,
                            method="Circular deviation G, circular hysteresis H and radial "
                                   "deviation F by ISO 230-4:2005; the squareness from the "
                                   "fitted ellipse, free of backlash and scale mismatch "
                                   "(Chapman, Calibration of machine squareness, Method 4). "
                                   "Its reversal fit cannot separate servo mismatch, lateral "
                                   "play, reversal spikes or cyclic error: the full ballbar "
                                   "diagnosis (axiscal ballbar analyze) fits them, and each "
                                   "figure it moves is stated with what was folded in.")
    if json_out:
        print_json(d)
    else:
        typer.echo(str(r))
        for line in statements:
            typer.echo(f"  {line}")
        typer.echo(_budget_line(budget))
    _wrote(plot, report)


def simulate(
    machine: int = typer.Option(1, "--machine", help="Machine 1 to 7 of Chapman, Calibration of machine squareness."),
    scope: str = typer.Option("global", "--scope", help="global (full travel) or local (five 1/4-travel locations)."),
    json_out: bool = typer.Option(False, "--json", help=_JSON_HELP),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Write the distorted plane with every test and its result (PNG/SVG/PDF)."),
    noise: float = typer.Option(0.0, "--noise", help="Random reading error of the instruments, µm (standard deviation); 0 gives the exact figures of the paper."),
    seed: int = typer.Option(1, "--seed", min=0, max=2**63 - 1, help="Random seed of the reading error (with --noise)."),
    report: Optional[Path] = _REPORT,
) -> None:
    """Every squareness method on a simulated machine of Chapman, Calibration of machine squareness (Figures 14-26).

    Example: axiscal squareness simulate --machine 3 --scope global
    """
    from axiscal.machines.xy_plane import seed004_machine
    from axiscal.procedures.squareness_study import compare_methods

    import numpy as np

    from axiscal._schema import check_option

    check_option("--noise", noise, "µm", lo=0, hi=1000)
    _outputs(plot, report)
    m = seed004_machine(machine)
    c = compare_methods(m, scope, np.random.default_rng(seed), noise * 1e-6)
    if plot is not None:
        from axiscal.report.squareness_plots import save_comparison_plot

        save_comparison_plot(m, c, plot)
    if report is not None:
        from axiscal.report.html import write_result_report
        from axiscal.report.squareness_plots import comparison_figure

        write_result_report(report, f"Squareness by every method — {m}", c.as_dict(),
                            figure=comparison_figure(m, c), simulation=True,
                            method="Every squareness test of Chapman, Calibration of machine "
                                   "squareness (Figures 14-26) on its simulated machine, with "
                                   "the true squareness the simulation knew.")
    if json_out:
        print_json(c.as_dict())
    else:
        render_comparison(c)
    _wrote(plot, report)


def render_comparison(c, console=None) -> None:
    """Methods as rows, test locations as columns (µm/m), then the averages the same way."""
    from rich.table import Table

    from axiscal.cli._common import console as make_console

    con = console or make_console()
    where = (lambda p: f"({p[0] * 1e3:+.0f}, {p[1] * 1e3:+.0f}) mm")
    con.print(f"[bold]{c.machine}[/bold]")
    con.print(f"{c.scope} squareness in µm/m, positive when the angle between +X and +Y exceeds "
              f"90°; truth θ0 = {c.truth:+.2f} µm/m")
    locations = c.locations()

    def table(title, names, value):
        caption = "columns: test centre (x, y) in mm"   # as wide as its longest line: unwrapped
        t = Table(title=title, title_justify="left", caption=caption, caption_justify="left",
                  min_width=max(len(title), len(caption)))
        t.add_column("", no_wrap=True)
        for loc in locations:
            t.add_column(f"{loc[0] * 1e3:+.0f}, {loc[1] * 1e3:+.0f}", justify="right",
                         no_wrap=True)
        for name in names:
            t.add_row(name, *[f"{value(name, loc):+.2f}" for loc in locations])
        con.print(t)

    table("squareness by each method [µm/m]",
          list(dict.fromkeys(r.method for r in c.results if not r.group)), c.value)
    names = list(dict.fromkeys(n for n, _, _ in c.averages if "ballbar" not in n))
    table("averages of opposite corners (L) and sides (T)", names, c.average)
    for r in (r for r in c.results if r.group):
        con.print(f"  {r.group}: circle at {where(r.centre)}: {r.squareness.um_per_m:+.2f}")
    for name, _, v in c.averages:
        if "ballbar" in name:
            con.print(f"  [bold]average of {name}: {v:+.2f}[/bold]")


def register(app: typer.Typer) -> None:
    """Add ``straightness`` and the ``squareness`` group to the application."""
    app.command("straightness")(straightness)
    squareness_app.command("biaxial")(biaxial)
    squareness_app.command("diagonal")(diagonal)
    squareness_app.command("circular")(circular)
    squareness_app.command("simulate")(simulate)
    app.add_typer(squareness_app, name="squareness")
