"""Real measurements in: ``axiscal compensate-environment``, ``axiscal capture``, ``axiscal formats``.

* ``compensate-environment RAW.csv --environment ENV.csv --out DATA.csv``: raw laser readings
  compensated for the air at each reading's time and referred to 20 °C (formats in
  :mod:`axiscal.io.measured`).
* ``capture RECORD --plan PLAN.csv --out DATA.csv``: a test taken without a trigger, from a
  continuous record (``.rtx`` or CSV): the stops found, matched to the plan, averaged.
* ``formats``: every file axiscal reads and writes.

JSON (``--json``), stable keys:

* ``compensate-environment``: ``out``, ``readings``, ``applied`` (the words kept in the
  metadata), ``index_min``, ``index_max``, ``air_temperature_c`` and ``material_temperature_c``
  (``[min, max]``, the latter null without material compensation).
* ``capture``: ``out``, ``stops`` (found), ``measurements``, ``overruns``, ``window_um``,
  ``dwell_s``, ``sample_rate_hz``, ``settling_s`` (``median``, ``max``), ``vibration`` (``peak_hz``,
  ``amplitude_um``), ``applied`` (environment compensation, or null), ``warnings`` (what the
  record's reader noted: an ``.rtx`` capture shorter than its header's ``Sample no``, padding
  dropped; a list of text). For an EPICS camonitor
  log (the setpoint's stops, :mod:`axiscal.io.epics`): ``sample_rate_hz``, ``settling_s`` and
  ``vibration`` are null, ``overruns`` counts every stop that is not a measurement, and
  ``notes`` says what was found and assumed.
* ``formats``: list of ``name``, ``read``, ``write``, ``extensions``, ``example``, ``described_in``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from axiscal.cli._common import note, plot_path, print_json, report_path, typed_path
from axiscal.cli._epics import (REFERENCE_OFFSET, REFERENCE_PV, REFERENCE_SCALE, SETPOINT_PV,
                                capture_log, is_camonitor_log)

__all__ = ["register"]

_EQ_HELP = "Refractive index equation: ciddor (default), edlen or birch-downs."


def compensate_environment(
    raw: Path = typer.Argument(..., help="Raw laser readings (CSV: time_s,target,direction,"
                               "run,reading)."),
    environment: Optional[Path] = typer.Option(None, "--environment", help="Environment log "
                                               "(CSV or JSON) over the test."),
    out: Path = typer.Option(..., "--out", help="Positioning CSV to write (what 'axiscal "
                             "iso230-2' reads)."),
    air_temperature: Optional[float] = typer.Option(None, "--air-temperature", min=-40,
                                                    max=100, help="Air temperature, °C "
                                                    "(instead of the log's)."),
    pressure: Optional[float] = typer.Option(None, "--pressure", min=1e3, max=2e5,
                                             help="Air pressure, Pa (instead of the log's)."),
    humidity: Optional[float] = typer.Option(None, "--humidity", min=0, max=100,
                                             help="Relative humidity, % (instead of the "
                                             "log's)."),
    material_temperature: Optional[float] = typer.Option(None, "--material-temperature",
                                                         min=-40, max=200, help="Material "
                                                         "temperature, °C."),
    expansion_ppm: Optional[float] = typer.Option(None, "--expansion-ppm", min=-100, max=100,
                                                  help="Expansion coefficient of the axis's "
                                                  "scale or work-piece, ppm/K (steel 11.5)."),
    air_only: bool = typer.Option(False, "--air-only", help="Compensate the air only; do not "
                                  "refer the material to 20 °C."),
    equation: str = typer.Option("ciddor", "--equation", help=_EQ_HELP),
    max_gap: float = typer.Option(300.0, "--max-gap", min=1, max=86400, help="Longest gap in "
                                  "the log a reading may fall into, s."),
    json_out: bool = typer.Option(False, "--json", help="Print what was done as JSON."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Plot the air and material over "
                                        "the test and the correction of each reading (.png, "
                                        ".svg, .pdf)."),
    report: Optional[Path] = typer.Option(None, "--report", help="Write a report of the "
                                          "compensation (the plot and what was applied): HTML "
                                          "or PDF."),
) -> None:
    """Compensate raw laser readings for the air (Ciddor) and refer the axis to 20 °C (ISO 1).

    Example: axiscal compensate-environment raw.csv --environment env.csv --out data.csv
    """
    from axiscal import api

    typed_path(out, "positioning CSV", (".csv",))
    if plot is not None:
        plot_path(plot)
    if report is not None:
        report_path(report)
    given = dict(air_temperature=air_temperature, pressure=pressure, humidity=humidity,
                 material_temperature=material_temperature, expansion_ppm=expansion_ppm)
    comp = api.compensate_environment(raw, environment or None, out=out, equation=equation,
                                      air_only=air_only, max_gap=max_gap,
                                      **{k: v for k, v in given.items() if v is not None})
    ds, d = comp.dataset, comp.test.json
    if plot is not None:
        from axiscal.report.plots import save_figure

        save_figure(comp.plot(), plot)
        note(f"wrote plot {plot}")
    if report is not None:
        comp.report(report)
        note(f"wrote report {report}")
    if json_out:
        print_json(d)
        return
    typer.echo(ds.metadata.notes)
    typer.echo(f"wrote {d['readings']} compensated readings to {out} "
               f"(evaluate: axiscal iso230-2 {out})")


def capture(
    record: Path = typer.Argument(..., help="Continuous record: Renishaw .rtx, CSV "
                                  "time_s,reading_mm[,commanded_mm], or an EPICS camonitor log "
                                  "(setpoint and reference PVs)."),
    plan: Path = typer.Option(..., "--plan", help="The plan the machine ran ('axiscal plan ... "
                              "--csv')."),
    out: Path = typer.Option(..., "--out", help="Positioning CSV to write."),
    window: float = typer.Option(1.0, "--window", min=1e-3, max=1e4, help="A stop is where "
                                 "the reading stays within this band, µm (arcsec rotary)."),
    dwell: Optional[float] = typer.Option(None, "--dwell", min=1e-3, max=3600, help="Shortest "
                                          "stop, s (default: 60 % of the plan's dwell)."),
    datum: Optional[float] = typer.Option(None, "--datum", help="Plan position where the "
                                          "laser was zeroed (default: the first target)."),
    unit: Optional[str] = typer.Option(None, "--unit", help="Unit of .rtx readings: um "
                                       "(default), mm, nm, arcsec, urad."),
    environment: Optional[Path] = typer.Option(None, "--environment", help="Environment log: "
                                               "compensate the record's raw readings."),
    plot: Optional[Path] = typer.Option(None, "--plot", help="Dynamic view: position, "
                                        "velocity, acceleration, settling, spectrum (.png)."),
    json_out: bool = typer.Option(False, "--json", help="Print what was found as JSON."),
    report: Optional[Path] = typer.Option(None, "--report", help="Write a report of the capture "
                                          "(the dynamic view and what was found): HTML or PDF."),
    setpoint_pv: Optional[str] = SETPOINT_PV,
    reference_pv: Optional[str] = REFERENCE_PV,
    reference_scale: Optional[float] = REFERENCE_SCALE,
    reference_offset: Optional[float] = REFERENCE_OFFSET,
) -> None:
    """Take a positioning test from a continuous record with no trigger: stops found, matched.

    Example: axiscal capture run.rtx --plan plan.csv --out data.csv --window 0.5 --plot dyn.png
    """
    from axiscal.io._files import write_text_atomic
    from axiscal.io.csv import format_positioning_csv
    from axiscal.io.measured import read_environment_log, read_plan_csv, read_record
    from axiscal.procedures.capture import capture_test

    typed_path(out, "positioning CSV", (".csv",))
    if is_camonitor_log(record):
        capture_log(record, plan, out, window, dwell,
                    {"setpoint_pv": setpoint_pv, "reference_pv": reference_pv,
                     "scale": reference_scale, "offset": reference_offset},
                    {"--datum": datum, "--unit": unit, "--environment": environment,
                     "--plot": plot, "--report": report}, json_out)
        return
    if plot is not None:
        plot_path(plot)
    if report is not None:
        report_path(report)
    rec = read_record(record, unit=unit)
    rows = read_plan_csv(plan)
    log = read_environment_log(environment) if environment else None
    result = capture_test(rec, rows, window=window, dwell=dwell, datum=datum, environment=log)
    write_text_atomic(out, format_positioning_csv(result.dataset))
    if plot is not None:
        from axiscal.report.capture_plots import save_dynamic_view

        save_dynamic_view(rec, result, plot)
        note(f"wrote plot {plot}")
    d = result.summary()
    if report is not None:
        from axiscal.report.capture_plots import dynamic_figure
        from axiscal.report.html import write_result_report

        write_result_report(report, f"Capture of {record.name}", {"out": str(out), **d},
                            figure=dynamic_figure(rec, result),
                            method="Stops found in the continuous record (the reading within "
                                   f"±{window:g} of its mean for the dwell), matched in order to "
                                   f"the plan {plan.name} and averaged over their second half; "
                                   "the positioning test they give is evaluated by ISO 230-2:2014 "
                                   f"with 'axiscal iso230-2 {out}'.")
        note(f"wrote report {report}")
    if json_out:
        print_json({"out": str(out), **d})
        return
    typer.echo(f"{d['stops']} stops found at {d['sample_rate_hz']:g} Hz: {d['measurements']} "
               f"measurements matched to the plan, {d['overruns']} overrun stops")
    typer.echo(f"settling time median {d['settling_s']['median']:.3f} s, longest "
               f"{d['settling_s']['max']:.3f} s; vibration peak {d['vibration']['peak_hz']:.1f} Hz"
               f" ({d['vibration']['amplitude_um']:.3g} µm)")
    if d["applied"]:
        typer.echo(d["applied"])
    for w in d["warnings"]:
        typer.echo(f"warning: {w}")
    typer.echo(f"wrote {out} (evaluate: axiscal iso230-2 {out})")


def formats(json_out: bool = typer.Option(False, "--json", help="Print the list as JSON.")):
    """Every file format axiscal reads and writes, with an example file each.

    Example: axiscal formats
    """
    from axiscal.io.formats import FORMATS

    if json_out:
        print_json([f.as_dict() for f in FORMATS])
        return
    for f in FORMATS:
        rw = "read/write" if f.read and f.write else "read" if f.read else "write"
        typer.echo(f"{f.name} [{rw}; {', '.join(f.extensions)}]")
        typer.echo(f"    example: {f.example}")
        typer.echo(f"    described in: {f.described_in}")


def register(app: typer.Typer) -> None:
    """Add the commands of real measurements to the application."""
    app.command("compensate-environment")(compensate_environment)
    app.command("capture")(capture)
    app.command("formats")(formats)
