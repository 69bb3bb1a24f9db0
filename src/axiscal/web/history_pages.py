"""History pages: machines, a machine's tests, a test, compare, trend, upload, tables.

Every page reads the calibration history through :mod:`axiscal.store` (the same calls as
``axiscal history``); evaluations are the library's. Interactive plots are uPlot specs (JSON)
that ``static/axiscal.js`` draws.
"""

from __future__ import annotations

from typing import Annotated

from fastapi import FastAPI, Request
from fastapi import Path as InPath
from fastapi.responses import HTMLResponse, RedirectResponse
from starlette.concurrency import run_in_threadpool

from axiscal.errors import InputError
from axiscal.web.inputs import Page, QueryId, TestId, checked_form, require_engineer
from axiscal.web.plot_specs import COLORS as _COLORS
from axiscal.web.plot_specs import positioning_plot, trend_plot, unit_text
from axiscal.web.rendering import download, query, render


__all__ = ["add_routes", "positioning_plot", "trend_plot"]

from axiscal.web.machine_view import PAGE, machine_view as _machine_view  # noqa: F401


def add_routes(app: FastAPI) -> None:
    """Add the history routes to ``app`` (its ``state.store`` is opened here)."""
    from axiscal.store import open_store

    app.state.store = open_store(app.state.db_url)
    from axiscal.web import squareness_pages

    squareness_pages.add_routes(app)        # squareness from two straightness tests

    def store(request: Request):
        return request.app.state.store

    @app.get("/", response_class=HTMLResponse)
    def machines(request: Request):
        return render(request, "machines.html", "Machines", machines=store(request).machines())

    @app.get("/machines/{name:path}")
    def machine_by_name(request: Request, name: str, page: Page = 1):   # page: checked here too
        """An old link (a machine by name, "/" in it or not; a name since renamed or merged)
        leads to the machine's page by id."""
        from axiscal.store.corrections import machine_id

        q = request.url.query
        return RedirectResponse(f"/machine/{machine_id(store(request), name)}"
                                + (f"?{q}" if q else ""), 303)

    @app.get("/machine/{machine_id}", response_class=HTMLResponse)
    async def machine(request: Request, machine_id: TestId, axis: str = "", kind: str = "",
                      page: Page = 1):
        """Served on the event loop: a kept page costs one statement and the rendering, one
        read again a few milliseconds of plain reads (no thread, no hand-over of the GIL)."""
        from axiscal.web.memo import memoised

        st, env = store(request), request.app.state.templates.env
        view = memoised(st, ("machine", machine_id, axis, kind, page),
                        lambda: _machine_view(st, env, machine_id, axis, kind, page))
        return render(request, "machine.html", view["name"], **view, query=query)

    @app.get("/tests/{test_id}", response_class=HTMLResponse)
    async def test_page(request: Request, test_id: TestId):
        """Served on the event loop when the test's evaluation and page parts are kept (a few
        plain reads and the rendering); made in a thread when they are not (a figure of a
        ballbar or five-error test takes a second)."""
        from axiscal.web.stored_test_page import stored_test_page as page

        return await page(request, test_id)

    @app.get("/tests/{test_id}/raw")
    def raw(request: Request, test_id: TestId):
        t = store(request).get(test_id)
        return download(t.raw, t.summary.filename, "application/octet-stream")

    @app.get("/tests/{test_id}/tables/{number}")
    def stored_table(request: Request, test_id: TestId, number: Annotated[int, InPath(ge=1,
                                                                                   le=10**6)]):
        """A compensation table written from this test, as it was written (the n-th listed)."""
        t = store(request).get(test_id)
        if number > len(t.tables):
            raise _missing(f"test {test_id} has {len(t.tables)} stored compensation tables; "
                           f"no table {number}")
        _, filename, text = t.tables[number - 1]
        return download(text, filename, "text/plain")

    @app.get("/tests/{test_id}/result.json")
    def result_json(request: Request, test_id: TestId):
        import json

        t = store(request).get(test_id)
        body = {"id": test_id, "machine": t.summary.machine, "axis": t.summary.axis,
                "kind": t.summary.kind, "date": t.summary.tested_at.isoformat(),
                "schema_version": t.result.get("schema_version", 0),   # the stored record's
                "quantities": t.result.get("quantities", {}),
                "uncertainty_inputs": t.result.get("uncertainty_inputs", {}),
                # deprecated (schema 1): the same numbers as quantities.NAME.value, .unit
                "parameters": {k: {"value": v, "unit": u}
                               for k, (v, u) in t.summary.parameters.items()},
                "result": t.result}
        return download(json.dumps(body, indent=2), f"test_{test_id}.json", "application/json")

    @app.get("/tests/{test_id}/report.html")
    async def report(request: Request, test_id: TestId):
        """The test's HTML report, of every kind: ``axiscal history show ID --report``'s, by
        the same call (:meth:`axiscal.api.History.report`), kept per stored bytes, names and
        uncertainty inputs (a rename makes it again with the new name)."""
        from axiscal.store.cache import digest

        t = await run_in_threadpool(request.app.state.store.get, test_id)
        what = digest([t.summary.machine, t.summary.axis,
                       t.result.get("uncertainty_inputs")]) + ".report.html"
        html = await _product(request, test_id, "HTML report", what,
                              lambda t, ev: _report_html(request.app.state.store, t),
                              any_kind=True)
        return _sent(html, f"test_{test_id}_report.html", "text/html")

    @app.get("/tests/{test_id}/standards.html")
    async def standards(request: Request, test_id: TestId):
        from axiscal.store.cache import digest

        t = await run_in_threadpool(request.app.state.store.get, test_id)
        names = digest(t.summary.machine, t.summary.axis)    # as the history names them now
        html = await _product(request, test_id, "report by every standard",
                              f"standards-{test_id}-{names}.html", _standards_html)
        return _sent(html, f"test_{test_id}_standards.html", "text/html")

    @app.get("/tests/{test_id}/certificate.pdf")
    async def certificate(request: Request, test_id: TestId, paper: str = "A4"):
        if paper not in ("A4", "Letter"):
            raise InputError(f"paper {paper!r}: A4 or Letter")
        import datetime as dt

        from axiscal.store.cache import digest
        from axiscal.web.certificate_preview import preview_inputs, preview_pdf

        st = request.app.state.store
        t = await run_in_threadpool(st.get, test_id)
        if t.summary.kind != "iso230-2":
            raise InputError(f"a {t.summary.kind} test has no certificate preview here; "
                             "download its JSON")
        # the sign-off as its form stands: the history's laboratory, names, date, instruments
        t, ev, cfg, tol, rule = await run_in_threadpool(preview_inputs, st, test_id)
        m = st.machine(t.summary.machine_id)
        what = "certificate-" + digest(cfg, tol, rule, paper, dt.date.today().isoformat(),
                                       t.summary.machine, t.summary.axis, m.maker, m.model,
                                       m.serial, m.location) + ".pdf"
        pdf = await _product(request, test_id, "certificate", what,
                             lambda t_, ev_: preview_pdf(st, t, ev, cfg, tol, rule, paper))
        return _sent(pdf, f"test_{test_id}_certificate.pdf", "application/pdf")

    @app.post("/tests/{test_id}/compensation")
    async def compensation(request: Request, test_id: TestId):
        """Write a compensation table from the test (kept with it). From the page (htmx): the
        lines ``axiscal compensate`` prints about it (:meth:`ControllerFile.summary`: reference
        point, shift, backlash value, what to enable), its download, its companion files, and
        the list of the test's tables, without a reload; a plain form post: the file."""
        from axiscal.errors import AxiscalError

        form = await checked_form(request)
        require_engineer(request)
        htmx = request.headers.get("hx-request") == "true"
        try:
            controller = str(form.get("controller", ""))
            spacing = _positive(form.get("spacing"), "spacing")
            axis = str(form.get("axis", "") or "").strip()      # as `compensate --axis`
            f = await run_in_threadpool(_write_table, store(request), test_id, controller,
                                        spacing, axis)
        except AxiscalError as exc:
            if not htmx:
                raise
            return render(request, "_compensation_result.html", "", error=str(exc))
        if not htmx:
            return download(f.text, f.filename, "text/plain")
        t = store(request).get(test_id)
        return render(request, "_compensation_result.html", "", t=t, f=f,
                      number=len(t.tables))

    @app.get("/compare", response_class=HTMLResponse)
    def compare(request: Request, a: QueryId, b: QueryId):
        from axiscal.store.analysis import compare_tests

        s = store(request)
        c = compare_tests(s.get(a), s.get(b))
        plot = None
        if c.targets is not None:
            plot = {"title": f"change of x̄, test {b} − test {a}", "x_label":
                    f"target [{c.target_unit}]", "y_label": f"change [{unit_text(c.unit)}]",
                    "x": c.targets.tolist(), "series": [{"label": "change",
                                                         "values": c.difference.tolist(),
                                                         "color": _COLORS["up"]}]}
        first = s.get(a).summary
        return render(request, "compare.html", f"Compare tests {a} and {b}", c=c, plot=plot,
                      machine=first.machine, axis=first.axis)

    @app.get("/trend", response_class=HTMLResponse)
    def trend_page(request: Request, machine: str, axis: str, parameter: str = "E",
                   tolerance: str = ""):
        """A parameter of one axis over time. ``parameter`` is a key (``R_up``, as ``history
        trend --parameter``) or the symbol the pages show (``R↑``); the form offers the
        parameters the axis's tests have, by their symbols. A name the axis has no value of is
        said on the page, beside the chooser, never as an error page."""
        from axiscal.report.labels import name as quantity_name
        from axiscal.store import trend

        st = store(request)
        choices = [(k, quantity_name(k, axis), u) for k, u in st.parameter_names(machine, axis)]
        if not choices:
            raise _missing(f"no test of {machine} axis {axis} is counted in trends "
                           "(none stored, or every one withdrawn)")
        if not parameter.strip():             # ?parameter= (empty): the page's default
            parameter = "E" if any(k == "E" for k, _, _ in choices) else choices[0][0]
        key = _parameter_key(parameter, choices)
        error, tr, tol = None, None, None
        try:
            tol = _positive(tolerance, "tolerance") if tolerance else None
        except InputError as exc:
            error = str(exc)
        if key is None:
            error = (f"{machine} axis {axis} has no parameter {parameter[:40]!r}: choose one "
                     "of the list")
        elif error is None:
            tr = trend(st, machine, axis, key, tol)
        shown = quantity_name(key, axis) if key else parameter[:40]
        return render(request, "trend.html", f"Trend of {shown}: {machine} {axis}",
                      400 if error else 200, tr=tr, plot=trend_plot(tr, shown) if tr else None,
                      machine=machine, axis=axis, parameter=key or "", shown=shown,
                      tolerance=tolerance, choices=choices, error=error)

    @app.get("/upload", response_class=HTMLResponse)
    def upload_form(request: Request):
        require_engineer(request)
        return render(request, "upload.html", "Upload a test", form={})

    @app.post("/upload")
    async def upload(request: Request):
        form = await checked_form(request)
        require_engineer(request)
        fields = {k: str(form.get(k, "") or "").strip() for k in
                  ("machine", "axis", "note", "date", "instrument")}
        try:
            f = form.get("file")
            if f is None or not hasattr(f, "read"):
                raise InputError("choose a data file to upload")
            raw = await f.read(request.app.state.upload_limit + 1)
            from axiscal.web.security import check_upload

            check_upload(f.filename, f.content_type, len(raw), request.app.state.upload_limit)
            r = await run_in_threadpool(_store_upload, request.app, raw, f.filename, fields)
        except InputError as exc:
            return render(request, "upload.html", "Upload a test", getattr(exc, "status", 400),
                          form=fields, error=str(exc))
        except Exception as exc:                  # noqa: BLE001 - shown, never a traceback
            from axiscal.errors import AxiscalError

            if not isinstance(exc, AxiscalError):
                raise
            return render(request, "upload.html", "Upload a test", 400, form=fields,
                          error=str(exc))
        return stored_page(r, fields)




def stored_page(r, fields: dict):
    """The answer to an upload: the stored test's page, told what of the form was not used as
    typed (shown there): for a file stored before, the date, instrument and note (offered as a
    correction); a machine typed where the file names its own (the form's machine is taken
    only when the file names none); an axis name stored in capitals (``Axis1`` as ``AXIS1``:
    the history keeps axis names in capitals, so ``x`` and ``X`` are one axis)."""
    typed = {k: fields[k] for k in ("date", "instrument", "note") if fields[k]} \
        if r.duplicate else {}        # not stored: shown, offered as a correction
    if fields.get("machine") and fields["machine"] != r.machine:
        typed["typed_machine"] = fields["machine"]
    if fields.get("axis") and fields["axis"] != r.axis:
        typed["typed_axis"] = fields["axis"]
    return RedirectResponse(f"/tests/{r.id}?" + query(
        stored="again" if r.duplicate else "new", **typed), 303)


def _store_upload(app, raw: bytes, filename: str, fields: dict):
    """Store an upload (:meth:`axiscal.api.History.add`, the one way a file is stored) and, when
    it is new, make its page in the same thread before the upload is answered, so the view the
    answer leads to is a look-up on the event loop in whichever worker process serves it (the
    parts are kept on disk). Made in a second thread after the answer, as before, it cost the
    upload two more hand-overs to the thread pool (the making, and the view waiting for it), each
    waiting for a busy event loop and a thread: 20 clients, server time of an upload's POST
    169 ms p50 before this change."""
    from axiscal import api

    r = api.History(store=app.state.store).add(
        raw, filename=filename, machine_default=fields["machine"] or None,
        axis=fields["axis"] or None, note=fields["note"], instrument=fields["instrument"],
        date=fields["date"] or None)
    if not r.duplicate:
        from axiscal.web.stored_test_page import prepare_view

        prepare_view(app, r.id)
    return r


async def _product(request: Request, test_id: int, words: str, what: str, make,
                   any_kind: bool = False):
    """A report or certificate of a stored test (positioning only unless ``any_kind``): kept,
    once made, under the test's stored-bytes SHA-256 and the axiscal version
    (:func:`axiscal.store.cache.kept`); made off the event loop, one at a time per worker
    (:func:`axiscal.web.workers.heavy`)."""
    from axiscal.store.cache import kept_file
    from axiscal.web.workers import heavy

    t = await run_in_threadpool(request.app.state.store.get, test_id)
    if t.summary.kind != "iso230-2" and not any_kind:
        raise InputError(f"a {t.summary.kind} test has no {words} here; download its JSON")
    path = kept_file(t.sha256, what)
    return path if path is not None else await heavy(_make, t, what, make)


def _sent(content, filename: str, media_type: str):
    """A download of a kept product: its file streamed from the cache (never read whole into
    memory), or the bytes when the cache could not keep it."""
    if isinstance(content, bytes):
        return download(content, filename, media_type)
    from fastapi.responses import FileResponse

    safe = download(b"", filename, media_type).headers["content-disposition"]
    return FileResponse(content, media_type=media_type, headers={"Content-Disposition": safe})


def _make(t, what: str, make):
    from axiscal.store.cache import kept, kept_file

    path = kept_file(t.sha256, what)          # made while this request waited its turn
    if path is not None:
        return path
    data = kept(t.sha256, what, lambda: make(t, t.evaluate_again()))
    return kept_file(t.sha256, what) or data


def _report_html(store, t) -> bytes:
    """The report ``axiscal history show ID --report`` writes (:meth:`axiscal.api.History.
    report`), as bytes."""
    import tempfile
    from pathlib import Path

    from axiscal import api

    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "report.html"
        api.History(store=store).report(t.summary.id, path)
        return path.read_bytes()


def _standards_html(t, ev) -> str:
    from axiscal.report.html import standards_report
    from axiscal.standards.positioning_standards import evaluate_all

    ev = t.named(ev)                 # the machine and axis as the history names them
    return standards_report(ev.dataset, evaluate_all(ev.dataset),
                            f"Test {t.summary.id} by every positioning standard").html()


def _write_table(store, test_id: int, controller: str, spacing: float, axis: str = ""):
    """The table of ``controller`` from stored test ``test_id``, stored with the test; ``axis``
    the name written in it, as ``axiscal compensate --axis`` (default: the test's axis)."""
    from axiscal.compensation.controllers import controller as controller_module
    from axiscal.compensation.tables import table_from_result

    t = store.get(test_id)
    mod = controller_module(controller)
    _check_axis_letter(mod, axis, t.summary.axis)
    ev = t.evaluate_again()
    if ev.kind != "iso230-2":
        raise InputError(f"a {ev.kind} test gives no compensation table here")
    table = table_from_result(ev.evaluation, spacing, axis=axis or t.summary.axis,
                              bidirectional=ev.evaluation.bidirectional)
    from axiscal.compensation.controllers.convert import convert

    f = convert(table, mod.NAME)          # the one writing path of the CLI and the API
    store.add_table(test_id, mod.NAME, f.filename, f.text)
    return f


def _check_axis_letter(mod, axis: str, test_axis: str) -> None:
    """Refuse, before anything is written, a name that is not an axis letter for a controller
    whose value column and file names are one (HEIDENHAIN: MANUALplus 620, "Entering
    compensation values"), naming the form's Axis field."""
    from axiscal.compensation.controllers._common import AXIS_LETTERS, is_axis_letter

    name = axis or test_axis
    if not getattr(mod, "AXIS_LETTER", False) or not name or is_axis_letter(name):   # "": X
        return
    whose = f"axis {name[:60]!r}" if axis else f"the test's axis {name[:60]!r}"
    raise InputError(f"{whose} is not an axis letter, which a {mod.NAME} table's value column and "
                     f"file names are ({', '.join(AXIS_LETTERS)}, one digit after it at most: "
                     "X2; HEIDENHAIN MANUALplus 620, \"Entering compensation values\"): type one "
                     "in the Axis field")


def _parameter_key(text: str, choices) -> str | None:
    """The key of the parameter ``text`` names among ``choices`` (key, name, unit): a key
    (``R_up``) or the name the pages show (``R↑``, ``Reversal spike X``), spaces and case
    aside; None when it names none."""
    text = (text or "").strip()
    for key, shown, _ in choices:
        if text in (key, shown):
            return key
    folded = text.casefold().replace(" ", "")
    for key, shown, _ in choices:
        if folded in (key.casefold(), shown.casefold().replace(" ", "")):
            return key
    return None


def _positive(text, what: str) -> float:
    import math

    try:
        v = float(str(text).replace(",", "."))
    except (TypeError, ValueError):
        raise InputError(f"{what} = {text!r}: give a positive number") from None
    if not math.isfinite(v) or not 0 < v <= 1e6:
        raise InputError(f"{what} = {text}: give a positive number up to 1e6")
    return v


def _missing(message: str):
    from axiscal.store import NotFoundError

    return NotFoundError(message)
