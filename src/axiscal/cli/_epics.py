"""The options of an EPICS camonitor log, shared by ``iso230-2``, ``evaluate`` and ``capture``
(the reader: :mod:`axiscal.io.epics`; the settings, shared with the workbench:
:mod:`axiscal.io.epics_options`)."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

__all__ = ["SETPOINT_PV", "REFERENCE_PV", "TARGETS", "REFERENCE_SCALE", "REFERENCE_OFFSET",
           "REST_WINDOW", "epics_options", "show_notes", "is_camonitor_log", "capture_log"]

_LOG = "EPICS camonitor log: "
SETPOINT_PV: Optional[str] = typer.Option(
    None, "--setpoint-pv", help=_LOG + "the setpoint PV whose steps are the stops (found when "
    "the log holds two PVs).")
REFERENCE_PV: Optional[str] = typer.Option(
    None, "--reference-pv", help=_LOG + "the reference (or readback) PV measured at each stop.")
TARGETS: Optional[str] = typer.Option(
    None, "--targets", help=_LOG + "the targets, comma-separated (default: the setpoint values "
    "passed through; turning points are over-travel).")
REFERENCE_SCALE: Optional[float] = typer.Option(
    None, "--reference-scale", help=_LOG + "position = scale × reference + offset (ecmc's "
    "REF_GR; default 1).")
REFERENCE_OFFSET: Optional[float] = typer.Option(
    None, "--reference-offset", help=_LOG + "the offset of that line, target unit (ecmc's "
    "REF_OFF; default 0).")
REST_WINDOW: Optional[float] = typer.Option(
    None, "--rest-window", help=_LOG + "the reference rests within this band, µm (arcsec "
    "rotary; default 1) for 0.5 s at a stop.")


def epics_options(setpoint_pv=None, reference_pv=None, targets=None, scale=None, offset=None,
                  window=None, plan: Path | None = None, dwell=None) -> dict:
    """The options given, as :func:`axiscal.io.epics.parse_epics` takes them (none: ``{}``):
    :func:`axiscal.io.epics_options.epics_options`, the plan read from its CSV."""
    from axiscal.io import epics_options as settings

    rows = None
    if plan is not None:
        from axiscal.io.measured import read_plan_csv

        rows = read_plan_csv(plan)
    return settings.epics_options(setpoint_pv, reference_pv, targets, scale, offset, window,
                                  plan=rows, dwell=dwell)


def show_notes(ds) -> None:
    """Print (stderr) what the reader of a camonitor log found and assumed."""
    from axiscal.cli._common import note
    from axiscal.io.detect import NOTES_START   # not the reader: no EPICS import for a CSV

    if ds.metadata.notes.startswith(NOTES_START):
        note(ds.metadata.notes)


def is_camonitor_log(path: Path) -> bool:
    """True if ``path`` is a readable file whose first line reads like camonitor's."""
    from axiscal.io.detect import looks_like_camonitor

    if not Path(path).is_file():   # a FIFO would block the open; the reader names the fault
        return False
    try:
        with open(path, "rb") as fh:
            head = fh.read(4096).decode("utf-8", errors="replace")
    except OSError:
        return False
    return looks_like_camonitor(head)


def capture_log(record: Path, plan: Path, out: Path, window: float, dwell, epics: dict,
                not_for_a_log: dict, json_out: bool) -> None:
    """``axiscal capture`` of a camonitor log: the stops of the setpoint matched to the plan,
    the reference read where it rests; written as a positioning CSV."""
    from axiscal.cli._common import print_json
    from axiscal.errors import InputError
    from axiscal.io._files import read_text, write_text_atomic
    from axiscal.io.csv import format_positioning_csv
    from axiscal.io.epics import capture_epics

    given = [name for name, value in not_for_a_log.items() if value is not None]
    if given:
        raise InputError(f"{given[0]} applies to a laser record; {record} is an EPICS camonitor "
                         "log (its reference is read where it rests, see --window)")
    opts = epics_options(**epics, window=window, plan=plan, dwell=dwell)
    cap = capture_epics(read_text(record), source=str(record), **opts)
    write_text_atomic(out, format_positioning_csv(cap.dataset))
    d = {"out": str(out), "stops": cap.stops, "measurements": cap.measurements,
         "overruns": cap.other_stops, "window_um": window, "dwell_s": opts.get("dwell", 1.0),
         "sample_rate_hz": None, "settling_s": None, "vibration": None, "applied": None,
         "warnings": [],
         "notes": cap.dataset.metadata.notes}
    if json_out:
        print_json(d)
        return
    typer.echo(cap.dataset.metadata.notes)
    typer.echo(f"wrote {out} (evaluate: axiscal iso230-2 {out})")
