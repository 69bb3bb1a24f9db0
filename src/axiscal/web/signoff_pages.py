"""Sign-off of a positioning test in the workbench: tolerances, the job, the ISO 14253-1 verdict,
a certificate issued through the history's certificate register.

The form carries what ``axiscal iso230-2 --tolerance NAME=VALUE --job JOB.toml --report`` takes:
tolerances by parameter, and the job's tables (``[customer]``, ``[machine]``, ``[conditions]``,
``[[instrument]]``, ``[operator]``, ``[certificate]``) over the user configuration (axiscal
config). :func:`job_from_form` only parses the fields into that job structure; the verdict is
:func:`axiscal.report.issue.sign_off` and the certificate :func:`axiscal.report.issue.
write_certificate`, the same library calls as the command line, numbered by the register of the
workbench's history (:meth:`axiscal.store.history.Store.issue_certificate`). A certificate whose
mandatory content (ISO/IEC 17025:2017 §7.8.2, §7.8.4) is incomplete is not numbered: the page
names each missing item, as the command line's DRAFT does.
"""

from __future__ import annotations

from fastapi import FastAPI, Request
from fastapi.responses import HTMLResponse, RedirectResponse, Response
from starlette.concurrency import run_in_threadpool

from axiscal.errors import AxiscalError, InputError
from axiscal.web.inputs import TestId, checked_form, form_number, require_engineer
from axiscal.web.plot_specs import COLORS, as_list, positioning_plot, unit_text
from axiscal.web.rendering import download, query, render

__all__ = ["add_routes", "job_from_form", "signoff_context", "signoff_plot", "INSTRUMENTS"]

#: Instrument rows of the form (``[[instrument]]`` of a job file).
INSTRUMENTS = 3
_JOB_FIELDS = {"customer_name": ("customer", "name"), "customer_address": ("customer", "address"),
               "machine_maker": ("machine", "maker"), "machine_model": ("machine", "model"),
               "machine_serial": ("machine", "serial"),
               "machine_location": ("machine", "location"),
               "date": ("conditions", "date"),
               "air_temperature": ("conditions", "air_temperature"),
               "material_temperature": ("conditions", "material_temperature"),
               "operator": ("operator", "name"),
               "signatory": ("certificate", "signatory"),
               "signatory_role": ("certificate", "signatory_role"),
               "specification": ("certificate", "specification")}
_TEMPERATURES = ("air_temperature", "material_temperature")
_INSTRUMENT_KEYS = ("name", "serial", "certificate", "due")
#: Colours of the verdicts (table cells and the tolerance envelope of the plot).
VERDICT_COLORS = {"PASS": "#1e7b34", "FAIL": "#d62728", "ZONE": "#ff7f0e"}


def add_routes(app: FastAPI) -> None:
    """The sign-off routes over the workbench's history (``app.state.store``)."""

    def store(request: Request):
        return request.app.state.store

    @app.post("/tests/{test_id}/signoff", response_class=HTMLResponse)
    async def signoff(request: Request, test_id: TestId):
        form = await checked_form(request)
        require_engineer(request)
        values = {k: str(v).strip() for k, v in form.items() if isinstance(v, str)}
        issue = values.get("action") == "issue"
        from axiscal.web.workers import heavy     # a certificate: one at a time per worker

        user = request.state.session.get("name") or ""    # signed in: the approver
        ctx = await (heavy if issue else run_in_threadpool)(_evaluate, store(request), test_id,
                                                            values, issue, user)
        partial = request.headers.get("hx-request") == "true"
        if ctx.get("number"):                  # issued: the test page lists it (POST-redirect-GET)
            url = f"/tests/{test_id}?{query(certificate=ctx['number'])}#signoff"
            return Response(headers={"HX-Redirect": url}) if partial else \
                RedirectResponse(url, 303)
        status = 200 if partial or not ctx.get("error") else 400
        return render(request, "signoff.html" if partial else "signoff_page.html",
                      f"Sign-off of test {test_id}", status, test_id=test_id, signoff=ctx)

    @app.get("/tests/{test_id}/certificate")
    def certificate_document(request: Request, test_id: TestId, number: str):
        """A certificate of this test as the register keeps it (bytes checked by SHA-256)."""
        rec = store(request).certificate(number)
        if rec.test_id != test_id:
            from axiscal.store import NotFoundError

            raise NotFoundError(f"certificate {number} is not one of test {test_id}")
        ext = ".pdf" if rec.media_type == "application/pdf" else ".html"
        return download(rec.document, f"{rec.number}{ext}", rec.media_type)


def signoff_context(st, t, ev, values: dict | None = None, certificate: str = "",
                    cfg: dict | None = None) -> dict | None:
    """What the test page's sign-off section shows: the form (prefilled from the user
    configuration ``cfg``, default read now, or from the inputs kept with ``certificate`` of
    this test, whose verdict is then shown) and the certificates of this test in the register;
    None for a test that is not a positioning test."""
    if ev.kind != "iso230-2":
        return None
    from axiscal.report.issue import load_config

    params = [n for n, v in ev.evaluation.parameters().items() if v is not None]
    records = st.certificates(test_id=t.summary.id)
    ctx = {"test_id": t.summary.id, "parameters": params, "certificates": records,
           "instruments": range(1, INSTRUMENTS + 1),
           "unit": _unit(ev.evaluation.deviation_unit)}
    issued = next((c for c in records if c.number == certificate), None)
    if issued is not None:
        inputs = st.certificate(issued.number, issued.laboratory).inputs
        tolerances = inputs.get("tolerances") or {}
        cfg = inputs["config"]
        ctx["form"] = {**_defaults(cfg, params),
                       **{f"tol_{p}": f"{v:g}" for p, v in tolerances.items()}}
        _verdict(ctx, ev, cfg, tolerances, inputs.get("rule"))
    else:
        ctx["form"] = values if values is not None else \
            _defaults(load_config(None) if cfg is None else cfg, params)
    return ctx


def job_from_form(values: dict, parameters) -> tuple[dict, dict, str | None, str]:
    """(job, tolerances, rule, paper) from the form's text fields.

    ``job`` has the tables of a job file (only the fields given: the user configuration stays
    beneath); ``tolerances`` maps each parameter given (``tol_A`` ...) to its value in the
    deviation unit, as ``--tolerance A=12``. An empty field is not given.

    Raises
    ------
    InputError
        A temperature or tolerance that is not a number; an unknown rule or paper size.
    """
    job: dict = {}
    for field, (table, key) in _JOB_FIELDS.items():
        text = values.get(field, "")
        if not text:
            continue
        value: object = text
        if field in _TEMPERATURES:
            value = form_number(text, field.replace("_", " ") + " [°C]", -50.0, 100.0)
        elif field == "customer_address":
            value = [line.strip() for line in text.splitlines() if line.strip()]
        job.setdefault(table, {})[key] = value
    rows = [{k: values.get(f"instrument{i}_{k}", "") for k in _INSTRUMENT_KEYS}
            for i in range(1, INSTRUMENTS + 1)]
    rows = [{k: v for k, v in r.items() if v} for r in rows if any(r.values())]
    for r in rows:
        if "name" not in r:
            raise InputError("an instrument row without a name: give the instrument's name")
    if rows:
        job["instrument"] = rows
    tolerances = {p: form_number(values[f"tol_{p}"], f"tolerance {p}", 0.0, 1e6)
                  for p in parameters if values.get(f"tol_{p}")}
    rule = values.get("rule") or None
    if rule not in (None, "iso14253-1", "simple"):
        raise InputError(f"decision rule {rule!r}: iso14253-1 or simple")
    paper = values.get("paper") or "A4"
    if paper not in ("A4", "Letter"):
        raise InputError(f"paper {paper!r}: A4 or Letter")
    return job, tolerances, rule, paper


def signoff_plot(ev, so=None, tolerances: dict | None = None) -> dict:
    """uPlot spec of an ISO 230-2 test for the page: the mean lines, x̄ ± 2s of each direction
    (the band of A, ISO 230-2:2014 clause 3; Yüksel et al., eq. 20, 21), every reading, and with
    a sign-off ``so`` the tolerance envelope of A, E and M in the colour of its verdict.

    An envelope is a band as wide as the tolerance, centred on the middle of what the parameter
    spans (x̄ ± 2s for A, the mean lines for E, x̄ for M; eq. 18, 19, 21): the parameter is within
    its tolerance exactly when its curves fit between the two lines. Where to draw a band of that
    width is not said by the standard; the centred position is this page's choice.
    """
    spec = positioning_plot(ev)
    r, ds = ev.evaluation, ev.dataset
    series = spec["series"]
    for arrow, mean, s, arr, color in (("↑", r.mean_up, r.s_up, ds.up, COLORS["up"]),
                                       ("↓", r.mean_down, r.s_down, ds.down, COLORS["down"])):
        if arr.shape[1] == 0:
            continue
        series += [{"label": f"x̄{arrow} + 2s", "values": as_list(mean + 2 * s), "color": color,
                    "dash": True, "thin": True},
                   {"label": f"x̄{arrow} − 2s", "values": as_list(mean - 2 * s), "color": color,
                    "dash": True, "thin": True}]
        runs = arr.shape[1]      # one legend entry for every run's readings of a direction
        series += [{"label": f"readings{arrow} (runs 1–{runs})" if j == 0 else
                    f"readings{arrow} run {j + 1}", "values": as_list(arr[:, j]), "color": color,
                    "points": True, "legend": j == 0} for j in range(runs)]
    if so is not None:
        series += _envelopes(r, so, tolerances or {})
        if so.overall is not None:
            spec["verdict"] = so.overall.short
            spec["title"] += f": {so.overall.value} (ISO 14253-1:2017)"
    return spec


def _envelopes(r, so, tolerances: dict) -> list:
    import numpy as np

    spans = {"A": np.concatenate([r.mean_up + 2 * r.s_up, r.mean_up - 2 * r.s_up,
                                  r.mean_down + 2 * r.s_down, r.mean_down - 2 * r.s_down]),
             "E": np.concatenate([r.mean_up, r.mean_down]), "M": r.mean_bi}
    out = []
    for d in so.decisions:
        values = spans.get(d.parameter)
        if values is None or d.outcome is None or not np.isfinite(values).any():
            continue
        mid = (np.nanmax(values) + np.nanmin(values)) / 2
        color = VERDICT_COLORS[d.outcome.short]
        for sign, edge in ((1, "upper"), (-1, "lower")):
            out.append({"label": f"tolerance {d.parameter} = {d.upper:g} ({d.outcome.short}), "
                                 f"{edge}", "values": [float(mid + sign * d.upper / 2)] *
                        r.targets.size, "color": color, "dash": True})
    return out


def _evaluate(st, test_id: int, values: dict, issue: bool, user: str = "") -> dict:
    """The sign-off's verdict and, with ``issue``, the certificate (library calls only).

    ``user`` is the signed-in account: the approver of the issue, who must be one of the
    laboratory's authorised signatories (:func:`axiscal.report.issue.authorisation`); without
    sign-in (a workbench on one's own computer) the form's signatory approves, as on the
    command line."""
    t = st.get(test_id)
    ev = t.evaluate_again()
    ctx = signoff_context(st, t, ev, values)
    if ctx is None:
        raise InputError(f"a {ev.kind} test is signed off by its command; the workbench signs "
                         "off ISO 230-2 positioning tests")
    try:
        job, tolerances, rule, paper = job_from_form(values, ctx["parameters"])
        from axiscal.io.user_config import config_problem, merge
        from axiscal.report.issue import load_config

        cfg = merge(load_config(None), job)
        _verdict(ctx, ev, cfg, tolerances, rule)
        if issue:
            out = _issue(st, t, ev, cfg, tolerances, rule, paper, config_problem(), user)
            ctx.update(missing=out.missing, number=out.number)
    except AxiscalError as exc:
        ctx["error"] = str(exc)
    return ctx


def _verdict(ctx: dict, ev, cfg: dict, tolerances: dict, rule) -> None:
    """The sign-off's verdict, verdict table and plot into ``ctx``."""
    from axiscal.report.issue import sign_off

    so = sign_off(ev.dataset, ev.evaluation, cfg, tolerances, rule)
    ctx.update(result=so, plot=signoff_plot(ev, so, tolerances),
               rows=_rows(ev.evaluation, so, tolerances), budget=so.budget)


def _issue(st, t, ev, cfg, tolerances, rule, paper, config_note, user: str = ""):
    import tempfile
    from pathlib import Path

    from axiscal.report.issue import write_certificate

    with tempfile.TemporaryDirectory() as d:
        return write_certificate(Path(d) / "certificate.pdf", ev.dataset, ev.evaluation, cfg,
                                 t.raw, tolerances, rule, paper, store=st,
                                 filename=t.summary.filename, config_note=config_note,
                                 customer_supplied=(), approved_by=user)


def _rows(result, so, tolerances: dict) -> list:
    """(parameter, value, U text, tolerance, where the tolerance comes from, outcome, short)."""
    params = result.parameters()
    out = []
    for d in so.decisions:
        source = "the sign-off" if d.parameter in tolerances else "user configuration"
        value = params[d.parameter]
        out.append((d.parameter, value, so.budget.U_text(d.parameter), d.upper, source,
                    d.outcome.value if d.outcome else "does not apply",
                    d.outcome.short if d.outcome else ""))
    return out


def _defaults(cfg: dict, params) -> dict:
    """The form as the user configuration fills it."""
    out = {}
    for field, (table, key) in _JOB_FIELDS.items():
        v = cfg.get(table, {}).get(key, "")
        out[field] = "\n".join(map(str, v)) if isinstance(v, list) else str(v)
    inst = cfg.get("instrument", [])
    for i, row in enumerate(inst if isinstance(inst, list) else [inst], 1):
        if i > INSTRUMENTS:
            break
        for k in _INSTRUMENT_KEYS:
            out[f"instrument{i}_{k}"] = str(row.get(k, ""))
    for p in params:
        tol = cfg.get("tolerance", {}).get(p)
        out[f"tol_{p}"] = "" if tol is None else f"{tol:g}"
    out["rule"] = str(cfg.get("certificate", {}).get("rule", "iso14253-1"))
    out["paper"] = str(cfg.get("certificate", {}).get("paper", "A4"))
    return out


def _unit(unit: str) -> str:
    return unit_text(unit)
