"""Squareness from two stored straightness tests (issue 40): the page and its report.

The same evaluation as ``axiscal squareness biaxial X.csv Y.csv``
(:func:`axiscal.standards.squareness_biaxial.evaluate_biaxial`) on the two tests' stored
trajectories, with the user configuration's ``[squareness_uncertainty]`` inputs as the command
reads them; the report is the command's ``--report``
(:func:`axiscal.report.squareness_plots.write_biaxial_report`). The page is a function of the
two stored tests and the form; its "Keep as a test" (``POST /squareness/keep``, an engineer's,
CSRF-checked) stores the result as a test of kind ``squareness``: the file ``axiscal squareness
biaxial --inline`` writes (:mod:`axiscal.io.biaxial`: both trajectories, every option, each
straightness file's SHA-256, by which the test's page links the two tests it came from).
"""

from __future__ import annotations

from fastapi import FastAPI, Request
from fastapi.responses import HTMLResponse, RedirectResponse
from starlette.concurrency import run_in_threadpool

from axiscal.errors import AxiscalError, InputError
from axiscal.web.inputs import QueryId, checked_form, require_engineer
from axiscal.web.rendering import download, render

__all__ = ["add_routes", "partners", "made_from"]

#: The form's choices (``axiscal squareness biaxial`` options).
REFERENCES = ("least_squares", "end_point", "minimum_zone")


def add_routes(app: FastAPI) -> None:
    """``GET /squareness`` (the page) and ``GET /squareness/report.html``."""

    @app.get("/squareness", response_class=HTMLResponse)
    async def squareness_page(request: Request, first: QueryId, second: QueryId,
                              config: str = "L", orientation: int = 0, prism_error: str = "0",
                              reference: str = "least_squares", square: str = "optics"):
        form = dict(first=first, second=second, config=config, orientation=orientation,
                    prism_error=prism_error, reference=reference, square=square)
        return await _page(request, form)

    @app.post("/squareness/keep", response_class=HTMLResponse)
    async def squareness_keep(request: Request):
        """Keep the squareness as a test (kind ``squareness``) and go to its page, where its
        report and sign-off are; refused: the squareness page again, the reason at the
        form (400). The same checks and evaluation as the page."""
        form = await checked_form(request)
        require_engineer(request)
        values = {k: str(form.get(k, "") or "").strip() for k in
                  ("first", "second", "config", "orientation", "prism_error", "reference",
                   "square")}
        try:
            values["first"], values["second"], values["orientation"] = (
                _whole(values[k], k) for k in ("first", "second", "orientation"))
        except InputError as exc:
            from axiscal.web.rendering import render_error

            return render_error(request, str(exc), 400)
        try:
            added = await run_in_threadpool(_keep, request.app.state.store, values)
        except AxiscalError as exc:
            return await _page(request, values, 400, keep_error=str(exc))
        return RedirectResponse(f"/tests/{added.id}?kept=squareness#made-from", 303)

    @app.get("/squareness/report.html")
    async def squareness_report(request: Request, first: QueryId, second: QueryId,
                                config: str = "L", orientation: int = 0,
                                prism_error: str = "0", reference: str = "least_squares",
                                square: str = "optics"):
        form = dict(first=first, second=second, config=config, orientation=orientation,
                    prism_error=prism_error, reference=reference, square=square)
        st = request.app.state.store
        form = await run_in_threadpool(_in_axis_order, st, form)
        first, second = form["first"], form["second"]
        data = await run_in_threadpool(_report, st, form)
        return download(data, f"squareness_tests_{first}_{second}.html", "text/html")


async def _page(request: Request, form: dict, status: int = 200, **extra):
    st = request.app.state.store
    form = await run_in_threadpool(_in_axis_order, st, form)   # as squareness biaxial x y
    one, two, b = await run_in_threadpool(_evaluate, st, form)
    figure = await run_in_threadpool(_figure, one, two, b, form)
    a, c = st.get(form["first"]).summary, st.get(form["second"]).summary
    from urllib.parse import urlencode

    return render(request, "squareness.html",
                  f"Squareness {a.axis}{c.axis} from tests {a.id} and {c.id}", status, b=b,
                  form=form, figure=figure, a=a, c=c, references=REFERENCES,
                  report_query=urlencode(form), **extra)


def _whole(text: str, what: str) -> int:
    if not text.isdigit() or len(text) > 9:
        raise InputError(f"{what} {text!r:.20}: a whole number")
    return int(text)


def _keep(store, form: dict):
    """Store the squareness of ``form`` (the page's options) as a test: the one file of
    :mod:`axiscal.io.biaxial`, with the machine of the two tests, dated by the later of the
    two when both state their date, and the user configuration's
    ``[squareness_uncertainty]`` inputs (:meth:`axiscal.store.history.Store.add`'s default,
    the page's)."""
    from axiscal.io.biaxial import biaxial_test, format_biaxial_test

    one, two, b = _evaluate(store, form)       # the page's checks and its evaluation
    ta, tc = store.get(form["first"]), store.get(form["second"])
    a, c = ta.summary, tc.summary
    test = biaxial_test(one, two, config=b.summary["config"], orientation=form["orientation"],
                        prism_error=b.summary["prism_error_arcsec"],
                        reference=form["reference"], square=form["square"],
                        machine=a.machine, sha256=(ta.sha256, tc.sha256))
    date = (max(a.tested_at, c.tested_at).strftime("%Y-%m-%d")
            if a.date_known and c.date_known else None)
    return store.add(format_biaxial_test(test).encode(),
                     f"squareness_{a.axis}{c.axis}_tests_{a.id}_{c.id}.toml",
                     machine=a.machine, date=date,
                     note=f"squareness from straightness tests {a.id} ({a.axis}) and {c.id} "
                          f"({c.axis}), kept from the workbench")


def made_from(store, ev) -> list:
    """The straightness files a squareness test (kind ``squareness``) was made from, each as
    (axis, file name, the stored test's id or None where this history does not hold it),
    found by the SHA-256 its file keeps; [] for another kind."""
    if getattr(ev, "kind", "") != "squareness":
        return []
    t = ev.dataset
    found = store.stored([d for d in t.sha256 if d])
    return [(data.axis or "?", data.source, getattr(found.get(d), "id", None))
            for data, d in ((t.one, t.sha256[0]), (t.two, t.sha256[1]))]


def partners(store, t) -> list:
    """The straightness tests of ``t``'s machine on another axis (counted ones), newest
    first: what a straightness test can give a squareness with."""
    if t.summary.kind != "straightness":
        return []
    return [o for o in store.tests(machine=t.summary.machine, kind="straightness",
                                   parameters=())
            if o.axis != t.summary.axis and not o.withdrawn][:20]


def _in_axis_order(store, form: dict) -> dict:
    """``form`` with the two tests in the order of their axes' names (X before Y, Y before Z):
    the page entered from either test is ``axiscal squareness biaxial x.csv y.csv``, the
    first axis the datum, the same sign and the same words (issue 40: entered from the Y test
    it said "X referred to datum Y", −65.11, where the command said +65.11)."""
    a, b = store.get(form["first"]).summary.axis, store.get(form["second"]).summary.axis
    if a > b:
        form = {**form, "first": form["second"], "second": form["first"]}
    return form


def _trajectories(store, form: dict):
    firsts = []
    for key in ("first", "second"):
        t = store.get(form[key])
        s = t.summary
        if s.kind != "straightness":
            raise InputError(f"test {s.id} is a {s.kind} test: squareness from trajectories "
                             "takes two straightness tests")
        if s.withdrawn:
            raise InputError(f"test {s.id} is withdrawn ({s.withdrawn}); reinstate it first")
        firsts.append((s, t.record().dataset))
    (a, one), (b, two) = firsts
    if a.id == b.id:
        raise InputError(f"test {a.id} with itself: choose the other axis's straightness test")
    if a.machine != b.machine:
        raise InputError(f"test {a.id} is of {a.machine}, test {b.id} of {b.machine}: two "
                         "tests of one machine")
    return one, two


def _evaluate(store, form: dict):
    from axiscal.io.user_config import load_user_config
    from axiscal.standards.squareness_biaxial import evaluate_biaxial

    one, two = _trajectories(store, form)
    if form["reference"] not in REFERENCES:
        raise InputError(f"reference {form['reference']!r}: least_squares, end_point or "
                         "minimum_zone")
    try:
        prism = float(str(form["prism_error"]).replace(",", "."))
    except ValueError:
        raise InputError(f"prism error {form['prism_error']!r}: a number of arcsec") from None
    if not abs(prism) <= 3600:
        raise InputError(f"prism error {form['prism_error']!r}: at most ±3600 arcsec")
    table = dict(load_user_config().get("squareness_uncertainty", {}))
    b = evaluate_biaxial(one, two, config=form["config"], orientation=form["orientation"],
                         prism_error=prism, reference=form["reference"], square=form["square"],
                         inputs=table)
    return one, two, b


def _figure(one, two, b, form) -> str:
    from axiscal.report.squareness_plots import biaxial_figure
    from axiscal.web.kind_pages import _figure as as_image

    return as_image(biaxial_figure, one, two, b.result,
                    f"Bi-axial {str(form['config']).upper()} {form['orientation']}°")


def _report(store, form: dict) -> bytes:
    import tempfile
    from pathlib import Path

    from axiscal.report.squareness_plots import write_biaxial_report
    from axiscal.web.kind_pages import _PLOT_LOCK

    one, two, b = _evaluate(store, form)
    a, c = store.get(form["first"]).summary, store.get(form["second"]).summary
    sources = (f"{a.machine}: test {a.id} ({a.filename}, axis {a.axis}), test {c.id} "
               f"({c.filename}, axis {c.axis})")
    with tempfile.TemporaryDirectory() as d, _PLOT_LOCK:
        path = Path(d) / "report.html"
        write_biaxial_report(path, one, two, b, sources, form["config"], form["orientation"])
        return path.read_bytes()
