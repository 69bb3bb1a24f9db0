"""Uploads that are more than one data file: a capture (a continuous record and the plan the
machine ran), raw laser readings with an environment log, an EPICS camonitor log with its
settings (and the plan, if any), and a history archive.

The same library calls as the command line, nothing computed here:

* ``POST /upload/measured`` (``kind=capture``): :func:`axiscal.io.measured.read_record`,
  :func:`~axiscal.io.measured.read_plan_csv` and :func:`axiscal.procedures.capture.capture_test`
  with the defaults of ``axiscal capture RECORD --plan PLAN`` (window 1 µm, dwell 60 % of the
  plan's, datum the first target); ``kind=raw``: :func:`~axiscal.io.measured.read_raw_readings`,
  :func:`~axiscal.io.measured.read_environment_log` and
  :func:`axiscal.io.simulation_results.environment_compensation` with the defaults of
  ``axiscal compensate-environment RAW --environment LOG`` (Ciddor 1996, material referred to
  20 °C by ISO 1:2022, longest gap 300 s); ``kind=epics``: :func:`axiscal.io.epics_options.
  capture_log` with the settings of :func:`~axiscal.io.epics_options.epics_options` from form
  fields named as the options of ``axiscal iso230-2 LOG`` (``setpoint_pv``, ``reference_pv``,
  ``targets``, ``reference_scale``, ``reference_offset``, ``rest_window``; a plan as the second
  file), every setting not given named with the default that acted. The positioning test each
  gives is stored through ``store.add`` as the CSV bytes the command writes with ``--out``
  (:func:`axiscal.io.csv.format_positioning_csv`); the note names the raw inputs and what was
  applied or assumed.
* ``POST /upload/archive``: :func:`axiscal.store.archive.import_history`, as
  ``axiscal history import ARCHIVE`` (all or nothing).

Both need an engineer and the session's CSRF token, and take files up to the workbench's upload
limit (:func:`axiscal.web.security.check_upload`).
"""

from __future__ import annotations

import tempfile
from contextlib import contextmanager
from pathlib import Path

from fastapi import FastAPI, Request
from fastapi.responses import RedirectResponse
from starlette.concurrency import run_in_threadpool

from axiscal.errors import AxiscalError, InputError
from axiscal.io.epics_options import SETTINGS
from axiscal.web.inputs import checked_form, require_engineer
from axiscal.web.rendering import query, render

__all__ = ["add_routes", "capture_csv", "raw_csv", "epics_csv"]

#: What each kind of measured upload takes: (first file's endings, second file's endings).
SUFFIXES = {"capture": ((".rtx", ".csv"), (".csv",)),
            "raw": ((".csv",), (".csv", ".json")),
            "epics": ((".log", ".txt", ".dat", ".csv"), (".csv",))}
#: How browsers send a camonitor log or a Renishaw .rtx record (besides the types of every
#: upload): .rtx is "rich text" (text/richtext) in the freedesktop.org shared MIME database
#: (shared-mime-info, freedesktop.org.xml: glob ``*.rtx``), by which Chromium on Linux types it.
EXTRA_TYPES = {"epics": ("text/x-log",), "capture": ("text/richtext",), "raw": ()}
#: The settings of an EPICS log: form fields named as ``axiscal iso230-2 LOG``'s options.
EPICS_FIELDS = tuple(name for name, _, _ in SETTINGS)
#: How browsers send a .zip (besides the types of every upload).
ZIP_TYPES = ("application/zip", "application/x-zip-compressed", "application/x-zip")
_TITLE = "Upload a test"
_FIELDS = ("machine", "axis", "note", "date", "instrument")


def add_routes(app: FastAPI) -> None:
    """Add ``POST /upload/measured`` and ``POST /upload/archive``."""

    @app.post("/upload/measured")
    async def upload_measured(request: Request):
        form = await checked_form(request)
        require_engineer(request)
        fields = {k: str(form.get(k, "") or "").strip()
                  for k in _FIELDS + ("kind",) + EPICS_FIELDS}
        try:
            kind = fields["kind"]
            if kind not in SUFFIXES:
                raise InputError(f"kind {kind!r}: capture (record + plan), raw (raw readings "
                                 "+ environment log) or epics (camonitor log [+ plan])")
            first = await _file(request, form.get("file"), SUFFIXES[kind][0], "the data file",
                                types=EXTRA_TYPES[kind])
            second = await _file(request, form.get("second"), SUFFIXES[kind][1],
                                 "the environment log" if kind == "raw" else "the plan",
                                 optional=kind != "capture")
            r = await run_in_threadpool(_store_measured, request.app.state.store, kind,
                                        first, second, fields)
        except AxiscalError as exc:
            return render(request, "upload.html", _TITLE, getattr(exc, "status", 400),
                          form=fields, error=str(exc))
        from axiscal.web.history_pages import stored_page

        return stored_page(r, fields)

    @app.post("/upload/archive")
    async def upload_archive(request: Request):
        form = await checked_form(request)
        require_engineer(request)
        try:
            name, raw = await _file(request, form.get("archive"), (".zip",), "the archive",
                                    types=ZIP_TYPES)
            done = await run_in_threadpool(_import, request.app.state.store, name, raw)
        except AxiscalError as exc:
            return render(request, "upload.html", _TITLE, getattr(exc, "status", 400),
                          form={}, error=str(exc))
        return render(request, "upload.html", _TITLE, form={},
                      imported=done.text(name))


async def _file(request: Request, f, suffixes: tuple, what: str, optional: bool = False,
                types: tuple = ()):
    """(name, bytes) of an uploaded file, checked as every upload is (also sent as one of
    ``types``); None if optional and not given."""
    from axiscal.web.security import UPLOAD_TYPES, check_upload

    if f is None or not hasattr(f, "read") or not f.filename:
        if optional:
            return None
        raise InputError(f"choose {what} to upload")
    limit = request.app.state.upload_limit
    raw = await f.read(limit + 1)
    check_upload(f.filename, f.content_type, len(raw), limit, suffixes, UPLOAD_TYPES + types)
    return Path(f.filename).name, raw


@contextmanager
def _folder():
    """A scratch folder for the uploads, named nowhere in what the user is told: an error of the
    readers names the uploaded file as it was sent."""
    with tempfile.TemporaryDirectory() as d:
        try:
            yield Path(d)
        except AxiscalError as exc:
            raise InputError(str(exc).replace(f"{Path(d)}/", "")) from None


def _saved(folder: Path, name: str, raw: bytes) -> Path:
    """The upload written into ``folder`` under a safe form of its name (the readers name the
    file in what they say and choose by its ending)."""
    safe = "".join(c if c.isalnum() or c in "._-" else "_" for c in name)[-100:]
    path = folder / (safe.lstrip(".") or "upload")
    path.write_bytes(raw)
    return path


def capture_csv(record: Path, plan: Path) -> tuple[str, str]:
    """``axiscal capture RECORD --plan PLAN``'s positioning CSV and what was found (its
    defaults: window 1 µm, dwell 60 % of the plan's; :func:`axiscal.procedures.capture.
    capture_test`)."""
    from axiscal.io.csv import format_positioning_csv
    from axiscal.io.measured import read_plan_csv, read_record
    from axiscal.procedures.capture import capture_test

    result = capture_test(read_record(record), read_plan_csv(plan), window=1.0)
    d = result.summary()
    words = (f"{d['stops']} stops found, {d['measurements']} measurements matched to the plan, "
             f"{d['overruns']} overrun stops (window ±{d['window_um']:g} µm, dwell "
             f"{d['dwell_s']:g} s)")
    return format_positioning_csv(result.dataset), words


def raw_csv(raw: Path, log: Path | None) -> tuple[str, str]:
    """``axiscal compensate-environment RAW --environment LOG``'s positioning CSV and what was
    applied (its defaults: Ciddor 1996, material to 20 °C, longest gap 300 s)."""
    from axiscal.io.csv import format_positioning_csv
    from axiscal.io.measured import read_environment_log, read_raw_readings
    from axiscal.io.simulation_results import environment_compensation

    sim = environment_compensation(read_raw_readings(raw),
                                   read_environment_log(log) if log else None,
                                   equation="ciddor", normalise_material=True, max_gap=300.0)
    return format_positioning_csv(sim.parts["dataset"]), sim.json["applied"]


def epics_csv(log: Path, plan: Path | None, settings: dict) -> tuple[str, str]:
    """``axiscal capture LOG [--plan PLAN]`` of a camonitor log with the settings of ``axiscal
    iso230-2 LOG`` (:func:`axiscal.io.epics_options.capture_log`): the positioning CSV and
    what was found, with every setting not given and the default that acted."""
    from axiscal.io._files import read_text
    from axiscal.io.csv import format_positioning_csv
    from axiscal.io.epics_options import capture_log, epics_options

    rows = None
    if plan is not None:            # named as uploaded: the notes kept with the test say it
        from axiscal.io.measured import parse_plan_csv

        rows = parse_plan_csv(read_text(plan), source=plan.name)
    cap, words = capture_log(read_text(log), log.name, epics_options(**settings, plan=rows))
    return format_positioning_csv(cap.dataset), words


def _store_measured(store, kind: str, first, second, fields: dict):
    with _folder() as d:
        a = _saved(d, *first)
        b = _saved(d, *second) if second else None
        if kind == "epics":
            text, words = epics_csv(a, b, {k: fields[k] for k in EPICS_FIELDS})
        else:
            text, words = capture_csv(a, b) if kind == "capture" else raw_csv(a, b)
    inputs = f"{first[0]} + {second[0]}" if second else first[0]
    what = {"capture": "capture", "raw": "compensate-environment",
            "epics": "iso230-2"}[kind]
    note = "; ".join(x for x in (fields["note"], f"from {what} of {inputs}: {words}") if x)
    return store.add(text.encode(), f"{Path(first[0]).stem}_{kind}.csv",
                     machine_default=fields["machine"] or None, axis=fields["axis"] or None,
                     note=note, instrument=fields["instrument"], date=fields["date"] or None)


def _import(store, name: str, raw: bytes):
    from axiscal.store.archive import import_history

    with _folder() as d:
        return import_history(store, _saved(d, name, raw))
