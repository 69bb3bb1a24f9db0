"""``axiscal compensate``: compensation tables a CNC controller accepts, and the loop that checks them.

Three uses:

* ``axiscal compensate DATA_OR_RESULT --controller NAME --spacing S [--bidirectional] [--out FILE]``
  builds a table from a positioning data file (evaluated by ISO 230-2) or an
  ``axiscal iso230-2 --json`` result, writes it in the controller's format and prints points,
  spacing, range, reference point, largest correction and what the controller must be told.
* ``axiscal compensate --verify CONFIG.toml`` runs measure → compensate → re-measure on the
  simulated machine of the configuration and prints A, E, M, R, B before and after; with
  ``--controller linuxcnc --on-controller`` both tests run through a real, headless LinuxCNC
  (issue 32) and the table is loaded as its ``[JOINT_0] COMP_FILE``.
* ``axiscal compensate --read TABLE --controller NAME [DATA_OR_RESULT]`` reads a table back and,
  with a data file or result, compares it with the deviations it should correct; with
  ``--to NAME [--out FILE]`` it writes the table read in another controller's format (a Renishaw
  ``.ren`` export converted to a Siemens, Fanuc, Heidenhain or LinuxCNC table).
* ``axiscal compensate --squareness 40 --axes XZ --aligned Z --start -200 --end 200 --spacing 50
  --controller siemens-840d`` writes the cross-axis table of Chapman, Calibration of machine squareness Appendix II (corrections on
  the axis aligned to the spindle, driven by the other axis).

Controllers: ``siemens-840d``, ``fanuc``, ``heidenhain``, ``linuxcnc``, ``csv``, ``renishaw-ren``
(Renishaw's ``.ren`` export). Format options
(``machine_axis``, ``detection_unit``, ``file_type``, ``reference_position`` …) go through
``--option KEY=VALUE``.

JSON (``--json``), stable keys. The *table data* keys: ``n_points``, ``spacing``, ``start``,
``end``, ``position_unit``, ``correction_unit``, ``reference_index``, ``reference_position``,
``largest_correction``, ``backlash``, ``bidirectional``, ``modulo``, ``equidistant`` (false
for a table at irregular positions, LinuxCNC only) and ``table`` (the table
itself: ``axis``, ``axis_kind``, ``positions``, ``up``, ``down``, ``spacing``, ``start``, ``end``,
``n_points``, ``position_unit``, ``correction_unit``, ``reference_index``,
``reference_position``, ``resolution``, ``extrapolation``, ``bidirectional``, ``modulo``,
``backlash``, ``largest``, ``equidistant``, ``origin``: for a table read from a controller
file its ``controller``, ``machine_axis``, ``measuring_system``, ``unit`` and ``kind_from``,
else null). Table: ``controller``, ``file`` (path written or null),
``extra_files`` (names), ``enable`` (list), ``notes`` (list) and the table data keys. Verify:
``controller``, ``before`` and ``after`` (the ISO 230-2 parameters ``A``, ``A_up``,
``A_down``, ``E``, ``E_up``, ``E_down``, ``M``, ``R``, ``R_up``, ``R_down``, ``B``,
``B_mean``), ``reduction``, ``budget_E``,
``spacing_residual``, ``sigma``, ``between_targets_E``, ``truth_before``, ``truth_after`` (E,
E_up, E_down, M, B), ``unit``, ``n_points``, ``spacing``, ``seed``, ``sign``; with
``--on-controller`` also ``applied`` (per target and direction: ``target`` mm, ``direction``,
``table`` and ``applied`` µm or arcsec, ``difference``, the largest over the runs, ``n``) and
``on_controller`` (``controller``, ``comp_file_type``, ``machine_units`` (mm, inch or deg),
``dwell_s``, ``plan_dwell_s``, ``applied_unit``, ``largest_applied_difference``,
``n_applied``). Squareness: the
table keys plus ``driving_axis``, ``compensated_axis``, ``factor_um_per_m``, ``advice``. Read:
``controller`` (detected from the file's content unless ``--controller`` is given), ``encoding``
(``utf-8``, ``utf-16`` or ``windows-1252``), ``notes`` (840D: what was read, assumed or left
out), ``shift_undone`` and ``comparison_note`` (with SOURCE: the reference shift undone),
``inputs`` (what the file does not carry, each ``name``,
``value``, ``unit``, ``assumed``, ``source`` = option, file or default, ``why``, ``set_with``:
Fanuc's reference position and detection unit, the 840D's MD10240 unit, LinuxCNC's unit,
``file_type`` and ``axis_kind`` with source ``ini`` when the INI naming the file gave them),
``trim_jumps`` (LinuxCNC: trims that jump from their neighbours beyond the plausible step, each
``direction``, ``kind``, ``position``, ``trim``, ``before``, ``after``, ``jump``, ``threshold``
in the table's units; empty otherwise) and the table data keys, plus ``residual`` (per target: ``target``, ``deviation``,
``correction``, ``residual`` = deviation + correction) and ``largest_residual`` when SOURCE is
given. Reading an 840D file of several tables without ``-o machine_axis=``: ``tables`` (each
``key`` = ``AX1`` or ``AX1/2`` for measuring system 2, ``machine_axis``, ``measuring_system`` and
the table data keys), ``refused`` (``key``, ``reason``; exit 2 when any) and ``notes``; an
``NC_CEC.INI``: ``kind``, ``tables`` (each ``index``, ``input_axis``, ``output_axis``,
``direction``, ``mult_by_table``, ``notes``, ``table``), ``refused`` (``index``, ``reason``;
exit 2 when any), ``not_in_use`` (``index``, ``reason``: a table reserved with STEP 0, not an
error) and ``notes`` (a loader program's ``NEWCONF``, MD32710, SD41300 … lines, said and left
out).

``--encoding NAME``: the code page of SOURCE when it is a Renishaw ``.rtl``/``.rta`` export
(``cp1250`` …; refused for another file, an unknown name, or without SOURCE).

Options that the chosen use does not read (``--bidirectional`` with ``--verify``, ``--plot``
without it ...) are refused by name rather than ignored.
"""

from __future__ import annotations

from pathlib import Path
from typing import List, Optional

import typer

from axiscal.cli._common import note, out_path, plot_path, print_json, report_path
from axiscal.cli._encoding import ENCODING
from axiscal.cli._compensate_io import (_render_table, _table_json, _typed, _value,
                                        _write_files)

__all__ = ["register"]


def compensate(
    ctx: typer.Context,
    source: Optional[Path] = typer.Argument(None, help="Positioning data (CSV, JSON, Renishaw .rtl/.rta, ecmc) or an 'axiscal iso230-2 --json' result."),
    controller: Optional[str] = typer.Option(None, "--controller", "-c", help="siemens-840d, fanuc, heidenhain, linuxcnc, csv or renishaw-ren (default csv; with --verify the configuration's)."),
    spacing: Optional[float] = typer.Option(None, "--spacing", help="Distance between table points, mm or deg (default: the mean target spacing)."),
    bidirectional: bool = typer.Option(False, "--bidirectional", help="Separate tables for the + and - directions (or one table plus a backlash value where the format has one)."),
    resolution: float = typer.Option(0.1, "--resolution", help="Round corrections to this step, um or arcsec (0: no rounding)."),
    start: Optional[float] = typer.Option(None, "--start", help="First table point, mm or deg (default: first target)."),
    end: Optional[float] = typer.Option(None, "--end", help="Last table point at or beyond this, mm or deg (default: last target)."),
    extrapolation: str = typer.Option("hold", "--extrapolation", help="Beyond the measured targets: 'hold' the end value or continue 'linear'."),
    reference: Optional[float] = typer.Option(None, "--home", help="Home (reference) position, mm or deg (default: the table start)."),
    travel: Optional[List[float]] = typer.Option(None, "--travel", help="Axis travel low and high, mm or deg (give twice); the table must lie inside."),
    axis: str = typer.Option("", "--axis", help="Axis name written in the table (X, C ...)."),
    option: Optional[List[str]] = typer.Option(None, "--option", "-o", help="Format option KEY=VALUE for the writer/parser (repeatable), e.g. machine_axis=X1, detection_unit=0.0001, unit=inch (840D: MD10240 = 0), axis_number=2 and reference_position=15 (reading a Fanuc tape)."),
    out: Optional[Path] = typer.Option(None, "--out", help="Write the controller file here: .csv for csv, the table's own name (X.COM) for heidenhain, whose .CMA goes next to it and names it; the format's extension (.INI, .TXT, .comp) or .txt for the others."),
    verify: Optional[Path] = typer.Option(None, "--verify", help="Run measure-compensate-remeasure on the simulated machine of this TOML configuration."),
    on_controller: bool = typer.Option(False, "--on-controller", help="With --verify --controller linuxcnc: run both ISO 230-2:2014 tests through a real LinuxCNC (headless, the machine's errors applied to joint.0.motor-pos-cmd), the file loaded as [JOINT_0] COMP_FILE (-o file_type=0|1, default 1; -o unit=mm|inch, default mm; a rotary joint in degrees); reports the trim LinuxCNC applied at every target and direction."),
    read: Optional[Path] = typer.Option(None, "--read", help="Read this controller file back (and compare with SOURCE if given)."),
    to: Optional[str] = typer.Option(None, "--to", help="With --read: write the table read in this controller's format (siemens-840d, fanuc, heidenhain, linuxcnc, csv, renishaw-ren), to --out or the terminal."),
    ini: Optional[Path] = typer.Option(None, "--ini", help="With --read of a LinuxCNC file: the INI whose [JOINT_n] COMP_FILE names it (default: the *.ini beside it); its [TRAJ] LINEAR_UNITS or ANGULAR_UNITS, [JOINT_n] UNITS, TYPE and COMP_FILE_TYPE are used (LinuxCNC, INI Configuration)."),
    squareness: Optional[float] = typer.Option(None, "--squareness", help="Write a cross-axis table for this squareness, µm/m (Chapman, Calibration of machine squareness sign: angle between + axes minus 90°)."),
    axes: str = typer.Option("XY", "--axes", help="The two axes of --squareness, e.g. XY or XZ."),
    aligned: Optional[str] = typer.Option(None, "--aligned", help="With --squareness: the axis aligned to the spindle; it receives the corrections (Chapman, Calibration of machine squareness Appendix II)."),
    seed: int = typer.Option(1, "--seed", min=0, help="Seed of the simulation, a whole number >= 0 (with --verify)."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="With --verify: write the before/table/after plot (PNG, SVG or PDF)."),
    report: Optional[Path] = typer.Option(None, "--report", help="With --verify: write the loop as a simulation report (plot, before/after parameters, table): HTML or PDF."),
    json_out: bool = typer.Option(False, "--json", help="Print the result as JSON (stable keys, see the docs)."),
    encoding: Optional[str] = ENCODING,
) -> None:
    """Write compensation tables for CNC controllers, read them back, or verify them by re-measuring.

    Example: axiscal compensate demo-output/linear_data.csv --controller siemens-840d --spacing 10 --out x.ini
    """
    from axiscal.errors import InputError

    opts = _options(option or [])
    if out is not None:
        out_path(out, "controller file")
    if plot is not None:
        plot_path(plot)
    if report is not None:
        report_path(report)
    if sum(x is not None for x in (verify, read)) > 1:
        raise InputError("give either --verify or --read, not both")
    _refuse_unused(ctx, "verify" if verify is not None else "read" if read is not None
                   else "squareness" if squareness is not None else "table")
    if verify is not None:
        return _verify(verify, seed, controller, spacing, opts, out, json_out, plot, report,
                       on_controller)
    if read is not None:
        if out is not None and to is None:
            raise InputError("--read writes --out only with --to NAME (the controller format to "
                             "convert the table to); give --to or drop --out")
        from axiscal.cli._compensate_read import read_back

        if encoding is not None and source is None:
            raise InputError("--encoding is the code page of SOURCE (a Renishaw export compared "
                             "with the table read); --read without SOURCE does not use it: drop it")
        return read_back(read, controller, source, opts, json_out, ini, to=to, out=out,
                         encoding=encoding)
    if squareness is not None:
        return _cross_axis(squareness, axes, aligned, controller or "csv", spacing, start, end,
                           resolution, travel, opts, out, json_out)
    if source is None:
        raise InputError("give a data file or ISO 230-2 result (or --verify CONFIG.toml, --read FILE)")
    from axiscal import api
    from axiscal.compensation.controllers import controller as get_controller

    mod = get_controller(controller or "csv")
    table = api.compensation_table(source, spacing, bidirectional=bidirectional,
                                   resolution=resolution, start=start, end=end,
                                   extrapolation=extrapolation, home=reference, axis=axis,
                                   encoding=encoding)
    cf = api.write_table(table, mod.NAME, travel=_travel(travel),
                         **_typed(mod.write, opts, f"--option for {mod.NAME}"))
    if reference is not None:
        from dataclasses import replace

        from axiscal.compensation.controllers import reference_note

        said = reference_note(mod.NAME, reference, table.position_unit)
        cf = replace(cf, notes=tuple(cf.notes) + (said,)) if said else cf
    cf = _write_files(cf, out)
    _render_table(cf, out, json_out)


# -- the three actions -----------------------------------------------------------------------
def _verify(config: Path, seed, controller, spacing, opts, out, json_out, plot=None,
            report=None, on_controller=False) -> None:
    from axiscal.compensation.loop import run_compensation_loop
    from axiscal.io._files import load_toml

    over = {}
    if controller is not None:   # another controller: the configuration's options do not apply
        over.update(controller=controller, options=_guessed(opts))
    elif opts:
        over.update(options=_guessed(opts))
    if spacing is not None:
        over.update(spacing=spacing)
    extra = {}
    if on_controller:
        from axiscal.compensation.on_controller import run_on_linuxcnc, summary

        r, applied, hook = run_on_linuxcnc(load_toml(config), seed=seed, **over)
        extra = summary(applied, hook)
    else:
        r = run_compensation_loop(load_toml(config), seed=seed, **over)
    _write_files(r.controller_file, out)
    if plot is not None:
        from axiscal.report.compensation_plots import save_compensation_plot

        save_compensation_plot(r, plot)
        note(f"wrote plot {plot}")
    d = dict(controller=r.controller_file.controller, before=r.before.parameters(),
             after=r.after.parameters(), reduction=r.reduction, budget_E=r.budget_E,
             spacing_residual=r.spacing_residual, sigma=r.sigma,
             between_targets_E=r.between_targets_E, truth_before=r.truth_before,
             truth_after=r.truth_after, unit=r.unit, n_points=r.table.n_points,
             spacing=r.table.spacing, seed=seed, sign=r.sign, **extra)
    if report is not None:
        from axiscal.report.compensation_plots import compensation_figure
        from axiscal.report.html import write_result_report

        write_result_report(report, f"Compensation verified by re-measuring — {config.name}", d,
                            figure=compensation_figure(r), simulation=True,
                            method="The simulated axis measured by ISO 230-2:2014, a "
                                   f"{r.controller_file.controller} table written from the mean "
                                   "deviations, loaded into the simulated controller, and the "
                                   "axis measured again the same way.")
        note(f"wrote report {report}")
    if json_out:
        print_json(d)
        return
    _render_loop(r)
    if extra:
        _render_applied(extra)


def _cross_axis(um_per_m, axes, aligned, controller, spacing, start, end, resolution, travel,
                opts, out, json_out) -> None:
    from axiscal.compensation.cross_axis import cross_axis_table, write_cross_axis
    from axiscal.compensation.squareness import squareness_compensation
    from axiscal.errors import InputError
    from axiscal.standards.iso230_1 import Squareness

    if len(axes) != 2:
        raise InputError(f"--axes {axes!r}: give two axis letters, e.g. XY")
    if start is None or end is None or spacing is None:
        raise InputError("--squareness needs --start, --end and --spacing (driving axis, mm)")
    comp = squareness_compensation(Squareness(um_per_m * 1e-6, (axes[0], axes[1])), aligned)
    ct = cross_axis_table(comp, start, end, spacing, resolution)
    cf = write_cross_axis(ct, controller, _travel(travel), **_cross_axis_options(controller, opts))
    cf = _write_files(cf, out)
    if json_out:
        d = dict(controller=cf.controller, file=None if out is None else str(out),
                 extra_files=sorted(cf.extra_files), enable=list(cf.enable), notes=list(cf.notes),
                 driving_axis=ct.driving_axis, compensated_axis=ct.compensated_axis,
                 factor_um_per_m=ct.factor, advice=list(comp.advice))
        d.update(_table_json(ct.table))
        print_json(d)
        return
    typer.echo(str(comp))
    typer.echo(str(ct))
    for e in cf.enable:
        typer.echo(f"  enable: {e}")
    if out is None:
        typer.echo("")
        typer.echo(cf.text.rstrip("\n"))


# -- helpers ---------------------------------------------------------------------------------
#: The options each use of the command reads; any other option given is a mistake to name.
_USES = {
    "table": ("a table from SOURCE", {"source", "controller", "spacing", "bidirectional",
              "resolution", "start", "end", "extrapolation", "reference", "travel", "axis",
              "option", "out", "json_out", "encoding"}),
    "verify": ("--verify", {"verify", "on_controller", "controller", "spacing", "option", "out",
               "seed", "plot",
               "report", "json_out"}),
    "read": ("--read", {"read", "source", "controller", "option", "json_out", "ini", "to", "out",
                        "encoding"}),
    "squareness": ("--squareness", {"squareness", "axes", "aligned", "controller", "spacing",
                   "start", "end", "resolution", "travel", "option", "out", "json_out"}),
}


def _refuse_unused(ctx, use: str) -> None:
    """Refuse options the chosen use ignores (``--verify --bidirectional`` would do nothing)."""
    from axiscal.errors import InputError

    what, reads = _USES[use]
    given = [p for p in ctx.command.params if p.name not in reads
             and getattr(ctx.get_parameter_source(p.name), "name", "DEFAULT") not in
             ("DEFAULT", "DEFAULT_MAP")]
    if given:
        names = ", ".join(p.opts[0] if p.opts[0].startswith("-") else p.name.upper() for p in given)
        raise InputError(f"{what} does not use {names}; drop {'it' if len(given) == 1 else 'them'}")


def _options(items: list[str]) -> dict[str, str]:
    """``["KEY=VALUE", ...]`` as text; :func:`_typed` converts them for their reader."""
    from axiscal.errors import InputError

    out = {}
    for item in items:
        if "=" not in item:
            raise InputError(f"--option {item!r} must be KEY=VALUE")
        k, v = item.split("=", 1)
        out[k.strip()] = v.strip()
    return out


def _guessed(raw: dict[str, str]) -> dict:
    """Options for a writer not known here (the configuration's): numbers and booleans by look."""
    return {k: _value(v) for k, v in raw.items()}


def _cross_axis_options(controller: str, raw: dict[str, str]) -> dict:
    """Check ``--option`` against the cross-axis writer of ``controller`` (csv takes none)."""
    from axiscal.compensation.controllers import controller as get_controller
    from axiscal.errors import InputError

    mod = get_controller(controller)
    what = f"--option for a {mod.NAME} cross-axis table"
    if mod.NAME == "siemens-840d":
        return _typed(mod.write_cross_axis, raw, what)
    if mod.NAME == "heidenhain":
        return _typed(mod.write, raw, what, exclude=("driving_axis",))
    if raw and mod.NAME == "csv":
        raise InputError(f"{what}: the csv table takes no options; drop {', '.join(sorted(raw))}")
    return _guessed(raw)


def _travel(travel):
    from axiscal.errors import InputError

    if not travel:
        return None
    if len(travel) != 2 or not travel[1] > travel[0]:
        raise InputError(f"--travel needs two values, low then high; got {list(travel)}")
    return (travel[0], travel[1])


def _render_loop(r) -> None:
    from rich.markup import escape
    from rich.table import Table

    from axiscal.cli._common import console
    from axiscal.standards.positioning_standards import parameter_label

    u = {"um": "µm"}.get(r.unit, r.unit)
    con = console()
    con.print(f"Compensation loop: {r.controller_file.controller} table, {r.table.n_points} points "
              f"every {r.table.spacing:g} {r.table.position_unit}, written, read back and applied")
    title = f"ISO 230-2 before and after [{u}]"
    t = Table(title=escape(title), title_justify="left", min_width=len(title))
    for c in ("parameter", "before", "after"):
        t.add_column(c, justify="left" if c == "parameter" else "right")
    for k, b, a in r.rows():
        t.add_row(parameter_label(k), "n/a" if b is None else f"{b:.3f}",
                  "n/a" if a is None else f"{a:.3f}")
    con.print(t)
    con.print(f"E fell by {100 * r.reduction:.1f} % ({r.before.E:.3f} → {r.after.E:.3f} {u}).")
    con.print(f"Budget for E after: {r.budget_E:.3f} {u} = table/target spacing {r.spacing_residual:.3f} "
              f"+ repeatability (σ = {r.sigma:.3f} {u}, {r.n_runs} runs) + rounding.")
    con.print(f"Truth: E {r.truth_before['E']:.3f} → {r.truth_after['E']:.3f} {u} at the targets; "
              f"{r.between_targets_E:.3f} {u} over the whole range.")


def _render_applied(extra) -> None:
    c = extra["on_controller"]
    unit = {"um": "µm"}.get(c["applied_unit"], c["applied_unit"])
    typer.echo(f"Measured through {c['controller']}: [JOINT_0] COMP_FILE_TYPE = "
               f"{c['comp_file_type']}, machine units {c['machine_units']}, dwell "
               f"{c['dwell_s']:g} s (the plan's {c['plan_dwell_s']:g} s is for a real machine "
               "to settle; the simulated drive settles at once). Trim applied (motor-pos-cmd − pos-cmd) against the table at "
               f"{c['n_applied']} targets and directions: largest difference "
               f"{c['largest_applied_difference']:.2g} {unit} (--json lists each).")


def register(app: typer.Typer) -> None:
    """Add the ``compensate`` command."""
    app.command("compensate")(compensate)
